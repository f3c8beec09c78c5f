// A system of Units tessellation units on one triangle stream (docs/microarchitecture.md §13;
// sim/system/system.hpp UnitSystem, its cycle-by-cycle specification): a distributor hands each
// triangle, or batch of DispatchBatch triangles, to a unit by its policy (tess_distributor); a
// reassembly buffer of ReorderSlots vertex slots shared by the units puts their output back in
// stream order for GePorts geometry-engine ports (tess_reassembly), so the system's output is a
// single unit's, vertex for vertex.
//
// Timing as the unit's (§2), with two exceptions that UnitSystem::tick specifies: with
// earliest_finish, tri_ready_o depends on the offered triangle's pattern descriptor (the choice
// weighs its vertex count); and ge_valid_o[p] / port p's vertex depend on ge_ready_i[p-1:0]
// (port p is offered the vertex after those the ready ports before it take). ge_ready_i must
// not depend on ge_valid_o. Every other output is a function of registered state.
//
// cpg_weight_i = (C + 1) N and te_weight_i = ops Mc (C the CPG's cycles a patch and ops the INT
// operations a vertex in the run's normal mode: sim::cpg_cycles, int_ops::ops_per_vertex) are
// static during a run, like mode_i; only earliest_finish reads them. RuntimeConfig = 1 takes the
// policy, the batch and the slots in use from cfg_*_i (static during a run; the Verilated test
// builds cover every policy, batch and R <= ReorderSlots with one model each); 0 from the
// parameters, the inputs unused.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_system #(
  parameter int unsigned Units         = 2,   // M
  parameter int unsigned GePorts       = 1,   // P
  parameter int unsigned ReorderSlots  = 256, // R
  parameter int unsigned Distribution  = 0,   // 0 round_robin, 1 least_loaded, 2 earliest_finish
  parameter int unsigned DispatchBatch = 1,   // 1..64
  parameter int unsigned RuntimeConfig = 0,
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
  localparam int unsigned AlphaW       = AlphaBits + 1,
  localparam int unsigned SCW          = $clog2(ReorderSlots + 1),
  localparam int unsigned FacW         = tess_pkg::FactorBits,
  localparam int unsigned IdW          = tess_pkg::IdBits
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  input  logic [tess_pkg::ModeBits-1:0]    mode_i,
  // Static configuration of a run
  input  logic [1:0]                       cfg_distribution_i,  // RuntimeConfig only
  input  logic [6:0]                       cfg_batch_i,         // RuntimeConfig only, 1..64
  input  logic [SCW-1:0]                   cfg_slots_i,         // RuntimeConfig only, 2..ReorderSlots
  input  logic [15:0]                      cpg_weight_i,
  input  logic [15:0]                      te_weight_i,
  // Triangles in (tess_unit's input stream)
  input  logic                             tri_valid_i,
  output logic                             tri_ready_o,
  input  logic [9*W-1:0]                   tri_p_i,
  input  logic [9*W-1:0]                   tri_n_i,
  input  logic [FacW-1:0]                  tri_l_i,
  input  logic [tess_pkg::PatternBits-1:0] tri_pattern_i,
  input  logic [4*tess_pkg::FixBits-1:0]   tri_factors_i,
  input  logic [IdW-1:0]                   tri_id_i,
  input  logic [18*W-1:0]                  tri_tags_i,
  input  logic [3*AlphaW-1:0]              tri_alpha_i,
  // Geometry-engine ports: port p's fields at [p X +: X], X each field's width in tess_unit
  output logic [GePorts-1:0]               ge_valid_o,
  input  logic [GePorts-1:0]               ge_ready_i,
  output logic [GePorts*3*W-1:0]           ge_pos_o,
  output logic [GePorts*3*W-1:0]           ge_nrm_o,
  output logic [GePorts*(BaryBits+1)-1:0]  ge_u_o,
  output logic [GePorts*(BaryBits+1)-1:0]  ge_v_o,
  output logic [GePorts*FacW-1:0]          ge_j_o,
  output logic [GePorts*FacW-1:0]          ge_k_o,
  output logic [GePorts*FacW-1:0]          ge_l_o,
  output logic [GePorts*tess_pkg::IndexBits-1:0] ge_index_o,
  output logic [GePorts*IdW-1:0]           ge_id_o,
  output logic [GePorts-1:0]               ge_last_o,
  output logic [GePorts*tess_pkg::FlagBits-1:0]  ge_flags_o
);

  localparam int unsigned UW     = (Units > 1) ? $clog2(Units) : 1;
  localparam int unsigned BW     = BaryBits + 1;
  localparam int unsigned IxW    = tess_pkg::IndexBits;
  localparam int unsigned FlagW  = tess_pkg::FlagBits;
  localparam int unsigned CtrW   = tess_pkg::CounterBits;
  localparam int unsigned VtxW   = tess_pkg::vtx_w(W, BaryBits);
  localparam int unsigned UnitPatches = tess_pkg::unit_patches(TriFifoDepth, CpgCopies, CpBuffers, VtxFifoDepth);
  localparam int unsigned NumCtr = tess_pkg::num_ctrs(IntBlocks);

  // ------------------------------------------------------------------ distributor
  logic [Units-1:0] unit_tri_ready, unit_tri_valid, admit, admit_last, unit_vtx_valid;
  logic             take;
  logic [UW-1:0]    target;
  tess_distributor #(
    .Units        (Units),
    .Distribution (Distribution),
    .DispatchBatch(DispatchBatch),
    .RuntimeConfig(RuntimeConfig),
    .UnitPatches  (UnitPatches)
  ) u_distributor (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .policy_i        (cfg_distribution_i),
    .batch_i         (cfg_batch_i),
    .cpg_weight_i    (cpg_weight_i),
    .te_weight_i     (te_weight_i),
    .tri_valid_i     (tri_valid_i),
    .tri_ready_o     (tri_ready_o),
    .tri_l_i         (tri_l_i),
    .tri_pattern_i   (tri_pattern_i),
    .tri_factors_i   (tri_factors_i),
    .unit_tri_ready_i(unit_tri_ready),
    .unit_tri_valid_o(unit_tri_valid),
    .take_o          (take),
    .target_o        (target),
    .admit_i         (admit),
    .admit_last_i    (admit_last)
  );

  // ------------------------------------------------------------------ units
  logic [Units*VtxW-1:0] unit_vtx;
  for (genvar u = 0; u < Units; u++) begin : g_unit
    logic [3*W-1:0]  pos, nrm;
    logic [BW-1:0]   bu, bv;
    logic [FacW-1:0] j, k, l;
    logic [IxW-1:0]  index;
    logic [IdW-1:0]  id;
    logic            last;
    logic [FlagW-1:0] flags;
    logic [NumCtr*CtrW-1:0] perf;  // the unit's counters, indexed by tess_pkg::ctr_e
    tess_unit #(
      .CoordIntBits (CoordIntBits),
      .CoordFracBits(CoordFracBits),
      .BaryBits     (BaryBits),
      .AlphaBits    (AlphaBits),
      .IntBlocks    (IntBlocks),
      .IntLatency   (IntLatency),
      .Contexts     (Contexts),
      .TriFifoDepth (TriFifoDepth),
      .VtxFifoDepth (VtxFifoDepth),
      .CpBuffers    (CpBuffers),
      .CpgLanes     (CpgLanes),
      .CpgDigitBits (CpgDigitBits),
      .CpgProductReg(CpgProductReg),
      .CpgTags      (CpgTags),
      .CpgCopies    (CpgCopies),
      .InjectBug    (InjectBug)
    ) u_unit (
      .clk_i                    (clk_i),
      .rst_ni                   (rst_ni),
      .mode_i                   (mode_i),
      .tri_valid_i              (unit_tri_valid[u]),
      .tri_ready_o              (unit_tri_ready[u]),
      .tri_p_i                  (tri_p_i),
      .tri_n_i                  (tri_n_i),
      .tri_l_i                  (tri_l_i),
      .tri_pattern_i            (tri_pattern_i),
      .tri_factors_i            (tri_factors_i),
      .tri_id_i                 (tri_id_i),
      .tri_tags_i               (tri_tags_i),
      .tri_alpha_i              (tri_alpha_i),
      .vtx_valid_o              (unit_vtx_valid[u]),
      .vtx_ready_i              (admit[u]),
      .vtx_pos_o                (pos),
      .vtx_nrm_o                (nrm),
      .vtx_u_o                  (bu),
      .vtx_v_o                  (bv),
      .vtx_j_o                  (j),
      .vtx_k_o                  (k),
      .vtx_l_o                  (l),
      .vtx_index_o              (index),
      .vtx_id_o                 (id),
      .vtx_last_o               (last),
      .vtx_flags_o              (flags),
      .perf_ctr_o               (perf)
    );
    // The vertex word of tess_unit's VTX FIFO: {flags, last, id, index, l, k, j, v, u, nrm, pos}.
    assign unit_vtx[u*VtxW +: VtxW] = {flags, last, id, index, l, k, j, bv, bu, nrm, pos};
    assign admit_last[u] = last;
    // The units' own counters are not part of the system's interface.
    logic unused_counters;
    assign unused_counters = ^perf;
  end

  // ------------------------------------------------------------------ reassembly buffer
  logic [GePorts*VtxW-1:0] port_vtx;
  tess_reassembly #(
    .Units        (Units),
    .GePorts      (GePorts),
    .ReorderSlots (ReorderSlots),
    .RuntimeConfig(RuntimeConfig),
    .UnitPatches  (UnitPatches),
    .VtxW         (VtxW),
    .IdLsb        (VtxW - FlagW - 1 - IdW),
    .LastBit      (VtxW - FlagW - 1)
  ) u_reassembly (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .slots_i     (cfg_slots_i),
    .unit_valid_i(unit_vtx_valid),
    .unit_vtx_i  (unit_vtx),
    .unit_ready_o(admit),
    .push_i      (take),
    .push_unit_i (target),
    .push_id_i   (tri_id_i),
    .port_valid_o(ge_valid_o),
    .port_ready_i(ge_ready_i),
    .port_vtx_o  (port_vtx)
  );

  for (genvar p = 0; p < GePorts; p++) begin : g_port
    assign {ge_flags_o[p*FlagW +: FlagW], ge_last_o[p], ge_id_o[p*IdW +: IdW], ge_index_o[p*IxW +: IxW],
            ge_l_o[p*FacW +: FacW], ge_k_o[p*FacW +: FacW], ge_j_o[p*FacW +: FacW], ge_v_o[p*BW +: BW],
            ge_u_o[p*BW +: BW], ge_nrm_o[p*3*W +: 3*W], ge_pos_o[p*3*W +: 3*W]} = port_vtx[p*VtxW +: VtxW];
  end

  // The systems sim::UnitConfig accepts (sim/config/params.cpp, UnitConfig::validate).
  `TESS_ASSERT_PARAM(UnitsRange_A, Units >= 1 && Units <= 16)
  `TESS_ASSERT_PARAM(GePortsRange_A, GePorts >= 1 && GePorts <= 16)
  `TESS_ASSERT_PARAM(ReorderSlotsRange_A, ReorderSlots >= 2 && ReorderSlots <= 65536)
  `TESS_ASSERT_PARAM(DistributionRange_A, Distribution <= 2)
  `TESS_ASSERT_PARAM(DispatchBatchRange_A, DispatchBatch >= 1 && DispatchBatch <= 64)
  `TESS_ASSERT_PARAM(RuntimeConfigRange_A, RuntimeConfig <= 1)

  // The system's handshakes are never X out of reset; a GE port's vertex offered and not taken
  // is offered, unchanged, in the next cycle (as tess_unit's VTX port).
  `TESS_ASSERT_KNOWN(TriValidKnown_A, tri_valid_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(TriReadyKnown_A, tri_ready_o, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(GeValidKnown_A, ge_valid_o, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(GeReadyKnown_A, ge_ready_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(AdmitKnown_A, admit, clk_i, !rst_ni)

endmodule
