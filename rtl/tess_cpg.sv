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
// Every value is exact until the one rounding the C++ reference (sim/cpg.cpp) applies, so the
// results are bit-identical to compute_control_points for every CpgLanes and CpgDigitBits.
module tess_cpg #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned CpgLanes      = tess_pkg::CpgLanes,
  parameter int unsigned CpgDigitBits  = tess_pkg::CpgDigitBits,
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

  localparam int unsigned LBits   = tess_pkg::FactorBits;
  localparam int unsigned IdBits  = tess_pkg::IdBits;
  localparam int unsigned SumTW   = W + 3;                     // sum of six tangent points
  localparam int unsigned X111W   = W + 5;                     // 3 sum(t) - 2 sum(P)
  // Edge cycles (sim/cpg.cpp cpg_edge_cycles), D digit steps per division or square root.
  localparam int unsigned D        = (W + CpgDigitBits - 1) / CpgDigitBits;
  localparam int unsigned EdgeLin  = 6;
  localparam int unsigned EdgeRef  = D + 8;
  localparam int unsigned EdgeQuad = 3 * D + 9;
  localparam int unsigned EdgesInTurn = (CpgLanes == 1) ? 3 : 1;  // edges one lane walks
  localparam int unsigned CyclesMax = EdgesInTurn * EdgeQuad + 2;
  localparam int unsigned CntW    = $clog2(CyclesMax);
  localparam int unsigned StepW   = $clog2(EdgeQuad);

  // ------------------------------------------------------------------ mode and control
  logic mode_linear, mode_reflect;
  assign mode_linear  = (mode_i == tess_pkg::ModeLinear);
  assign mode_reflect = (mode_i == tess_pkg::ModeReflect);

  logic [CntW-1:0]  cycles_m1;   // C - 1 = EdgesInTurn * E + 1
  logic [StepW-1:0] edge_last;   // E - 1
  always_comb begin
    if (mode_linear) begin
      cycles_m1 = CntW'(EdgesInTurn * EdgeLin + 1);
      edge_last = StepW'(EdgeLin - 1);
    end else if (mode_reflect) begin
      cycles_m1 = CntW'(EdgesInTurn * EdgeRef + 1);
      edge_last = StepW'(EdgeRef - 1);
    end else begin
      cycles_m1 = CntW'(EdgesInTurn * EdgeQuad + 1);
      edge_last = StepW'(EdgeQuad - 1);
    end
  end

  logic             busy_q;
  logic [CntW-1:0]  counter_q;
  logic [1:0]       edge_q;      // 0..2 the edge of a single lane, 3 = b111
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
        // Three lanes finish all edges at once.
        edge_q <= (CpgLanes == 1) ? edge_q + 2'd1 : 2'd3;
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
  (* mem2reg *) logic [3*W-1:0] p_q [3];  // [vertex], component c at [cW +: W]
  (* mem2reg *) logic [3*W-1:0] n_q [3];
  logic [LBits-1:0]  l_q;
  logic [IdBits-1:0] id_q;

  always_ff @(posedge clk_i) begin
    if (accept) begin
      for (int v = 0; v < 3; v++) begin
        p_q[v] <= tri_i[3 * v * W +: 3 * W];
        n_q[v] <= tri_i[9 * W + 3 * v * W +: 3 * W];
      end
      l_q  <= tri_i[18 * W +: LBits];
      id_q <= tri_i[18 * W + LBits +: IdBits];
    end
  end

  logic in_edge, in_b111;
  assign in_edge = compute && (edge_q != 2'd3);
  assign in_b111 = compute && (edge_q == 2'd3);

  // ------------------------------------------------------------------ staged results
  // Tangent points (edge e: entry 2e near its start, 2e + 1 near its end), mid-edge normals and
  // b111, held until the write (the target buffer may still be in use while the CPG computes).
  localparam int unsigned VecW = 3 * W;
  logic [CpgLanes-1:0]                    lane_tan_a, lane_tan_b, lane_mid_valid;
  logic [CpgLanes*VecW-1:0]               lane_tangent, lane_mid;
  logic [CpgLanes*tess_pkg::FlagBits-1:0] lane_flags;
  logic [6*VecW-1:0]                      stage_tan;
  logic [3*VecW-1:0]                      stage_mid;
  logic [VecW-1:0]                        stage_b111_q;

  // The lane that computes edge e, and whether it is on edge e in this cycle.
  for (genvar i = 0; i < 6; i++) begin : g_stage_tan
    localparam int unsigned Lane = (CpgLanes == 1) ? 0 : i / 2;
    logic            hit;
    logic [VecW-1:0] q;
    assign hit = ((i % 2 == 0) ? lane_tan_a[Lane] : lane_tan_b[Lane])
              && (CpgLanes != 1 || edge_q == 2'(i / 2));
    always_ff @(posedge clk_i) begin
      if (hit) q <= lane_tangent[Lane*VecW +: VecW];
    end
    assign stage_tan[i*VecW +: VecW] = q;
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
  // x111 = 3 sum(t) - 2 sum(P) from the staged tangent points (all six are staged by then).
  logic [3*X111W-1:0] x111;
  for (genvar c = 0; c < 3; c++) begin : g_x111
    logic signed [SumTW-1:0] sum_t;
    logic signed [X111W-1:0] st3, corners;
    always_comb begin
      sum_t = '0;
      for (int i = 0; i < 6; i++) sum_t = sum_t + SumTW'($signed(stage_tan[i*VecW + c*W +: W]));
    end
    assign st3     = X111W'(sum_t) * $signed(X111W'(3));
    assign corners = X111W'($signed(p_q[0][c*W +: W])) + X111W'($signed(p_q[1][c*W +: W]))
                   + X111W'($signed(p_q[2][c*W +: W]));
    assign x111[c*X111W +: X111W] = st3 - (corners <<< 1);
  end

  // ------------------------------------------------------------------ edge lanes
  logic [VecW-1:0] b111;

  for (genvar e = 0; e < CpgLanes; e++) begin : g_lane
    // The lane's edge a->b: the edge counter's for a single lane, edge e for three lanes.
    logic [1:0]      edge_idx;
    logic [VecW-1:0] pa, pb, na, nb, lane_b111;
    assign edge_idx = (CpgLanes == 1) ? edge_q : 2'(e);
    always_comb begin
      case (edge_idx)
        2'd0:    begin pa = p_q[0]; pb = p_q[1]; na = n_q[0]; nb = n_q[1]; end
        2'd1:    begin pa = p_q[1]; pb = p_q[2]; na = n_q[1]; nb = n_q[2]; end
        default: begin pa = p_q[2]; pb = p_q[0]; na = n_q[2]; nb = n_q[0]; end
      endcase
    end

    tess_cpg_edge #(
      .CoordIntBits (CoordIntBits),
      .CoordFracBits(CoordFracBits),
      .DigitBits    (CpgDigitBits)
    ) u_edge (
      .clk_i         (clk_i),
      .mode_reflect_i(mode_reflect),
      .edge_i        (in_edge),
      .step_i        (step_q),
      .pa_i          (pa),
      .pb_i          (pb),
      .na_i          (na),
      .nb_i          (nb),
      .b111_i        ((e == 0) && in_b111),
      .x111_i        (x111),
      .tangent_o     (lane_tangent[e*VecW +: VecW]),
      .tangent_a_o   (lane_tan_a[e]),
      .tangent_b_o   (lane_tan_b[e]),
      .mid_o         (lane_mid[e*VecW +: VecW]),
      .mid_valid_o   (lane_mid_valid[e]),
      .b111_o        (lane_b111),
      .flags_o       (lane_flags[e*tess_pkg::FlagBits +: tess_pkg::FlagBits])
    );

    if (e == 0) begin : g_b111
      assign b111 = lane_b111;
    end else begin : g_no_b111
      logic unused_b111;
      assign unused_b111 = ^lane_b111;
    end
  end

  always_ff @(posedge clk_i) begin
    if (in_b111) stage_b111_q <= b111;
  end

  // ------------------------------------------------------------------ sticky flags
  logic [tess_pkg::FlagBits-1:0] flags_q, flags_step;
  always_comb begin
    flags_step = '0;
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
        .x_i  ({n_q[v][c*W +: W], 1'b0}),
        .y_o  (twice),
        .sat_o(corner_sat[3 * v + c])
      );
      assign corner_n[v][c*W +: W] = mode_linear ? n_q[v][c*W +: W] : twice;
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
