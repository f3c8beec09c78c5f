// Sequential integer square root, digit by digit: DigitBits root bits a cycle, Steps =
// ceil(RootW / DigitBits) cycles, of a 2*RootW-bit radicand. After the last step root_o =
// floor(sqrt(x)) (sim/base/fixed.hpp isqrt).
// The radicand is taken zero-extended to 2*RW bits (RW = Steps * DigitBits >= RootW), which
// only adds leading zero root bits. Each sub-step brings down the next two radicand bits and
// subtracts the trial 4r + 1 where it fits; the remainder stays <= 2r, so it needs RW + 1 bits.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_isqrt #(
  parameter int unsigned RootW     = 24,
  parameter int unsigned DigitBits = 1,
  localparam int unsigned Steps = (RootW + DigitBits - 1) / DigitBits,
  localparam int unsigned RW    = Steps * DigitBits
) (
  input  logic               clk_i,
  input  logic               load_i,
  input  logic [2*RootW-1:0] x_i,
  input  logic               step_i,
  output logic [RootW-1:0]   root_o
);

  localparam int unsigned RemW = RW + 2;

  logic [2*RW-1:0] x_q;
  logic [RemW-1:0] rem_q;
  logic [RW-1:0]   root_q;

  // DigitBits sub-steps: each brings down the next two radicand bits.
  logic [2*RW-1:0] x_step;
  logic [RemW-1:0] rem_step;
  logic [RW-1:0]   root_step;
  logic [RemW+1:0] rem_in, trial;
  logic            fits;
  always_comb begin
    x_step    = x_q;
    rem_step  = rem_q;
    root_step = root_q;
    rem_in    = '0;
    trial     = '0;
    fits      = 1'b0;
    for (int i = 0; i < DigitBits; i++) begin
      rem_in    = {rem_step, x_step[2*RW-1 -: 2]};
      trial     = {2'b00, root_step, 2'b01};
      fits      = (rem_in >= trial);
      rem_step  = fits ? RemW'(rem_in - trial) : rem_in[RemW-1:0];
      root_step = {root_step[RW-2:0], fits};
      x_step    = {x_step[2*RW-3:0], 2'b00};
    end
  end

  // Datapath registers: loaded before use, no reset needed.
  always_ff @(posedge clk_i) begin
    if (load_i) begin
      x_q    <= (2 * RW)'(x_i);
      rem_q  <= '0;
      root_q <= '0;
    end else if (step_i) begin
      x_q    <= x_step;
      rem_q  <= rem_step;
      root_q <= root_step;
    end
  end

  assign root_o = root_q[RootW-1:0];
  if (RW > RootW) begin : g_pad
    logic unused_root_pad;  // leading root bits of the zero-extended radicand: always 0
    assign unused_root_pad = ^root_q[RW-1:RootW];
  end

  // r root bits a cycle, at least one, at most the root.
  `TESS_ASSERT_PARAM(DigitBitsRange_A, DigitBits >= 1 && DigitBits <= RootW)

endmodule
