// A cycle observer (sim/run/hooks.hpp) for `tessim sim --schedule`: how the INT blocks are used
// cycle by cycle and how often vertices retire.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/run/hooks.hpp"

namespace tessim::sim {

// Records the issue pattern of the first cycles and the retirement cycle of the first vertices:
// the input of `tessim sim --schedule` and docs/schedule.md.
class ScheduleRecorder : public CycleObserver {
 public:
  explicit ScheduleRecorder(int table_cycles = 48, std::size_t max_vertices = 8192);
  bool on_cycle(const Unit& unit, const GpeCycle& gpe) override;

  // Cycles per vertex between retirements over the last whole multiple of 2520 vertices within
  // the second half of the recorded vertices (so any schedule period of up to 10 vertices
  // averages exactly); 0 when fewer than 16 vertices retired.
  double steady_cycles_per_vertex() const;
  // The issue table: one row per cycle from the first issue, one column per INT block,
  // cells "v<vertex>.<op>", plus allocation and retirement of the cycle.
  std::string table(int int_blocks) const;

 private:
  struct Row {
    std::uint64_t cycle;
    std::vector<IssuedOp> ops;
    bool allocated, retired;
    std::uint64_t allocated_vertex, retired_vertex;
    TeClass te;
  };
  int table_cycles_;
  std::size_t max_vertices_;
  std::vector<Row> rows_;
  std::vector<std::uint64_t> retire_cycles_;
};

}  // namespace tessim::sim
