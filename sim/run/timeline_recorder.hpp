// A run's Timeline (sim/values/timeline.hpp) filled as the run goes: the unit's and the GPE's
// cumulative counters are read at the bucket boundaries only, so a cycle costs one comparison.
#pragma once

#include <cstdint>

#include "sim/ge/gpe.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/timeline.hpp"

namespace tessim::sim {

class TimelineRecorder {
 public:
  explicit TimelineRecorder(Timeline& timeline) : timeline_(timeline), end_(timeline.next_boundary()) {}

  // The cycle count at which the current bucket ends: a fast-forwarded stretch of cycles in which
  // the TE issues must stop there (its cycles are not all alike).
  std::uint64_t next_boundary() const { return end_; }
  // The run has done `cycles` cycles, the last one stepped alone.
  void cycle_done(std::uint64_t cycles, const Unit& unit, const Gpe& gpe) {
    if (cycles == end_) close(unit, gpe);
  }
  // The run has done `cycles` cycles, the last ones a fast-forwarded stretch of identical quiet
  // cycles in which the GPE's class was `gpe_class`.
  void stretch_done(std::uint64_t cycles, const Unit& unit, const Gpe& gpe, GpeClass gpe_class);
  // The run ended after `cycles` cycles.
  void finish(std::uint64_t cycles, const Unit& unit, const Gpe& gpe);

 private:
  void close(const Unit& unit, const Gpe& gpe);

  Timeline& timeline_;
  std::uint64_t end_;
};

}  // namespace tessim::sim
