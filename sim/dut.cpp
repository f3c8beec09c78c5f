#include "sim/dut.hpp"

namespace tessim::sim {

UnitCounters counters_of(const UnitStats& s) {
  UnitCounters c;
  c.cycles = s.cycles;
  c.triangles_in = s.triangles_in;
  c.vertices_out = s.vertices_out;
  for (std::size_t i = 0; i < s.int_blocks.size() && i < c.int_busy.size(); ++i) c.int_busy[i] = s.int_blocks[i].busy;
  c.te_context_limited = s.te.context_limited;
  c.te_int_limited = s.te.int_limited;
  c.te_busy = s.te.busy;
  c.te_blocked_by_gpe = s.te.blocked_by_gpe;
  c.te_starved_by_cpg = s.te.starved_by_cpg;
  c.te_idle = s.te.idle;
  c.te_pipeline = s.te.pipeline;
  c.cpg_busy = s.cpg.busy;
  c.cpg_blocked = s.cpg.blocked;
  c.cpg_wait_gpe = s.cpg.wait_gpe;
  c.cpg_idle = s.cpg.idle;
  return c;
}

}  // namespace tessim::sim
