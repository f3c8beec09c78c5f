// Sequential restoring divider of one CPG lane: one quotient bit a cycle, QuotW cycles.
// Computes sim/fixed.hpp div_trunc(num, den) for den >= 0: the quotient of |num| by den
// truncated, given the sign of num, saturated to QuotW bits (two's complement); den = 0
// gives 0 and the divide-by-zero flag.
//
// The dividend magnitude is loaded into {rem, quot} (AccW + QuotW bits). The first step also
// checks rem >= den, i.e. |num| >= den * 2^QuotW: the quotient does not fit in QuotW bits
// and saturates whatever the remaining steps compute. Otherwise rem < den throughout and
// each step shifts one dividend bit into rem and subtracts den where it fits.
module tess_div #(
  parameter int unsigned DenW  = 50,  // divisor bits (unsigned)
  parameter int unsigned QuotW = 24,  // quotient bits = steps = signed result width
  localparam int unsigned AccW = DenW + 1,
  localparam int unsigned MagW = AccW + QuotW
) (
  input  logic            clk_i,
  input  logic            load_i,   // load |num| and its sign
  input  logic [MagW-1:0] mag_i,
  input  logic            neg_i,
  input  logic            step_i,   // one quotient bit
  input  logic            first_i,  // the step is the first after load (overflow check)
  input  logic [DenW-1:0] den_i,    // held constant during the steps
  // Result after the current step (valid in the cycle of the last step).
  output logic [QuotW-1:0] res_o,
  output logic            sat_o,
  output logic            dbz_o
);

  logic [MagW-1:0] acc_q, acc_d;
  logic            neg_q, ovf_q, ovf_d;

  logic [AccW-1:0] rem_shifted, rem_next;
  logic            fits;
  logic            ovf_now;

  // {rem, quot} shifted left by one: the next dividend bit moves from quot into rem.
  assign rem_shifted = acc_q[MagW-2:QuotW-1];
  assign fits        = (rem_shifted >= {1'b0, den_i});
  assign rem_next    = fits ? rem_shifted - {1'b0, den_i} : rem_shifted;
  assign ovf_now     = (acc_q[MagW-1:QuotW] >= {1'b0, den_i});

  always_comb begin
    acc_d = acc_q;
    ovf_d = ovf_q;
    if (load_i) begin
      acc_d = mag_i;
      ovf_d = 1'b0;
    end else if (step_i) begin
      acc_d = {rem_next, acc_q[QuotW-2:0], fits};
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
  localparam logic [QuotW:0] MaxPos = {2'b01, {(QuotW - 1){1'b0}}};  // 2^(QuotW-1)
  logic [QuotW-1:0] quot;
  logic             den_zero;
  logic [QuotW:0]   quot_ext;
  logic [QuotW-1:0] quot_neg;
  assign quot     = acc_d[QuotW-1:0];
  assign den_zero = (den_i == '0);
  assign quot_ext = {1'b0, quot};
  assign quot_neg = -quot;  // only used when quot <= 2^(QuotW-1)

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
        res_o = quot;
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

endmodule
