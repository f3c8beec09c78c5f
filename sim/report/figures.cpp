#include "sim/report/report.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

#include "sim/base/int_ops.hpp"

namespace tessim::sim {

namespace {

double ratio(std::uint64_t a, std::uint64_t b) { return b == 0 ? 0.0 : static_cast<double>(a) / b; }

}  // namespace

double throughput(const SimResult& r) { return ratio(r.unit.vertices_out, r.run_cycles()); }
double cycles_per_vertex(const SimResult& r) { return ratio(r.run_cycles(), r.unit.vertices_out); }

double int_utilisation(const SimResult& r) {
  std::uint64_t busy = 0;
  for (std::uint64_t b : r.unit.int_busy_used()) busy += b;
  return ratio(busy, r.unit.cycles * static_cast<std::uint64_t>(r.unit.int_blocks));
}

// A system of units: the GE ports when they are busy, else what the ports waited for (the
// oldest patch's unit, or a stream with nothing in flight), and the buffer when it held the units.
static std::string system_limit(const SimResult& r) {
  const SystemStats& s = r.system->stats;
  const std::uint64_t port_cycles = s.cycles * r.system->ports.size();
  const double busy = ratio(r.gpe[GpeClass::Busy], port_cycles);
  const double waited_unit = ratio(s.ports_waiting_unit, port_cycles);
  const double waited_stream = ratio(s.ports_waiting_stream, port_cycles);
  const double blocked = ratio(s.unit_blocked, s.cycles * r.system->units.size());
  char buf[320];
  const char* limit = busy >= std::max(waited_unit, waited_stream) ? "GE ports"
                      : blocked > 0.05                             ? "reassembly buffer"
                      : waited_unit >= waited_stream               ? "units"
                                                                   : "distributor";
  const bool ordered = r.config.reassembly == Reassembly::Ordered;
  std::snprintf(buf, sizeof buf,
                "%s: ports busy %.1f%%, waiting for %s %.1f%%, for the stream %.1f%%; units "
                "blocked by a full buffer %.1f%%; %llu cycles of dispatch stalls",
                limit, 100 * busy, ordered ? "the oldest patch's unit" : "the units (unordered)", 100 * waited_unit,
                100 * waited_stream, 100 * blocked,
                static_cast<unsigned long long>(s.dispatch_stalls));
  return buf;
}

std::string bottleneck(const SimResult& r) {
  const std::uint64_t cycles = r.unit.cycles;
  if (cycles == 0) return "none (empty run)";
  if (r.system) return system_limit(r);
  const UnitConfig& c = r.config;
  char buf[320];
  // The GPE limits when it waited for a vertex no more often than the TE waited for it.
  if (r.gpe_waited <= r.unit.te[TeClass::BlockedByGpe]) {
    // A shader core's K is derived (fractional); a fixed K is whole cycles.
    const double k = c.ge_core() ? core_cycles_per_vertex(with_ge_cost(c, r.ge)) : r.ge.total();
    std::snprintf(buf, sizeof buf,
                  "GPE: waited for a vertex %.1f%% of cycles, TE blocked by GPE %.1f%% "
                  "(one vertex / %g cycles, busy %.1f%%)",
                  100 * ratio(r.gpe_waited, cycles), 100 * ratio(r.unit.te[TeClass::BlockedByGpe], cycles), k,
                  100 * ratio(r.gpe[GpeClass::Busy], cycles));
    return buf;
  }
  // Otherwise the unit delivered vertices late: the stall class of the TE that dominates the late
  // vertex intervals.
  const ClassCounts<TeClass>& w = r.te_late;
  const double waited = static_cast<double>(w.total());
  const std::uint64_t chain_waits = w[TeClass::ContextLimited], int_limited = w[TeClass::IntLimited],
                      starved_by_cpg = w[TeClass::StarvedByCpg];
  const std::uint64_t top = std::max({chain_waits, int_limited, starved_by_cpg});
  if (top == 0) {
    std::snprintf(buf, sizeof buf,
                  "none dominant: GPE waited %.1f%% of cycles, no TE stall class in the late vertex "
                  "intervals (busy %.1f%%, pipeline %.1f%%)",
                  100 * ratio(r.gpe_waited, cycles), 100 * w[TeClass::Busy] / waited,
                  100 * w[TeClass::Pipeline] / waited);
  } else if (starved_by_cpg == top) {
    std::snprintf(buf, sizeof buf,
                  "CPG: TE starved by CPG in %.1f%% of the late vertex intervals (GPE waited %.1f%% of cycles; "
                  "%s mapping, C = %d cycles per triangle on %d cop%s, %.4g vertices per patch)",
                  100 * starved_by_cpg / waited, 100 * ratio(r.gpe_waited, cycles),
                  to_string(c.cpg_mapping).c_str(), r.cpg_cycles, c.cpg.copies, c.cpg.copies == 1 ? "y" : "ies",
                  ratio(r.factors.vertices, r.triangles));
  } else if (int_limited == top) {
    std::snprintf(buf, sizeof buf,
                  "INT blocks: all %d busy with ready ops left in %.1f%% of the late vertex intervals "
                  "(GPE waited %.1f%% of cycles; utilisation %.1f%%, %.2f cycles/vertex at best)",
                  c.int_blocks, 100 * int_limited / waited, 100 * ratio(r.gpe_waited, cycles),
                  100 * int_utilisation(r), static_cast<double>(int_ops::ops_per_vertex(c.normals)) / c.int_blocks);
  } else {
    std::snprintf(buf, sizeof buf,
                  "TE contexts: oldest vertex waiting on its dependence chain in %.1f%% of the late vertex "
                  "intervals (GPE waited %.1f%% of cycles; %d contexts, INT latency %d, INT utilisation %.1f%%)",
                  100 * chain_waits / waited, 100 * ratio(r.gpe_waited, cycles), c.te_contexts,
                  c.int_latency, 100 * int_utilisation(r));
  }
  return buf;
}

}  // namespace tessim::sim
