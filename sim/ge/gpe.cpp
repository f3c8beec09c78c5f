#include "sim/ge/gpe.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/ge/ge_cost.hpp"

namespace tessim::sim {

Gpe::Gpe(int cycles_per_vertex, double stall_prob, std::uint64_t seed)
    : cycles_per_vertex_(cycles_per_vertex), stall_prob_(stall_prob), seed_(seed), rng_(seed) {
  if (cycles_per_vertex < 1) throw std::invalid_argument("Gpe: cycles per vertex must be >= 1");
  if (!(stall_prob >= 0.0 && stall_prob < 1.0))
    throw std::invalid_argument("Gpe: stall probability must be in [0, 1)");
}

Gpe::Gpe(const EnvironmentConfig& cfg) : Gpe(cfg.gpe_cycles, cfg.gpe_stall_prob, cfg.seed) {
  if (!cfg.ge_core()) return;
  if (cfg.ge_core_issue < 1 || !(cfg.ge_core_mhz >= 1) || !(cfg.unit_mhz >= 1) || cfg.ge_core_fifo < 1)
    throw std::invalid_argument("Gpe: the shader core needs issue, clocks and FIFO entries >= 1");
  core_ = true;
  lanes_ = static_cast<std::uint64_t>(cfg.ge_core_lanes);
  wave_cycles_ = core_wave_cycles(cfg);
  fifo_depth_ = static_cast<std::uint64_t>(cfg.ge_core_fifo);
  // The clocks to 1 kHz: the phase accumulator then counts edges exactly.
  unit_khz_ = static_cast<std::uint64_t>(std::llround(cfg.unit_mhz * 1000));
  core_khz_ = static_cast<std::uint64_t>(std::llround(cfg.ge_core_mhz * 1000));
}

void Gpe::reset() {
  rng_ = SplitMix64(seed_);
  remaining_ = 0;
  stats_ = GpeStats{};
  phase_ = written_ = read_ = issue_left_ = 0;
  read_sync_ = written_sync_ = {};
  core_stats_ = GeCoreStats{};
}

GpeCycle Gpe::core_tick(bool vtx_valid, bool cpg_computing, bool stall) {
  // The unit's side of this cycle: room as the write side sees the read pointer.
  const bool room = written_ - read_sync_[1] < fifo_depth_;
  GpeCycle c;
  c.ready = room && !stall;
  c.accepted = c.ready && vtx_valid;
  c.spare = c.ready && !vtx_valid;
  ++stats_.cycles;
  if (c.accepted) {
    ++written_;
    ++stats_.vertices;
    core_stats_.fifo_peak = std::max(core_stats_.fifo_peak, written_ - read_);
  }
  // The core's edges within this unit cycle, then the unit's edge samples the read pointer.
  bool issued = false;
  phase_ += core_khz_;
  while (phase_ >= unit_khz_) {
    phase_ -= unit_khz_;
    issued |= core_edge();
  }
  read_sync_[1] = read_sync_[0];
  read_sync_[0] = read_;
  c.cls = issued || !room ? GpeClass::Busy
          : stall         ? GpeClass::Stalled
          : cpg_computing ? GpeClass::Cpg
                          : GpeClass::Starved;
  ++stats_[c.cls];
  return c;
}

bool Gpe::core_edge() {
  ++core_stats_.core_cycles;
  bool issued = true;
  if (issue_left_ > 0) {
    --issue_left_;
  } else if (const std::uint64_t seen = written_sync_[1] - read_; seen > 0) {
    // A wave of what the core sees, up to W lanes; its vertices leave the FIFO for its registers.
    const std::uint64_t n = std::min(seen, lanes_);
    read_ += n;
    ++core_stats_.waves;
    core_stats_.lanes_filled += n;
    issue_left_ = wave_cycles_ - 1;
  } else {
    issued = false;
  }
  if (issued) ++core_stats_.issue_cycles;
  written_sync_[1] = written_sync_[0];
  written_sync_[0] = written_;
  return issued;
}

std::uint64_t Gpe::drain_cycles() const {
  if (!core_) return static_cast<std::uint64_t>(remaining_);
  Gpe g = *this;
  std::uint64_t n = 0;
  while (!g.core_idle()) {
    (void)g.core_tick(false, false, false);
    ++n;
  }
  return n;
}

}  // namespace tessim::sim
