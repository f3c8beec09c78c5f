// One fixed-point lane in the unit's coordinate format (docs/number-formats.md: W = 1 + I + F
// bits, two's complement, F fraction bits): d = sat(round_half_up(a * b / 2^F) + c), the product
// exact, rounded half up once (as sim/fixed.hpp round_shift) and the sum saturated to W bits (as
// sim/fixed.hpp saturate). Written only to measure what such a lane costs
// (scripts/ge_lane_cost.sh); not part of the unit. The output is registered once.
module ge_mac_lane #(
  parameter int unsigned IntBits  = tess_pkg::CoordIntBits,   // I
  parameter int unsigned FracBits = tess_pkg::CoordFracBits,  // F, at least 1
  localparam int unsigned W = 1 + IntBits + FracBits
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         valid_i,
  input  logic [W-1:0] a_i,
  input  logic [W-1:0] b_i,
  input  logic [W-1:0] c_i,
  output logic         valid_o,
  output logic [W-1:0] d_o
);

  localparam int unsigned ProdW = 2 * W;
  localparam int unsigned RndW  = ProdW - FracBits;  // the rounded product: W + I + 1 bits
  localparam int unsigned SumW  = RndW + 1;

  // Exact product. Adding half an LSB cannot overflow: |a * b| <= 2^(2W-2).
  logic signed [ProdW-1:0] prod, prod_half;
  assign prod      = $signed(a_i) * $signed(b_i);
  assign prod_half = prod + $signed(ProdW'(1) << (FracBits - 1));

  // Dropping the F low bits of the biased product floors it: round half up (towards +inf).
  logic signed [RndW-1:0] rnd;
  assign rnd = prod_half[ProdW-1:FracBits];

  // Exact sum, then clamp to [-2^(W-1), 2^(W-1) - 1]: it fits iff the bits from the result's
  // sign bit up all equal the sum's sign.
  logic [SumW-1:0]  sum;
  logic [SumW-W:0]  top;
  logic [W-1:0]     d_d, d_q;
  logic             valid_q;
  assign sum = {rnd[RndW-1], rnd} + {{(SumW - W){c_i[W-1]}}, c_i};
  assign top = sum[SumW-1:W-1];
  always_comb begin
    if (top == '0 || top == '1) d_d = sum[W-1:0];
    else if (sum[SumW-1]) d_d = {1'b1, {(W - 1){1'b0}}};
    else d_d = {1'b0, {(W - 1){1'b1}}};
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_q <= 1'b0;
    else valid_q <= valid_i;
  end
  always_ff @(posedge clk_i) begin
    d_q <= d_d;
  end
  assign valid_o = valid_q;
  assign d_o     = d_q;

  // The F dropped bits of the biased product only carry into the kept ones.
  logic unused_bits;
  assign unused_bits = ^prod_half[FracBits-1:0];

endmodule
