// The run's guard against a hang of the cycle model: the unit never deadlocks (every wait in
// docs/microarchitecture.md §5-§9 ends by itself), so a run that accepts no vertex for longer
// than any of those waits can take is an internal error.
#pragma once

#include <cstdint>

#include "sim/config/config.hpp"

namespace tessim::sim {

class Watchdog {
 public:
  // `cpg_cycles`: C of the unit (Unit::cpg_cycles); scalar tags add their margin.
  Watchdog(const UnitConfig& cfg, int cpg_cycles);

  std::uint64_t limit() const { return limit_; }
  // A vertex accepted in `cycle`.
  void progress(std::uint64_t cycle) { last_ = cycle; }
  // How many cycles the run may skip at once from `cycle` (never past the one at which check() fires).
  std::uint64_t cycles_left(std::uint64_t cycle) const { return limit_ + 1 - (cycle - last_); }
  // Throws std::logic_error once the run has gone past the limit without a vertex.
  void check(std::uint64_t cycle) const {
    if (cycle - last_ > limit_) fire(cycle);
  }

 private:
  [[noreturn]] void fire(std::uint64_t cycle) const;

  std::uint64_t limit_;
  std::uint64_t last_ = 0;  // the cycle of the last accepted vertex
};

}  // namespace tessim::sim
