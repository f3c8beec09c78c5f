#include "sim/run/watchdog.hpp"

#include <stdexcept>
#include <string>

#include "sim/values/cpg.hpp"

namespace tessim::sim {

namespace {

std::uint64_t watchdog_cycles(const UnitConfig& cfg, int cpg_c) {
  const double k = cfg.gpe_cycles / (1.0 - cfg.gpe_stall_prob);
  return 1000 + 100 * static_cast<std::uint64_t>(cpg_c + k * (cfg.vtx_fifo_depth + 2) +
                                                  16 * cfg.int_latency * cfg.te_contexts);
}

// A tagged triangle keeps the CPG longer: the watchdog allows for three tagged corners.
int tag_margin(const UnitConfig& cfg) {
  if (!cfg.cpg_tags) return 0;
  TriangleFx all_tagged;
  for (TagsFx& t : all_tagged.tags) t.delta[0] = 1;
  return cpg_tag_cycles(all_tagged, cfg.format, cfg.cpg);
}

}  // namespace

Watchdog::Watchdog(const UnitConfig& cfg, int cpg_cycles) : limit_(watchdog_cycles(cfg, cpg_cycles + tag_margin(cfg))) {}

void Watchdog::fire(std::uint64_t cycle) const {
  throw std::logic_error("cycle model: no vertex accepted for " + std::to_string(limit_) + " cycles (cycle " +
                         std::to_string(cycle) + ")");
}

}  // namespace tessim::sim
