// The limit line's counts (SimResult::gpe_waited and te_late; docs/statistics.md): the cycles
// after its first vertex in which the GPE waited for the next one, and the TE's classes over the
// late vertex intervals. An interval runs from the cycle after one accepted vertex up to and
// including the next acceptance; it is late when the GPE waited in it.
#pragma once

#include <cstdint>

#include "sim/base/counter_registry.hpp"

namespace tessim::sim {

class LateIntervals {
 public:
  // `cycles` cycles in which the GPE was ready and found no vertex, after its first vertex.
  void waited(std::uint64_t cycles) {
    gpe_waited_ += cycles;
    late_ = true;
  }
  // A vertex accepted; `te`: the TE's class counts from cycle 0 to the end of the accepting cycle.
  void accepted(const ClassCounts<TeClass>& te) {
    if (late_) te_late_ += te - start_;
    start_ = te;
    late_ = false;
  }
  std::uint64_t gpe_waited() const { return gpe_waited_; }
  const ClassCounts<TeClass>& te_late() const { return te_late_; }

 private:
  std::uint64_t gpe_waited_ = 0;
  ClassCounts<TeClass> te_late_;
  ClassCounts<TeClass> start_;  // the counts at the end of the last accepting cycle
  bool late_ = false;           // the GPE waited in the current interval
};

}  // namespace tessim::sim
