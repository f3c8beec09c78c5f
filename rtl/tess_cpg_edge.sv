// One edge lane of the CPG (docs/microarchitecture.md §5): the datapath that computes the two
// tangent points and the mid-edge normal of an edge a->b in E micro-steps, driven by the step
// index of tess_cpg. The sequential CPG (CpgLanes = 1) walks the three edges through one lane;
// the parallel CPG (CpgLanes = 3) has a lane per edge. Lane 0 also computes b111.
//
// Three component slices (x, y, z), each with one general multiplier (DotW x MulBW bits), one
// constant multiplier by round(2^G/3) (G = F + 8), a restoring divider retiring DigitBits
// quotient bits a cycle and, shared, one square root retiring DigitBits root bits a cycle.
// With D = ceil(W / DigitBits) digit steps, the micro-steps s are:
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
// Every value is exact until the one rounding the C++ reference (sim/cpg.cpp) applies, so the
// results are bit-identical to compute_control_points whatever DigitBits is.
module tess_cpg_edge #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned DigitBits     = tess_pkg::CpgDigitBits,
  localparam int unsigned W      = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned D      = (W + DigitBits - 1) / DigitBits,
  localparam int unsigned StepW  = $clog2(3 * D + 9),
  localparam int unsigned X111W  = W + 5                       // 3 sum(t) - 2 sum(P)
) (
  input  logic                          clk_i,
  input  logic                          mode_reflect_i,
  input  logic                          edge_i,       // computing step step_i of an edge
  input  logic [StepW-1:0]              step_i,
  input  logic                          keep_a_i,     // the tangent point near a is this lane's
  input  logic                          keep_b_i,     // (else the tag pass computes it)
  input  logic [3*W-1:0]                pa_i,         // component c at [cW +: W]
  input  logic [3*W-1:0]                pb_i,
  input  logic [3*W-1:0]                na_i,
  input  logic [3*W-1:0]                nb_i,
  input  logic                          b111_i,       // the b111 cycle (lane 0 only)
  input  logic [3*X111W-1:0]            x111_i,       // 3 sum(t) - 2 sum(P), per component
  // Results, each valid in the cycle its strobe is high.
  output logic [3*W-1:0]                tangent_o,
  output logic                          tangent_a_o,  // tangent_o is the point near a
  output logic                          tangent_b_o,  // tangent_o is the point near b
  output logic [3*W-1:0]                mid_o,
  output logic                          mid_valid_o,
  output logic [3*W-1:0]                b111_o,       // valid while b111_i
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
  // Micro-step indices within an edge.
  localparam int unsigned SDiv1   = 7;
  localparam int unsigned SM      = 7 + D;
  localparam int unsigned SMM     = 8 + D;
  localparam int unsigned SSqrt   = 9 + D;
  localparam int unsigned SDiv2   = 9 + 2 * D;

  // ------------------------------------------------------------------ step decode
  logic st_dot_a, st_mul_a, st_dot_b, st_mul_b, st_dot_s, st_dot_d, st_num;
  logic st_div1, st_div1_first, st_div1_last, st_m, st_mm, st_sqrt;
  logic st_div2, st_div2_first, st_div2_last;

  assign st_dot_a      = edge_i && (step_i == StepW'(0));
  assign st_mul_a      = edge_i && (step_i == StepW'(1));
  assign st_dot_b      = edge_i && (step_i == StepW'(2));
  assign st_mul_b      = edge_i && (step_i == StepW'(3));
  assign st_dot_s      = edge_i && (step_i == StepW'(4));
  assign st_dot_d      = edge_i && (step_i == StepW'(5));
  assign st_num        = edge_i && (step_i == StepW'(6));
  assign st_div1       = edge_i && (step_i >= StepW'(SDiv1)) && (step_i < StepW'(SDiv1 + D));
  assign st_div1_first = edge_i && (step_i == StepW'(SDiv1));
  assign st_div1_last  = edge_i && (step_i == StepW'(SDiv1 + D - 1));
  assign st_m          = edge_i && (step_i == StepW'(SM));
  assign st_mm         = edge_i && (step_i == StepW'(SMM));
  assign st_sqrt       = edge_i && (step_i >= StepW'(SSqrt)) && (step_i < StepW'(SSqrt + D));
  assign st_div2       = edge_i && (step_i >= StepW'(SDiv2)) && (step_i < StepW'(SDiv2 + D));
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
  logic [DotW-1:0]   wa_q, wb_q; // d.Na, d.Nb
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

  // ------------------------------------------------------------------ general slice multipliers
  (* mem2reg *) logic signed [DotW-1:0]  mul_a [3];
  (* mem2reg *) logic signed [MulBW-1:0] mul_b [3];
  (* mem2reg *) logic signed [ProdW-1:0] prod [3];

  // round(2^G / 12) = floor((2^G + 6) / 12), round(2^G / 3) = floor((2^G + 1) / 3)
  localparam logic [G:0] PowG = {1'b1, {G{1'b0}}};
  localparam logic [G:0] KTwelfthU = (PowG + (G + 1)'(6)) / (G + 1)'(12);
  localparam logic [G:0] KThirdU   = (PowG + (G + 1)'(1)) / (G + 1)'(3);
  localparam logic signed [MulBW-1:0] KTwelfth = MulBW'(KTwelfthU);

  for (genvar c = 0; c < 3; c++) begin : g_mul
    logic [W:0] d_abs;
    assign d_abs = d_q[c][W] ? -d_q[c] : d_q[c];
    always_comb begin
      mul_a[c] = '0;
      mul_b[c] = '0;
      if (st_dot_a) begin
        mul_a[c] = DotW'(d_now[c]);
        mul_b[c] = MulBW'($signed(na[c]));
      end else if (st_mul_a) begin
        mul_a[c] = $signed(wa_q);
        mul_b[c] = MulBW'($signed(na[c]));
      end else if (st_dot_b) begin
        mul_a[c] = DotW'($signed(d_q[c]));
        mul_b[c] = MulBW'($signed(nb[c]));
      end else if (st_mul_b) begin
        mul_a[c] = $signed(wb_q);
        mul_b[c] = MulBW'($signed(nb[c]));
      end else if (st_dot_s) begin
        mul_a[c] = DotW'($signed(d_q[c]));
        mul_b[c] = MulBW'($signed(s_q[c]));
      end else if (st_dot_d) begin
        mul_a[c] = DotW'($signed(d_q[c]));
        mul_b[c] = MulBW'($signed(d_q[c]));
      end else if (st_num) begin
        mul_a[c] = $signed(pdot_q);                    // |d.s|
        mul_b[c] = $signed(MulBW'(d_abs));             // |d_c|
      end else if (st_mm) begin
        mul_a[c] = DotW'($signed(m_q[c]));
        mul_b[c] = MulBW'($signed(m_q[c]));
      end else if (b111_i) begin
        mul_a[c] = DotW'($signed(x111_i[c*X111W +: X111W]));
        mul_b[c] = KTwelfth;
      end
    end
    assign prod[c] = mul_a[c] * mul_b[c];
  end

  // Sum over the slices: the dot products (exact, DotW bits suffice).
  logic [DotW-1:0] dot;
  assign dot = prod[0][DotW-1:0] + prod[1][DotW-1:0] + prod[2][DotW-1:0];

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
    assign chord    = st_mul_a ? chord_a : chord_b;
    assign chord_sh = NumW'(chord) <<< (2 * F);
    assign wn       = prod[c][NumW-1:0];
    assign num_next[c] = st_mul_a ? chord_sh - wn : chord_sh + wn;
    assign kprod    = $signed(num_q[c]) * KThird;
    assign krnd     = kprod + KHalf;
    tess_sat #(.InW(KProdW - KShift), .OutW(W)) u_sat (
      .x_i  (krnd[KProdW-1:KShift]),
      .y_o  (tangent_o[c*W +: W]),
      .sat_o(tangent_sat[c])
    );
  end
  assign tangent_a_o = st_dot_b && keep_a_i;
  assign tangent_b_o = st_dot_s && keep_b_i;

  // ------------------------------------------------------------------ b111
  // b111 = sat(round_half_up((3 sum(t) - 2 sum(P)) * round(2^G/12), G))
  localparam logic [ProdW-1:0] BHalf = ProdW'(1) << (G - 1);
  logic [2:0]     b111_sat;
  for (genvar c = 0; c < 3; c++) begin : g_b111
    logic [ProdW-1:0]        brnd;
    logic                    unused_brnd;
    assign unused_brnd = ^brnd[G-1:0];
    assign brnd    = prod[c] + BHalf;
    tess_sat #(.InW(ProdW - G), .OutW(W)) u_sat (
      .x_i  (brnd[ProdW-1:G]),
      .y_o  (b111_o[c*W +: W]),
      .sat_o(b111_sat[c])
    );
  end

  // ------------------------------------------------------------------ dividers, square root
  (* mem2reg *) logic [W-1:0]    div_res [3];
  logic [2:0]      div_sat, div_dbz;
  logic [W-1:0]    root;
  logic [DenW-1:0] div_den;
  logic            div_load, div_step, div_first;
  assign div_den   = st_div2 ? DenW'(root) : q_q;
  assign div_load  = st_num || st_mm;
  assign div_step  = st_div1 || st_div2;
  assign div_first = st_div1_first || st_div2_first;

  for (genvar c = 0; c < 3; c++) begin : g_div
    logic [MagW-1:0] mag;
    logic            neg;
    logic [W-1:0]    m_abs;
    assign m_abs = m_q[c][W-1] ? -m_q[c] : m_q[c];
    always_comb begin
      if (st_num) begin
        mag = prod[c][MagW-1:0];               // |d_c| |d.s|
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
    .load_i(st_mm),
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

  // ------------------------------------------------------------------ datapath registers
  always_ff @(posedge clk_i) begin
    if (st_dot_a) begin
      wa_q <= dot;
      for (int c = 0; c < 3; c++) begin
        d_q[c] <= d_now[c];
        s_q[c] <= s_now[c];
      end
    end
    if (st_dot_b) wb_q <= dot;
    if (st_dot_s) pdot_q <= dot;
    if (st_dot_d) begin
      q_q    <= dot[DenW-1:0];
      pdot_q <= pdot_q[DotW-1] ? -pdot_q : pdot_q;
      pneg_q <= pdot_q[DotW-1];
    end
    for (int c = 0; c < 3; c++) begin
      if (st_mul_a || st_mul_b) num_q[c] <= num_next[c];
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
    if (b111_i && (b111_sat != '0)) flags_o |= tess_pkg::FlagSaturated;
  end

endmodule
