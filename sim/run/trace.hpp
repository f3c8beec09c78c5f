// Chrome / Perfetto trace of a cycle-model run (JSON trace event format, open it in
// ui.perfetto.dev or chrome://tracing). One microsecond on the timeline is one cycle.
// Tracks: the CPG's action (a slice per action and triangle, with the triangle's id), the TE's
// and the GPE's class of each cycle (runs of equal cycles merged), one per INT block (a slice
// per issued op, with its vertex, patch and context), one per TE context (a slice per vertex
// from allocation to retirement), flows from each patch's CPG write to the allocation of each of
// its vertices, and counters for the TRI FIFO, the VTX FIFO and the contexts in use.
// Only a window of cycles is recorded; a path ending in .gz is written gzip-compressed (the
// Perfetto UI opens .json.gz as it is). docs/statistics.md gives the bytes per cycle.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "model/base/output_file.hpp"
#include "sim/run/hooks.hpp"

namespace tessim::sim {

// The cycles recorded: [from, to).
struct TraceWindow {
  std::uint64_t from = 0;
  std::uint64_t to = 20000;
};

class TraceWriter : public CycleObserver {
 public:
  TraceWriter(const std::filesystem::path& path, int int_blocks, int contexts, TraceWindow window);
  ~TraceWriter() override;

  bool on_cycle(const Unit& unit, const GpeCycle& gpe) override;
  // Closes the open slices and moves the file into place (nothing is written before).
  void finish();

 private:
  struct Span {
    const char* name = nullptr;
    std::uint32_t triangle = 0;
    bool has_triangle = false;
    std::uint64_t start = 0;
  };
  struct Vertex {  // the vertex a context holds
    bool valid = false;
    std::uint64_t vertex = 0;
    std::uint32_t patch = 0;
    std::uint64_t start = 0;
  };
  void close_span(Span& span, int tid, std::uint64_t end);
  void update_span(Span& span, int tid, const char* name, std::uint64_t cycle, bool has_triangle = false,
                   std::uint32_t triangle = 0);
  void close_vertex(int context, std::uint64_t end);
  void counter(const char* name, int value, std::uint64_t ts);
  void event(const char* json);

  AtomicOutput out_;
  std::unique_ptr<std::streambuf> gzip_;  // deflates into out_ when the path ends in .gz
  std::unique_ptr<std::ostream> gzip_stream_;
  std::ostream* os_ = nullptr;
  TraceWindow window_;
  int contexts_ = 1;
  std::uint64_t last_cycle_ = 0;  // one past the last recorded cycle
  bool first_event_ = true;
  bool finished_ = false;
  Span cpg_, te_, gpe_;
  std::vector<Vertex> in_context_;
  std::deque<std::pair<std::uint32_t, std::uint64_t>> writes_;  // (patch, cycle of its CPG write)
  int tri_count_ = -1, vtx_count_ = -1, contexts_in_use_ = -1;
};

}  // namespace tessim::sim
