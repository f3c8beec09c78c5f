// The unit's performance counters (the perf_* outputs of rtl/tess_unit.sv; the rows of
// sim/blocks/counter_registry.hpp, definitions in docs/microarchitecture.md §10). Every cycle is
// counted in exactly one class per block.
#pragma once

#include <array>
#include <cstdint>

#include "sim/blocks/counter_registry.hpp"
#include "sim/unit_io.hpp"

namespace tessim::sim {

// Per cycle it only increments a few array entries (this runs every simulated cycle); the
// per-block figures are derived when stats() is read.
class Counters {
 public:
  explicit Counters(int int_blocks) : int_blocks_(int_blocks) { reset(); }

  void reset() {
    cycles_ = triangles_in_ = vertices_out_ = 0;
    issued_hist_.fill(0);
    te_ = {};
    cpg_ = {};
  }

  std::uint64_t cycles() const { return cycles_; }
  // Cycles so far per TE class (cheap: nothing derived).
  const ClassCounts<TeClass>& te_class_cycles() const { return te_; }

  // One cycle: `issued` ops went to INT blocks 0..issued-1.
  void count(int issued, TeClass te, CpgClass cpg, bool tri_push, bool vtx_pop) {
    count(issued, te, cpg, 1);
    triangles_in_ += tri_push;
    vertices_out_ += vtx_pop;
  }
  // `cycles` identical cycles that move no data (fast-forwarded).
  void count(int issued, TeClass te, CpgClass cpg, std::uint64_t cycles) {
    cycles_ += cycles;
    issued_hist_[static_cast<std::size_t>(issued)] += cycles;
    te_[te] += cycles;
    cpg_[cpg] += cycles;
  }

  const UnitCounters& stats() const {
    UnitCounters& s = stats_;
    s.cycles = cycles_;
    s.triangles_in = triangles_in_;
    s.vertices_out = vertices_out_;
    s.int_blocks = int_blocks_;
    // Block i was busy in every cycle that issued more than i ops.
    std::uint64_t busy = cycles_;
    for (int i = 0; i < int_blocks_; ++i) {
      busy -= issued_hist_[static_cast<std::size_t>(i)];
      s.int_busy[static_cast<std::size_t>(i)] = busy;
    }
    s.te = te_;
    s.cpg = cpg_;
    return s;
  }

 private:
  int int_blocks_;
  std::uint64_t cycles_ = 0, triangles_in_ = 0, vertices_out_ = 0;
  std::array<std::uint64_t, kMaxIntBlocks + 1> issued_hist_{};  // index k: cycles that issued k ops
  ClassCounts<TeClass> te_;
  ClassCounts<CpgClass> cpg_;
  mutable UnitCounters stats_;  // derived on read
};

}  // namespace tessim::sim
