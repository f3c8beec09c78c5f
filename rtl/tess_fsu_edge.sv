// One factor's edge setup (docs/microarchitecture.md §7; sim/values/d3d11_walk.cpp d3d11_edge):
// how a D3D11 factor spreads its points along a unit edge. From the half factor
// H = (F + 2^-16) / 2 (plus 1/2 when odd) come the points per half edge ceil(H), the split
// point (ruler order: the top bit of floor(H) cleared), the segment counts of floor(H) and
// ceil(H) and their 16.16 reciprocals from a 64-entry table, and the blend's weights
// fw = R(n_floor)(1 - phi), cw = R(n_ceil) phi, kept as cw and fw + cw: the DPG steps the blend
// i' fw + i cw of consecutive points by fw + cw, or by cw where i' stays (tess_dpg).
//
// Three stages of one cycle each, so that one setup takes a new factor every cycle (tess_fsu)
// and each fits the depth budget (docs/rtl.md): the edge's shape and its two reciprocals come
// from the factor of this cycle, the weights' 17 x 17-bit products from the reciprocals
// registered in the cycle before, their sum a cycle later.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_fsu_edge (
  input  logic                         clk_i,
  input  logic [tess_pkg::FixBits-1:0] factor_i,      // 16.16, 1..64
  input  logic                         odd_i,
  // The shape of factor_i's edge
  output logic [6:0]                   points_o,
  output logic [5:0]                   split_o,
  output logic [5:0]                   half_points_o,
  // The blend weights of the factor_i two cycles before
  output logic [33:0]                  sum_weight_o,   // fw + cw
  output logic [32:0]                  ceil_weight_o
);

  localparam int unsigned FW = tess_pkg::FixBits;

  // ------------------------------------------------------------------ stage 1: shape, reciprocals
  logic [FW-1:0] half0, half, floor_half, ceil_half;
  logic [15:0]   phi;
  assign half0      = FW'(({1'b0, factor_i} + (FW + 1)'(1)) >> 1);
  // An even factor of 1 is handled as an odd one: half a segment cannot be centred.
  assign half       = (odd_i || half0 == FW'(32'h8000)) ? half0 + FW'(32'h8000) : half0;
  assign phi        = half[15:0];
  assign floor_half = {half[FW-1:16], 16'h0};
  assign ceil_half  = (phi != '0) ? floor_half + FW'(32'h10000) : half;

  logic [5:0] half_points, floor_int, split, wo_msb_in, wo_msb;
  assign half_points = ceil_half[21:16];  // <= 33
  assign floor_int   = floor_half[21:16];
  assign wo_msb_in   = odd_i ? floor_int - 6'd1 : floor_int;
  // Highest set bit cleared (0 stays 0).
  always_comb begin
    wo_msb = wo_msb_in;
    for (int b = 0; b < 6; b++) begin
      if ({1'b0, wo_msb_in} >= (7'd1 << b) && {1'b0, wo_msb_in} < (7'd1 << (b + 1))) wo_msb[b] = 1'b0;
    end
  end
  always_comb begin
    if (phi == '0) split = half_points + 6'd1;  // no split: never reached
    else if (odd_i && floor_half == FW'(32'h10000)) split = '0;
    else split = {wo_msb[4:0], 1'b1};
  end

  logic [6:0] floor_segments, ceil_segments;
  assign floor_segments = {floor_int, 1'b0} - 7'(odd_i);
  assign ceil_segments  = {half_points, 1'b0} - 7'(odd_i);

  // R(n) = round(2^16 / n) for n = 1..64 (0 otherwise: never used), a constant table read by the
  // segment count: Yosys builds a 7-level multiplexer tree over the constants (a comparison per
  // entry ORed together maps to a path three times as deep).
  localparam int unsigned RecipW = 17;
  function automatic logic [128*RecipW-1:0] recip_table();
    logic [128*RecipW-1:0] t;
    t = '0;
    for (int n = 1; n <= tess_pkg::MaxFactor; n++) t[n*RecipW +: RecipW] = RecipW'((32'h10000 + n / 2) / n);
    recip_table = t;
  endfunction
  localparam logic [128*RecipW-1:0] RecipTable = recip_table();
  logic [16:0] inv_floor, inv_ceil;
  assign inv_floor = RecipTable[floor_segments*RecipW +: RecipW];
  assign inv_ceil  = RecipTable[ceil_segments*RecipW +: RecipW];

  assign points_o      = {half_points, 1'b0} + 7'(!odd_i);
  assign split_o       = split;
  assign half_points_o = half_points;

  // ------------------------------------------------------------------ stage 2: blend weights
  // Pipeline registers: data only, read in the cycle after the factor they belong to.
  logic [16:0] inv_floor_q, inv_ceil_q;
  logic [15:0] phi_q;
  always_ff @(posedge clk_i) begin
    inv_floor_q <= inv_floor;
    inv_ceil_q  <= inv_ceil;
    phi_q       <= phi;
  end

  logic [16:0] one_minus_phi;
  logic [32:0] floor_weight, ceil_weight, floor_weight_q, ceil_weight_q;
  assign one_minus_phi = 17'h10000 - {1'b0, phi_q};
  assign floor_weight  = 33'(inv_floor_q) * 33'(one_minus_phi);
  assign ceil_weight   = 33'(inv_ceil_q) * 33'(phi_q);

  // ------------------------------------------------------------------ stage 3: their sum
  always_ff @(posedge clk_i) begin
    floor_weight_q <= floor_weight;
    ceil_weight_q  <= ceil_weight;
  end
  assign ceil_weight_o = ceil_weight_q;
  assign sum_weight_o  = 34'(floor_weight_q) + 34'(ceil_weight_q);

  // ceil_half's fraction is floor_half's (zero); bit 22 is never set (H <= 33); the split
  // takes the cleared value's low five bits (floor(H) <= 32).
  logic unused_bits;
  assign unused_bits = ^{ceil_half[FW-1], ceil_half[15:0], wo_msb[5]};

  // A D3D11 factor is at most 64.0 in 16.16: its ceiling's points fit points_o.
  `TESS_ASSERT_PARAM(FactorFits_A, tess_pkg::FixBits >= 23 && tess_pkg::MaxFactor + 1 < (1 << 7))

endmodule
