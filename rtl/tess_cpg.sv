// CPG: the dedicated, sequential control-point generator (docs/microarchitecture.md §5).
//
// Control: accept (pop the TRI FIFO into the latch, counter <- C - 1), C - 1 compute cycles,
// then write the control points into buffer[wr_ptr] when it is EMPTY (else blocked).
//
// Datapath: three lanes (x, y, z), each with one general multiplier (DotW x MulBW bits), one
// constant multiplier by round(2^G/3) (G = F + 8), a restoring divider and, shared, one square root.
// The lanes walk the edges P1->P2, P2->P3, P3->P1, E cycles each, then one cycle for b111.
// Micro-steps of an edge a->b (step index s; one general multiplication per lane per step):
//   s0        d = Pb - Pa, s = Na + Nb;        wa = d.Na  (lanes multiply, adder tree sums)
//   s1        num = (2Pa + Pb) 2^2F - wa Na    (per lane)
//   s2        wb = d.Nb;                       tangent near a = round(num / 3)
//   s3        num = (2Pb + Pa) 2^2F + wb Nb
//   s4        p = d.s;                         tangent near b = round(num / 3)
//   s5        q = d.d;                         p <- |p|
//   --- linear: E = 6 ends here ---
//   s6        load dividers with |d_c| |p| (sign of d_c p)
//   s7 ..     W division steps (divisor q), the last one yields t_c
//   s7+W      m = sat(s - k t)                 (reflect: mid-edge normal = m; E = W + 8 ends)
//   s8+W      m.m into the square root; load dividers with |m_c| 2^F (sign of m_c)
//   s9+W ..   W square-root steps: |m| = isqrt(m.m)
//   s9+2W ..  W division steps (divisor |m|), the last one yields the mid-edge normal
//   --- quadratic: E = 3W + 9 ends here ---
// Every value is exact until the one rounding the C++ reference (sim/cpg.cpp) applies, so
// the results are bit-identical to compute_control_points.
module tess_cpg #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  localparam int unsigned W      = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned TriW   = 18 * W + tess_pkg::FactorBits + tess_pkg::IdBits
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic [tess_pkg::ModeBits-1:0]     mode_i,
  // TRI FIFO head: {id, L, N (9W), P (9W)}
  input  logic                              tri_avail_i,
  input  logic [TriW-1:0]                   tri_i,
  output logic                              tri_pop_o,
  // Control-point buffer write port (buffer[wr_ptr])
  input  logic                              buf_empty_i,
  output logic                              buf_wr_o,
  output logic [30*W-1:0]                   buf_b_o,      // b[0..9], 3 components each
  output logic [18*W-1:0]                   buf_n_o,      // n[0..5]
  output logic [tess_pkg::FactorBits-1:0]   buf_l_o,
  output logic [tess_pkg::IdBits-1:0]       buf_id_o,
  output logic [tess_pkg::FlagBits-1:0]     buf_flags_o,
  // Status for the counters
  output logic                              busy_o,       // accepting, computing or writing
  output logic                              blocked_o,    // done, buffer[wr_ptr] not EMPTY
  output logic                              active_o      // the busy register (§10 TE classes)
);

  localparam int unsigned F       = CoordFracBits;
  localparam int unsigned G       = CoordFracBits + tess_pkg::ConstGuardBits;
  localparam int unsigned LBits   = tess_pkg::FactorBits;
  localparam int unsigned IdBits  = tess_pkg::IdBits;
  // Exact intermediate widths (two's complement, all values provably fit):
  localparam int unsigned DotW    = 2 * W + 3;                 // d.s, d.Na, d.Nb, d.d, m.m
  localparam int unsigned MulBW   = (W + 1 > G - 2) ? W + 1 : G - 2;  // round(2^G/12) < 2^(G-3)
  localparam int unsigned ProdW   = DotW + MulBW;              // general lane product
  localparam int unsigned ChordW  = W + 2 + 2 * F;             // (2Pn + Pf) 2^2F
  localparam int unsigned NumW    = ((ChordW > 3 * W + 1) ? ChordW : 3 * W + 1) + 1;
  localparam int unsigned KProdW  = NumW + G;                  // num * round(2^G/3) < 2^(G-1)
  localparam int unsigned KShift  = 2 * F + G;                 // 3F fraction bits -> F
  localparam int unsigned SumTW   = W + 3;                     // sum of six tangent points
  localparam int unsigned X111W   = W + 5;                     // 3 sum(t) - 2 sum(P)
  localparam int unsigned DenW    = 2 * W + 2;                 // d.d < 3 * 2^2W
  localparam int unsigned MagW    = DenW + 1 + W;              // divider dividend magnitude
  localparam int unsigned EdgeLin = 6;
  localparam int unsigned EdgeRef = W + 8;
  localparam int unsigned EdgeQuad = 3 * W + 9;
  localparam int unsigned CyclesMax = 3 * EdgeQuad + 2;
  localparam int unsigned CntW    = $clog2(CyclesMax);
  localparam int unsigned StepW   = $clog2(EdgeQuad);
  // Micro-step indices within an edge.
  localparam int unsigned SDiv1   = 7;
  localparam int unsigned SM      = 7 + W;
  localparam int unsigned SMM     = 8 + W;
  localparam int unsigned SSqrt   = 9 + W;
  localparam int unsigned SDiv2   = 9 + 2 * W;

  // ------------------------------------------------------------------ mode and control
  logic mode_linear, mode_reflect;
  assign mode_linear  = (mode_i == tess_pkg::ModeLinear);
  assign mode_reflect = (mode_i == tess_pkg::ModeReflect);

  logic [CntW-1:0]  cycles_m1;   // C - 1
  logic [StepW-1:0] edge_last;   // E - 1
  always_comb begin
    if (mode_linear) begin
      cycles_m1 = CntW'(3 * EdgeLin + 1);
      edge_last = StepW'(EdgeLin - 1);
    end else if (mode_reflect) begin
      cycles_m1 = CntW'(3 * EdgeRef + 1);
      edge_last = StepW'(EdgeRef - 1);
    end else begin
      cycles_m1 = CntW'(3 * EdgeQuad + 1);
      edge_last = StepW'(EdgeQuad - 1);
    end
  end

  logic             busy_q;
  logic [CntW-1:0]  counter_q;
  logic [1:0]       edge_q;      // 0..2 edges, 3 = b111
  logic [StepW-1:0] step_q;
  logic             accept, compute, write;

  assign accept  = !busy_q && tri_avail_i;
  assign compute = busy_q && (counter_q != '0);
  assign write   = busy_q && (counter_q == '0) && buf_empty_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q    <= 1'b0;
      counter_q <= '0;
      edge_q    <= '0;
      step_q    <= '0;
    end else if (accept) begin
      busy_q    <= 1'b1;
      counter_q <= cycles_m1;
      edge_q    <= '0;
      step_q    <= '0;
    end else if (compute) begin
      counter_q <= counter_q - CntW'(1);
      if (step_q == edge_last) begin
        step_q <= '0;
        edge_q <= edge_q + 2'd1;
      end else begin
        step_q <= step_q + StepW'(1);
      end
    end else if (write) begin
      busy_q <= 1'b0;
    end
  end

  assign tri_pop_o = accept;
  assign busy_o    = accept || compute || write;
  assign blocked_o = busy_q && (counter_q == '0) && !buf_empty_i;
  assign active_o  = busy_q;

  // ------------------------------------------------------------------ the latched triangle
  (* mem2reg *) logic [W-1:0]     p_q [3][3];  // [vertex][component]
  (* mem2reg *) logic [W-1:0]     n_q [3][3];
  logic [LBits-1:0] l_q;
  logic [IdBits-1:0] id_q;

  always_ff @(posedge clk_i) begin
    if (accept) begin
      for (int v = 0; v < 3; v++) begin
        for (int c = 0; c < 3; c++) begin
          p_q[v][c] <= tri_i[(3 * v + c) * W +: W];
          n_q[v][c] <= tri_i[9 * W + (3 * v + c) * W +: W];
        end
      end
      l_q  <= tri_i[18 * W +: LBits];
      id_q <= tri_i[18 * W + LBits +: IdBits];
    end
  end

  // ------------------------------------------------------------------ step decode
  logic in_edge, in_b111;
  logic st_dot_a, st_mul_a, st_dot_b, st_mul_b, st_dot_s, st_dot_d, st_num;
  logic st_div1, st_div1_first, st_div1_last, st_m, st_mm, st_sqrt;
  logic st_div2, st_div2_first, st_div2_last;

  assign in_edge       = compute && (edge_q != 2'd3);
  assign in_b111       = compute && (edge_q == 2'd3);
  assign st_dot_a      = in_edge && (step_q == StepW'(0));
  assign st_mul_a      = in_edge && (step_q == StepW'(1));
  assign st_dot_b      = in_edge && (step_q == StepW'(2));
  assign st_mul_b      = in_edge && (step_q == StepW'(3));
  assign st_dot_s      = in_edge && (step_q == StepW'(4));
  assign st_dot_d      = in_edge && (step_q == StepW'(5));
  assign st_num        = in_edge && (step_q == StepW'(6));
  assign st_div1       = in_edge && (step_q >= StepW'(SDiv1)) && (step_q < StepW'(SDiv1 + W));
  assign st_div1_first = in_edge && (step_q == StepW'(SDiv1));
  assign st_div1_last  = in_edge && (step_q == StepW'(SDiv1 + W - 1));
  assign st_m          = in_edge && (step_q == StepW'(SM));
  assign st_mm         = in_edge && (step_q == StepW'(SMM));
  assign st_sqrt       = in_edge && (step_q >= StepW'(SSqrt)) && (step_q < StepW'(SSqrt + W));
  assign st_div2       = in_edge && (step_q >= StepW'(SDiv2)) && (step_q < StepW'(SDiv2 + W));
  assign st_div2_first = in_edge && (step_q == StepW'(SDiv2));
  assign st_div2_last  = in_edge && (step_q == StepW'(SDiv2 + W - 1));

  // ------------------------------------------------------------------ the current edge a->b
  (* mem2reg *) logic [W-1:0] pa [3], pb [3], na [3], nb [3];
  always_comb begin
    for (int c = 0; c < 3; c++) begin
      case (edge_q)
        2'd0:    begin pa[c] = p_q[0][c]; pb[c] = p_q[1][c]; na[c] = n_q[0][c]; nb[c] = n_q[1][c]; end
        2'd1:    begin pa[c] = p_q[1][c]; pb[c] = p_q[2][c]; na[c] = n_q[1][c]; nb[c] = n_q[2][c]; end
        default: begin pa[c] = p_q[2][c]; pb[c] = p_q[0][c]; na[c] = n_q[2][c]; nb[c] = n_q[0][c]; end
      endcase
    end
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
  (* mem2reg *) logic [SumTW-1:0]  sum_t_q [3];

  // Combinational edge vector of s0 (d is registered at the end of s0).
  (* mem2reg *) logic signed [W:0] d_now [3], s_now [3];
  for (genvar c = 0; c < 3; c++) begin : g_edge
    assign d_now[c] = $signed({pb[c][W-1], pb[c]}) - $signed({pa[c][W-1], pa[c]});
    assign s_now[c] = $signed({na[c][W-1], na[c]}) + $signed({nb[c][W-1], nb[c]});
  end

  // ------------------------------------------------------------------ general lane multipliers
  (* mem2reg *) logic signed [DotW-1:0]  mul_a [3];
  (* mem2reg *) logic signed [MulBW-1:0] mul_b [3];
  (* mem2reg *) logic signed [ProdW-1:0] prod [3];
  (* mem2reg *) logic signed [X111W-1:0] x111 [3];

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
      end else if (in_b111) begin
        mul_a[c] = DotW'(x111[c]);
        mul_b[c] = KTwelfth;
      end
    end
    assign prod[c] = mul_a[c] * mul_b[c];
  end

  // Sum over the lanes: the dot products (exact, DotW bits suffice).
  logic [DotW-1:0] dot;
  assign dot = prod[0][DotW-1:0] + prod[1][DotW-1:0] + prod[2][DotW-1:0];

  // ------------------------------------------------------------------ tangent points
  // num = (2Pn + Pf) 2^2F -/+ w Nn; tangent = sat(round_half_up(num * round(2^G/3), 2F + G)).
  localparam logic signed [G-1:0] KThird = KThirdU[G-1:0];
  localparam logic [KProdW-1:0] KHalf = KProdW'(1) << (KShift - 1);
  (* mem2reg *) logic [W-1:0]  tangent [3];
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
      .y_o  (tangent[c]),
      .sat_o(tangent_sat[c])
    );
  end

  // ------------------------------------------------------------------ b111
  // b111 = sat(round_half_up((3 sum(t) - 2 sum(P)) * round(2^G/12), G))
  localparam logic [ProdW-1:0] BHalf = ProdW'(1) << (G - 1);
  logic [3*W-1:0] b111;
  logic [2:0]     b111_sat;
  for (genvar c = 0; c < 3; c++) begin : g_b111
    logic signed [X111W-1:0] st3, corners;
    logic [ProdW-1:0]        brnd;
    logic                    unused_brnd;
    assign unused_brnd = ^brnd[G-1:0];
    assign st3     = X111W'($signed(sum_t_q[c])) * $signed(X111W'(3));
    assign corners = X111W'($signed(p_q[0][c])) + X111W'($signed(p_q[1][c]))
                   + X111W'($signed(p_q[2][c]));
    assign x111[c] = st3 - (corners <<< 1);
    assign brnd    = prod[c] + BHalf;
    tess_sat #(.InW(ProdW - G), .OutW(W)) u_sat (
      .x_i  (brnd[ProdW-1:G]),
      .y_o  (b111[c*W +: W]),
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
    tess_div #(.DenW(DenW), .QuotW(W)) u_div (
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

  tess_isqrt #(.RootW(W)) u_isqrt (
    .clk_i (clk_i),
    .load_i(st_mm),
    .x_i   (dot[2*W-1:0]),
    .step_i(st_sqrt),
    .root_o(root)
  );

  // m = sat(s - k t), k = 2 (quadratic) or 4 (reflect)
  (* mem2reg *) logic [W-1:0] m_next [3];
  logic [2:0]   m_sat;
  for (genvar c = 0; c < 3; c++) begin : g_m
    logic signed [W+3:0] s_ext, kt, diff;
    assign s_ext = (W + 4)'($signed(s_q[c]));
    assign kt    = (W + 4)'($signed(t_q[c])) <<< (mode_reflect ? 2 : 1);
    assign diff  = s_ext - kt;
    tess_sat #(.InW(W + 4), .OutW(W)) u_sat (
      .x_i  (diff),
      .y_o  (m_next[c]),
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
      if (st_m) m_q[c] <= m_next[c];
    end
  end

  // Running sum of the tangent points (for b111), reset at accept.
  logic tangent_step;
  assign tangent_step = st_dot_b || st_dot_s;
  always_ff @(posedge clk_i) begin
    for (int c = 0; c < 3; c++) begin
      if (accept) sum_t_q[c] <= '0;
      else if (tangent_step) sum_t_q[c] <= sum_t_q[c] + SumTW'($signed(tangent[c]));
    end
  end

  // ------------------------------------------------------------------ staging of results
  // Tangent points in edge order (near a, near b), the mid-edge normals and b111, held until
  // the write (the target buffer may still be in use while the CPG computes).
  (* mem2reg *) logic [3*W-1:0] stage_tan_q [6];
  (* mem2reg *) logic [3*W-1:0] stage_mid_q [3];
  logic [3*W-1:0] stage_b111_q;
  logic [3*W-1:0] tangent_vec, m_vec, div_vec;
  for (genvar c = 0; c < 3; c++) begin : g_vec
    assign tangent_vec[c*W +: W] = tangent[c];
    assign m_vec[c*W +: W]       = m_next[c];
    assign div_vec[c*W +: W]     = div_res[c];
  end

  always_ff @(posedge clk_i) begin
    if (st_dot_b) stage_tan_q[{edge_q, 1'b0}] <= tangent_vec;
    if (st_dot_s) stage_tan_q[{edge_q, 1'b1}] <= tangent_vec;
    if (st_m && mode_reflect) stage_mid_q[edge_q] <= m_vec;
    if (st_div2_last) stage_mid_q[edge_q] <= div_vec;
    if (in_b111) stage_b111_q <= b111;
  end

  // ------------------------------------------------------------------ sticky flags
  logic [tess_pkg::FlagBits-1:0] flags_q, flags_step;
  always_comb begin
    flags_step = '0;
    if (tangent_step && (tangent_sat != '0)) flags_step |= tess_pkg::FlagSaturated;
    if ((st_div1_last || st_div2_last) && (div_sat != '0)) flags_step |= tess_pkg::FlagSaturated;
    if ((st_div1_last || st_div2_last) && (div_dbz != '0)) flags_step |= tess_pkg::FlagDivByZero;
    if (st_m && (m_sat != '0)) flags_step |= tess_pkg::FlagSaturated;
    if (in_b111 && (b111_sat != '0)) flags_step |= tess_pkg::FlagSaturated;
  end
  always_ff @(posedge clk_i) begin
    if (accept) flags_q <= '0;
    else flags_q <= flags_q | flags_step;
  end

  // ------------------------------------------------------------------ the write
  // Corners come straight from the latch; normal corners are 2 Ni (saturated) except linear.
  (* mem2reg *) logic [3*W-1:0] corner_n [3];
  logic [8:0]     corner_sat;
  for (genvar v = 0; v < 3; v++) begin : g_corner
    for (genvar c = 0; c < 3; c++) begin : g_comp
      logic [W-1:0] twice;
      tess_sat #(.InW(W + 1), .OutW(W)) u_sat (
        .x_i  ({n_q[v][c], 1'b0}),
        .y_o  (twice),
        .sat_o(corner_sat[3 * v + c])
      );
      assign corner_n[v][c*W +: W] = mode_linear ? n_q[v][c] : twice;
    end
  end

  (* mem2reg *) logic [3*W-1:0] corner_p [3];
  for (genvar v = 0; v < 3; v++) begin : g_corner_p
    assign corner_p[v] = {p_q[v][2], p_q[v][1], p_q[v][0]};
  end

  // Geometry net: b300 b210 b120 b030 | b201 b111 b021 | b102 b012 | b003
  assign buf_b_o = {corner_p[2],       // 9: b003 = P3
                    stage_tan_q[3],    // 8: b012, edge P2->P3 near P3
                    stage_tan_q[4],    // 7: b102, edge P3->P1 near P3
                    stage_tan_q[2],    // 6: b021, edge P2->P3 near P2
                    stage_b111_q,      // 5: b111
                    stage_tan_q[5],    // 4: b201, edge P3->P1 near P1
                    corner_p[1],       // 3: b030 = P2
                    stage_tan_q[1],    // 2: b120, edge P1->P2 near P2
                    stage_tan_q[0],    // 1: b210, edge P1->P2 near P1
                    corner_p[0]};      // 0: b300 = P1
  // Normal net: n200 n110 n020 | n101 n011 | n002 (mid-edges zero in linear mode)
  (* mem2reg *) logic [3*W-1:0] mid [3];
  for (genvar e = 0; e < 3; e++) begin : g_mid
    assign mid[e] = mode_linear ? '0 : stage_mid_q[e];
  end
  assign buf_n_o = {corner_n[2],       // 5: n002
                    mid[1],            // 4: n011 (edge P2->P3)
                    mid[2],            // 3: n101 (edge P3->P1)
                    corner_n[1],       // 2: n020
                    mid[0],            // 1: n110 (edge P1->P2)
                    corner_n[0]};      // 0: n200
  assign buf_l_o     = l_q;
  assign buf_id_o    = id_q;
  assign buf_flags_o = flags_q | ((!mode_linear && (corner_sat != '0)) ? tess_pkg::FlagSaturated
                                                                       : '0);
  assign buf_wr_o    = write;

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      assert (mode_i == tess_pkg::ModeQuadratic || mode_i == tess_pkg::ModeReflect || mode_linear)
        else $error("tess_cpg: mode %0d is not defined", mode_i);
    end
  end
`endif

endmodule
