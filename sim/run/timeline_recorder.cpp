#include "sim/run/timeline_recorder.hpp"

namespace tessim::sim {

namespace {

// The run's counts from cycle 0 in the timeline's terms.
Timeline::Bucket run_totals(const Unit& unit, const Gpe& gpe) {
  Timeline::Bucket t;
  t.te = unit.te_class_cycles();
  const UnitCounters& s = unit.stats();
  for (std::uint64_t busy : s.int_busy_used()) t.int_busy += busy;
  t.cpg_busy = s.cpg[CpgClass::Busy];
  t.vertices = s.vertices_out;
  t.gpe = gpe.stats();
  return t;
}

}  // namespace

void TimelineRecorder::close(const Unit& unit, const Gpe& gpe) {
  timeline_.close(run_totals(unit, gpe));
  end_ = timeline_.next_boundary();
}

void TimelineRecorder::stretch_done(std::uint64_t cycles, const Unit& unit, const Gpe& gpe, GpeClass gpe_class) {
  // A stretch past a boundary is one of identical cycles (an issuing one ends there at most).
  if (cycles < end_) return;
  const CycleActivity& a = unit.activity();
  timeline_.close_within(run_totals(unit, gpe), cycles, Timeline::quiet_cycle(a.te, a.cpg, gpe_class));
  end_ = timeline_.next_boundary();
}

void TimelineRecorder::finish(std::uint64_t cycles, const Unit& unit, const Gpe& gpe) {
  timeline_.finish(run_totals(unit, gpe), cycles);
}

}  // namespace tessim::sim
