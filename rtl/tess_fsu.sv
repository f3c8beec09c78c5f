// FSU: factor setup unit (docs/microarchitecture.md §7; sim/values/d3d11_walk.cpp
// d3d11_factors_from_fixed, d3d11_setup). The factors arrive processed by the host (clamped,
// rounded, 16.16): this is the tessellator's integer part, no floating point.
//
// Sequential beside the CPG: the CPG holds the triangle's pattern descriptor from the cycle after
// it takes the triangle until it takes the next one, at least C >= 8 cycles later, and writes the
// control points no earlier than C cycles after taking it. One edge setup (tess_fsu_edge, three
// stages) takes the four factors in turn, one a cycle, into four records: they are complete six
// cycles after the CPG took the triangle. The per-patch part (points of an inner edge, rings,
// point count) is registered from the records' shapes in two steps, complete after them, and the
// CPG's buffer write stores the setup with the nets, so the DPG walks a D3D11 patch from its
// first cycle at one point per cycle. Every stage fits the depth budget (docs/rtl.md).
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_fsu (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  input  logic                           start_i,  // the CPG takes a triangle: desc_i from the next cycle
  input  logic [tess_pkg::DescBits-1:0]  desc_i,   // {factors[3..0], pattern, L}, held by the CPG
  output logic                           busy_o,   // records still being computed
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

  // ------------------------------------------------------------------ the factors in turn
  // One-hot: factor e is in the setup's first stage in the (e + 1)-th cycle after start_i, in its
  // second and third stages the cycles after; the per-patch part is registered in two steps after
  // the inner edge's first stage.
  logic [3:0] first_d, first_q, second_d, second_q, third_d, third_q;
  logic       patch_d, patch_q, count_d, count_q;
  assign first_d  = start_i ? 4'b0001 : {first_q[2:0], 1'b0};
  assign second_d = first_q;
  assign third_d  = second_q;
  assign patch_d  = first_q[3];
  assign count_d  = patch_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      first_q  <= '0;
      second_q <= '0;
      third_q  <= '0;
      patch_q  <= 1'b0;
      count_q  <= 1'b0;
    end else begin
      first_q  <= first_d;
      second_q <= second_d;
      third_q  <= third_d;
      patch_q  <= patch_d;
      count_q  <= count_d;
    end
  end
  assign busy_o = (first_q != '0) || (second_q != '0) || (third_q != '0) || patch_q || count_q;

  logic [FW-1:0] cur_factor;
  logic          cur_inner;
  always_comb begin
    cur_factor = '0;
    for (int e = 0; e < 4; e++) cur_factor |= first_q[e] ? factor[e] : '0;
  end
  assign cur_inner = first_q[3];

  // Parity: integer factors their own (an inner factor of 1 counts as even: the rings end in a
  // centre point); fractional_odd odd, fractional_even even.
  logic cur_odd;
  assign cur_odd = (pattern == tess_pkg::PatInteger) ? cur_factor[16] && !(cur_inner && cur_factor == FW'(32'h10000))
                                                     : (pattern == tess_pkg::PatFracOdd);

  logic [6:0]  cur_points;
  logic [5:0]  cur_split, cur_half_points;
  logic [33:0] prev_sum_weight;
  logic [32:0] prev_ceil_weight;
  tess_fsu_edge u_edge (
    .clk_i         (clk_i),
    .factor_i      (cur_factor),
    .odd_i         (cur_odd),
    .points_o      (cur_points),
    .split_o       (cur_split),
    .half_points_o (cur_half_points),
    .sum_weight_o  (prev_sum_weight),
    .ceil_weight_o (prev_ceil_weight)
  );

  // ------------------------------------------------------------------ the four records
  // Data only (not reset): written after every start_i before the CPG's buffer write reads them.
  (* mem2reg *) logic [19:0] shape_q [4];    // {points, split, half points, odd}
  (* mem2reg *) logic [66:0] weights_q [4];  // {ceil weight, sum weight}
  for (genvar e = 0; e < 4; e++) begin : g_record
    always_ff @(posedge clk_i) begin
      if (first_q[e]) shape_q[e] <= {cur_points, cur_split, cur_half_points, cur_odd};
      if (third_q[e]) weights_q[e] <= {prev_ceil_weight, prev_sum_weight};
    end
  end

  // One edge's setup as the DPG reads it: {points, cw, fw + cw, split, half points, odd}.
  (* mem2reg *) logic [EW-1:0] edges [4];
  for (genvar e = 0; e < 4; e++) begin : g_edge
    assign edges[e] = {shape_q[e][19:13], weights_q[e], shape_q[e][12:0]};
  end
  logic inner_odd;
  assign inner_odd = shape_q[3][0];

  // ------------------------------------------------------------------ the patch
  // All four factors 1 (not fractional_even): the domain itself, three points.
  logic single;
  assign single = (pattern != tess_pkg::PatFracEven) && factor[0] == FW'(32'h10000) &&
                  factor[1] == FW'(32'h10000) && factor[2] == FW'(32'h10000) && factor[3] == FW'(32'h10000);

  // Points of an inner edge (at least one ring inside the outer one), rings R = n/2 - 1 of
  // 3 (n - 1 - 2r) points, and the centre of an even pattern.
  logic [6:0] inner_pts, n_inner, min_inner, rings;
  assign inner_pts = edges[3][EW-1 -: 7];
  assign min_inner = inner_odd ? 7'd4 : 7'd3;
  assign n_inner   = single ? '0 : (inner_pts > min_inner ? inner_pts : min_inner);
  assign rings     = (n_inner >= 7'd2) ? (n_inner >> 1) - 7'd1 : '0;

  // Two registered steps, a cycle each (each within the depth budget): the ring count and the
  // last ring's width with the outer ring's points, then the product and the sums.
  logic [tess_pkg::IndexBits-1:0] outer_ring, outer_ring_q, ring_points, point_count, point_count_q;
  logic [6:0]  ring_width, rings_q, ring_width_q, n_inner_q;  // n - 2 - R: points of the last ring's edge
  logic        single_q, inner_odd_q;
  logic [13:0] ring_product;  // R (n - 2 - R) <= 31 * 32
  assign outer_ring  = tess_pkg::IndexBits'(edges[0][EW-1 -: 7]) + tess_pkg::IndexBits'(edges[1][EW-1 -: 7]) +
                       tess_pkg::IndexBits'(edges[2][EW-1 -: 7]) - tess_pkg::IndexBits'(3);
  assign ring_width  = n_inner - 7'd2 - rings;
  always_ff @(posedge clk_i) begin
    if (patch_q) begin
      outer_ring_q <= outer_ring;
      rings_q      <= rings;
      ring_width_q <= ring_width;
      n_inner_q    <= n_inner;
      single_q     <= single;
      inner_odd_q  <= inner_odd;
    end
  end
  assign ring_product = 14'(rings_q) * 14'(ring_width_q);
  assign ring_points  = tess_pkg::IndexBits'(ring_product) + tess_pkg::IndexBits'({ring_product, 1'b0});
  assign point_count  = outer_ring_q + (single_q ? '0 : ring_points + tess_pkg::IndexBits'(!inner_odd_q));
  always_ff @(posedge clk_i) begin
    if (count_q) point_count_q <= point_count;
  end

  assign setup_o = {point_count_q, n_inner_q, edges[3], edges[2], edges[1], edges[0]};

  logic unused_l;  // the uniform pattern's factor goes past the FSU
  assign unused_l = ^desc_i[Pat-1:0];

  // The CPG's start strobe and the busy flag it waits on are never X out of reset.
  `TESS_ASSERT_KNOWN(StartKnown_A, start_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(BusyKnown_A, busy_o, clk_i, !rst_ni)

endmodule
