// DPG: domain-point generator (docs/microarchitecture.md §7). Walks the lattice of the patch
// in buffer[rd_ptr] in pattern order (rows k = 0..L, in a row j = 0..L-k) and gives the
// barycentric weights of the current point: u = bary_weight(j, L), v = bary_weight(k, L),
// w = 2^B - u - v, where bary_weight(j, L) = floor((j 2^(B+1) + L) / 2L) is the round half up
// of j 2^B / L (sim/fixed.hpp).
//
// No divider: the weights are kept as quotient and remainder of that division and advanced
// exactly. Going from j to j + 1 adds 2^(B+1) to the numerator, i.e. q(L) = floor(2^B / L) to
// the quotient and r(L) = 2^(B+1) mod 2L to the remainder (with one carry when the remainder
// reaches 2L). q and r come from a 64-entry constant table indexed by L. At j = 0 the weight
// is 0 with remainder L, so a new row or patch needs no state.
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

  localparam int unsigned B    = BaryBits;
  localparam int unsigned RemW = LBits + 1;  // remainders < 2L <= 128

  // ---- per-L step of the weight: q = floor(2^B / L), r = 2^(B+1) mod 2L
  logic [B:0]      step_q;
  logic [RemW-1:0] step_r;
  always_comb begin
    step_q = '0;
    step_r = '0;
    for (int l = 1; l <= tess_pkg::MaxFactor; l++) begin
      if (l_i == LBits'(l)) begin
        step_q = (B + 1)'((64'd1 << B) / 64'(l));
        step_r = RemW'((64'd1 << (B + 1)) % (64'd2 * 64'(l)));
      end
    end
  end

  logic [LBits-1:0] j_q, k_q;
  logic [B:0]       u_q, v_q;      // weights of j_q, k_q (meaningful when they are > 0)
  logic [RemW-1:0]  ru_q, rv_q;    // their remainders

  // Weight and remainder of the current j and k (index 0: weight 0, remainder L).
  logic [B:0]      u_cur, v_cur;
  logic [RemW-1:0] ru_cur, rv_cur, two_l;
  assign two_l  = {l_i, 1'b0};
  assign u_cur  = (j_q == '0) ? '0 : u_q;
  assign v_cur  = (k_q == '0) ? '0 : v_q;
  assign ru_cur = (j_q == '0) ? RemW'(l_i) : ru_q;
  assign rv_cur = (k_q == '0) ? RemW'(l_i) : rv_q;

  // One lattice step of a weight: quotient + q (+ 1 on carry), remainder + r (- 2L on carry).
  logic [RemW:0]   ru_sum, rv_sum;
  logic            u_carry, v_carry;
  logic [B:0]      u_next, v_next;
  logic [RemW-1:0] ru_next, rv_next;
  assign ru_sum  = {1'b0, ru_cur} + {1'b0, step_r};
  assign rv_sum  = {1'b0, rv_cur} + {1'b0, step_r};
  assign u_carry = (ru_sum >= {1'b0, two_l});
  assign v_carry = (rv_sum >= {1'b0, two_l});
  assign u_next  = u_cur + step_q + (B + 1)'(u_carry);
  assign v_next  = v_cur + step_q + (B + 1)'(v_carry);
  assign ru_next = u_carry ? RemW'(ru_sum - {1'b0, two_l}) : ru_sum[RemW-1:0];
  assign rv_next = v_carry ? RemW'(rv_sum - {1'b0, two_l}) : rv_sum[RemW-1:0];

  logic row_continues;
  assign last_o        = (k_q == l_i);
  assign row_continues = ({1'b0, j_q} + {1'b0, k_q} + 8'd1 <= {1'b0, l_i});

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      j_q <= '0;
      k_q <= '0;
    end else if (consume_i) begin
      if (last_o) begin
        j_q <= '0;
        k_q <= '0;
      end else if (row_continues) begin
        j_q <= j_q + LBits'(1);
      end else begin
        j_q <= '0;
        k_q <= k_q + LBits'(1);
      end
    end
  end

  // Weight registers: read only for an index > 0, which was reached by a step that wrote them.
  always_ff @(posedge clk_i) begin
    if (consume_i && !last_o) begin
      if (row_continues) begin
        u_q  <= u_next;
        ru_q <= ru_next;
      end else begin
        v_q  <= v_next;
        rv_q <= rv_next;
      end
    end
  end

  assign u_o = u_cur;
  assign v_o = v_cur;
  assign w_o = {1'b1, {B{1'b0}}} - u_cur - v_cur;
  assign j_o = j_q;
  assign k_o = k_q;

endmodule
