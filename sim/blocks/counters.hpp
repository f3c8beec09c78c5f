// The unit's performance counters (the perf_* outputs of rtl/tess_unit.sv; definitions in
// docs/microarchitecture.md §10). Every cycle is counted in exactly one class per block.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/blocks/cpg.hpp"
#include "sim/blocks/te.hpp"

namespace tessim::sim {

struct IntBlockStats {
  std::uint64_t busy = 0;
  std::uint64_t idle = 0;
  bool operator==(const IntBlockStats&) const = default;
};
struct TeStats {
  std::uint64_t context_limited = 0;
  std::uint64_t int_limited = 0;
  std::uint64_t busy = 0;
  std::uint64_t blocked_by_gpe = 0;
  std::uint64_t starved_by_cpg = 0;
  std::uint64_t idle = 0;
  std::uint64_t pipeline = 0;
  bool operator==(const TeStats&) const = default;
};
// Adds `n` cycles (default one) of class `c` to `s`.
inline void add_class(TeStats& s, TeClass c, std::uint64_t n) {
  switch (c) {
    case TeClass::ContextLimited: s.context_limited += n; break;
    case TeClass::IntLimited: s.int_limited += n; break;
    case TeClass::Busy: s.busy += n; break;
    case TeClass::BlockedByGpe: s.blocked_by_gpe += n; break;
    case TeClass::StarvedByCpg: s.starved_by_cpg += n; break;
    case TeClass::Idle: s.idle += n; break;
    case TeClass::Pipeline: s.pipeline += n; break;
  }
}
inline void count_class(TeStats& s, TeClass c) { add_class(s, c, 1); }

inline void add(TeStats& s, const TeStats& t) {
  s.context_limited += t.context_limited;
  s.int_limited += t.int_limited;
  s.busy += t.busy;
  s.blocked_by_gpe += t.blocked_by_gpe;
  s.starved_by_cpg += t.starved_by_cpg;
  s.idle += t.idle;
  s.pipeline += t.pipeline;
}

struct CpgStats {
  std::uint64_t busy = 0;
  std::uint64_t blocked = 0;
  std::uint64_t wait_gpe = 0;
  std::uint64_t idle = 0;
  bool operator==(const CpgStats&) const = default;
};
struct UnitStats {
  std::uint64_t cycles = 0;
  std::uint64_t triangles_in = 0;   // triangles pushed into the TRI FIFO
  std::uint64_t vertices_out = 0;   // vertices popped from the VTX FIFO (accepted by the GPE)
  std::vector<IntBlockStats> int_blocks;  // N entries, sized once by reset()
  TeStats te;
  CpgStats cpg;
  bool operator==(const UnitStats&) const = default;
};

// Per cycle it only increments a few array entries (this runs every simulated cycle); the
// per-block and per-class figures are derived when stats() is read.
class Counters {
 public:
  explicit Counters(int int_blocks)
      : int_blocks_(int_blocks), issued_hist_(static_cast<std::size_t>(int_blocks) + 1) {
    reset();
  }

  void reset() {
    cycles_ = triangles_in_ = vertices_out_ = 0;
    for (std::uint64_t& n : issued_hist_) n = 0;
    te_.fill(0);
    cpg_.fill(0);
  }

  std::uint64_t cycles() const { return cycles_; }
  // Cycles so far per TE class, indexed by TeClass (cheap: nothing derived).
  const std::array<std::uint64_t, kTeClasses.size()>& te_class_cycles() const { return te_; }

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
    te_[static_cast<std::size_t>(te)] += cycles;
    cpg_[static_cast<std::size_t>(cpg)] += cycles;
  }

  const UnitStats& stats() const {
    UnitStats& s = stats_;
    s.cycles = cycles_;
    s.triangles_in = triangles_in_;
    s.vertices_out = vertices_out_;
    s.int_blocks.resize(static_cast<std::size_t>(int_blocks_));
    // Block i was busy in every cycle that issued more than i ops.
    std::uint64_t busy = cycles_;
    for (int i = 0; i < int_blocks_; ++i) {
      busy -= issued_hist_[static_cast<std::size_t>(i)];
      s.int_blocks[static_cast<std::size_t>(i)] = IntBlockStats{busy, cycles_ - busy};
    }
    s.te = TeStats{};
    for (TeClass c : kTeClasses) add_class(s.te, c, te_[static_cast<std::size_t>(c)]);
    s.cpg = CpgStats{cpg_[static_cast<std::size_t>(CpgClass::Busy)], cpg_[static_cast<std::size_t>(CpgClass::Blocked)],
                     cpg_[static_cast<std::size_t>(CpgClass::WaitGpe)], cpg_[static_cast<std::size_t>(CpgClass::Idle)]};
    return s;
  }

 private:
  int int_blocks_;
  std::uint64_t cycles_ = 0, triangles_in_ = 0, vertices_out_ = 0;
  std::vector<std::uint64_t> issued_hist_;  // index k: cycles that issued k ops
  std::array<std::uint64_t, kTeClasses.size()> te_{};
  std::array<std::uint64_t, kCpgClasses.size()> cpg_{};
  mutable UnitStats stats_;  // derived on read
};

}  // namespace tessim::sim
