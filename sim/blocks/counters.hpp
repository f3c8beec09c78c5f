// The unit's performance counters (the perf_* outputs of rtl/tess_unit.sv; the rows of
// sim/base/counter_registry.hpp, definitions in docs/microarchitecture.md §10). Every cycle is
// counted in exactly one class per block.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "sim/base/counter_registry.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// The run counters (registry block Run) one cycle increments besides `cycles`: one bit per
// RunCounter, set by the block that decides the event (Unit::tick).
using RunEvents = std::uint32_t;
static_assert(row_count(CounterBlock::Run) <= 32, "RunEvents has a bit per run counter");
constexpr RunEvents run_event(RunCounter c) { return RunEvents{1} << static_cast<unsigned>(c); }

// A cycle's handshakes at the unit's boundary and the run counters they increment: a triangle
// pushed into the TRI FIFO (triangles_in) or offered and refused (tri_stalls), a vertex popped
// from the VTX FIFO (vertices_out) or offered and refused (vtx_stalls). One definition for sim::Unit and the unit without TE of
// evaluation gpe (GeEvaluationUnit), whose boundaries are the same.
struct BoundaryCycle {
  bool tri_push = false;
  bool vtx_pop = false;
  RunEvents events = 0;
};
constexpr BoundaryCycle boundary_cycle(const UnitInputs& in, bool tri_fifo_full, bool vtx_fifo_empty) {
  const bool tri_push = in.tri_valid && !tri_fifo_full;
  const bool vtx_pop = in.vtx_ready && !vtx_fifo_empty;
  return {tri_push, vtx_pop,
          (tri_push ? run_event(RunCounter::TrianglesIn) : 0) | (vtx_pop ? run_event(RunCounter::VerticesOut) : 0) |
              (in.tri_valid && !tri_push ? run_event(RunCounter::TriStalls) : 0) |
              (!vtx_fifo_empty && !in.vtx_ready ? run_event(RunCounter::VtxStalls) : 0)};
}

// Per cycle it only increments a few array entries (this runs every simulated cycle); the
// per-block figures are derived when stats() is read.
class Counters {
 public:
  explicit Counters(int int_blocks) : int_blocks_(int_blocks) { reset(); }

  void reset() {
    run_.fill(0);
    issued_hist_.fill(0);
    te_ = {};
    cpg_ = {};
  }

  std::uint64_t cycles() const { return run_[static_cast<std::size_t>(RunCounter::Cycles)]; }
  // Cycles so far per TE class (cheap: nothing derived).
  const ClassCounts<TeClass>& te_class_cycles() const { return te_; }

  // `cycles` identical cycles (one, or a fast-forwarded stretch that moves no data): `issued` ops
  // went to INT blocks 0..issued-1 in each, and each had the run events `events`.
  void count(int issued, TeClass te, CpgClass cpg, RunEvents events, std::uint64_t cycles = 1) {
    events |= run_event(RunCounter::Cycles);
    for (; events != 0; events &= events - 1) run_[static_cast<std::size_t>(std::countr_zero(events))] += cycles;
    issued_hist_[static_cast<std::size_t>(issued)] += cycles;
    te_[te] += cycles;
    cpg_[cpg] += cycles;
  }

  // A run event counted apart from its cycle (a triangle injected by a threaded system run).
  void add_event(RunCounter c) { ++run_[static_cast<std::size_t>(c)]; }

  const UnitCounters& stats() const {
    UnitCounters& s = stats_;
#define TESSIM_RUN_STAT(BLOCK, ID, KEY, ...) s.KEY = run_[static_cast<std::size_t>(RunCounter::ID)];
    TESSIM_RUN_COUNTERS(TESSIM_RUN_STAT)
#undef TESSIM_RUN_STAT
    s.int_blocks = int_blocks_;
    // Block i was busy in every cycle that issued more than i ops.
    std::uint64_t busy = cycles();
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
  std::array<std::uint64_t, row_count(CounterBlock::Run)> run_{};
  std::array<std::uint64_t, kMaxIntBlocks + 1> issued_hist_{};  // index k: cycles that issued k ops
  ClassCounts<TeClass> te_;
  ClassCounts<CpgClass> cpg_;
  mutable UnitCounters stats_;  // derived on read
};

}  // namespace tessim::sim
