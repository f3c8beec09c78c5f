// Scalar-tag datapath of one CPG lane (docs/microarchitecture.md §5, Scalar tags): the
// operations a scalar-tagged triangle adds before the edge pass, one per cycle as tess_cpg's
// tag sequencer drives them. Three component slices, each with one general multiplier
// (2W+3 x max(W+1, G+1) bits), a restoring divider retiring DigitBits quotient bits a cycle
// and, shared, one square root retiring DigitBits root bits a cycle.
//
//   face0, face1   face normal e1 x e2 in two halves (lane 0 only; exact)
//   side           the sign of face . Δ: the side of the crease this triangle lies on
//   scale (k)      v = sat(round((N 2^F + s V) / 2^F)), (s, V) = (±σ, Δ) for N' (k = 0),
//                  (β, Δ) for Y (k = 1), (σ, N' - N) for X (k = 2)
//   dot            v.v into the square root; the dividers load |v_c| 2^F
//   sqrt           D root steps: |v| = isqrt(v.v)
//   div            D division steps (divisor |v|): the last yields normalize(v)
//   tan0 .. tan3   the tagged tangent point near Pj on edge Pj -> Pk:
//                  step = (1 - θ)(Pk - Pj); d = sat(Pj + sat(round(step/3)));
//                  Π = -n.(d - Pj); b = sat(d + round(Π m))
// Every value is exact until the one rounding the C++ reference (sim/values/cpg.cpp,
// compute_control_points) applies, so the results are bit-identical to it.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_cpg_tag #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned DigitBits     = tess_pkg::CpgDigitBits,
  localparam int unsigned W     = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned FaceW = 2 * W + 3                   // e1 x e2, exact
) (
  input  logic                          clk_i,
  // the operation of this cycle (at most one)
  input  logic                          face0_i,
  input  logic                          face1_i,
  input  logic                          side_i,
  input  logic                          scale_i,
  input  logic [1:0]                    norm_k_i,     // 0: N', 1: Y, 2: X
  input  logic                          dot_i,
  input  logic                          sqrt_i,
  input  logic                          div_i,
  input  logic                          div_first_i,
  input  logic                          div_last_i,
  input  logic [3:0]                    tan_i,        // one-hot: tangent steps 0..3
  // face operands (lane 0): e1 = P2 - P1, e2 = P3 - P1, component c at [c(W+1) +: W+1]
  input  logic [3*(W+1)-1:0]            e1_i,
  input  logic [3*(W+1)-1:0]            e2_i,
  input  logic [3*FaceW-1:0]            face_i,       // the triangle's face normal
  output logic [3*FaceW-1:0]            face_o,       // lane 0's face register
  // the corner being normalized
  input  logic [3*W-1:0]                n_i,          // N (the input normal)
  input  logic [3*W-1:0]                delta_i,      // Δ
  input  logic [3*W-1:0]                field_i,      // N' (after k = 0)
  input  logic [W-1:0]                  sigma_i,
  input  logic [W-1:0]                  beta_i,
  // the tangent being computed
  input  logic [3*W-1:0]                pj_i,
  input  logic [3*W-1:0]                pk_i,
  input  logic [W-1:0]                  theta_i,
  input  logic [3*W-1:0]                tn_i,         // n: N (crease) or X
  input  logic [3*W-1:0]                tm_i,         // m: Y (crease) or X
  // results, each valid in the cycle its step runs
  output logic [3*W-1:0]                norm_o,       // at div_last_i
  output logic [3*W-1:0]                tan_o,        // at tan_i[3]
  output logic [tess_pkg::FlagBits-1:0] flags_o
);

  localparam int unsigned F      = CoordFracBits;
  localparam int unsigned G      = CoordFracBits + tess_pkg::ConstGuardBits;
  localparam int unsigned MulAW  = FaceW;                          // widest first operand
  localparam int unsigned MulBW  = (W + 1 > G + 1) ? W + 1 : G + 1;  // widest second operand
  localparam int unsigned ProdW  = MulAW + MulBW;
  localparam int unsigned StepW  = 2 * W + 2;                      // (1 - θ)(Pk - Pj)
  localparam int unsigned PiW    = 2 * W + 3;                      // Π = -n.(d - Pj)
  localparam int unsigned SideW  = FaceW + W + 2;                  // face . Δ
  localparam int unsigned DivMagW = 2 * W + 1;                     // |v_c| 2^F, zero-extended

  // round(2^G / 3) = floor((2^G + 1) / 3), as tess_cpg_edge
  localparam logic [G:0] PowG    = {1'b1, {G{1'b0}}};
  localparam logic [G:0] KThirdU = (PowG + (G + 1)'(1)) / (G + 1)'(3);
  localparam logic signed [MulBW-1:0] KThird = MulBW'(KThirdU);
  localparam logic signed [W:0] One = (W + 1)'(1) << F;

  // ------------------------------------------------------------------ operands
  (* mem2reg *) logic signed [W:0]   e1 [3], e2 [3];
  (* mem2reg *) logic signed [W-1:0] n [3], delta [3], field [3], pj [3], pk [3], tn [3], tm [3];
  (* mem2reg *) logic signed [FaceW-1:0] face [3];
  for (genvar c = 0; c < 3; c++) begin : g_in
    assign e1[c]    = e1_i[c*(W+1) +: W+1];
    assign e2[c]    = e2_i[c*(W+1) +: W+1];
    assign n[c]     = n_i[c*W +: W];
    assign delta[c] = delta_i[c*W +: W];
    assign field[c] = field_i[c*W +: W];
    assign pj[c]    = pj_i[c*W +: W];
    assign pk[c]    = pk_i[c*W +: W];
    assign tn[c]    = tn_i[c*W +: W];
    assign tm[c]    = tm_i[c*W +: W];
    assign face[c]  = face_i[c*FaceW +: FaceW];
  end

  // ------------------------------------------------------------------ registers
  (* mem2reg *) logic signed [FaceW-1:0] facep_q [3];  // first half of the cross product
  (* mem2reg *) logic signed [FaceW-1:0] face_q [3];
  logic                                 side_neg_q;   // face . Δ < 0: the scale uses -σ
  (* mem2reg *) logic signed [W-1:0]     v_q [3];      // the vector being normalized
  (* mem2reg *) logic signed [StepW-1:0] step_q [3];
  (* mem2reg *) logic signed [W-1:0]     d_q [3];
  logic signed [PiW-1:0]                pi_q;

  // ------------------------------------------------------------------ the slice multipliers
  // scale: the scalar s and the vector V
  logic signed [W:0] scalar;
  always_comb begin
    case (norm_k_i)
      2'd0:    scalar = side_neg_q ? -((W + 1)'($signed(sigma_i))) : (W + 1)'($signed(sigma_i));
      2'd1:    scalar = (W + 1)'($signed(beta_i));
      default: scalar = (W + 1)'($signed(sigma_i));
    endcase
  end

  (* mem2reg *) logic signed [MulAW-1:0] mul_a [3];
  (* mem2reg *) logic signed [MulBW-1:0] mul_b [3];
  (* mem2reg *) logic signed [ProdW-1:0] prod [3];
  (* mem2reg *) logic signed [W:0]       dj [3];       // d - Pj
  for (genvar c = 0; c < 3; c++) begin : g_mul
    localparam int unsigned C1 = (c + 1) % 3;
    localparam int unsigned C2 = (c + 2) % 3;
    logic signed [W:0] vec;  // V of the scale step
    logic signed [W:0] chord, one_m_theta;  // Pk - Pj and 1 - θ of the tangent step
    assign chord       = (W + 1)'(pk[c]) - (W + 1)'(pj[c]);
    assign one_m_theta = One - (W + 1)'($signed(theta_i));
    assign vec   = (norm_k_i == 2'd2) ? (W + 1)'(field[c]) - (W + 1)'(n[c]) : (W + 1)'(delta[c]);
    assign dj[c] = (W + 1)'(d_q[c]) - (W + 1)'(pj[c]);
    always_comb begin
      mul_a[c] = '0;
      mul_b[c] = '0;
      if (face0_i) begin
        mul_a[c] = MulAW'(e1[C1]);
        mul_b[c] = MulBW'(e2[C2]);
      end else if (face1_i) begin
        mul_a[c] = MulAW'(e1[C2]);
        mul_b[c] = MulBW'(e2[C1]);
      end else if (side_i) begin
        mul_a[c] = MulAW'(face[c]);
        mul_b[c] = MulBW'(delta[c]);
      end else if (scale_i) begin
        mul_a[c] = MulAW'(vec);
        mul_b[c] = MulBW'(scalar);
      end else if (dot_i) begin
        mul_a[c] = MulAW'(v_q[c]);
        mul_b[c] = MulBW'(v_q[c]);
      end else if (tan_i[0]) begin
        mul_a[c] = MulAW'(chord);
        mul_b[c] = MulBW'(one_m_theta);
      end else if (tan_i[1]) begin
        mul_a[c] = MulAW'(step_q[c]);
        mul_b[c] = KThird;
      end else if (tan_i[2]) begin
        mul_a[c] = MulAW'(dj[c]);
        mul_b[c] = MulBW'(tn[c]);
      end else if (tan_i[3]) begin
        mul_a[c] = MulAW'(pi_q);
        mul_b[c] = MulBW'(tm[c]);
      end
    end
    assign prod[c] = mul_a[c] * mul_b[c];
  end

  // Sum over the slices (side: face . Δ; dot: v.v; tan2: n.(d - Pj)), exact.
  logic signed [SideW-1:0] dot;
  assign dot = SideW'(prod[0]) + SideW'(prod[1]) + SideW'(prod[2]);

  // ------------------------------------------------------------------ rounding per slice
  localparam int unsigned ScaleW = 2 * W + 4;             // N 2^F + s V
  localparam int unsigned ThirdShift = F + G;             // step (2F) * K (G) -> F
  localparam int unsigned TanW = 3 * W + 4;               // Π m
  (* mem2reg *) logic [W-1:0] v_next [3], d_next [3], b_next [3];
  logic [2:0] scale_sat, third_sat, d_sat, b_sat;
  for (genvar c = 0; c < 3; c++) begin : g_round
    // scale: sat(round_half_up(N 2^F + s V, F))
    logic signed [ScaleW-1:0] sx, sr;
    assign sx = (ScaleW'(n[c]) <<< F) + ScaleW'(prod[c]);
    assign sr = (sx + (ScaleW'(1) <<< (F - 1))) >>> F;
    tess_sat #(.InW(ScaleW), .OutW(W)) u_sat_scale (.x_i(sr), .y_o(v_next[c]), .sat_o(scale_sat[c]));

    // tan1: inner = sat(round_half_up(step K, F + G)); d = sat(Pj + inner)
    logic signed [ProdW-1:0] tr;
    logic [W-1:0]            inner;
    logic signed [W+1:0]     dsum;
    assign tr = (prod[c] + (ProdW'(1) <<< (ThirdShift - 1))) >>> ThirdShift;
    tess_sat #(.InW(ProdW), .OutW(W)) u_sat_third (.x_i(tr), .y_o(inner), .sat_o(third_sat[c]));
    assign dsum = (W + 2)'(pj[c]) + (W + 2)'($signed(inner));
    tess_sat #(.InW(W + 2), .OutW(W)) u_sat_d (.x_i(dsum), .y_o(d_next[c]), .sat_o(d_sat[c]));

    // tan3: b = sat(d + round_half_up(Π m, 2F))
    logic signed [TanW-1:0] pr, bsum;
    assign pr   = (TanW'(prod[c]) + (TanW'(1) <<< (2 * F - 1))) >>> (2 * F);
    assign bsum = TanW'(d_q[c]) + pr;
    tess_sat #(.InW(TanW), .OutW(W)) u_sat_b (.x_i(bsum), .y_o(b_next[c]), .sat_o(b_sat[c]));
    assign tan_o[c*W +: W] = b_next[c];
  end

  // ------------------------------------------------------------------ square root, dividers
  logic [W-1:0] root;
  tess_isqrt #(.RootW(W), .DigitBits(DigitBits)) u_isqrt (
    .clk_i (clk_i),
    .load_i(dot_i),
    .x_i   ((2 * W)'(dot)),
    .step_i(sqrt_i),
    .root_o(root)
  );

  logic [2:0] div_sat, div_dbz;
  for (genvar c = 0; c < 3; c++) begin : g_div
    logic [W-1:0] v_abs;
    assign v_abs = v_q[c][W-1] ? -v_q[c] : v_q[c];
    tess_div #(.DenW(W), .QuotW(W), .DigitBits(DigitBits)) u_div (
      .clk_i  (clk_i),
      .load_i (dot_i),
      .mag_i  (DivMagW'(v_abs) << F),
      .neg_i  (v_q[c][W-1]),
      .step_i (div_i),
      .first_i(div_first_i),
      .den_i  (root),
      .res_o  (norm_o[c*W +: W]),
      .sat_o  (div_sat[c]),
      .dbz_o  (div_dbz[c])
    );
  end

  // ------------------------------------------------------------------ registers
  always_ff @(posedge clk_i) begin
    for (int c = 0; c < 3; c++) begin
      if (face0_i) facep_q[c] <= FaceW'(prod[c]);
      if (face1_i) face_q[c] <= facep_q[c] - FaceW'(prod[c]);
      if (scale_i) v_q[c] <= v_next[c];
      if (tan_i[0]) step_q[c] <= StepW'(prod[c]);
      if (tan_i[1]) d_q[c] <= d_next[c];
    end
    if (side_i) side_neg_q <= dot[SideW-1];
    if (tan_i[2]) pi_q <= -(PiW'(dot));
  end

  for (genvar c = 0; c < 3; c++) begin : g_face_o
    assign face_o[c*FaceW +: FaceW] = face_q[c];
  end

  always_comb begin
    flags_o = '0;
    if (scale_i && (scale_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
    if (tan_i[1] && ((third_sat | d_sat) != '0)) flags_o |= tess_pkg::FlagSaturated;
    if (tan_i[3] && (b_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
    if (div_last_i && (div_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
    if (div_last_i && (div_dbz != '0)) flags_o |= tess_pkg::FlagDivByZero;
  end

  `TESS_ASSERT_PARAM(CoordWidthRange_A, CoordIntBits >= 1 && CoordFracBits >= 8 && 1 + CoordIntBits + CoordFracBits <= 32)
  `TESS_ASSERT_PARAM(DigitBitsRange_A, DigitBits >= 1 && DigitBits <= 1 + CoordIntBits + CoordFracBits)

endmodule
