// Geometry processing engine (GPE) model of docs/microarchitecture.md §9: the consumer of the
// unit's vertex stream. It is not part of the RTL; the same object drives vtx_ready of the
// cycle model and, in co-simulation, of the Verilated RTL, so both see identical backpressure.
#pragma once

#include <array>
#include <cstdint>

#include "sim/base/counter_registry.hpp"
#include "sim/config/config.hpp"

namespace tessim::sim {

// splitmix64 (Steele, Lea, Flood 2014): the GPE's random source, advanced once per cycle.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed = 0) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1) with 53 bits: (next() >> 11) * 2^-53, exact in double.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

// Cycles per GPE class (GpeClass, sim/base/counter_registry.hpp: doc §10, in priority order),
// and the GPE's totals.
struct GpeStats : ClassCounts<GpeClass> {
  std::uint64_t cycles = 0;
  std::uint64_t vertices = 0;  // vertices accepted
  bool operator==(const GpeStats&) const = default;
};

// The shader core's own counters (EnvironmentConfig::ge_core()): in core cycles and waves.
struct GeCoreStats {
  std::uint64_t core_cycles = 0;  // core clock edges over the run
  std::uint64_t issue_cycles = 0; // core cycles issuing a wave's instructions
  std::uint64_t waves = 0;        // waves launched
  std::uint64_t lanes_filled = 0; // vertices launched: lanes_filled / (waves × W) is the lane use
  std::uint64_t fifo_peak = 0;    // most vertices the cross-clock FIFO held
  bool operator==(const GeCoreStats&) const = default;
};

// What the GPE does in one cycle.
struct GpeCycle {
  bool ready = false;     // drives vtx_ready of the unit
  bool accepted = false;  // ready and the unit offered a vertex: transferred this cycle
  bool spare = false;     // ready, no vertex offered: a spare cycle (drives cpg_step)
  GpeClass cls = GpeClass::Starved;
};

// The GE in one of two forms. A fixed K: it accepts a vertex, is busy K - 1 cycles, and is ready
// again. A shader core on its own clock (docs/microarchitecture.md §12): the unit writes vertices
// into a cross-clock FIFO of D entries while it is not full; the core, whenever its issue is free,
// launches a wave of the up to W vertices it sees there and issues it for ceil(slots / I) core
// cycles. Each side sees the other's FIFO pointer through two registers of its own clock.
class Gpe {
 public:
  Gpe(int cycles_per_vertex, double stall_prob, std::uint64_t seed);
  explicit Gpe(const EnvironmentConfig& cfg);

  void reset();  // back to the state after construction (generator re-seeded, stats cleared)

  // One cycle. `vtx_valid` is the unit's (registered) vtx_valid output of this cycle;
  // `cpg_computing` whether a gpe-mapped CPG is waiting for a compute step (only used to
  // classify a spare cycle as `cpg` rather than `starved`). Advances the state to the end of
  // the cycle and returns the values the GPE presents during it.
  GpeCycle tick(bool vtx_valid, bool cpg_computing) {
    // No draw at probability 0: nothing could observe it (the generator only decides stalls).
    const bool stall = stall_prob_ > 0 && rng_.uniform() < stall_prob_;
    if (core_) return core_tick(vtx_valid, cpg_computing, stall);
    GpeCycle c;
    c.ready = remaining_ == 0 && !stall;
    c.accepted = c.ready && vtx_valid;
    c.spare = c.ready && !vtx_valid;
    ++stats_.cycles;
    if (c.accepted) {
      remaining_ = cycles_per_vertex_ - 1;
      ++stats_.vertices;
      c.cls = GpeClass::Busy;
    } else if (remaining_ > 0) {
      --remaining_;
      c.cls = GpeClass::Busy;
    } else if (stall) {
      c.cls = GpeClass::Stalled;
    } else if (cpg_computing) {
      c.cls = GpeClass::Cpg;
    } else {
      c.cls = GpeClass::Starved;
    }
    ++stats_[c.cls];
    return c;
  }

  // Fast-forward: how many cycles in a row, from now, the GPE presents the same values while
  // `vtx_valid` stays as it is — the rest of a busy countdown, or endless (~0) waiting for a
  // vertex; 0 when it takes a vertex now or may stall at random (its draws cannot be skipped).
  std::uint64_t quiet_cycles(bool vtx_valid) const {
    if (stall_prob_ > 0 || core_) return 0;  // a core's clocks and synchronizers move every cycle
    if (remaining_ > 0) return static_cast<std::uint64_t>(remaining_);
    return vtx_valid ? 0 : ~std::uint64_t{0};
  }
  // `n` <= quiet_cycles(vtx_valid) cycles at once, as n tick() calls would; returns the last.
  GpeCycle skip(std::uint64_t n, bool vtx_valid, bool cpg_computing) {
    GpeCycle c;
    stats_.cycles += n;
    if (remaining_ > 0) {
      remaining_ -= static_cast<int>(n);
      c.cls = GpeClass::Busy;
    } else {
      c.ready = true;
      c.spare = !vtx_valid;
      c.cls = cpg_computing ? GpeClass::Cpg : GpeClass::Starved;
    }
    stats_[c.cls] += n;
    return c;
  }

  // Whether the next cycle presents ready, when it cannot stall (stall probability 0).
  bool ready_now() const { return remaining_ == 0; }

  // Cycles from now until the GE has finished every vertex it took, if no more come: the rest of
  // K, or the FIFO's vertices through the core and its last wave's issue.
  std::uint64_t drain_cycles() const;

  const GpeStats& stats() const { return stats_; }
  const GeCoreStats& core_stats() const { return core_stats_; }
  int cycles_per_vertex() const { return cycles_per_vertex_; }
  double stall_prob() const { return stall_prob_; }
  std::uint64_t seed() const { return seed_; }

 private:
  int cycles_per_vertex_;
  double stall_prob_;
  std::uint64_t seed_;
  SplitMix64 rng_;
  int remaining_ = 0;
  GpeStats stats_;

  // The shader core (core_): its shape, and the clocks as a phase accumulator — each unit cycle
  // adds core_khz_, and every unit_khz_ of it is one core clock edge.
  GpeCycle core_tick(bool vtx_valid, bool cpg_computing, bool stall);
  bool core_edge();  // one core cycle; whether it issued
  bool core_idle() const { return written_ == read_ && issue_left_ == 0; }
  bool core_ = false;
  std::uint64_t lanes_ = 1, wave_cycles_ = 1, fifo_depth_ = 1, unit_khz_ = 1, core_khz_ = 1;
  std::uint64_t phase_ = 0;
  std::uint64_t written_ = 0, read_ = 0;  // the FIFO's pointers as vertex counts (unit side, core side)
  std::array<std::uint64_t, 2> read_sync_{}, written_sync_{};  // [1]: what the other side sees
  std::uint64_t issue_left_ = 0;  // core cycles of the current wave still to issue
  GeCoreStats core_stats_;
};

}  // namespace tessim::sim
