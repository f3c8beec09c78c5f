// The unit's performance counters (the perf_* outputs of rtl/tess_unit.sv; definitions in
// docs/microarchitecture.md §10). Every cycle is counted in exactly one class per block.
#pragma once

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
// Adds one cycle of class `c` to `s`.
inline void count_class(TeStats& s, TeClass c) {
  switch (c) {
    case TeClass::ContextLimited: ++s.context_limited; break;
    case TeClass::IntLimited: ++s.int_limited; break;
    case TeClass::Busy: ++s.busy; break;
    case TeClass::BlockedByGpe: ++s.blocked_by_gpe; break;
    case TeClass::StarvedByCpg: ++s.starved_by_cpg; break;
    case TeClass::Idle: ++s.idle; break;
    case TeClass::Pipeline: ++s.pipeline; break;
  }
}

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

class Counters {
 public:
  explicit Counters(int int_blocks) : int_blocks_(int_blocks) { reset(); }

  void reset() {
    stats_ = UnitStats{};
    stats_.int_blocks.assign(static_cast<std::size_t>(int_blocks_), IntBlockStats{});
  }

  const UnitStats& stats() const { return stats_; }
  std::uint64_t cycles() const { return stats_.cycles; }

  // One cycle: `issued` ops went to INT blocks 0..issued-1.
  void count(int issued, TeClass te, CpgClass cpg, bool tri_push, bool vtx_pop) {
    ++stats_.cycles;
    for (int i = 0; i < int_blocks_; ++i) {
      IntBlockStats& s = stats_.int_blocks[static_cast<std::size_t>(i)];
      if (i < issued) ++s.busy;
      else ++s.idle;
    }
    count_class(stats_.te, te);
    switch (cpg) {
      case CpgClass::Busy: ++stats_.cpg.busy; break;
      case CpgClass::Blocked: ++stats_.cpg.blocked; break;
      case CpgClass::WaitGpe: ++stats_.cpg.wait_gpe; break;
      case CpgClass::Idle: ++stats_.cpg.idle; break;
    }
    if (tri_push) ++stats_.triangles_in;
    if (vtx_pop) ++stats_.vertices_out;
  }

 private:
  int int_blocks_;
  UnitStats stats_;
};

}  // namespace tessim::sim
