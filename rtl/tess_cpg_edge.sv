// One edge lane of the CPG (docs/microarchitecture.md §5): the datapath that computes the two
// tangent points and the mid-edge normal of an edge a->b in E micro-steps, driven by the step
// index of tess_cpg. The sequential CPG (CpgLanes = 1) walks the three edges through one lane;
// the parallel CPG (CpgLanes = 3) has a lane per edge. Lane 0 also computes b111.
//
// Three component slices (x, y, z), each with one general multiplier (DotW x MulBW bits), one
// constant multiplier by round(2^G/3) (G = F + 8), a restoring divider retiring DigitBits
// quotient bits a cycle and, shared, one square root retiring DigitBits root bits a cycle.
// With D = ceil(W / DigitBits) digit steps and ProductReg = 0, the micro-steps s are:
//   s0        d = Pb - Pa, s = Na + Nb;        wa = d.Na  (slices multiply, adder tree sums)
//   s1        num = (2Pa + Pb) 2^2F - wa Na    (per slice)
//   s2        wb = d.Nb;                       tangent near a = round(num / 3)
//   s3        num = (2Pb + Pa) 2^2F + wb Nb
//   s4        p = d.s;                         tangent near b = round(num / 3)
//   s5        q = d.d;                         p <- |p|
//   --- linear: E = 6 ends here ---
//   s6        load dividers with |d_c| |p| (sign of d_c p)
//   s7 ..     D division steps (divisor q), the last one yields t_c
//   s7+D      m = sat(s - k t)                 (reflect: mid-edge normal = m; E = D + 8 ends)
//   s8+D      m.m into the square root; load dividers with |m_c| 2^F (sign of m_c)
//   s9+D ..   D square-root steps: |m| = isqrt(m.m)
//   s9+2D ..  D division steps (divisor |m|), the last one yields the mid-edge normal
//   --- quadratic: E = 3D + 9 ends here ---
// With ProductReg = 1 the multipliers' products are registered: a product issued in step k is
// used in step k + 1, so the multiplier and the adders, the dividers' loads and the tangent
// points behind it are in different cycles; the constant multiplication of a tangent point
// takes a cycle of its own too. Step 0 only registers d, |d| and s (Pb - Pa in front of a
// multiplier would undo the gain), and the independent products overlap:
//   s0  d, |d|, s                s1  issue d.Na              s2  wa = d.Na; issue d.Nb
//   s3  wb = d.Nb; issue wa Na   s4  num_a; issue wb Nb      s5  num_a / 3; num_b; issue d.s
//   s6  tangent near a; num_b / 3; p = d.s; issue d.d        s7  tangent near b; q = d.d; p <- |p|
//   --- linear: E = 9 ends here (the last tangent point reaches b111's sum in s8) ---
//   s8  issue |d_c| |p|          s9  load dividers           s10 .. D division steps
//   s10+D  m (reflect: E = D + 11)                           s11+D  issue m.m
//   s12+D  m.m into the square root; load dividers with |m_c| 2^F
//   s13+D ..  D square-root steps; s13+2D ..  D division steps (quadratic: E = 3D + 13)
// and b111 takes two cycles instead of one (issue, then round). sim/values/cpg.cpp cpg_edge_cycles
// holds the same E.
// The silhouette blend (AlphaBits = A > 0) scales each w by the edge's alpha before it meets
// its normal, w <- round(alpha w / 2^A) on one (A + 1) x DotW multiplier of its own, in the step
// after w is summed. Without registered products the steps are reordered at no cost:
//   s0 wa = d.Na   s1 wb = d.Nb; wa <- alpha wa   s2 issue wa Na; wb <- alpha wb
//   s3 num_b (wb Nb); tangent near a              s4 p = d.s; tangent near b      s5 q = d.d
// With them, d.s moves into the slot the first w product leaves, and the tangent point near b
// leaves a step later (linear: E = 10; the divisions start in s10 as before):
//   s1 issue d.Na   s2 wa = d.Na; issue d.Nb   s3 wb = d.Nb; issue d.s; operand alpha wa
//   s4 issue wa Na; operand alpha wb   s5 issue wb Nb   s6 issue d.d   s7 tangent near a
//   s8 tangent near b
// Every value is exact until the one rounding the C++ reference (sim/values/cpg.cpp) applies, so the
// results are bit-identical to compute_control_points whatever DigitBits and ProductReg are.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_cpg_edge #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned DigitBits     = tess_pkg::CpgDigitBits,
  parameter int unsigned ProductReg    = tess_pkg::CpgProductReg,
  parameter int unsigned AlphaBits     = tess_pkg::AlphaBits,
  localparam int unsigned W      = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned AlphaW = AlphaBits + 1,
  localparam int unsigned D      = (W + DigitBits - 1) / DigitBits,
  localparam int unsigned StepW  = $clog2(3 * D + 9 + 4 * ((ProductReg != 0) ? 1 : 0)),
  localparam int unsigned X111W  = W + 5                       // 3 sum(t) - 2 sum(P)
) (
  input  logic                          clk_i,
  input  logic                          mode_reflect_i,
  input  logic                          edge_i,       // computing step step_i of an edge
  input  logic [StepW-1:0]              step_i,
  input  logic                          last_i,       // step_i is the edge's last step
  input  logic                          keep_a_i,     // the tangent point near a is this lane's
  input  logic                          keep_b_i,     // (else the tag pass computes it)
  input  logic [3*W-1:0]                pa_i,         // component c at [cW +: W]
  input  logic [3*W-1:0]                pb_i,
  input  logic [3*W-1:0]                na_i,
  input  logic [3*W-1:0]                nb_i,
  input  logic [AlphaW-1:0]             alpha_i,      // the edge's silhouette weight (AlphaBits)
  input  logic                          b111_i,       // the b111 cycles (lane 0 only), counted
                                                      // by step_i from 0
  input  logic                          b111_next_i,  // the next cycle is b111's first
  input  logic [3*X111W-1:0]            x111_i,       // 3 sum(t) - 2 sum(P), per component
  input  logic [3*X111W-1:0]            x111_next_i,  // ... as it is at the end of this cycle
  // Results, each valid in the cycle its strobe is high.
  output logic [3*W-1:0]                tangent_o,
  output logic                          tangent_a_o,  // tangent_o is the point near a
  output logic                          tangent_b_o,  // tangent_o is the point near b
  output logic [3*W-1:0]                mid_o,
  output logic                          mid_valid_o,
  output logic [3*W-1:0]                b111_o,
  output logic                          b111_valid_o, // in b111 step ProductReg
  output logic [tess_pkg::FlagBits-1:0] flags_o       // raised by this cycle's results
);

  localparam int unsigned F       = CoordFracBits;
  localparam int unsigned G       = CoordFracBits + tess_pkg::ConstGuardBits;
  // Exact intermediate widths (two's complement, all values provably fit):
  localparam int unsigned DotW    = 2 * W + 3;                 // d.s, d.Na, d.Nb, d.d, m.m
  localparam int unsigned MulBW   = (W + 1 > G - 2) ? W + 1 : G - 2;  // round(2^G/12) < 2^(G-3)
  localparam int unsigned ProdW   = DotW + MulBW;              // general slice product
  localparam int unsigned ChordW  = W + 2 + 2 * F;             // (2Pn + Pf) 2^2F
  localparam int unsigned NumW    = ((ChordW > 3 * W + 1) ? ChordW : 3 * W + 1) + 1;
  localparam int unsigned KProdW  = NumW + G;                  // num * round(2^G/3) < 2^(G-1)
  localparam int unsigned KShift  = 2 * F + G;                 // 3F fraction bits -> F
  localparam int unsigned DenW    = 2 * W + 2;                 // d.d < 3 * 2^2W
  localparam int unsigned MagW    = DenW + 1 + W;              // divider dividend magnitude
  // Micro-step indices within an edge: the step that issues each product (it is used R steps
  // later) and the steps that use results (sim/values/cpg.cpp cpg_edge_cycles).
  localparam bit          PR      = (ProductReg != 0);
  localparam bit          Al      = (AlphaBits != 0);
  localparam int unsigned R       = PR ? 1 : 0;
  localparam int unsigned SDotA   = R;                 // d.Na
  localparam int unsigned SMulA   = PR ? (Al ? 4 : 3) : (Al ? 2 : 1);  // wa Na
  localparam int unsigned SDotB   = Al && !PR ? 1 : 2; // d.Nb
  localparam int unsigned SMulB   = PR ? (Al ? 5 : 4) : 3;  // wb Nb
  localparam int unsigned SDotS   = PR ? (Al ? 3 : 5) : 4;  // d.s
  localparam int unsigned SDotD   = PR ? 6 : 5;         // d.d
  localparam int unsigned STanA   = SMulA + 2 * R + 1; // the tangent point near a leaves
  localparam int unsigned STanB   = SMulB + 2 * R + 1; // the tangent point near b leaves
  localparam int unsigned SAbs    = SDotD + R;         // q = d.d; p <- |p|
  localparam int unsigned SNum    = SAbs + 1;          // |d_c| |p|
  localparam int unsigned SLoad1  = SNum + R;          // the dividers take |d_c| |p|
  localparam int unsigned SDiv1   = SLoad1 + 1;
  localparam int unsigned SM      = SDiv1 + D;
  localparam int unsigned SMM     = SM + 1;            // m.m
  localparam int unsigned SLoad2  = SMM + R;           // the square root takes m.m
  localparam int unsigned SSqrt   = SLoad2 + 1;
  localparam int unsigned SDiv2   = SSqrt + D;

  // ------------------------------------------------------------------ step decode
  // st_*: a step's work; use_*: a product is used (iss_*, below: a product is issued).
  logic st_edge0, use_dot_a, use_mul_a, use_dot_b, use_mul_b, use_dot_s, use_b111;
  logic st_tan_a, st_tan_b, st_abs, st_load1, st_load2, st_m;
  logic st_div1, st_div1_first, st_div1_last, st_sqrt, st_div2, st_div2_first, st_div2_last;

  assign st_edge0      = edge_i && (step_i == StepW'(0));
  assign use_dot_a     = edge_i && (step_i == StepW'(SDotA + R));
  assign use_mul_a     = edge_i && (step_i == StepW'(SMulA + R));
  assign use_dot_b     = edge_i && (step_i == StepW'(SDotB + R));
  assign use_mul_b     = edge_i && (step_i == StepW'(SMulB + R));
  assign use_dot_s     = edge_i && (step_i == StepW'(SDotS + R));
  assign use_b111      = b111_i && (step_i == StepW'(R));
  assign st_tan_a      = edge_i && (step_i == StepW'(STanA));
  assign st_tan_b      = edge_i && (step_i == StepW'(STanB));
  assign st_abs        = edge_i && (step_i == StepW'(SAbs));
  assign st_load1      = edge_i && (step_i == StepW'(SLoad1));
  assign st_load2      = edge_i && (step_i == StepW'(SLoad2));
  assign st_m          = edge_i && (step_i == StepW'(SM));
  assign st_div1       = edge_i && (step_i >= StepW'(SDiv1)) && (step_i < StepW'(SDiv1 + D));
  assign st_div1_first = edge_i && (step_i == StepW'(SDiv1));
  assign st_div1_last  = edge_i && (step_i == StepW'(SDiv1 + D - 1));
  assign st_sqrt       = edge_i && (step_i >= StepW'(SSqrt)) && (step_i < StepW'(SSqrt + D));
  assign st_div2       = edge_i && (step_i >= StepW'(SDiv2));  // the quadratic edge's last D
  assign st_div2_first = edge_i && (step_i == StepW'(SDiv2));
  assign st_div2_last  = edge_i && (step_i == StepW'(SDiv2 + D - 1));

  // ------------------------------------------------------------------ the edge a->b
  (* mem2reg *) logic [W-1:0] pa [3], pb [3], na [3], nb [3];
  for (genvar c = 0; c < 3; c++) begin : g_in
    assign pa[c] = pa_i[c*W +: W];
    assign pb[c] = pb_i[c*W +: W];
    assign na[c] = na_i[c*W +: W];
    assign nb[c] = nb_i[c*W +: W];
  end

  // ------------------------------------------------------------------ edge registers
  (* mem2reg *) logic [W:0]        d_q [3];    // Pb - Pa
  (* mem2reg *) logic [W:0]        s_q [3];    // Na + Nb
  logic [DotW-1:0]   pdot_q;     // d.s, then |d.s|
  logic              pneg_q;     // sign of d.s
  logic [DenW-1:0]   q_q;        // d.d
  (* mem2reg *) logic [NumW-1:0]   num_q [3];  // numerator of the tangent point being computed
  (* mem2reg *) logic [W-1:0]      t_q [3];    // projection t_c = trunc(d_c (d.s) / (d.d))
  (* mem2reg *) logic [W-1:0]      m_q [3];    // m = s - k t

  // Combinational edge vector of s0 (d is registered at the end of s0).
  (* mem2reg *) logic signed [W:0] d_now [3], s_now [3];
  for (genvar c = 0; c < 3; c++) begin : g_edge
    assign d_now[c] = $signed({pb[c][W-1], pb[c]}) - $signed({pa[c][W-1], pa[c]});
    assign s_now[c] = $signed({na[c][W-1], na[c]}) + $signed({nb[c][W-1], nb[c]});
  end

  // |d_c|, an operand of the first division's dividend: from d_q, or registered with d.
  (* mem2reg *) logic [W:0] d_abs [3];
  if (PR) begin : g_dabs_reg
    (* mem2reg *) logic [W:0] dabs_q [3];
    always_ff @(posedge clk_i) begin
      for (int c = 0; c < 3; c++) begin
        if (st_edge0) dabs_q[c] <= d_now[c][W] ? -d_now[c] : d_now[c];
      end
    end
    for (genvar c = 0; c < 3; c++) begin : g_c
      assign d_abs[c] = dabs_q[c];
    end
  end else begin : g_dabs_comb
    for (genvar c = 0; c < 3; c++) begin : g_c
      assign d_abs[c] = d_q[c][W] ? -d_q[c] : d_q[c];
    end
  end

  // ------------------------------------------------------------------ general slice multipliers
  // The operands are an AND-OR over the steps (at most one is active): no priority chain in
  // front of the multiplier.
  (* mem2reg *) logic [DotW-1:0]         mul_a [3];
  (* mem2reg *) logic [MulBW-1:0]        mul_b [3];
  (* mem2reg *) logic signed [ProdW-1:0] prod [3];  // this cycle's product
  (* mem2reg *) logic signed [ProdW-1:0] prd [3];   // the product the using step sees

  // round(2^G / 12) = floor((2^G + 6) / 12), round(2^G / 3) = floor((2^G + 1) / 3)
  localparam logic [G:0] PowG = {1'b1, {G{1'b0}}};
  localparam logic [G:0] KTwelfthU = (PowG + (G + 1)'(6)) / (G + 1)'(12);
  localparam logic [G:0] KThirdU   = (PowG + (G + 1)'(1)) / (G + 1)'(3);
  localparam logic signed [MulBW-1:0] KTwelfth = MulBW'(KTwelfthU);

  for (genvar c = 0; c < 3; c++) begin : g_mul
    assign prod[c] = $signed(mul_a[c]) * $signed(mul_b[c]);
    if (PR) begin : g_prod_reg
      logic signed [ProdW-1:0] prod_q;
      always_ff @(posedge clk_i) begin
        prod_q <= prod[c];
      end
      assign prd[c] = prod_q;
    end else begin : g_prod_now
      assign prd[c] = prod[c];
    end
  end

  // Sum over the slices: the dot products (exact, DotW bits suffice).
  logic [DotW-1:0] dot;
  assign dot = prd[0][DotW-1:0] + prd[1][DotW-1:0] + prd[2][DotW-1:0];

  // ------------------------------------------------------------------ tangent points
  // num = (2Pn + Pf) 2^2F -/+ w Nn; tangent = sat(round_half_up(num * round(2^G/3), 2F + G)).
  localparam logic signed [G-1:0] KThird = KThirdU[G-1:0];
  localparam logic [KProdW-1:0] KHalf = KProdW'(1) << (KShift - 1);
  logic [2:0]    tangent_sat;
  (* mem2reg *) logic [NumW-1:0] num_next [3];
  for (genvar c = 0; c < 3; c++) begin : g_tan
    logic signed [W+1:0]   chord_a, chord_b, chord;
    logic signed [NumW-1:0] chord_sh, wn;
    logic signed [KProdW-1:0] kprod;
    logic [KProdW-1:0]        krnd;
    logic                     unused_krnd;
    assign unused_krnd = ^krnd[KShift-1:0];
    assign chord_a  = $signed({pa[c][W-1], pa[c], 1'b0}) + $signed({{2{pb[c][W-1]}}, pb[c]});
    assign chord_b  = $signed({pb[c][W-1], pb[c], 1'b0}) + $signed({{2{pa[c][W-1]}}, pa[c]});
    assign chord    = use_mul_a ? chord_a : chord_b;
    assign chord_sh = NumW'(chord) <<< (2 * F);
    assign wn       = prd[c][NumW-1:0];
    assign num_next[c] = use_mul_a ? chord_sh - wn : chord_sh + wn;
    assign kprod    = $signed(num_q[c]) * KThird;
    if (PR) begin : g_kprod_reg
      // With registered products the constant multiplication has a cycle of its own too.
      logic signed [KProdW-1:0] kprod_q;
      always_ff @(posedge clk_i) begin
        kprod_q <= kprod;
      end
      assign krnd = kprod_q + KHalf;
    end else begin : g_kprod_now
      assign krnd = kprod + KHalf;
    end
    tess_sat #(.InW(KProdW - KShift), .OutW(W)) u_sat (
      .x_i  (krnd[KProdW-1:KShift]),
      .y_o  (tangent_o[c*W +: W]),
      .sat_o(tangent_sat[c])
    );
  end
  assign tangent_a_o = st_tan_a && keep_a_i;
  assign tangent_b_o = st_tan_b && keep_b_i;

  // ------------------------------------------------------------------ b111
  // b111 = sat(round_half_up((3 sum(t) - 2 sum(P)) * round(2^G/12), G))
  localparam logic [ProdW-1:0] BHalf = ProdW'(1) << (G - 1);
  logic [2:0]     b111_sat;
  for (genvar c = 0; c < 3; c++) begin : g_b111
    logic [ProdW-1:0]        brnd;
    logic                    unused_brnd;
    assign unused_brnd = ^brnd[G-1:0];
    assign brnd    = prd[c] + BHalf;
    tess_sat #(.InW(ProdW - G), .OutW(W)) u_sat (
      .x_i  (brnd[ProdW-1:G]),
      .y_o  (b111_o[c*W +: W]),
      .sat_o(b111_sat[c])
    );
  end
  assign b111_valid_o = use_b111;

  // ------------------------------------------------------------------ dividers, square root
  (* mem2reg *) logic [W-1:0]    div_res [3];
  logic [2:0]      div_sat, div_dbz;
  logic [W-1:0]    root;
  logic [DenW-1:0] div_den;
  logic            div_load, div_step, div_first;
  assign div_den   = st_div2 ? DenW'(root) : q_q;
  assign div_load  = st_load1 || st_load2;
  assign div_step  = st_div1 || st_div2;
  assign div_first = st_div1_first || st_div2_first;

  for (genvar c = 0; c < 3; c++) begin : g_div
    logic [MagW-1:0] mag;
    logic            neg;
    logic [W-1:0]    m_abs;
    assign m_abs = m_q[c][W-1] ? -m_q[c] : m_q[c];
    always_comb begin
      if (st_load1) begin
        mag = prd[c][MagW-1:0];                // |d_c| |d.s|
        neg = pneg_q ^ d_q[c][W];
      end else begin
        mag = MagW'(m_abs) << F;               // |m_c| 2^F
        neg = m_q[c][W-1];
      end
    end
    tess_div #(.DenW(DenW), .QuotW(W), .DigitBits(DigitBits)) u_div (
      .clk_i  (clk_i),
      .load_i (div_load),
      .mag_i  (mag),
      .neg_i  (neg),
      .step_i (div_step),
      .first_i(div_first),
      .den_i  (div_den),
      .res_o  (div_res[c]),
      .sat_o  (div_sat[c]),
      .dbz_o  (div_dbz[c])
    );
  end

  tess_isqrt #(.RootW(W), .DigitBits(DigitBits)) u_isqrt (
    .clk_i (clk_i),
    .load_i(st_load2),
    .x_i   (dot[2*W-1:0]),
    .step_i(st_sqrt),
    .root_o(root)
  );

  // m = sat(s - k t), k = 2 (quadratic) or 4 (reflect)
  logic [3*W-1:0] m_next;
  logic [2:0]     m_sat;
  for (genvar c = 0; c < 3; c++) begin : g_m
    logic signed [W+3:0] s_ext, kt, diff;
    assign s_ext = (W + 4)'($signed(s_q[c]));
    assign kt    = (W + 4)'($signed(t_q[c])) <<< (mode_reflect_i ? 2 : 1);
    assign diff  = s_ext - kt;
    tess_sat #(.InW(W + 4), .OutW(W)) u_sat (
      .x_i  (diff),
      .y_o  (m_next[c*W +: W]),
      .sat_o(m_sat[c])
    );
  end

  // ------------------------------------------------------------------ silhouette blend
  // w_alpha = round_half_up(alpha_src alpha / 2^A): alpha 2^A gives w itself, 0 gives 0.
  logic [DotW-1:0] alpha_src, w_alpha;
  if (Al) begin : g_alpha
    localparam int unsigned APW = DotW + AlphaW + 1;
    localparam logic [APW-1:0] AHalf = APW'(1) << (AlphaBits - 1);
    logic signed [APW-1:0] a_prod;
    logic [APW-1:0]        a_rnd;
    logic                  unused_a_rnd;
    assign a_prod  = APW'($signed(alpha_src)) * $signed({{(APW - AlphaW){1'b0}}, alpha_i});
    assign a_rnd   = a_prod + AHalf;
    assign w_alpha = a_rnd[AlphaBits +: DotW];
    assign unused_a_rnd = ^{a_rnd[AlphaBits-1:0], a_rnd[APW-1:AlphaBits+DotW]};
  end else begin : g_no_alpha
    logic unused_alpha;
    assign unused_alpha = ^alpha_i;
    assign w_alpha = alpha_src;
  end

  // ------------------------------------------------------------------ multiplier operands
  // The operands. Without registered products they are selected in the step that issues the
  // product (d.Na in step 0 straight from Pb - Pa, its select nearest the multiplier). With
  // registered products they are registered too, selected at the end of the step before from
  // the values the sources take then (every product is issued in step 1 or later; the step
  // after an edge's last is another edge's step 0 or b111's first), so that the multiplier
  // has a cycle to itself.
  if (PR) begin : g_ops_reg
    logic more;  // the next cycle is step step_i + 1 of this edge
    logic nx_dot_a, nx_mul_a, nx_dot_b, nx_mul_b, nx_dot_s, nx_dot_d, nx_num, nx_mm, nx_b111;
    logic nx_dq_a;
    logic [DotW-1:0] pdot_abs;
    assign more     = edge_i && !last_i;
    assign nx_dot_a = more && (step_i == StepW'(SDotA - 1));
    assign nx_mul_a = more && (step_i == StepW'(SMulA - 1));
    assign nx_dot_b = more && (step_i == StepW'(SDotB - 1));
    assign nx_mul_b = more && (step_i == StepW'(SMulB - 1));
    assign nx_dot_s = more && (step_i == StepW'(SDotS - 1));
    assign nx_dot_d = more && (step_i == StepW'(SDotD - 1));
    assign nx_num   = more && (step_i == StepW'(SNum - 1));
    assign nx_mm    = more && (step_i == StepW'(SMM - 1));
    assign nx_b111  = b111_next_i;
    assign nx_dq_a  = nx_dot_b || nx_dot_s || nx_dot_d;
    assign pdot_abs = pdot_q[DotW-1] ? -pdot_q : pdot_q;  // what step SAbs writes
    // wa, wb as the w products take them: as they are summed, or held and scaled by alpha.
    logic [DotW-1:0] w_op;
    if (Al) begin : g_w_alpha
      logic [DotW-1:0] wa_q, wb_q;  // d.Na, d.Nb
      always_ff @(posedge clk_i) begin
        if (use_dot_a) wa_q <= dot;
        if (use_dot_b) wb_q <= dot;
      end
      assign alpha_src = nx_mul_a ? wa_q : wb_q;
      assign w_op      = w_alpha;
    end else begin : g_w_dot
      assign alpha_src = dot;
      assign w_op      = dot;
    end
    for (genvar c = 0; c < 3; c++) begin : g_c
      logic [DotW-1:0]  opa_q;
      logic [MulBW-1:0] opb_q;
      always_ff @(posedge clk_i) begin
        opa_q <= ({DotW{nx_dot_a}}            & DotW'(d_now[c]))
               | ({DotW{nx_dq_a}}             & DotW'($signed(d_q[c])))
               | ({DotW{nx_mul_a || nx_mul_b}} & w_op)  // wa = d.Na, wb = d.Nb
               | ({DotW{nx_num}}              & pdot_abs)
               | ({DotW{nx_mm}}               & DotW'($signed(m_next[c*W +: W])))
               | ({DotW{nx_b111}}             & DotW'($signed(x111_next_i[c*X111W +: X111W])));
        opb_q <= ({MulBW{nx_dot_a || nx_mul_a}} & MulBW'($signed(na[c])))
               | ({MulBW{nx_dot_b || nx_mul_b}} & MulBW'($signed(nb[c])))
               | ({MulBW{nx_dot_s}}             & MulBW'($signed(s_q[c])))
               | ({MulBW{nx_dot_d}}             & MulBW'($signed(d_q[c])))
               | ({MulBW{nx_num}}               & MulBW'(d_abs[c]))  // |d_c|
               | ({MulBW{nx_mm}}                & MulBW'($signed(m_next[c*W +: W])))
               | ({MulBW{nx_b111}}              & KTwelfth);
      end
      assign mul_a[c] = opa_q;
      assign mul_b[c] = opb_q;
    end
    logic unused_ops;
    assign unused_ops = (^x111_i) ^ use_dot_a ^ use_dot_b;
  end else begin : g_ops_now
    logic iss_dot_a, iss_mul_a, iss_dot_b, iss_mul_b, iss_dot_s, iss_dot_d, iss_num, iss_mm;
    logic iss_b111, dq_op_a, st_alpha_a, st_alpha_b;
    logic [DotW-1:0] wa_q, wb_q;  // d.Na, d.Nb (then scaled by alpha in the step after)
    assign st_alpha_a = Al && edge_i && (step_i == StepW'(SDotA + 1));
    assign st_alpha_b = Al && edge_i && (step_i == StepW'(SDotB + 1));
    assign alpha_src  = st_alpha_a ? wa_q : wb_q;
    always_ff @(posedge clk_i) begin
      if (use_dot_a) wa_q <= dot;
      else if (st_alpha_a) wa_q <= w_alpha;
      if (use_dot_b) wb_q <= dot;
      else if (st_alpha_b) wb_q <= w_alpha;
    end
    assign iss_dot_a = edge_i && (step_i == StepW'(SDotA));
    assign iss_mul_a = edge_i && (step_i == StepW'(SMulA));
    assign iss_dot_b = edge_i && (step_i == StepW'(SDotB));
    assign iss_mul_b = edge_i && (step_i == StepW'(SMulB));
    assign iss_dot_s = edge_i && (step_i == StepW'(SDotS));
    assign iss_dot_d = edge_i && (step_i == StepW'(SDotD));
    assign iss_num   = edge_i && (step_i == StepW'(SNum));
    assign iss_mm    = edge_i && (step_i == StepW'(SMM));
    assign iss_b111  = b111_i && (step_i == StepW'(0));
    assign dq_op_a   = iss_dot_b || iss_dot_s || iss_dot_d;
    for (genvar c = 0; c < 3; c++) begin : g_c
      logic [DotW-1:0] reg_op_a;  // the operands held in registers
      assign reg_op_a = ({DotW{dq_op_a}}   & DotW'($signed(d_q[c])))
                      | ({DotW{iss_mul_a}} & wa_q)
                      | ({DotW{iss_mul_b}} & wb_q)
                      | ({DotW{iss_num}}   & pdot_q)            // |d.s|
                      | ({DotW{iss_mm}}    & DotW'($signed(m_q[c])))
                      | ({DotW{iss_b111}}  & DotW'($signed(x111_i[c*X111W +: X111W])));
      assign mul_a[c] = iss_dot_a ? DotW'(d_now[c]) : reg_op_a;
      assign mul_b[c] = ({MulBW{iss_dot_a || iss_mul_a}} & MulBW'($signed(na[c])))
                      | ({MulBW{iss_dot_b || iss_mul_b}} & MulBW'($signed(nb[c])))
                      | ({MulBW{iss_dot_s}}              & MulBW'($signed(s_q[c])))
                      | ({MulBW{iss_dot_d}}              & MulBW'($signed(d_q[c])))
                      | ({MulBW{iss_num}}                & MulBW'(d_abs[c]))  // |d_c|
                      | ({MulBW{iss_mm}}                 & MulBW'($signed(m_q[c])))
                      | ({MulBW{iss_b111}}               & KTwelfth);
    end
    logic unused_ops;
    assign unused_ops = last_i ^ b111_next_i ^ (^x111_next_i);
  end

  // ------------------------------------------------------------------ datapath registers
  always_ff @(posedge clk_i) begin
    if (st_edge0) begin
      for (int c = 0; c < 3; c++) begin
        d_q[c] <= d_now[c];
        s_q[c] <= s_now[c];
      end
    end
    if (use_dot_s) pdot_q <= dot;
    if (st_abs) begin
      q_q    <= dot[DenW-1:0];
      pdot_q <= pdot_q[DotW-1] ? -pdot_q : pdot_q;
      pneg_q <= pdot_q[DotW-1];
    end
    for (int c = 0; c < 3; c++) begin
      if (use_mul_a || use_mul_b) num_q[c] <= num_next[c];
      if (st_div1_last) t_q[c] <= div_res[c];
      if (st_m) m_q[c] <= m_next[c*W +: W];
    end
  end

  // ------------------------------------------------------------------ results
  logic [3*W-1:0] div_vec;
  for (genvar c = 0; c < 3; c++) begin : g_vec
    assign div_vec[c*W +: W] = div_res[c];
  end
  // Reflect: the mid-edge normal is m; quadratic: m normalized by the second division.
  assign mid_valid_o = (st_m && mode_reflect_i) || st_div2_last;
  assign mid_o       = st_div2_last ? div_vec : m_next;

  // Flags of this cycle's results (tess_cpg keeps them sticky per triangle).
  always_comb begin
    flags_o = '0;
    if ((tangent_a_o || tangent_b_o) && (tangent_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
    if ((st_div1_last || st_div2_last) && (div_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
    if ((st_div1_last || st_div2_last) && (div_dbz != '0)) flags_o |= tess_pkg::FlagDivByZero;
    if (st_m && (m_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
    if (use_b111 && (b111_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
  end

  // The coordinate formats and digit widths sim::UnitConfig accepts (tess_unit checks them too;
  // a lane instantiated on its own is held to them as well).
  `TESS_ASSERT_PARAM(CoordWidthRange_A, CoordIntBits >= 1 && CoordFracBits >= 8 && 1 + CoordIntBits + CoordFracBits <= 32)
  `TESS_ASSERT_PARAM(DigitBitsRange_A, DigitBits >= 1 && DigitBits <= 1 + CoordIntBits + CoordFracBits)
  `TESS_ASSERT_PARAM(ProductRegRange_A, ProductReg <= 1)
  `TESS_ASSERT_PARAM(AlphaBitsRange_A, AlphaBits <= 16)

endmodule
