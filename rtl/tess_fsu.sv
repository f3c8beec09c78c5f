// FSU: factor setup unit (docs/microarchitecture.md §7; model/d3d11_pattern.cpp
// d3d11_factors_from_fixed, d3d11_setup). Combinational from the pattern descriptor the CPG
// holds while it computes the control points; the control-point buffer stores the result with
// the nets, so the DPG walks a D3D11 patch from its first cycle at one point per cycle. The
// factors arrive processed by the host (clamped, rounded, 16.16): this is the tessellator's
// integer part, no floating point.
module tess_fsu (
  input  logic [tess_pkg::DescBits-1:0]  desc_i,   // {factors[3..0], pattern, L}
  output logic [tess_pkg::SetupBits-1:0] setup_o   // {point count, inner points, inner, outer 2..0}
);

  localparam int unsigned FW  = tess_pkg::FixBits;
  localparam int unsigned EW  = tess_pkg::EdgeBits;
  localparam int unsigned Pat = tess_pkg::FactorBits;  // pattern field
  localparam int unsigned Fac = Pat + tess_pkg::PatternBits;

  logic [1:0]    pattern;
  (* mem2reg *) logic [FW-1:0] factor [4];
  assign pattern = desc_i[Pat +: 2];
  for (genvar e = 0; e < 4; e++) begin : g_factor
    assign factor[e] = desc_i[Fac + e * FW +: FW];
  end

  // Parity: integer factors their own (an inner factor of 1 counts as even: the rings end in a
  // centre point); fractional_odd odd, fractional_even even.
  logic [3:0] odd;
  for (genvar e = 0; e < 4; e++) begin : g_parity
    if (e < 3) begin : g_outer
      assign odd[e] = (pattern == tess_pkg::PatInteger) ? factor[e][16] : (pattern == tess_pkg::PatFracOdd);
    end else begin : g_inner
      assign odd[e] = (pattern == tess_pkg::PatInteger) ? factor[e][16] && factor[e] != FW'(32'h10000)
                                                         : (pattern == tess_pkg::PatFracOdd);
    end
  end

  (* mem2reg *) logic [EW-1:0] edges [4];
  for (genvar e = 0; e < 4; e++) begin : g_edge
    tess_fsu_edge u_edge (.factor_i(factor[e]), .odd_i(odd[e]), .edge_o(edges[e]));
  end

  // All four factors 1 (not fractional_even): the domain itself, three points.
  logic single;
  assign single = (pattern != tess_pkg::PatFracEven) && factor[0] == FW'(32'h10000) &&
                  factor[1] == FW'(32'h10000) && factor[2] == FW'(32'h10000) && factor[3] == FW'(32'h10000);

  // Points of an inner edge (at least one ring inside the outer one), rings R = n/2 - 1 of
  // 3 (n - 1 - 2r) points, and the centre of an even pattern.
  logic [6:0] inner_pts, n_inner, min_inner, rings;
  assign inner_pts = edges[3][EW-1 -: 7];
  assign min_inner = odd[3] ? 7'd4 : 7'd3;
  assign n_inner   = single ? '0 : (inner_pts > min_inner ? inner_pts : min_inner);
  assign rings     = (n_inner >= 7'd2) ? (n_inner >> 1) - 7'd1 : '0;

  logic [tess_pkg::IndexBits-1:0] outer_ring, ring_points, point_count;
  assign outer_ring  = tess_pkg::IndexBits'(edges[0][EW-1 -: 7]) + tess_pkg::IndexBits'(edges[1][EW-1 -: 7]) +
                       tess_pkg::IndexBits'(edges[2][EW-1 -: 7]) - tess_pkg::IndexBits'(3);
  logic [6:0]  ring_width;    // n - 2 - R: points of the last ring's edge
  logic [13:0] ring_product;  // R (n - 2 - R) <= 31 * 32
  assign ring_width   = n_inner - 7'd2 - rings;
  assign ring_product = 14'(rings) * 14'(ring_width);
  assign ring_points  = tess_pkg::IndexBits'(ring_product) + tess_pkg::IndexBits'({ring_product, 1'b0});
  assign point_count = outer_ring + (single ? '0 : ring_points + tess_pkg::IndexBits'(!odd[3]));

  assign setup_o = {point_count, n_inner, edges[3], edges[2], edges[1], edges[0]};

  logic unused_l;  // the uniform pattern's factor goes past the FSU
  assign unused_l = ^desc_i[Pat-1:0];

endmodule
