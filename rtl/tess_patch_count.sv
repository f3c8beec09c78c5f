// The number of vertices of a triangle's pattern, from its descriptor alone, in one combinational
// step (sim/values/cpg.cpp patch_vertex_count): (L + 1)(L + 2) / 2 for the uniform pattern; for a D3D11
// pattern the outer ring's points plus 3R(n - 2 - R) of the R = n/2 - 1 inner rings and the centre
// of an even pattern, n the points of the inner edge (tess_fsu's per-patch part, with the edge
// shapes of tess_fsu_edge's first stage: the same arithmetic, not registered). The distributor of
// a system of units (tess_distributor) needs it in the cycle it takes the triangle.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_patch_count (
  input  logic [tess_pkg::FactorBits-1:0]  l_i,
  input  logic [tess_pkg::PatternBits-1:0] pattern_i,
  input  logic [4*tess_pkg::FixBits-1:0]   factors_i,  // factor e at [e FixBits +: FixBits], 3 = inner
  output logic [tess_pkg::IndexBits-1:0]   count_o     // 3..3169 (uniform: 3..2145)
);

  localparam int unsigned FW = tess_pkg::FixBits;
  localparam int unsigned CW = tess_pkg::IndexBits;

  // ------------------------------------------------------------------ each edge's points
  (* mem2reg *) logic [FW-1:0] factor [4];
  logic [3:0] odd;
  (* mem2reg *) logic [6:0] points [4];
  for (genvar e = 0; e < 4; e++) begin : g_edge
    logic [FW-1:0] half0, half;
    logic [5:0]    half_points;
    assign factor[e] = factors_i[e*FW +: FW];
    // Parity as tess_fsu: integer factors their own (an inner factor of 1 counts as even),
    // fractional_odd odd, fractional_even even.
    if (e == 3) begin : g_inner
      assign odd[e] = (pattern_i == tess_pkg::PatInteger) ? factor[e][16] && factor[e] != FW'(32'h10000)
                                                           : (pattern_i == tess_pkg::PatFracOdd);
    end else begin : g_outer
      assign odd[e] = (pattern_i == tess_pkg::PatInteger) ? factor[e][16] : (pattern_i == tess_pkg::PatFracOdd);
    end
    assign half0       = FW'(({1'b0, factor[e]} + (FW + 1)'(1)) >> 1);
    assign half        = (odd[e] || half0 == FW'(32'h8000)) ? half0 + FW'(32'h8000) : half0;
    assign half_points = half[21:16] + 6'(half[15:0] != '0);
    assign points[e]   = {half_points, 1'b0} + 7'(!odd[e]);
    logic unused_half;  // H <= 33: bit 22 is never set
    assign unused_half = half[FW-1];
  end

  // ------------------------------------------------------------------ the D3D11 patch
  logic single;
  assign single = (pattern_i != tess_pkg::PatFracEven) && factor[0] == FW'(32'h10000) &&
                  factor[1] == FW'(32'h10000) && factor[2] == FW'(32'h10000) && factor[3] == FW'(32'h10000);
  logic [6:0]  min_inner, n_inner, rings, ring_width;
  logic [13:0] ring_product;
  logic [CW-1:0] outer_ring, d3d11_count;
  assign min_inner    = odd[3] ? 7'd4 : 7'd3;
  assign n_inner      = single ? '0 : (points[3] > min_inner ? points[3] : min_inner);
  assign rings        = (n_inner >= 7'd2) ? (n_inner >> 1) - 7'd1 : '0;
  assign ring_width   = n_inner - 7'd2 - rings;
  assign ring_product = 14'(rings) * 14'(ring_width);
  assign outer_ring   = CW'(points[0]) + CW'(points[1]) + CW'(points[2]) - CW'(3);
  assign d3d11_count  = outer_ring + (single ? '0 : CW'(ring_product) + CW'({ring_product, 1'b0}) + CW'(!odd[3]));

  // ------------------------------------------------------------------ the uniform pattern
  logic [13:0] uniform_product;
  assign uniform_product = (14'(l_i) + 14'd1) * (14'(l_i) + 14'd2);

  assign count_o = (pattern_i == tess_pkg::PatUniform) ? CW'(uniform_product >> 1) : d3d11_count;

  // The largest pattern, 3169 points (fractional_even at 64), fits count_o.
  `TESS_ASSERT_PARAM(CountFits_A, (1 << tess_pkg::IndexBits) > 3169)

endmodule
