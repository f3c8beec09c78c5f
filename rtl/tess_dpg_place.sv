// The position of point `index_i` along an edge set up by tess_fsu_edge, 16.16 in [0, 1]
// (docs/microarchitecture.md §7; sim/d3d11_walk.cpp d3d11_place). Points past the middle
// are 1 - t of their mirror, so an edge gives the same points walked from either end; the
// middle is exact; otherwise t = (i' fw + i cw + 2^15) >> 16, with i' = i - 1 past the split.
module tess_dpg_place (
  input  logic [tess_pkg::EdgeBits-1:0] edge_i,
  input  logic [6:0]                    index_i,
  output logic [16:0]                   t_o
);

  logic        odd;
  logic [5:0]  half_points, split;
  logic [32:0] floor_weight, ceil_weight;
  logic [6:0]  unused_points;
  assign {unused_points, ceil_weight, floor_weight, split, half_points, odd} = edge_i;

  logic       mirrored;
  logic [6:0] i, floor_i;
  assign mirrored = index_i >= 7'(half_points);
  assign i        = mirrored ? {half_points, 1'b0} - index_i - 7'(odd) : index_i;
  assign floor_i  = (i > 7'(split)) ? i - 7'd1 : i;

  logic [39:0] blend;
  logic [16:0] position;
  assign blend    = 40'(floor_i) * 40'(floor_weight) + 40'(i) * 40'(ceil_weight) + 40'h8000;
  assign position = (i == 7'(half_points)) ? 17'h8000 : blend[32:16];
  assign t_o      = mirrored ? 17'h10000 - position : position;

  logic unused_blend;
  assign unused_blend = ^{blend[39:33], blend[15:0]};

endmodule
