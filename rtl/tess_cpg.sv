// CPG: the dedicated control-point generator (docs/microarchitecture.md §5).
//
// Control: accept (pop the TRI FIFO into the latch, counter <- C - 1), C - 1 compute cycles,
// then write the control points into buffer[wr_ptr] when it is EMPTY (else blocked).
//
// Datapath: CpgLanes edge lanes (tess_cpg_edge), each a 3-slice vector unit whose dividers and
// square root retire CpgDigitBits bits a cycle, so an edge takes E = 6 (linear), D + 8 (reflect)
// or 3D + 9 (quadratic) cycles with D = ceil(W / CpgDigitBits). One lane walks the edges
// P1->P2, P2->P3, P3->P1 in turn (C = 3E + 2); three lanes compute the three edges at once
// (C = E + 2). Then one cycle for b111 (on lane 0's multipliers) and the write.
// With CpgTags, the TRI FIFO also carries each corner's scalar tags (Δ, σ, θ, β), and a
// triangle with non-neutral tags first runs a tag pass on tess_cpg_tag (one per lane) for
// T = sim::cpg_tag_cycles cycles: the face normal, each non-neutral corner's normalizations
// (N', Y, X; X alone for a θ-only corner) and each non-neutral corner's two tangent points. The
// edge pass then takes the field normals (N' at tagged corners) and keeps the tag pass's tangent
// points. One lane takes the corners and the tangents in turn; three lanes one each at a time.
// Every value is exact until the one rounding the C++ reference (sim/values/cpg.cpp) applies, so the
// results are bit-identical to compute_control_points for every CpgLanes and CpgDigitBits.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_cpg #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned CpgLanes      = tess_pkg::CpgLanes,
  parameter int unsigned CpgDigitBits  = tess_pkg::CpgDigitBits,
  parameter int unsigned CpgProductReg = tess_pkg::CpgProductReg,
  parameter int unsigned CpgTags       = tess_pkg::CpgTags,
  parameter int unsigned AlphaBits     = tess_pkg::AlphaBits,
  localparam int unsigned W      = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned AlphaW = AlphaBits + 1,
  localparam int unsigned TriW   = tess_pkg::tri_w(W, CpgTags, AlphaBits)
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic [tess_pkg::ModeBits-1:0]     mode_i,
  // TRI FIFO head: {alpha (3 (A + 1), with AlphaBits), tags (18W, with CpgTags), id, pattern
  // descriptor, N (9W), P (9W)}
  input  logic                              tri_avail_i,
  input  logic [TriW-1:0]                   tri_i,
  output logic                              tri_pop_o,
  // Control-point buffer write port (buffer[wr_ptr])
  input  logic                              buf_empty_i,
  output logic                              buf_wr_o,
  output logic [30*W-1:0]                   buf_b_o,      // b[0..9], 3 components each
  output logic [18*W-1:0]                   buf_n_o,      // n[0..5]
  output logic [tess_pkg::DescBits-1:0]     buf_desc_o,   // the FSU sets the patch up from it
  output logic [tess_pkg::IdBits-1:0]       buf_id_o,
  output logic [tess_pkg::FlagBits-1:0]     buf_flags_o,
  // Status for the counters
  output logic                              busy_o,       // accepting, computing or writing
  output logic                              blocked_o,    // done, buffer[wr_ptr] not EMPTY
  output logic                              active_o      // the busy register (§10 TE classes)
);

  localparam int unsigned DescW   = tess_pkg::DescBits;
  localparam int unsigned IdBits  = tess_pkg::IdBits;
  localparam int unsigned SumTW   = W + 3;                     // sum of six tangent points
  localparam int unsigned X111W   = W + 5;                     // 3 sum(t) - 2 sum(P)
  // Edge cycles (sim/values/cpg.cpp cpg_edge_cycles), D digit steps per division or square root;
  // registered products (tess_cpg_edge) add steps to each edge and a cycle to b111.
  localparam int unsigned D        = (W + CpgDigitBits - 1) / CpgDigitBits;
  localparam bit          PR       = (CpgProductReg != 0);
  // The silhouette blend (AlphaBits) adds a step to the linear edge with registered products.
  localparam int unsigned EdgeLin  = PR ? 9 + ((AlphaBits != 0) ? 1 : 0) : 6;
  localparam int unsigned EdgeRef  = PR ? D + 11 : D + 8;
  localparam int unsigned EdgeQuad = PR ? 3 * D + 13 : 3 * D + 9;
  localparam int unsigned B111Len  = PR ? 2 : 1;          // b111 cycles
  localparam int unsigned EdgesInTurn = (CpgLanes == 1) ? 3 : 1;  // edges one lane walks
  // Tag pass (sim/values/cpg.cpp cpg_tag_cycles): a normalization takes scale, dot, D root and D
  // division steps; a tagged corner the side test and three normalizations; a tangent 4 steps.
  localparam bit          Tags      = (CpgTags != 0);
  localparam int unsigned NormLen   = 2 + 2 * D;
  localparam int unsigned TaggedLen = 1 + 3 * NormLen;
  localparam int unsigned FaceLen   = 2;
  localparam int unsigned TanLen    = 4;
  localparam int unsigned TagMax    = !Tags ? 0
                                    : (CpgLanes == 1) ? FaceLen + 3 * TaggedLen + 6 * TanLen
                                                      : FaceLen + TaggedLen + 2 * TanLen;
  localparam int unsigned CyclesMax = EdgesInTurn * EdgeQuad + B111Len + 1 + TagMax;
  localparam int unsigned CntW    = $clog2(CyclesMax);
  localparam int unsigned StepW   = $clog2(EdgeQuad);

  // ------------------------------------------------------------------ mode and control
  logic mode_linear, mode_reflect;
  assign mode_linear  = (mode_i == tess_pkg::ModeLinear);
  assign mode_reflect = (mode_i == tess_pkg::ModeReflect);

  logic [CntW-1:0]  cycles_m1;   // C - 1 = EdgesInTurn * E + B111Len
  logic [StepW-1:0] edge_last;   // E - 1
  always_comb begin
    if (mode_linear) begin
      cycles_m1 = CntW'(EdgesInTurn * EdgeLin + B111Len);
      edge_last = StepW'(EdgeLin - 1);
    end else if (mode_reflect) begin
      cycles_m1 = CntW'(EdgesInTurn * EdgeRef + B111Len);
      edge_last = StepW'(EdgeRef - 1);
    end else begin
      cycles_m1 = CntW'(EdgesInTurn * EdgeQuad + B111Len);
      edge_last = StepW'(EdgeQuad - 1);
    end
  end

  logic             busy_q;
  logic [CntW-1:0]  counter_q;
  logic [1:0]       edge_q;      // 0..2 the edge of a single lane, 3 = b111 (step_q counts)
  logic [StepW-1:0] step_q;
  logic             accept, compute, write;
  logic             tag_pass;    // the tag pass runs (before the edge pass)
  logic [CntW-1:0]  tag_cycles;  // T of the triangle at the TRI FIFO head

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
      counter_q <= cycles_m1 + tag_cycles;
      edge_q    <= '0;
      step_q    <= '0;
    end else if (compute) begin
      counter_q <= counter_q - CntW'(1);
      if (!tag_pass) begin
        if (step_q == edge_last) begin
          step_q <= '0;
          // Three lanes finish all edges at once.
          edge_q <= (CpgLanes == 1) ? edge_q + 2'd1 : 2'd3;
        end else begin
          step_q <= step_q + StepW'(1);
        end
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
  (* mem2reg *) logic [3*W-1:0] p_q [3];  // [vertex], component c at [cW +: W]
  (* mem2reg *) logic [3*W-1:0] n_q [3];
  logic [DescW-1:0]  desc_q;
  logic [IdBits-1:0] id_q;
  (* mem2reg *) logic [AlphaW-1:0] alpha [3];  // edge e's silhouette weight (1 without AlphaBits)

  always_ff @(posedge clk_i) begin
    if (accept) begin
      for (int v = 0; v < 3; v++) begin
        p_q[v] <= tri_i[3 * v * W +: 3 * W];
        n_q[v] <= tri_i[9 * W + 3 * v * W +: 3 * W];
      end
      desc_q <= tri_i[18 * W +: DescW];
      id_q   <= tri_i[18 * W + DescW +: IdBits];
    end
  end
  if (AlphaBits != 0) begin : g_alpha
    (* mem2reg *) logic [AlphaW-1:0] alpha_q [3];
    always_ff @(posedge clk_i) begin
      if (accept) begin
        for (int e = 0; e < 3; e++) alpha_q[e] <= tri_i[TriW - 3 * AlphaW + e * AlphaW +: AlphaW];
      end
    end
    for (genvar e = 0; e < 3; e++) begin : g_e
      assign alpha[e] = alpha_q[e];
    end
  end else begin : g_no_alpha
    for (genvar e = 0; e < 3; e++) begin : g_e
      assign alpha[e] = '1;  // unused: the lanes have no blend
    end
  end

  // ------------------------------------------------------------------ scalar tags
  // nrm: the normals the edge pass takes (N' at tagged corners); slot_nn: tangent point i
  // (edge i/2, near its start for even i) belongs to a non-neutral corner and comes from the
  // tag pass; tag_tan_*: the tag pass's tangent-point writes.
  localparam int unsigned VecW  = 3 * W;
  localparam int unsigned FaceW = 2 * W + 3;
  (* mem2reg *) logic [3*W-1:0] nrm [3];
  logic [5:0]                   slot_nn;
  logic [5:0]                   tag_tan_wr;
  logic [6*VecW-1:0]            tag_tan_val;
  logic [tess_pkg::FlagBits-1:0] tag_flags;

  if (Tags) begin : g_tags
    localparam int unsigned TagBase = 18 * W + DescW + IdBits;
    localparam int unsigned RW      = $clog2(NormLen);
    localparam logic [1:0] PNone = 2'd0, PFace = 2'd1, PCorner = 2'd2, PTan = 2'd3;

    // Non-neutral (Δ != 0 or θ != 0) and tagged (Δ != 0) corners of the FIFO head, and T.
    logic [2:0] nn_in, tg_in;
    (* mem2reg *) logic [CntW-1:0] corner_len [3], tan_len [3];
    for (genvar v = 0; v < 3; v++) begin : g_len
      assign tg_in[v] = (tri_i[TagBase + 6 * v * W +: 3 * W] != '0);
      assign nn_in[v] = tg_in[v] || (tri_i[TagBase + 6 * v * W + 4 * W +: W] != '0);
      assign corner_len[v] = tg_in[v] ? CntW'(TaggedLen) : nn_in[v] ? CntW'(NormLen) : '0;
      assign tan_len[v] = CntW'(TanLen) * (CntW'(nn_in[v]) + CntW'(nn_in[(v + 1) % 3]));
    end
    // One lane takes every corner and tangent point in turn (the sums), three lanes take them
    // at once (the slowest corner and the slowest edge).
    logic [CntW-1:0] face_len, csum, tsum, cmax, tmax;
    assign face_len = (tg_in != '0) ? CntW'(FaceLen) : '0;
    always_comb begin
      csum = '0;
      tsum = '0;
      cmax = '0;
      tmax = '0;
      for (int v = 0; v < 3; v++) begin
        csum = csum + corner_len[v];
        tsum = tsum + tan_len[v];
        if (corner_len[v] > cmax) cmax = corner_len[v];
        if (tan_len[v] > tmax) tmax = tan_len[v];
      end
    end
    assign tag_cycles = face_len + ((CpgLanes == 1) ? csum + tsum : cmax + tmax);

    // The latched tags and the tag pass's results per corner.
    (* mem2reg *) logic [3*W-1:0] delta_q [3], field_q [3], x_q [3], y_q [3];
    (* mem2reg *) logic [W-1:0]   sigma_q [3], theta_q [3], beta_q [3];
    logic [2:0] nn_q, tg_q;
    for (genvar v = 0; v < 3; v++) begin : g_nrm
      assign nrm[v] = field_q[v];
    end
    assign slot_nn = {nn_q[0], nn_q[2], nn_q[2], nn_q[1], nn_q[1], nn_q[0]};

    // ---- phases: face normal, corners, tangent points; then the edge pass
    logic [1:0] phase_q, phase_d;
    logic       face_step_q;
    logic [CpgLanes-1:0] lane_ctodo_last, lane_ttodo_last;  // the lane's last job ends now
    assign tag_pass = (phase_q != PNone);
    always_comb begin
      phase_d = phase_q;
      if (accept) begin
        phase_d = (nn_in == '0) ? PNone : (tg_in != '0) ? PFace : PCorner;
      end else if (compute) begin
        case (phase_q)
          PFace:   if (face_step_q) phase_d = PCorner;
          PCorner: if (&lane_ctodo_last) phase_d = PTan;
          PTan:    if (&lane_ttodo_last) phase_d = PNone;
          default: ;
        endcase
      end
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        phase_q     <= PNone;
        face_step_q <= 1'b0;
      end else begin
        phase_q     <= phase_d;
        face_step_q <= accept ? 1'b0 : (compute && phase_q == PFace) ? !face_step_q : face_step_q;
      end
    end

    // ---- lanes: each walks its corners, then its tangent points
    logic [FaceW*3-1:0] face;
    (* mem2reg *) logic [1:0]      lane_corner [CpgLanes];
    (* mem2reg *) logic [1:0]      lane_k [CpgLanes];
    (* mem2reg *) logic [2:0]      lane_slot [CpgLanes];
    logic [CpgLanes-1:0]           lane_norm_wr, lane_tan_wr;
    logic [CpgLanes*VecW-1:0]      lane_norm, lane_tan;
    logic [CpgLanes*tess_pkg::FlagBits-1:0] lane_tflags;

    for (genvar e = 0; e < CpgLanes; e++) begin : g_lane
      localparam logic [2:0] CMask = (CpgLanes == 1) ? 3'b111 : 3'(1 << e);
      localparam logic [5:0] SMask = (CpgLanes == 1) ? 6'b111111 : 6'(3 << (2 * e));
      logic [2:0]    ctodo_q, ctodo_d;
      logic [5:0]    ttodo_q, ttodo_d;
      logic          fresh_q, side_q;
      logic [1:0]    k_q, t_q;
      logic [RW-1:0] r_q;
      logic [1:0]    ccur;
      logic [2:0]    tcur;
      always_comb begin
        ccur = ctodo_q[0] ? 2'd0 : ctodo_q[1] ? 2'd1 : 2'd2;
        tcur = 3'd5;
        for (int i = 5; i >= 0; i--) if (ttodo_q[i]) tcur = 3'(i);
      end

      // the corner job's step: side test, then normalizations k = 0..2 of NormLen steps
      logic          in_corner, in_tan, eff_side;
      logic [1:0]    eff_k;
      logic [RW-1:0] eff_r;
      assign in_corner = compute && (phase_q == PCorner) && (ctodo_q != '0);
      assign in_tan    = compute && (phase_q == PTan) && (ttodo_q != '0);
      assign eff_side  = fresh_q ? tg_q[ccur] : side_q;
      assign eff_k     = fresh_q ? (tg_q[ccur] ? 2'd0 : 2'd2) : k_q;
      assign eff_r     = fresh_q ? '0 : r_q;

      logic op_face0, op_face1, op_side, op_scale, op_dot, op_sqrt, op_div, op_div_first, op_div_last;
      logic c_done, t_done;
      logic [3:0] op_tan;
      assign op_face0     = (e == 0) && compute && (phase_q == PFace) && !face_step_q;
      assign op_face1     = (e == 0) && compute && (phase_q == PFace) && face_step_q;
      assign op_side      = in_corner && eff_side;
      assign op_scale     = in_corner && !eff_side && (eff_r == RW'(0));
      assign op_dot       = in_corner && !eff_side && (eff_r == RW'(1));
      assign op_sqrt      = in_corner && !eff_side && (eff_r >= RW'(2)) && (eff_r < RW'(D + 2));
      assign op_div       = in_corner && !eff_side && (eff_r >= RW'(D + 2));
      assign op_div_first = in_corner && !eff_side && (eff_r == RW'(D + 2));
      assign op_div_last  = in_corner && !eff_side && (eff_r == RW'(NormLen - 1));
      assign c_done       = op_div_last && (eff_k == 2'd2);
      assign op_tan       = in_tan ? (4'b0001 << t_q) : 4'b0000;
      assign t_done       = in_tan && (t_q == 2'd3);

      assign ctodo_d = c_done ? ctodo_q & ~(3'b001 << ccur) : ctodo_q;
      assign ttodo_d = t_done ? ttodo_q & ~(6'b000001 << tcur) : ttodo_q;
      assign lane_ctodo_last[e] = (ctodo_d == '0);
      assign lane_ttodo_last[e] = (ttodo_d == '0);

      always_ff @(posedge clk_i) begin
        if (accept) begin
          ctodo_q <= CMask & nn_in;
          ttodo_q <= SMask & {nn_in[0], nn_in[2], nn_in[2], nn_in[1], nn_in[1], nn_in[0]};
          fresh_q <= 1'b1;
          t_q     <= '0;
        end else begin
          ctodo_q <= ctodo_d;
          ttodo_q <= ttodo_d;
          if (in_corner) begin
            fresh_q <= c_done;
            side_q  <= 1'b0;
            if (eff_side) begin
              k_q <= eff_k;
              r_q <= '0;
            end else if (eff_r == RW'(NormLen - 1)) begin
              k_q <= eff_k + 2'd1;
              r_q <= '0;
            end else begin
              k_q <= eff_k;
              r_q <= eff_r + RW'(1);
            end
          end
          if (in_tan) t_q <= t_done ? 2'd0 : t_q + 2'd1;
        end
      end

      // operands: the corner ccur; the tangent point tcur near Pj on edge Pj -> Pk
      logic [1:0] near, far;
      always_comb begin
        case (tcur)
          3'd0:    begin near = 2'd0; far = 2'd1; end
          3'd1:    begin near = 2'd1; far = 2'd0; end
          3'd2:    begin near = 2'd1; far = 2'd2; end
          3'd3:    begin near = 2'd2; far = 2'd1; end
          3'd4:    begin near = 2'd2; far = 2'd0; end
          default: begin near = 2'd0; far = 2'd2; end
        endcase
      end
      logic crease;
      assign crease = tg_q[near] && tg_q[far];

      logic [3*(W+1)-1:0] e1, e2;
      for (genvar c = 0; c < 3; c++) begin : g_e
        assign e1[c*(W+1) +: W+1] = (W + 1)'($signed(p_q[1][c*W +: W])) - (W + 1)'($signed(p_q[0][c*W +: W]));
        assign e2[c*(W+1) +: W+1] = (W + 1)'($signed(p_q[2][c*W +: W])) - (W + 1)'($signed(p_q[0][c*W +: W]));
      end

      logic [3*FaceW-1:0] face_lane;
      tess_cpg_tag #(
        .CoordIntBits (CoordIntBits),
        .CoordFracBits(CoordFracBits),
        .DigitBits    (CpgDigitBits)
      ) u_tag (
        .clk_i      (clk_i),
        .face0_i    (op_face0),
        .face1_i    (op_face1),
        .side_i     (op_side),
        .scale_i    (op_scale),
        .norm_k_i   (eff_k),
        .dot_i      (op_dot),
        .sqrt_i     (op_sqrt),
        .div_i      (op_div),
        .div_first_i(op_div_first),
        .div_last_i (op_div_last),
        .tan_i      (op_tan),
        .e1_i       (e1),
        .e2_i       (e2),
        .face_i     (face),
        .face_o     (face_lane),
        .n_i        (n_q[ccur]),
        .delta_i    (delta_q[ccur]),
        .field_i    (field_q[ccur]),
        .sigma_i    (sigma_q[ccur]),
        .beta_i     (beta_q[ccur]),
        .pj_i       (p_q[near]),
        .pk_i       (p_q[far]),
        .theta_i    (theta_q[near]),
        .tn_i       (crease ? n_q[near] : x_q[near]),
        .tm_i       (crease ? y_q[near] : x_q[near]),
        .norm_o     (lane_norm[e*VecW +: VecW]),
        .tan_o      (lane_tan[e*VecW +: VecW]),
        .flags_o    (lane_tflags[e*tess_pkg::FlagBits +: tess_pkg::FlagBits])
      );
      if (e == 0) begin : g_face
        assign face = face_lane;
      end else begin : g_no_face
        logic unused_face;
        assign unused_face = ^face_lane;
      end
      assign lane_corner[e]  = ccur;
      assign lane_k[e]       = eff_k;
      assign lane_slot[e]    = tcur;
      assign lane_norm_wr[e] = op_div_last;
      assign lane_tan_wr[e]  = t_done;
    end

    // ---- the tag pass's results into the corner registers and the staged tangent points
    for (genvar v = 0; v < 3; v++) begin : g_corner_q
      always_ff @(posedge clk_i) begin
        if (accept) begin
          delta_q[v] <= tri_i[TagBase + 6 * v * W +: 3 * W];
          sigma_q[v] <= tri_i[TagBase + 6 * v * W + 3 * W +: W];
          theta_q[v] <= tri_i[TagBase + 6 * v * W + 4 * W +: W];
          beta_q[v]  <= tri_i[TagBase + 6 * v * W + 5 * W +: W];
          field_q[v] <= tri_i[9 * W + 3 * v * W +: 3 * W];
          nn_q[v]    <= nn_in[v];
          tg_q[v]    <= tg_in[v];
        end else begin
          for (int e = 0; e < CpgLanes; e++) begin
            if (lane_norm_wr[e] && lane_corner[e] == 2'(v)) begin
              case (lane_k[e])
                2'd0:    field_q[v] <= lane_norm[e*VecW +: VecW];
                2'd1:    y_q[v]     <= lane_norm[e*VecW +: VecW];
                default: x_q[v]     <= lane_norm[e*VecW +: VecW];
              endcase
            end
          end
        end
      end
    end
    always_comb begin
      tag_tan_wr  = '0;
      tag_tan_val = '0;
      tag_flags   = '0;
      for (int e = 0; e < CpgLanes; e++) begin
        if (lane_tan_wr[e]) begin
          tag_tan_wr[lane_slot[e]]            = 1'b1;
          tag_tan_val[lane_slot[e]*VecW +: VecW] = lane_tan[e*VecW +: VecW];
        end
        tag_flags |= lane_tflags[e*tess_pkg::FlagBits +: tess_pkg::FlagBits];
      end
    end

    // The tag pass takes exactly T cycles: the edge pass starts with C - 1 cycles left.
    `TESS_ASSERT(TagPassLength_A, compute && tag_pass && phase_d == PNone |-> counter_q == cycles_m1 + CntW'(1),
                 clk_i, !rst_ni)
  end else begin : g_no_tags
    assign tag_pass    = 1'b0;
    assign tag_cycles  = '0;
    assign slot_nn     = '0;
    assign tag_tan_wr  = '0;
    assign tag_tan_val = '0;
    assign tag_flags   = '0;
    for (genvar v = 0; v < 3; v++) begin : g_nrm
      assign nrm[v] = n_q[v];
    end
  end

  logic in_edge, in_b111, edge_last_step, b111_next;
  assign in_edge = compute && !tag_pass && (edge_q != 2'd3);
  assign in_b111 = compute && !tag_pass && (edge_q == 2'd3);
  assign edge_last_step = (step_q == edge_last);
  assign b111_next = in_edge && edge_last_step && (CpgLanes != 1 || edge_q == 2'd2);

  // ------------------------------------------------------------------ staged results
  // Tangent points (edge e: entry 2e near its start, 2e + 1 near its end), mid-edge normals and
  // b111, held until the write (the target buffer may still be in use while the CPG computes).
  logic [CpgLanes-1:0]                    lane_tan_a, lane_tan_b, lane_mid_valid, lane_b111_valid;
  logic [CpgLanes*VecW-1:0]               lane_tangent, lane_mid;
  logic [CpgLanes*tess_pkg::FlagBits-1:0] lane_flags;
  logic [6*VecW-1:0]                      stage_tan;
  logic [3*VecW-1:0]                      stage_mid;
  logic [VecW-1:0]                        stage_b111_q;

  logic [5:0]                             stage_tan_wr;  // tangent point i is staged now

  // The lane that computes edge e, and whether it is on edge e in this cycle.
  for (genvar i = 0; i < 6; i++) begin : g_stage_tan
    localparam int unsigned Lane = (CpgLanes == 1) ? 0 : i / 2;
    logic            hit;
    logic [VecW-1:0] q;
    assign hit = ((i % 2 == 0) ? lane_tan_a[Lane] : lane_tan_b[Lane])
              && (CpgLanes != 1 || edge_q == 2'(i / 2));
    always_ff @(posedge clk_i) begin
      if (hit) q <= lane_tangent[Lane*VecW +: VecW];
      else if (tag_tan_wr[i]) q <= tag_tan_val[i*VecW +: VecW];
    end
    assign stage_tan[i*VecW +: VecW] = q;
    assign stage_tan_wr[i] = hit || tag_tan_wr[i];
  end
  for (genvar e = 0; e < 3; e++) begin : g_stage_mid
    localparam int unsigned Lane = (CpgLanes == 1) ? 0 : e;
    logic            hit;
    logic [VecW-1:0] q;
    assign hit = lane_mid_valid[Lane] && (CpgLanes != 1 || edge_q == 2'(e));
    always_ff @(posedge clk_i) begin
      if (hit) q <= lane_mid[Lane*VecW +: VecW];
    end
    assign stage_mid[e*VecW +: VecW] = q;
  end

  // ------------------------------------------------------------------ b111 operand
  // x111 = 3 sum(t) - 2 sum(P), accumulated as the tangent points are staged: -2 sum(P) when the
  // triangle is taken, then 3 t for each tangent point in the cycle after it was staged (from the
  // staging register, off the tangent's own path). Each of the six is staged once per triangle,
  // the last one in step 4 of the last edge (E >= 6; step 7 of E >= 9 with registered
  // products, step 8 of E >= 10 with them and the silhouette blend), so x111 is complete in the
  // first b111 cycle.
  // The sums are modulo 2^X111W and the result fits, so the order does not change a bit.
  // At most one tangent point is staged a cycle per lane (edge pass and tag pass alike): one of
  // all six with one lane, one of each edge's pair {2e, 2e + 1} with three.
  logic [5:0]         staged_d, staged_q;  // tangent point i was staged in the previous cycle
  logic [3*X111W-1:0] x111_d, x111_q;
  assign staged_d = stage_tan_wr;
  for (genvar c = 0; c < 3; c++) begin : g_x111
    (* mem2reg *) logic signed [W-1:0] pair [3];  // the tangent point of edge e staged last cycle, or 0
    logic signed [SumTW-1:0] staged_sum;
    logic signed [X111W-1:0] corners;
    for (genvar e = 0; e < 3; e++) begin : g_pair
      assign pair[e] = (staged_q[2 * e] ? stage_tan[2 * e * VecW + c * W +: W] : '0)
                     | (staged_q[2 * e + 1] ? stage_tan[(2 * e + 1) * VecW + c * W +: W] : '0);
    end
    if (CpgLanes == 1) begin : g_one
      logic signed [W-1:0] only;  // at most one pair is not 0
      assign only       = pair[0] | pair[1] | pair[2];
      assign staged_sum = SumTW'(only);
    end else begin : g_three
      assign staged_sum = SumTW'(pair[0]) + SumTW'(pair[1]) + SumTW'(pair[2]);
    end
    assign corners = X111W'($signed(tri_i[c*W +: W])) + X111W'($signed(tri_i[3*W + c*W +: W]))
                   + X111W'($signed(tri_i[6*W + c*W +: W]));
    assign x111_d[c*X111W +: X111W] = accept ? -(corners <<< 1)
                                    : x111_q[c*X111W +: X111W] + X111W'(staged_sum) * $signed(X111W'(3));
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) staged_q <= '0;
    else staged_q <= staged_d;
  end
  // Data: set when the triangle is taken, read in its b111 cycle.
  always_ff @(posedge clk_i) begin
    x111_q <= x111_d;
  end

  // ------------------------------------------------------------------ edge lanes
  logic [VecW-1:0] b111;

  for (genvar e = 0; e < CpgLanes; e++) begin : g_lane
    // The lane's edge a->b: the edge counter's for a single lane, edge e for three lanes.
    logic [1:0]        edge_idx;
    logic [VecW-1:0]   pa, pb, na, nb, lane_b111;
    logic [AlphaW-1:0] lane_alpha;
    assign edge_idx = (CpgLanes == 1) ? edge_q : 2'(e);
    always_comb begin
      case (edge_idx)
        2'd0:    begin pa = p_q[0]; pb = p_q[1]; na = nrm[0]; nb = nrm[1]; lane_alpha = alpha[0]; end
        2'd1:    begin pa = p_q[1]; pb = p_q[2]; na = nrm[1]; nb = nrm[2]; lane_alpha = alpha[1]; end
        default: begin pa = p_q[2]; pb = p_q[0]; na = nrm[2]; nb = nrm[0]; lane_alpha = alpha[2]; end
      endcase
    end

    // A non-neutral corner's tangent point comes from the tag pass: the lane's is dropped.
    logic [1:0] keep;
    always_comb begin
      case (edge_idx)
        2'd0:    keep = ~slot_nn[1:0];
        2'd1:    keep = ~slot_nn[3:2];
        default: keep = ~slot_nn[5:4];
      endcase
    end

    tess_cpg_edge #(
      .CoordIntBits (CoordIntBits),
      .CoordFracBits(CoordFracBits),
      .DigitBits    (CpgDigitBits),
      .ProductReg   (CpgProductReg),
      .AlphaBits    (AlphaBits)
    ) u_edge (
      .clk_i         (clk_i),
      .mode_reflect_i(mode_reflect),
      .edge_i        (in_edge),
      .step_i        (step_q),
      .last_i        (edge_last_step),
      .keep_a_i      (keep[0]),
      .keep_b_i      (keep[1]),
      .pa_i          (pa),
      .pb_i          (pb),
      .na_i          (na),
      .nb_i          (nb),
      .alpha_i       (lane_alpha),
      .b111_i        ((e == 0) && in_b111),
      .b111_next_i   ((e == 0) && b111_next),
      .x111_i        (x111_q),
      .x111_next_i   (x111_d),
      .tangent_o     (lane_tangent[e*VecW +: VecW]),
      .tangent_a_o   (lane_tan_a[e]),
      .tangent_b_o   (lane_tan_b[e]),
      .mid_o         (lane_mid[e*VecW +: VecW]),
      .mid_valid_o   (lane_mid_valid[e]),
      .b111_o        (lane_b111),
      .b111_valid_o  (lane_b111_valid[e]),
      .flags_o       (lane_flags[e*tess_pkg::FlagBits +: tess_pkg::FlagBits])
    );

    if (e == 0) begin : g_b111
      assign b111 = lane_b111;
    end else begin : g_no_b111
      logic unused_b111;
      assign unused_b111 = ^lane_b111 ^ lane_b111_valid[e];
    end
  end

  always_ff @(posedge clk_i) begin
    if (lane_b111_valid[0]) stage_b111_q <= b111;
  end

  // ------------------------------------------------------------------ sticky flags
  logic [tess_pkg::FlagBits-1:0] flags_q, flags_step;
  always_comb begin
    flags_step = tag_flags;
    for (int e = 0; e < CpgLanes; e++) flags_step |= lane_flags[e*tess_pkg::FlagBits +: tess_pkg::FlagBits];
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
        .x_i  ({nrm[v][c*W +: W], 1'b0}),
        .y_o  (twice),
        .sat_o(corner_sat[3 * v + c])
      );
      assign corner_n[v][c*W +: W] = mode_linear ? nrm[v][c*W +: W] : twice;
    end
  end

  // Geometry net: b300 b210 b120 b030 | b201 b111 b021 | b102 b012 | b003
  assign buf_b_o = {p_q[2],            // 9: b003 = P3
                    stage_tan[3*VecW +: VecW],    // 8: b012, edge P2->P3 near P3
                    stage_tan[4*VecW +: VecW],    // 7: b102, edge P3->P1 near P3
                    stage_tan[2*VecW +: VecW],    // 6: b021, edge P2->P3 near P2
                    stage_b111_q,      // 5: b111
                    stage_tan[5*VecW +: VecW],    // 4: b201, edge P3->P1 near P1
                    p_q[1],            // 3: b030 = P2
                    stage_tan[1*VecW +: VecW],    // 2: b120, edge P1->P2 near P2
                    stage_tan[0*VecW +: VecW],    // 1: b210, edge P1->P2 near P1
                    p_q[0]};           // 0: b300 = P1
  // Normal net: n200 n110 n020 | n101 n011 | n002 (mid-edges zero in linear mode)
  (* mem2reg *) logic [3*W-1:0] mid [3];
  for (genvar e = 0; e < 3; e++) begin : g_mid
    assign mid[e] = mode_linear ? '0 : stage_mid[e*VecW +: VecW];
  end
  assign buf_n_o = {corner_n[2],       // 5: n002
                    mid[1],            // 4: n011 (edge P2->P3)
                    mid[2],            // 3: n101 (edge P3->P1)
                    corner_n[1],       // 2: n020
                    mid[0],            // 1: n110 (edge P1->P2)
                    corner_n[0]};      // 0: n200
  assign buf_desc_o  = desc_q;
  assign buf_id_o    = id_q;
  assign buf_flags_o = flags_q | ((!mode_linear && (corner_sat != '0)) ? tess_pkg::FlagSaturated
                                                                       : '0);
  assign buf_wr_o    = write;

`ifndef SYNTHESIS
  // The accumulated operand is 3 sum(t) - 2 sum(P) of the six staged tangent points (the sum
  // only the assertion reads).
  logic [3*X111W-1:0] x111_sum;
  for (genvar c = 0; c < 3; c++) begin : g_x111_sum
    logic signed [SumTW-1:0] sum_t;
    always_comb begin
      sum_t = '0;
      for (int i = 0; i < 6; i++) sum_t = sum_t + SumTW'($signed(stage_tan[i*VecW + c*W +: W]));
    end
    assign x111_sum[c*X111W +: X111W] = X111W'(sum_t) * $signed(X111W'(3))
      - ((X111W'($signed(p_q[0][c*W +: W])) + X111W'($signed(p_q[1][c*W +: W])) + X111W'($signed(p_q[2][c*W +: W]))) <<< 1);
  end
`endif
  `TESS_ASSERT(X111Sum_A, in_b111 |-> x111_q == x111_sum, clk_i, !rst_ni)
  `TESS_ASSERT(ModeDefined_A, mode_i == tess_pkg::ModeQuadratic || mode_i == tess_pkg::ModeReflect || mode_linear,
               clk_i, !rst_ni)

endmodule
