// PN-triangle tessellation unit: TRI FIFO -> CPG -> control-point buffers -> TE (DPG,
// contexts, scheduler, INT blocks) -> VTX FIFO, plus the performance counters.
// Cycle-by-cycle specification: docs/microarchitecture.md. Every output is a function of
// registered state only.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_unit #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned BaryBits      = tess_pkg::BaryBits,
  parameter int unsigned AlphaBits     = tess_pkg::AlphaBits,
  parameter int unsigned IntBlocks     = tess_pkg::IntBlocks,
  parameter int unsigned IntLatency    = tess_pkg::IntLatency,
  parameter int unsigned Contexts      = tess_pkg::Contexts,
  parameter int unsigned TriFifoDepth  = tess_pkg::TriFifoDepth,
  parameter int unsigned VtxFifoDepth  = tess_pkg::VtxFifoDepth,
  parameter int unsigned CpBuffers     = tess_pkg::CpBuffers,
  parameter int unsigned CpgLanes      = tess_pkg::CpgLanes,
  parameter int unsigned CpgDigitBits  = tess_pkg::CpgDigitBits,
  parameter int unsigned CpgProductReg = tess_pkg::CpgProductReg,
  parameter int unsigned CpgTags       = tess_pkg::CpgTags,
  parameter int unsigned CpgCopies     = tess_pkg::CpgCopies,
  parameter int unsigned InjectBug     = tess_pkg::InjectBug,
  localparam int unsigned W            = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned AlphaW       = AlphaBits + 1,             // alpha in 0..2^A
  localparam int unsigned CtrW         = tess_pkg::CounterBits,
  localparam int unsigned NumCtr       = tess_pkg::num_ctrs(IntBlocks)
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic [tess_pkg::ModeBits-1:0]   mode_i,      // static during a run
  // Triangles in
  input  logic                            tri_valid_i,
  output logic                            tri_ready_o,
  input  logic [9*W-1:0]                  tri_p_i,     // vertex v component c at [(3v+c)W +: W]
  input  logic [9*W-1:0]                  tri_n_i,
  input  logic [tess_pkg::FactorBits-1:0] tri_l_i,     // uniform pattern: L in 1..64
  input  logic [tess_pkg::PatternBits-1:0] tri_pattern_i,  // tess_pkg::Pat*
  input  logic [4*tess_pkg::FixBits-1:0]  tri_factors_i, // D3D11: factor e at [e FixBits +: FixBits], 3 = inner
  input  logic [tess_pkg::IdBits-1:0]     tri_id_i,
  // Scalar tags, read only with CpgTags: vertex v's Δ (3W), σ, θ, β at [6vW +: 6W]
  input  logic [18*W-1:0]                 tri_tags_i,
  // Silhouette weights, read only with AlphaBits > 0: edge e's (corners e -> e + 1) alpha at
  // [e AlphaW +: AlphaW], unsigned with AlphaBits fraction bits, 0..2^AlphaBits
  input  logic [3*AlphaW-1:0]             tri_alpha_i,
  // Vertices out
  output logic                            vtx_valid_o,
  input  logic                            vtx_ready_i,
  output logic [3*W-1:0]                  vtx_pos_o,   // component c at [cW +: W]
  output logic [3*W-1:0]                  vtx_nrm_o,
  output logic [BaryBits:0]               vtx_u_o,
  output logic [BaryBits:0]               vtx_v_o,
  output logic [tess_pkg::FactorBits-1:0] vtx_j_o,
  output logic [tess_pkg::FactorBits-1:0] vtx_k_o,
  output logic [tess_pkg::FactorBits-1:0] vtx_l_o,
  output logic [tess_pkg::IndexBits-1:0]  vtx_index_o,
  output logic [tess_pkg::IdBits-1:0]     vtx_id_o,
  output logic                            vtx_last_o,
  output logic [tess_pkg::FlagBits-1:0]   vtx_flags_o,
  // Performance counters (§10; sim/values/unit_io.hpp UnitCounters): counter k (tess_pkg::ctr_e) at
  // [k CtrW +: CtrW], INT block i's busy cycles at k = CtrIntBusy + i
  output logic [NumCtr*CtrW-1:0]          perf_ctr_o
);

  localparam int unsigned LBits  = tess_pkg::FactorBits;
  localparam int unsigned IdBits = tess_pkg::IdBits;
  localparam int unsigned FlagW  = tess_pkg::FlagBits;
  localparam int unsigned AlphaWords = (AlphaBits != 0) ? 3 * AlphaW : 0;
  localparam int unsigned TriW   = tess_pkg::tri_w(W, CpgTags, AlphaBits);
  localparam int unsigned VtxW   = tess_pkg::vtx_w(W, BaryBits);
  localparam int unsigned TriCntW = $clog2(TriFifoDepth + 1);
  localparam int unsigned VtxCntW = $clog2(VtxFifoDepth + 1);

  // ------------------------------------------------------------------ TRI FIFO
  logic            tri_push, tri_pop, tri_full, tri_empty;
  logic [TriW-1:0] tri_head;
  logic [TriCntW-1:0] tri_count;
  assign tri_ready_o = !tri_full;
  assign tri_push    = tri_valid_i && tri_ready_o;

  // The TRI FIFO word: {alpha (with AlphaBits), tags (with CpgTags), id, descriptor, N, P}.
  logic [TriW-AlphaWords-1:0] tri_base;
  logic [TriW-1:0] tri_in;
  if (CpgTags != 0) begin : g_tri_tags
    assign tri_base = {tri_tags_i, tri_id_i, tri_factors_i, tri_pattern_i, tri_l_i, tri_n_i, tri_p_i};
  end else begin : g_tri_plain
    logic unused_tags;  // a plain-PN unit ignores the tag inputs
    assign unused_tags = ^tri_tags_i;
    assign tri_base = {tri_id_i, tri_factors_i, tri_pattern_i, tri_l_i, tri_n_i, tri_p_i};
  end
  if (AlphaBits != 0) begin : g_tri_alpha
    assign tri_in = {tri_alpha_i, tri_base};
  end else begin : g_tri_no_alpha
    logic unused_alpha;  // a unit without the silhouette blend ignores alpha
    assign unused_alpha = ^tri_alpha_i;
    assign tri_in = tri_base;
  end

  tess_fifo #(.Width(TriW), .Depth(TriFifoDepth)) u_tri_fifo (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .push_i (tri_push),
    .data_i (tri_in),
    .pop_i  (tri_pop),
    .data_o (tri_head),
    .count_o(tri_count),
    .full_o (tri_full),
    .empty_o(tri_empty)
  );

  // ------------------------------------------------------------------ CPG (copies and their FSUs)
  logic                cpg_wr, buf_wr_empty;
  logic [30*W-1:0]     cpg_b;
  logic [18*W-1:0]     cpg_n;
  logic [tess_pkg::PatchBits-1:0] cpg_patch;
  logic [IdBits-1:0]   cpg_id;
  logic [FlagW-1:0]    cpg_flags;
  logic                cpg_busy, cpg_blocked, cpg_active;

  tess_cpg_array #(
    .CoordIntBits (CoordIntBits),
    .CoordFracBits(CoordFracBits),
    .CpgLanes     (CpgLanes),
    .CpgDigitBits (CpgDigitBits),
    .CpgProductReg(CpgProductReg),
    .CpgTags      (CpgTags),
    .AlphaBits    (AlphaBits),
    .CpgCopies    (CpgCopies)
  ) u_cpgs (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .mode_i      (mode_i),
    .tri_avail_i (!tri_empty),
    .tri_i       (tri_head),
    .tri_pop_o   (tri_pop),
    .buf_empty_i (buf_wr_empty),
    .buf_wr_o    (cpg_wr),
    .buf_b_o     (cpg_b),
    .buf_n_o     (cpg_n),
    .buf_patch_o (cpg_patch),
    .buf_id_o    (cpg_id),
    .buf_flags_o (cpg_flags),
    .busy_o      (cpg_busy),
    .blocked_o   (cpg_blocked),
    .active_o    (cpg_active)
  );

  // ------------------------------------------------------------------ control-point buffers
  localparam int unsigned BufW = (CpBuffers > 1) ? $clog2(CpBuffers) : 1;
  logic               rd_full, drain, release_last;
  logic [BufW-1:0]    rd_ptr, release_buf;
  logic [tess_pkg::PatchBits-1:0] rd_patch;
  logic [IdBits-1:0]  rd_id;
  logic [FlagW-1:0]   rd_flags;
  logic [CpBuffers*30*W-1:0] cp_b;
  logic [CpBuffers*18*W-1:0] cp_n;

  tess_cpbuf #(.CoordWidth(W), .Buffers(CpBuffers)) u_cpbuf (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .wr_empty_o   (buf_wr_empty),
    .wr_i         (cpg_wr),
    .wr_b_i       (cpg_b),
    .wr_n_i       (cpg_n),
    .wr_patch_i   (cpg_patch),
    .wr_id_i      (cpg_id),
    .wr_flags_i   (cpg_flags),
    .rd_full_o    (rd_full),
    .rd_ptr_o     (rd_ptr),
    .rd_patch_o   (rd_patch),
    .rd_id_o      (rd_id),
    .rd_flags_o   (rd_flags),
    .drain_i      (drain),
    .release_i    (release_last),
    .release_buf_i(release_buf),
    .b_o          (cp_b),
    .n_o          (cp_n)
  );

  // ------------------------------------------------------------------ TE
  logic                 vtx_push, vtx_full, vtx_empty;
  logic [VtxW-1:0]      vtx_in, vtx_head;
  logic [VtxCntW-1:0]   vtx_count;
  logic [IntBlocks-1:0] int_busy;
  logic                 te_ctx_limited, te_int_limited, te_busy, te_blocked, te_starved, te_idle;
  logic                 te_pipeline;

  tess_te #(
    .CoordWidth(W),
    .BaryBits  (BaryBits),
    .IntBlocks (IntBlocks),
    .IntLatency(IntLatency),
    .Contexts  (Contexts),
    .Buffers   (CpBuffers),
    .InjectBug (InjectBug)
  ) u_te (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .mode_i         (mode_i),
    .rd_full_i      (rd_full),
    .rd_ptr_i       (rd_ptr),
    .rd_patch_i     (rd_patch),
    .rd_id_i        (rd_id),
    .rd_flags_i     (rd_flags),
    .b_i            (cp_b),
    .n_i            (cp_n),
    .drain_o        (drain),
    .release_o      (release_last),
    .release_buf_o  (release_buf),
    .vtx_full_i     (vtx_full),
    .vtx_push_o     (vtx_push),
    .vtx_o          (vtx_in),
    .upstream_busy_i(cpg_active || !tri_empty),
    .int_busy_o     (int_busy),
    .te_ctx_limited_o(te_ctx_limited),
    .te_int_limited_o(te_int_limited),
    .te_busy_o      (te_busy),
    .te_blocked_o   (te_blocked),
    .te_starved_o   (te_starved),
    .te_idle_o      (te_idle),
    .te_pipeline_o  (te_pipeline)
  );

  // ------------------------------------------------------------------ VTX FIFO
  logic vtx_pop;
  assign vtx_pop = vtx_valid_o && vtx_ready_i;

  tess_fifo #(.Width(VtxW), .Depth(VtxFifoDepth)) u_vtx_fifo (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .push_i (vtx_push),
    .data_i (vtx_in),
    .pop_i  (vtx_pop),
    .data_o (vtx_head),
    .count_o(vtx_count),
    .full_o (vtx_full),
    .empty_o(vtx_empty)
  );

  assign vtx_valid_o = !vtx_empty;
  assign {vtx_flags_o, vtx_last_o, vtx_id_o, vtx_index_o, vtx_l_o, vtx_k_o, vtx_j_o, vtx_v_o, vtx_u_o,
          vtx_nrm_o, vtx_pos_o} = vtx_head;

  // The FIFO levels only matter through full/empty.
  logic unused_counts;
  assign unused_counts = ^{tri_count, vtx_count};

  // ------------------------------------------------------------------ performance counters
  // One increment per counter, set at its tess_pkg::ctr_e index; one adder each:
  // counter k += inc[k] every cycle out of reset.
  logic [NumCtr-1:0] ctr_inc;
  assign ctr_inc[tess_pkg::CtrCycles]           = 1'b1;
  assign ctr_inc[tess_pkg::CtrTriIn]            = tri_push;
  assign ctr_inc[tess_pkg::CtrVtxOut]           = vtx_pop;
  assign ctr_inc[tess_pkg::CtrTriStalls]        = tri_valid_i && !tri_ready_o;
  assign ctr_inc[tess_pkg::CtrVtxStalls]        = vtx_valid_o && !vtx_ready_i;
  assign ctr_inc[tess_pkg::CtrTeContextLimited] = te_ctx_limited;
  assign ctr_inc[tess_pkg::CtrTeIntLimited]     = te_int_limited;
  assign ctr_inc[tess_pkg::CtrTeBusy]           = te_busy;
  assign ctr_inc[tess_pkg::CtrTeBlockedByGpe]   = te_blocked;
  assign ctr_inc[tess_pkg::CtrTeStarvedByCpg]   = te_starved;
  assign ctr_inc[tess_pkg::CtrTeIdle]           = te_idle;
  assign ctr_inc[tess_pkg::CtrTePipeline]       = te_pipeline;
  assign ctr_inc[tess_pkg::CtrCpgBusy]          = cpg_busy;
  assign ctr_inc[tess_pkg::CtrCpgBlocked]       = cpg_blocked;
  assign ctr_inc[tess_pkg::CtrCpgIdle]          = !cpg_busy && !cpg_blocked;
  assign ctr_inc[tess_pkg::CtrIntBusy +: IntBlocks] = int_busy;

  for (genvar k = 0; k < NumCtr; k++) begin : g_ctr
    logic [CtrW-1:0] ctr_d, ctr_q;
    assign ctr_d = ctr_inc[k] ? ctr_q + CtrW'(1) : ctr_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) ctr_q <= '0;
      else         ctr_q <= ctr_d;
    end
    assign perf_ctr_o[k*CtrW +: CtrW] = ctr_q;
  end

  // The configurations sim::UnitConfig accepts (sim/config/params.cpp, UnitConfig::validate); the RTL
  // is verified in no other.
  `TESS_ASSERT_PARAM(CoordIntBitsRange_A, CoordIntBits >= 1 && CoordIntBits <= 8)
  `TESS_ASSERT_PARAM(CoordFracBitsRange_A, CoordFracBits >= 8 && CoordFracBits <= 26)
  `TESS_ASSERT_PARAM(CoordWidthRange_A, W <= 32)
  `TESS_ASSERT_PARAM(BaryBitsRange_A, BaryBits >= 7 && BaryBits <= 20)
  `TESS_ASSERT_PARAM(AlphaBitsRange_A, AlphaBits <= 16)
  `TESS_ASSERT_PARAM(IntBlocksRange_A, IntBlocks >= 1 && IntBlocks <= 32)
  `TESS_ASSERT_PARAM(IntLatencyRange_A, IntLatency >= 1 && IntLatency <= 8)
  `TESS_ASSERT_PARAM(ContextsRange_A, Contexts >= 1 && Contexts <= 16)
  `TESS_ASSERT_PARAM(TriFifoDepthRange_A, TriFifoDepth >= 1 && TriFifoDepth <= 64)
  `TESS_ASSERT_PARAM(VtxFifoDepthRange_A, VtxFifoDepth >= 1 && VtxFifoDepth <= 64)
  `TESS_ASSERT_PARAM(CpBuffersRange_A, CpBuffers >= 1 && CpBuffers <= 8)
  `TESS_ASSERT_PARAM(CpgLanesRange_A, CpgLanes == 1 || CpgLanes == 3)
  `TESS_ASSERT_PARAM(CpgDigitBitsRange_A, CpgDigitBits >= 1 && CpgDigitBits <= W)
  `TESS_ASSERT_PARAM(CpgCopiesRange_A, CpgCopies >= 1 && CpgCopies <= 16)
  `TESS_ASSERT_PARAM(CpgProductRegRange_A, CpgProductReg <= 1)
  `TESS_ASSERT_PARAM(CpgTagsRange_A, CpgTags <= 1)

  // Handshakes and the vertex offered are never X out of reset (4-state simulation).
  `TESS_ASSERT_KNOWN(TriValidKnown_A, tri_valid_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(TriReadyKnown_A, tri_ready_o, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(VtxValidKnown_A, vtx_valid_o, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(VtxReadyKnown_A, vtx_ready_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(VtxKnown_A, vtx_valid_o ? vtx_head : '0, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(ModeKnown_A, mode_i, clk_i, !rst_ni)

  // Interface rules the unit itself must keep: a vertex offered and not taken stays, unchanged;
  // an accepted uniform patch has L in 1..64; the FSU's records are complete when the CPG writes.
  `TESS_ASSERT(VtxValidHeld_A, vtx_valid_o && !vtx_ready_i |=> vtx_valid_o, clk_i, !rst_ni)
  `TESS_ASSERT(VtxDataHeld_A, vtx_valid_o && !vtx_ready_i |=> $stable(vtx_head), clk_i, !rst_ni)
  `TESS_ASSERT(FactorInRange_A, tri_push && tri_pattern_i == tess_pkg::PatUniform
                                |-> tri_l_i >= LBits'(1) && tri_l_i <= LBits'(tess_pkg::MaxFactor), clk_i, !rst_ni)

endmodule
