// Analytical throughput model of the unit: cycles per vertex predicted as the largest of the
// per-block bounds (docs/results/load-balancing.md §Analytical model), reported next to the
// simulated figures in `tessim sim --stats` so that a sweep shows where the simple model holds
// and where the interaction of the blocks (the cycle model) costs more.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "sim/config/config.hpp"

namespace tessim::sim {

struct AnalyticPrediction {
  // Steady-state cycles per vertex each block needs on its own.
  double int_issue = 0;    // ops per vertex / N: every op takes an INT issue slot
  double te_chain = 0;     // (1 + S + Λ) / V: a context is held from allocation to reuse
  double cpg = 0;          // CPG cycles per triangle / vertices per patch
  double gpe = 0;          // GPE cycles per vertex, plus the CPG's cycles per vertex in the gpe mapping
  double gpe_vertex = 0;   // GPE cycles per vertex alone: K - 1 + 1 / (1 - stall probability)
  double dpg = 1;          // one domain point allocated and one vertex retired per cycle
  int ops_per_vertex = 14;
  int chain_span = 0;      // S: allocation to last issue of one vertex alone in the TE
  double patch_vertices = 0;  // (L+1)(L+2)/2, or the mean over a workload whose patches differ
  int cpg_cycles = 0;      // C of the configuration (dedicated) or cpg_gpe_cycles (gpe mapping)
  double fill_cycles = 0;  // reset to the first issue: the first patch's control points
  double tail_cycles = 0;  // last issue to the last acceptance: result, retirement, accept

  double cycles_per_vertex = 0;  // max of the bounds above
  std::string bottleneck;        // name of the largest bound (int_issue, te_chain, cpg, gpe, dpg)

  // A whole run of `triangles` patches: fill (first control points), steady state, drain.
  double run_cycles(std::uint64_t triangles) const;
};

// cpg_cycles: C of the configuration as the unit uses it (Unit::cpg_cycles()). The patches have
// cfg.tess_factor's pattern, or `mean_patch_vertices` vertices on average.
AnalyticPrediction predict(const UnitConfig& cfg, int cpg_cycles, std::optional<double> mean_patch_vertices = {});

// A workload whose patches differ (per-patch factors): the CPG takes C + 1 cycles per patch
// while the blocks behind it (INT issue, context chain, DPG, GPE; b cycles per vertex) work on
// the previous patch. Without buffering between them each patch costs max(C + 1, P_i b); with
// unbounded buffering the run costs max(n (C + 1), V b). The simulated run lies between the two;
// where, tells how much the unit's FIFOs and control-point buffers absorb the variation.
struct VaryingWorkloadBounds {
  double no_buffer_cycles = 0;
  double full_buffer_cycles = 0;
};
// `patches_with_vertices`: vertices per patch -> patches (any pattern).
VaryingWorkloadBounds varying_bounds(const AnalyticPrediction& p, const std::map<int, std::uint64_t>& patches_with_vertices);

// Span S of one vertex's dependence graph when it has the INT blocks to itself: the cycles
// from its allocation to the issue of its last op under the scheduler's rule (ops in index
// order, at most N per cycle, a dependent op Λ cycles after its operands).
int single_vertex_span(int int_blocks, int int_latency, NormalMode normals);

// The "analytic" object of the stats JSON: every bound, the prediction, and the derived figures
// (throughput, INT utilisation, GPE busy share, run cycles) for a run of `triangles` patches.
nlohmann::json analytic_json(const AnalyticPrediction& p, const UnitConfig& cfg, std::uint64_t triangles);

}  // namespace tessim::sim
