// Sequential integer square root, digit by digit: one root bit a cycle, RootW cycles, of a
// 2*RootW-bit radicand. After the last step root_o = floor(sqrt(x)) (sim/fixed.hpp isqrt).
// Each step brings down the next two radicand bits and subtracts the trial 4r + 1 where it
// fits; the remainder stays <= 2r, so it needs RootW + 1 bits.
module tess_isqrt #(
  parameter int unsigned RootW = 24
) (
  input  logic               clk_i,
  input  logic               load_i,
  input  logic [2*RootW-1:0] x_i,
  input  logic               step_i,
  output logic [RootW-1:0]   root_o
);

  localparam int unsigned RemW = RootW + 2;

  logic [2*RootW-1:0] x_q;
  logic [RemW-1:0]    rem_q;
  logic [RootW-1:0]   root_q;

  logic [RemW+1:0] rem_in, trial;
  logic            fits;
  assign rem_in = {rem_q, x_q[2*RootW-1 -: 2]};
  assign trial  = {2'b00, root_q, 2'b01};
  assign fits   = (rem_in >= trial);

  // Datapath registers: loaded before use, no reset needed.
  always_ff @(posedge clk_i) begin
    if (load_i) begin
      x_q    <= x_i;
      rem_q  <= '0;
      root_q <= '0;
    end else if (step_i) begin
      x_q    <= {x_q[2*RootW-3:0], 2'b00};
      rem_q  <= fits ? RemW'(rem_in - trial) : rem_in[RemW-1:0];
      root_q <= {root_q[RootW-2:0], fits};
    end
  end

  assign root_o = root_q;

endmodule
