#include "sim/ge/ge_evaluation.hpp"

#include <stdexcept>

namespace tessim::sim {

namespace {

// Cycles the CPG stage takes per triangle: the dedicated CPG's C, the GE program's cycles, or one
// for the host's control points (accept, then write into the buffer).
int cpg_stage_cycles(const UnitConfig& cfg) {
  switch (cfg.cpg_mapping) {
    case CpgMapping::Dedicated: return cpg_cycles(cfg.normals, cfg.format, cfg.cpg);
    case CpgMapping::Gpe: return cfg.cpg_gpe_cycles;
    case CpgMapping::Host: return 1;
  }
  return 1;
}

const UnitConfig& checked(const UnitConfig& cfg) {
  if (cfg.evaluation != Evaluation::Gpe) throw std::invalid_argument("GeEvaluationUnit: evaluation must be gpe");
  return cfg;
}

}  // namespace

GeEvaluationUnit::GeEvaluationUnit(const UnitConfig& cfg)
    : tri_fifo_(checked(cfg).tri_fifo_depth),
      cpg_(cfg.cpg.copies, cfg.normals, cfg.format, cpg_stage_cycles(cfg), cfg.cpg_mapping == CpgMapping::Gpe,
           cfg.cpg_tags != 0 && cfg.cpg_mapping == CpgMapping::Dedicated, cfg.cpg),
      buffers_(cfg.cp_buffers),
      dpg_(cfg.format),
      vtx_fifo_(cfg.vtx_fifo_depth),
      counters_(0) {
  reset();
}

void GeEvaluationUnit::reset() {
  tri_fifo_.reset();
  cpg_.reset();
  buffers_.reset();
  dpg_.reset();
  vtx_fifo_.reset();
  counters_.reset();
}

void GeEvaluationUnit::tick(const UnitInputs& in) {
  // ---- Decisions from the registered state and the inputs.
  const BoundaryCycle boundary = boundary_cycle(in, tri_fifo_.full(), vtx_fifo_.empty());
  const bool tri_push = boundary.tri_push, vtx_pop = boundary.vtx_pop;
  const bool point_available = buffers_.rd_full();
  const bool hand_out = point_available && !vtx_fifo_.full();
  const CpgArray::Actions cpg = cpg_.decide(!tri_fifo_.empty(), buffers_.wr_empty(), in.cpg_step);
  const TeClass dpg_class = hand_out          ? TeClass::Busy
                            : point_available ? TeClass::BlockedByGpe
                            : cpg_.busy() || !tri_fifo_.empty() ? TeClass::StarvedByCpg
                                                                : TeClass::Idle;
  counters_.count(0, dpg_class, cpg_.classify(cpg), boundary.events);

  // ---- The clock edge. The GE's acceptance of a patch's last point frees its buffer.
  if (vtx_pop && vtx_fifo_.front().point.last) buffers_.release(vtx_fifo_.front().buffer);
  if (hand_out) {
    const ControlPointBuffer::Entry& e = buffers_.rd();
    GePoint& slot = vtx_fifo_.tail();
    slot.point = dpg_.point(e);
    slot.buffer = buffers_.rd_ptr();
    slot.id = e.id;
    dpg_.consume(e);
    if (slot.point.last) buffers_.drain();
  }
  vtx_fifo_.commit(hand_out, vtx_pop);
  const bool tri_pop = cpg_.accepts(cpg);
  cpg_.commit(cpg, tri_fifo_.front(), buffers_);
  if (tri_push) tri_fifo_.tail() = in.tri;
  tri_fifo_.commit(tri_push, tri_pop);
}

}  // namespace tessim::sim
