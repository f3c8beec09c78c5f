#include "sim/config/analytic.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <utility>

#include <nlohmann/json.hpp>

#include "model/pattern.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/config/ge_program.hpp"

namespace tessim::sim {

namespace {

bool op_exists(int op, NormalMode normals) { return (int_ops::absent_ops(normals) >> op & 1u) == 0; }

// Expected cycles the GPE needs per vertex: the accept cycle, K - 1 busy cycles, then a
// geometric wait for a cycle without a random stall (1 / (1 - p) cycles including the accept).
// A shader core: its derived K at full waves, stretched by the stalls in the same way.
double gpe_cycles_per_vertex(const UnitConfig& cfg) {
  if (cfg.ge_core()) return core_cycles_per_vertex(cfg) / (1.0 - cfg.gpe_stall_prob);
  return cfg.gpe_cycles - 1 + 1.0 / (1.0 - cfg.gpe_stall_prob);
}

// The share of cycles the GE is busy with vertices at one vertex per `cycles_per_vertex`.
double gpe_busy_share(const UnitConfig& cfg, double cycles_per_vertex) {
  return (cfg.ge_core() ? core_cycles_per_vertex(cfg) : cfg.gpe_cycles) / cycles_per_vertex;
}

}  // namespace

int single_vertex_span(int int_blocks, int int_latency, NormalMode normals) {
  // issue[o]: cycle (from the allocation cycle 0) in which op o issues; 0 = not yet.
  std::array<int, int_ops::kOpCount> issue{};
  int remaining = 0;
  for (int o = 0; o < int_ops::kOpCount; ++o) remaining += op_exists(o, normals) ? 1 : 0;
  int last = 0;
  for (int t = 1; remaining > 0; ++t) {
    int issued_now = 0;
    for (int o = 0; o < int_ops::kOpCount && issued_now < int_blocks; ++o) {
      if (!op_exists(o, normals) || issue[o] != 0) continue;
      bool ready = true;
      for (int d = 0; d < int_ops::kOpCount; ++d) {
        if (!(int_ops::kIntOps[static_cast<std::size_t>(o)].depends >> d & 1u) || !op_exists(d, normals)) continue;
        if (issue[d] == 0 || issue[d] + int_latency > t) ready = false;
      }
      if (!ready) continue;
      issue[o] = t;
      ++issued_now;
      --remaining;
      last = t;
    }
  }
  return last;
}

AnalyticPrediction predict(const UnitConfig& cfg, int cpg_cycles, std::optional<double> mean_patch_vertices) {
  AnalyticPrediction p;
  p.ops_per_vertex = int_ops::ops_per_vertex(cfg.normals);
  p.patch_vertices = mean_patch_vertices ? *mean_patch_vertices : pattern_vertex_count(cfg.tess_factor);
  p.cpg_cycles = cpg_cycles;
  p.int_issue = static_cast<double>(p.ops_per_vertex) / cfg.int_blocks;

  // One context per vertex from allocation (cycle 0) to the issue of its last op (S), its result
  // Λ - 1 cycles later, retirement in the next cycle, reuse by an allocation the cycle after.
  p.chain_span = single_vertex_span(cfg.int_blocks, cfg.int_latency, cfg.normals);
  p.te_chain = static_cast<double>(p.chain_span + cfg.int_latency + 1) / cfg.te_contexts;

  const double P = p.patch_vertices;
  const double spare_wait = 1.0 / (1.0 - cfg.gpe_stall_prob);
  p.gpe_vertex = gpe_cycles_per_vertex(cfg);
  if (cfg.cpg_mapping == CpgMapping::Dedicated) {
    // Accept, C - 1 compute cycles, write: C + 1 cycles per triangle on each of the Mc copies,
    // which take triangles in turn. The first patch: push (cycle 0), accept (1), compute
    // (2..C), write (C + 1), allocate (C + 2), first issue.
    p.cpg = (cpg_cycles + 1) / (static_cast<double>(cfg.cpg.copies) * P);
    p.gpe = p.gpe_vertex;
    p.fill_cycles = cpg_cycles + 3;
  } else {
    // Accept, C compute steps on spare GPE cycles, write: the CPG holds at least C + 2 cycles
    // per triangle. When the GPE's cycles bound the run it has no spare cycle while it has
    // vertices, so each patch costs it its vertices, the C compute steps, and the CPG's write
    // and next accept, two cycles in which it has neither a vertex nor a step to do.
    p.cpg = (cpg_cycles * spare_wait + 2) / P;
    p.gpe = p.gpe_vertex + (cpg_cycles * spare_wait + 2) / P;
    p.fill_cycles = cpg_cycles * spare_wait + 4;
  }
  p.dpg = 1.0;
  p.tail_cycles = cfg.int_latency + 1;
  if (cfg.evaluation == Evaluation::Gpe) {
    // No TE: the DPG's points go straight to the GE (microarchitecture.md §12); the host's control
    // points take the CPG stage's accept and write, two cycles per patch.
    p.int_issue = p.te_chain = 0.0;
    p.chain_span = 0;
    p.tail_cycles = 1;
    if (cfg.cpg_mapping == CpgMapping::Host) {
      p.cpg = 2.0 / P;
      p.gpe = p.gpe_vertex;
      p.fill_cycles = 4;
    }
  }

  const std::array<std::pair<const char*, double>, 5> bounds = {{
      {"int_issue", p.int_issue}, {"te_chain", p.te_chain}, {"cpg", p.cpg}, {"gpe", p.gpe}, {"dpg", p.dpg}}};
  const auto largest = std::max_element(bounds.begin(), bounds.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
  p.cycles_per_vertex = largest->second;
  p.bottleneck = largest->first;
  return p;
}

double AnalyticPrediction::run_cycles(std::uint64_t triangles) const {
  if (triangles == 0) return 0;
  // The first patch waits for its control points (push, accept, compute, write, allocate; one
  // more cycle in the gpe mapping, whose accept does not count down) and the last patch is not
  // overlapped with a following CPG, so it runs at the rate of the blocks behind the CPG.
  // After the last issue: the result (Λ - 1), retirement, acceptance.
  const double behind_cpg = std::max({int_issue, te_chain, dpg, gpe_vertex});
  return fill_cycles + (static_cast<double>(triangles) - 1) * patch_vertices * cycles_per_vertex +
         patch_vertices * behind_cpg + tail_cycles;
}

VaryingWorkloadBounds varying_bounds(const AnalyticPrediction& p, const std::map<int, std::uint64_t>& patches_with_vertices) {
  const double behind_cpg = std::max({p.int_issue, p.te_chain, p.dpg, p.gpe_vertex});
  const double per_patch_cpg = p.cpg * p.patch_vertices;  // (C + 1) / Mc (dedicated) per patch
  double no_buffer = 0, patches = 0, vertices = 0;
  for (const auto& [points, count] : patches_with_vertices) {
    const auto n = static_cast<double>(count);
    const auto P = static_cast<double>(points);
    no_buffer += n * std::max(per_patch_cpg, P * behind_cpg);
    patches += n;
    vertices += n * P;
  }
  VaryingWorkloadBounds b;
  b.no_buffer_cycles = p.fill_cycles + no_buffer + p.tail_cycles;
  b.full_buffer_cycles = p.fill_cycles + std::max(patches * per_patch_cpg, vertices * behind_cpg) + p.tail_cycles;
  return b;
}

nlohmann::json analytic_json(const AnalyticPrediction& p, const UnitConfig& cfg, std::uint64_t triangles) {
  const double cycles = p.run_cycles(triangles);
  const double vertices = static_cast<double>(triangles) * p.patch_vertices;
  return {
      {"bounds",
       {{"int_issue", p.int_issue}, {"te_chain", p.te_chain}, {"cpg", p.cpg}, {"gpe", p.gpe}, {"dpg", p.dpg}}},
      {"chain_span", p.chain_span},
      {"cycles_per_vertex", p.cycles_per_vertex},
      {"throughput", 1.0 / p.cycles_per_vertex},
      {"bottleneck", p.bottleneck},
      {"int_utilisation", p.ops_per_vertex / (cfg.int_blocks * p.cycles_per_vertex)},
      {"gpe_busy", gpe_busy_share(cfg, p.cycles_per_vertex)},
      {"run_cycles", cycles},
      {"run_cycles_per_vertex", vertices > 0 ? cycles / vertices : 0.0},
  };
}

}  // namespace tessim::sim
