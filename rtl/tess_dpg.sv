// DPG: domain-point generator (docs/microarchitecture.md §7). Walks the lattice of the patch
// in buffer[rd_ptr] in pattern order (rows k = 0..L, in a row j = 0..L-k) and gives the
// barycentric weights of the current point: u = bary_weight(j, L), v = bary_weight(k, L),
// w = 2^B - u - v, with bary_weight(j, L) = floor((j 2^(B+1) + L) / 2L), the round half up of
// j 2^B / L (sim/fixed.hpp). The divisions by the runtime L are combinational.
module tess_dpg #(
  parameter int unsigned BaryBits = tess_pkg::BaryBits,
  localparam int unsigned LBits   = tess_pkg::FactorBits
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic [LBits-1:0]    l_i,        // L of the patch in buffer[rd_ptr]
  input  logic                consume_i,  // a context takes the current point
  output logic [LBits-1:0]    j_o,
  output logic [LBits-1:0]    k_o,
  output logic [BaryBits:0]   w_o,
  output logic [BaryBits:0]   u_o,
  output logic [BaryBits:0]   v_o,
  output logic                last_o      // (0, L): the patch's last point
);

  localparam int unsigned NumW = BaryBits + 1 + LBits;  // j 2^(B+1) + L < 2^(B+8)
  localparam int unsigned DenW = LBits + 1;             // 2L

  logic [LBits-1:0] j_q, k_q;

  assign last_o = (k_q == l_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      j_q <= '0;
      k_q <= '0;
    end else if (consume_i) begin
      if (last_o) begin
        j_q <= '0;
        k_q <= '0;
      end else if ({1'b0, j_q} + {1'b0, k_q} + 8'd1 <= {1'b0, l_i}) begin
        j_q <= j_q + LBits'(1);
      end else begin
        j_q <= '0;
        k_q <= k_q + LBits'(1);
      end
    end
  end

  logic [NumW-1:0] num_u, num_v, quo_u, quo_v;
  logic [DenW-1:0] den;
  assign den   = {l_i, 1'b0};
  assign num_u = {j_q, {(BaryBits + 1){1'b0}}} + NumW'(l_i);
  assign num_v = {k_q, {(BaryBits + 1){1'b0}}} + NumW'(l_i);
  assign quo_u = num_u / NumW'(den);
  assign quo_v = num_v / NumW'(den);

  // Weights never exceed 2^B (j <= L); the upper quotient bits are zero.
  logic unused_quo;
  assign unused_quo = ^{quo_u[NumW-1:BaryBits+1], quo_v[NumW-1:BaryBits+1]};
  assign u_o = quo_u[BaryBits:0];
  assign v_o = quo_v[BaryBits:0];
  assign w_o = {1'b1, {BaryBits{1'b0}}} - u_o - v_o;
  assign j_o = j_q;
  assign k_o = k_q;

endmodule
