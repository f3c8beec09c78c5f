// Distributor of a system of units (sim/system/system.cpp UnitSystem::choose and the dispatch part of
// UnitSystem::tick): hands the offered triangle, or a batch of DispatchBatch of them, to one of
// the Units units by its policy, and keeps per unit the patches and vertices dispatched to it and
// not yet admitted into the reassembly buffer (a patch leaves with its last vertex).
//
//   round_robin     (0): unit i mod M for triangle (batch) i, waiting for it when its TRI FIFO is full
//   least_loaded    (1): among the units whose TRI FIFO has room, the fewest vertices outstanding
//                        (lowest index on a tie); none with room: the round-robin turn
//   earliest_finish (2): among them, the least max((patches + 1) cpg_weight, (vertices + n) te_weight),
//                        n the offered patch's vertices (lowest index on a tie); none: the turn
//
// The choice comes from registered state (pending counts, turn, batch, the units' tri_ready),
// and for earliest_finish also from the offered triangle's pattern descriptor: with that policy
// tri_ready_o depends combinationally on tri_*_i (as UnitSystem::tick specifies it).
//
// RuntimeConfig = 1 takes the policy and the batch from policy_i and batch_i (static during a
// run: the Verilated test builds cover every policy with one model); 0 from the parameters.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_distributor #(
  parameter int unsigned Units         = 2,
  parameter int unsigned Distribution  = 0,  // 0 round_robin, 1 least_loaded, 2 earliest_finish
  parameter int unsigned DispatchBatch = 1,  // 1..64
  parameter int unsigned RuntimeConfig = 0,
  // Patches a unit can hold at once (TRI FIFO, CPG copies, buffers, VTX FIFO, one more): bounds
  // the pending counters.
  parameter int unsigned UnitPatches   = tess_pkg::unit_patches(tess_pkg::TriFifoDepth, tess_pkg::CpgCopies,
                                                                tess_pkg::CpBuffers, tess_pkg::VtxFifoDepth),
  localparam int unsigned UW     = (Units > 1) ? $clog2(Units) : 1,
  localparam int unsigned PatW   = $clog2(UnitPatches + 1) + 1,
  localparam int unsigned VtxCW  = PatW + tess_pkg::IndexBits,
  localparam int unsigned WeightW = 16,
  localparam int unsigned BatchW = 7
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  input  logic [1:0]                       policy_i,       // read with RuntimeConfig only
  input  logic [BatchW-1:0]                batch_i,        // 1..64, read with RuntimeConfig only
  input  logic [WeightW-1:0]               cpg_weight_i,   // (C + 1) N, static during a run
  input  logic [WeightW-1:0]               te_weight_i,    // ops Mc, static during a run
  // The offered triangle's pattern descriptor
  input  logic                             tri_valid_i,
  output logic                             tri_ready_o,
  input  logic [tess_pkg::FactorBits-1:0]  tri_l_i,
  input  logic [tess_pkg::PatternBits-1:0] tri_pattern_i,
  input  logic [4*tess_pkg::FixBits-1:0]   tri_factors_i,
  // The units' TRI FIFOs
  input  logic [Units-1:0]                 unit_tri_ready_i,
  output logic [Units-1:0]                 unit_tri_valid_o,
  // The dispatch, for the order FIFO
  output logic                             take_o,
  output logic [UW-1:0]                    target_o,
  // Vertices admitted into the reassembly buffer this cycle, and whether each is its patch's last
  input  logic [Units-1:0]                 admit_i,
  input  logic [Units-1:0]                 admit_last_i
);

  localparam int unsigned FinW = VtxCW + 1 + WeightW;

  logic [1:0]        policy;
  logic [BatchW-1:0] batch;
  if (RuntimeConfig != 0) begin : g_runtime
    assign policy = policy_i;
    assign batch  = batch_i;
  end else begin : g_fixed
    assign policy = 2'(Distribution);
    assign batch  = BatchW'(DispatchBatch);
    logic unused_cfg;
    assign unused_cfg = ^{policy_i, batch_i};
  end

  // ------------------------------------------------------------------ registered state
  (* mem2reg *) logic [PatW-1:0]  pend_pat_q [Units];
  (* mem2reg *) logic [VtxCW-1:0] pend_vtx_q [Units];
  (* mem2reg *) logic [PatW-1:0]  pend_pat_d [Units];
  (* mem2reg *) logic [VtxCW-1:0] pend_vtx_d [Units];
  logic [UW-1:0]     batch_unit_q, batch_unit_d, next_rr_q, next_rr_d;
  logic [BatchW-1:0] batch_left_q, batch_left_d;

  // ------------------------------------------------------------------ the choice
  logic [tess_pkg::IndexBits-1:0] count;
  tess_patch_count u_count (
    .l_i      (tri_l_i),
    .pattern_i(tri_pattern_i),
    .factors_i(tri_factors_i),
    .count_o  (count)
  );

  logic [UW-1:0]    ll_best, ef_best, target;
  logic             ll_found, ef_found;
  logic [VtxCW-1:0] ll_best_vtx;
  logic [FinW-1:0]  ef_best_finish;
  logic [FinW-1:0]  fin_cpg, fin_te, finish;
  always_comb begin
    ll_best = '0;
    ll_found = 1'b0;
    ll_best_vtx = '0;
    ef_best = '0;
    ef_found = 1'b0;
    ef_best_finish = '0;
    fin_cpg = '0;
    fin_te = '0;
    finish = '0;
    for (int u = 0; u < Units; u++) begin
      if (unit_tri_ready_i[u]) begin
        if (!ll_found || pend_vtx_q[u] < ll_best_vtx) begin
          ll_best = UW'(u);
          ll_best_vtx = pend_vtx_q[u];
        end
        ll_found = 1'b1;
        fin_cpg = FinW'(FinW'(pend_pat_q[u]) + FinW'(1)) * FinW'(cpg_weight_i);
        fin_te  = FinW'(FinW'(pend_vtx_q[u]) + FinW'(count)) * FinW'(te_weight_i);
        finish  = (fin_cpg > fin_te) ? fin_cpg : fin_te;
        if (!ef_found || finish < ef_best_finish) begin
          ef_best = UW'(u);
          ef_best_finish = finish;
        end
        ef_found = 1'b1;
      end
    end
  end

  always_comb begin
    if (batch_left_q != '0) target = batch_unit_q;
    else if (policy == 2'd1 && ll_found) target = ll_best;
    else if (policy == 2'd2 && ef_found) target = ef_best;
    else target = next_rr_q;
  end

  logic take;
  assign tri_ready_o = unit_tri_ready_i[target];
  assign take        = tri_valid_i && tri_ready_o;
  assign take_o      = take;
  assign target_o    = target;
  for (genvar u = 0; u < Units; u++) begin : g_valid
    assign unit_tri_valid_o[u] = tri_valid_i && target == UW'(u);
  end

  // ------------------------------------------------------------------ next state
  logic [BatchW-1:0] batch_start;
  assign batch_start = (batch_left_q == '0) ? batch : batch_left_q;
  always_comb begin
    batch_unit_d = batch_unit_q;
    batch_left_d = batch_left_q;
    next_rr_d    = next_rr_q;
    if (take) begin
      if (batch_left_q == '0) batch_unit_d = target;
      batch_left_d = batch_start - BatchW'(1);
      if (batch_start == BatchW'(1)) next_rr_d = (target == UW'(Units - 1)) ? '0 : target + UW'(1);
    end
    for (int u = 0; u < Units; u++) begin
      pend_pat_d[u] = pend_pat_q[u] + PatW'(take && target == UW'(u)) - PatW'(admit_i[u] && admit_last_i[u]);
      pend_vtx_d[u] = pend_vtx_q[u] + ((take && target == UW'(u)) ? VtxCW'(count) : '0) - VtxCW'(admit_i[u]);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      batch_unit_q <= '0;
      batch_left_q <= '0;
      next_rr_q    <= '0;
    end else begin
      batch_unit_q <= batch_unit_d;
      batch_left_q <= batch_left_d;
      next_rr_q    <= next_rr_d;
    end
  end
  for (genvar u = 0; u < Units; u++) begin : g_pending
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        pend_pat_q[u] <= '0;
        pend_vtx_q[u] <= '0;
      end else begin
        pend_pat_q[u] <= pend_pat_d[u];
        pend_vtx_q[u] <= pend_vtx_d[u];
      end
    end
    // The counters never wrap: a unit holds at most UnitPatches patches.
    logic pending_in_range;
    assign pending_in_range = pend_pat_q[u] <= PatW'(UnitPatches);
    `TESS_ASSERT(PendingInRange_A, pending_in_range, clk_i, !rst_ni)
  end

  `TESS_ASSERT(BatchInRange_A, batch >= BatchW'(1) && batch <= BatchW'(64), clk_i, !rst_ni)
  `TESS_ASSERT(PolicyKnown_A, policy != 2'd3, clk_i, !rst_ni)

endmodule
