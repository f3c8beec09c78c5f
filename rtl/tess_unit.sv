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
  localparam int unsigned CtrW         = tess_pkg::CounterBits
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
  // Performance counters (§10; sim/unit_io.hpp UnitCounters)
  output logic [CtrW-1:0]                 perf_cycles_o,
  output logic [CtrW-1:0]                 perf_tri_in_o,
  output logic [CtrW-1:0]                 perf_vtx_out_o,
  output logic [CtrW-1:0]                 perf_tri_stalls_o,
  output logic [IntBlocks*CtrW-1:0]       perf_int_busy_o,
  output logic [CtrW-1:0]                 perf_te_context_limited_o,
  output logic [CtrW-1:0]                 perf_te_int_limited_o,
  output logic [CtrW-1:0]                 perf_te_busy_o,
  output logic [CtrW-1:0]                 perf_te_blocked_by_gpe_o,
  output logic [CtrW-1:0]                 perf_te_starved_by_cpg_o,
  output logic [CtrW-1:0]                 perf_te_idle_o,
  output logic [CtrW-1:0]                 perf_te_pipeline_o,
  output logic [CtrW-1:0]                 perf_cpg_busy_o,
  output logic [CtrW-1:0]                 perf_cpg_blocked_o,
  output logic [CtrW-1:0]                 perf_cpg_idle_o
);

  localparam int unsigned LBits  = tess_pkg::FactorBits;
  localparam int unsigned IdBits = tess_pkg::IdBits;
  localparam int unsigned FlagW  = tess_pkg::FlagBits;
  localparam int unsigned DescW  = tess_pkg::DescBits;
  localparam int unsigned TagW   = (CpgTags != 0) ? 18 * W : 0;
  localparam int unsigned AlphaWords = (AlphaBits != 0) ? 3 * AlphaW : 0;
  localparam int unsigned TriW   = 18 * W + DescW + IdBits + TagW + AlphaWords;
  localparam int unsigned VtxW   = 6 * W + 2 * (BaryBits + 1) + 3 * LBits + tess_pkg::IndexBits + IdBits + 1 + FlagW;
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
  // One increment vector, one adder each: counters[k] += inc[k] every cycle out of reset.
  localparam int unsigned NumCtr = 14 + IntBlocks;
  logic [NumCtr-1:0] ctr_inc;
  (* mem2reg *) logic [CtrW-1:0]   ctr_q [NumCtr];
  assign ctr_inc = {int_busy,
                    tri_valid_i && !tri_ready_o,  // 13: triangles refused (input back-pressure)
                    te_int_limited,             // 12
                    te_ctx_limited,             // 11
                    !cpg_busy && !cpg_blocked,  // 10: cpg idle
                    cpg_blocked,                // 9
                    cpg_busy,                   // 8
                    te_pipeline,                // 7
                    te_idle,                    // 6
                    te_starved,                 // 5
                    te_blocked,                 // 4
                    te_busy,                    // 3
                    vtx_pop,                    // 2: vertices accepted by the GPE
                    tri_push,                   // 1: triangles accepted at the input
                    1'b1};                      // 0: cycles

  for (genvar k = 0; k < NumCtr; k++) begin : g_ctr
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) ctr_q[k] <= '0;
      else if (ctr_inc[k]) ctr_q[k] <= ctr_q[k] + CtrW'(1);
    end
  end

  assign perf_cycles_o            = ctr_q[0];
  assign perf_tri_in_o            = ctr_q[1];
  assign perf_vtx_out_o           = ctr_q[2];
  assign perf_te_busy_o           = ctr_q[3];
  assign perf_te_blocked_by_gpe_o = ctr_q[4];
  assign perf_te_starved_by_cpg_o = ctr_q[5];
  assign perf_te_idle_o           = ctr_q[6];
  assign perf_te_pipeline_o       = ctr_q[7];
  assign perf_cpg_busy_o          = ctr_q[8];
  assign perf_cpg_blocked_o       = ctr_q[9];
  assign perf_cpg_idle_o          = ctr_q[10];
  assign perf_te_context_limited_o = ctr_q[11];
  assign perf_te_int_limited_o    = ctr_q[12];
  assign perf_tri_stalls_o        = ctr_q[13];
  for (genvar i = 0; i < IntBlocks; i++) begin : g_int_ctr
    assign perf_int_busy_o[i*CtrW +: CtrW] = ctr_q[14 + i];
  end

  // Interface rules the unit itself must keep: a vertex offered and not taken stays, unchanged;
  // an accepted uniform patch has L in 1..64; the FSU's records are complete when the CPG writes.
  `TESS_ASSERT(VtxValidHeld_A, vtx_valid_o && !vtx_ready_i |=> vtx_valid_o, clk_i, !rst_ni)
  `TESS_ASSERT(VtxDataHeld_A, vtx_valid_o && !vtx_ready_i |=> $stable(vtx_head), clk_i, !rst_ni)
  `TESS_ASSERT(FactorInRange_A, tri_push && tri_pattern_i == tess_pkg::PatUniform
                                |-> tri_l_i >= LBits'(1) && tri_l_i <= LBits'(tess_pkg::MaxFactor), clk_i, !rst_ni)

endmodule
