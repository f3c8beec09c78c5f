// Sequential restoring divider of one CPG lane: DigitBits quotient bits a cycle (radix
// 2^DigitBits), Steps = ceil(QuotW / DigitBits) cycles. Computes sim/base/fixed.hpp
// div_trunc(num, den) for den >= 0: the quotient of |num| by den truncated, given the sign of
// num, saturated to QuotW bits (two's complement); den = 0 gives 0 and the divide-by-zero flag.
//
// The quotient register has QW = Steps * DigitBits >= QuotW bits; the dividend magnitude is
// loaded zero-extended into {rem, quot} (AccW + QW bits). The first step also checks rem >= den,
// i.e. |num| >= den * 2^QW: the quotient does not fit in QW bits and saturates whatever the
// remaining steps compute. Otherwise rem < den throughout and each of the DigitBits sub-steps of
// a cycle shifts one dividend bit into rem and subtracts den where it fits. Quotient bits above
// QuotW are real quotient bits: the saturation test sees the whole QW-bit quotient.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_div #(
  parameter int unsigned DenW      = 50,  // divisor bits (unsigned)
  parameter int unsigned QuotW     = 24,  // quotient bits = signed result width
  parameter int unsigned DigitBits = 1,   // quotient bits a cycle
  localparam int unsigned Steps = (QuotW + DigitBits - 1) / DigitBits,
  localparam int unsigned QW    = Steps * DigitBits,
  localparam int unsigned AccW  = DenW + 1,
  localparam int unsigned MagW  = AccW + QuotW,  // the dividend magnitude as loaded
  localparam int unsigned RegW  = AccW + QW
) (
  input  logic            clk_i,
  input  logic            load_i,   // load |num| and its sign
  input  logic [MagW-1:0] mag_i,
  input  logic            neg_i,
  input  logic            step_i,   // DigitBits quotient bits
  input  logic            first_i,  // the step is the first after load (overflow check)
  input  logic [DenW-1:0] den_i,    // held constant during the steps
  // Result after the current step (valid in the cycle of the last step).
  output logic [QuotW-1:0] res_o,
  output logic            sat_o,
  output logic            dbz_o
);

  logic [RegW-1:0] acc_q, acc_d, acc_step;
  logic            neg_q, ovf_q, ovf_d;
  logic            ovf_now;

  // DigitBits restoring sub-steps: {rem, quot} shifted left by one, the next dividend bit
  // moves from quot into rem, den is subtracted where it fits and the quotient bit enters at
  // the bottom.
  logic [AccW-1:0] rem_shifted;
  logic            fits;
  always_comb begin
    acc_step    = acc_q;
    rem_shifted = '0;
    fits        = 1'b0;
    for (int i = 0; i < DigitBits; i++) begin
      rem_shifted = acc_step[RegW-2:QW-1];
      fits        = (rem_shifted >= {1'b0, den_i});
      acc_step    = {fits ? rem_shifted - {1'b0, den_i} : rem_shifted, acc_step[QW-2:0], fits};
    end
  end
  assign ovf_now = (acc_q[RegW-1:QW] >= {1'b0, den_i});

  always_comb begin
    acc_d = acc_q;
    ovf_d = ovf_q;
    if (load_i) begin
      acc_d = RegW'(mag_i);
      ovf_d = 1'b0;
    end else if (step_i) begin
      acc_d = acc_step;
      if (first_i) ovf_d = ovf_now;
    end
  end

  // Datapath registers: loaded before use, no reset needed.
  always_ff @(posedge clk_i) begin
    acc_q <= acc_d;
    neg_q <= load_i ? neg_i : neg_q;
    ovf_q <= ovf_d;
  end

  // Signed, saturated result of the quotient in acc_d.
  localparam logic [QW:0] MaxPos = (QW + 1)'(1) << (QuotW - 1);  // 2^(QuotW-1)
  logic [QW-1:0]    quot;
  logic             den_zero;
  logic [QW:0]      quot_ext;
  logic [QuotW-1:0] quot_neg;
  assign quot     = acc_d[QW-1:0];
  assign den_zero = (den_i == '0);
  assign quot_ext = {1'b0, quot};
  assign quot_neg = -quot[QuotW-1:0];  // only used when quot <= 2^(QuotW-1)

  always_comb begin
    res_o = '0;
    sat_o = 1'b0;
    dbz_o = 1'b0;
    if (den_zero) begin
      dbz_o = 1'b1;
    end else if (!neg_q) begin
      if (ovf_d || quot_ext >= MaxPos) begin
        res_o = {1'b0, {(QuotW - 1){1'b1}}};
        sat_o = 1'b1;
      end else begin
        res_o = quot[QuotW-1:0];
      end
    end else begin
      if (ovf_d || quot_ext > MaxPos) begin
        res_o = {1'b1, {(QuotW - 1){1'b0}}};
        sat_o = 1'b1;
      end else begin
        res_o = quot_neg;
      end
    end
  end

  // r quotient bits a cycle, at least one, at most the quotient.
  `TESS_ASSERT_PARAM(DigitBitsRange_A, DigitBits >= 1 && DigitBits <= QuotW)

endmodule
