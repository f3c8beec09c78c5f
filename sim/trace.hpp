// Chrome / Perfetto trace of a cycle-model run (JSON trace event format, open it in
// ui.perfetto.dev or chrome://tracing). One microsecond on the timeline is one cycle.
// Tracks: one per INT block (a complete event per issued op, named "op<o> v<vertex>"), the
// CPG's action, the TE's and the GPE's class of each cycle (runs of equal cycles merged), and
// counters for the TRI FIFO, the VTX FIFO and the contexts in use. Only the cycles
// [0, window) are recorded, so files stay small.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "model/output_file.hpp"
#include "sim/simulate.hpp"

namespace tessim::sim {

class TraceWriter : public CycleObserver {
 public:
  TraceWriter(const std::filesystem::path& path, int int_blocks, std::uint64_t window_cycles);
  ~TraceWriter() override;

  bool on_cycle(const Unit& unit, const GpeCycle& gpe) override;
  // Closes the open spans and moves the file into place (nothing is written before).
  void finish();

 private:
  struct Span {
    const char* name = nullptr;
    std::uint64_t start = 0;
  };
  void close_span(Span& span, int tid, std::uint64_t end);
  void update_span(Span& span, int tid, const char* name, std::uint64_t cycle);
  void counter(const char* name, int value, std::uint64_t ts);
  void event(const std::string& json);

  AtomicOutput out_;
  std::uint64_t window_;
  std::uint64_t last_cycle_ = 0;  // one past the last recorded cycle
  bool first_event_ = true;
  bool finished_ = false;
  Span cpg_, te_, gpe_;
  int tri_count_ = -1, vtx_count_ = -1, contexts_ = -1;
};

}  // namespace tessim::sim
