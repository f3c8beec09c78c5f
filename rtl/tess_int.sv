// INT block: one barycentric combination of three points, r = w A + u B + v C per component,
// with w + u + v = 2^B (sim/base/fixed.hpp int_op): the exact sum of the three products is
// rounded half up once, and cannot overflow because r is a convex combination.
//
// Latency (docs/microarchitecture.md §8): an op issued in cycle t leaves on res_o in cycle
// t + Latency - 1, so that the TE writes it at the end of that cycle. With Latency = 1 the
// block is combinational, behind the TE's operand select in one path. With Latency >= 2 the
// first register takes the selected operands (the select and the 45-level multiply-add then sit
// in different cycles: docs/rtl.md, Depth budget); with Latency >= 3 the second sits between
// the multipliers and the adder; any further registers delay the result. The TE gives the block
// one register fewer than its IntLatency when it registers the slots' choices itself.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_int #(
  parameter int unsigned CoordWidth = 24,               // W
  parameter int unsigned BaryBits   = tess_pkg::BaryBits,  // B
  parameter int unsigned Latency    = tess_pkg::IntLatency,
  parameter int unsigned TagWidth   = 8,                // context index and op, carried along
  parameter int unsigned InjectBug  = tess_pkg::InjectBug
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    valid_i,
  input  logic [TagWidth-1:0]     tag_i,
  input  logic [BaryBits:0]       w_i,
  input  logic [BaryBits:0]       u_i,
  input  logic [BaryBits:0]       v_i,
  input  logic [3*CoordWidth-1:0] a_i,
  input  logic [3*CoordWidth-1:0] b_i,
  input  logic [3*CoordWidth-1:0] c_i,
  output logic                    valid_o,
  output logic [TagWidth-1:0]     tag_o,
  output logic [3*CoordWidth-1:0] res_o
);

  localparam int unsigned W     = CoordWidth;
  localparam int unsigned ProdW = BaryBits + 2 + W;  // (B+2)-bit signed weight x W-bit operand
  localparam int unsigned SumW  = ProdW + 2;

  // Optional input register (Latency >= 2): the TE's operand select ends in the issue cycle, the
  // multiply-add has the next cycle to itself.
  logic                    in_valid;
  logic [TagWidth-1:0]     in_tag;
  logic [BaryBits:0]       in_w, in_u, in_v;
  logic [3*CoordWidth-1:0] in_a, in_b, in_c;
  if (Latency >= 2) begin : g_in_reg
    logic                    valid_d, valid_q;
    logic [TagWidth-1:0]     tag_d, tag_q;
    logic [BaryBits:0]       w_d, w_q, u_d, u_q, v_d, v_q;
    logic [3*CoordWidth-1:0] a_d, a_q, b_d, b_q, c_d, c_q;
    assign valid_d = valid_i;
    assign tag_d   = tag_i;
    assign w_d     = w_i;
    assign u_d     = u_i;
    assign v_d     = v_i;
    assign a_d     = a_i;
    assign b_d     = b_i;
    assign c_d     = c_i;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q <= 1'b0;
      end else begin
        valid_q <= valid_d;
      end
    end
    always_ff @(posedge clk_i) begin
      tag_q <= tag_d;
      w_q   <= w_d;
      u_q   <= u_d;
      v_q   <= v_d;
      a_q   <= a_d;
      b_q   <= b_d;
      c_q   <= c_d;
    end
    assign in_valid = valid_q;
    assign in_tag   = tag_q;
    assign in_w     = w_q;
    assign in_u     = u_q;
    assign in_v     = v_q;
    assign in_a     = a_q;
    assign in_b     = b_q;
    assign in_c     = c_q;
  end else begin : g_in_comb
    logic unused_clk;
    assign unused_clk = clk_i ^ rst_ni;
    assign in_valid = valid_i;
    assign in_tag   = tag_i;
    assign in_w     = w_i;
    assign in_u     = u_i;
    assign in_v     = v_i;
    assign in_a     = a_i;
    assign in_b     = b_i;
    assign in_c     = c_i;
  end

  // Stage 1: nine exact products (weights are unsigned, so they get a zero sign bit).
  (* mem2reg *) logic signed [BaryBits+1:0] weight [3];
  (* mem2reg *) logic signed [W-1:0]        operand [3][3];  // [component][A, B, C]
  (* mem2reg *) logic signed [ProdW-1:0]    prod_s [3][3];
  (* mem2reg *) logic [ProdW-1:0]           prod [3][3];
  assign weight[0] = $signed({1'b0, in_w});
  assign weight[1] = $signed({1'b0, in_u});
  assign weight[2] = $signed({1'b0, in_v});
  for (genvar c = 0; c < 3; c++) begin : g_comp
    assign operand[c][0] = $signed(in_a[c*W +: W]);
    assign operand[c][1] = $signed(in_b[c*W +: W]);
    assign operand[c][2] = $signed(in_c[c*W +: W]);
    for (genvar o = 0; o < 3; o++) begin : g_op
      assign prod_s[c][o] = weight[o] * operand[c][o];
      assign prod[c][o]   = prod_s[c][o];
    end
  end

  // Optional pipeline register after the multipliers (Latency >= 3).
  (* mem2reg *) logic [ProdW-1:0]    sum_in [3][3];
  logic                stage_valid;
  logic [TagWidth-1:0] stage_tag;
  if (Latency >= 3) begin : g_mul_reg
    (* mem2reg *) logic [ProdW-1:0] prod_d [3][3], prod_q [3][3];
    logic                valid_d, valid_q;
    logic [TagWidth-1:0] tag_d, tag_q;
    assign valid_d = in_valid;
    assign tag_d   = in_tag;
    for (genvar c = 0; c < 3; c++) begin : g_prod_d
      for (genvar o = 0; o < 3; o++) begin : g_o
        assign prod_d[c][o] = prod[c][o];
      end
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q <= 1'b0;
      end else begin
        valid_q <= valid_d;
      end
    end
    always_ff @(posedge clk_i) begin
      tag_q <= tag_d;
      for (int c = 0; c < 3; c++) begin
        for (int o = 0; o < 3; o++) prod_q[c][o] <= prod_d[c][o];
      end
    end
    for (genvar c = 0; c < 3; c++) begin : g_c
      for (genvar o = 0; o < 3; o++) begin : g_o
        assign sum_in[c][o] = prod_q[c][o];
      end
    end
    assign stage_valid = valid_q;
    assign stage_tag   = tag_q;
  end else begin : g_mul_comb
    for (genvar c = 0; c < 3; c++) begin : g_c
      for (genvar o = 0; o < 3; o++) begin : g_o
        assign sum_in[c][o] = prod[c][o];
      end
    end
    assign stage_valid = in_valid;
    assign stage_tag   = in_tag;
  end

  // Stage 2: exact sum, one rounding half up (InjectBug 1: the +half is dropped).
  localparam logic [SumW-1:0] Half = (InjectBug == 1) ? '0 : SumW'(1) << (BaryBits - 1);
  (* mem2reg *) logic signed [SumW-1:0] term [3][3];
  (* mem2reg *) logic [SumW-1:0]        sum [3];
  logic [3*W-1:0]         res;
  for (genvar c = 0; c < 3; c++) begin : g_sum
    for (genvar o = 0; o < 3; o++) begin : g_term
      assign term[c][o] = {{(SumW - ProdW){sum_in[c][o][ProdW-1]}}, sum_in[c][o]};
    end
    assign sum[c] = term[c][0] + term[c][1] + term[c][2] + Half;
    assign res[c*W +: W] = sum[c][BaryBits +: W];
  end

  // Further Latency - 3 registers delay the result.
  if (Latency >= 4) begin : g_out_regs
    localparam int unsigned Extra = Latency - 3;
    (* mem2reg *) logic                valid_d [Extra], valid_q [Extra];
    (* mem2reg *) logic [TagWidth-1:0] tag_d [Extra], tag_q [Extra];
    (* mem2reg *) logic [3*W-1:0]      res_d [Extra], res_q [Extra];
    always_comb begin
      valid_d[0] = stage_valid;
      tag_d[0]   = stage_tag;
      res_d[0]   = res;
      for (int i = 1; i < Extra; i++) begin
        valid_d[i] = valid_q[i-1];
        tag_d[i]   = tag_q[i-1];
        res_d[i]   = res_q[i-1];
      end
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        for (int i = 0; i < Extra; i++) valid_q[i] <= 1'b0;
      end else begin
        for (int i = 0; i < Extra; i++) valid_q[i] <= valid_d[i];
      end
    end
    always_ff @(posedge clk_i) begin
      for (int i = 0; i < Extra; i++) begin
        tag_q[i] <= tag_d[i];
        res_q[i] <= res_d[i];
      end
    end
    assign valid_o = valid_q[Extra-1];
    assign tag_o   = tag_q[Extra-1];
    assign res_o   = res_q[Extra-1];
  end else begin : g_out_comb
    assign valid_o = stage_valid;
    assign tag_o   = stage_tag;
    assign res_o   = res;
  end

  // The issue handshake: valid in, valid out never X out of reset; Λ as the TE schedules it.
  `TESS_ASSERT_KNOWN(ValidInKnown_A, valid_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(ValidOutKnown_A, valid_o, clk_i, !rst_ni)
  `TESS_ASSERT_PARAM(LatencyRange_A, Latency >= 1 && Latency <= 8)

endmodule
