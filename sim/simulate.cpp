#include "sim/simulate.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/pattern.hpp"
#include "sim/analytic.hpp"
#include "sim/chunked.hpp"
#include "sim/testbench.hpp"
#include "sim/version.hpp"

namespace tessim::sim {

namespace {

// A cycle count after which a run that has not accepted a vertex is an internal error (the
// unit never deadlocks: every wait in doc §5-§9 ends by itself).
std::uint64_t watchdog_cycles(const UnitConfig& cfg, int cpg_c) {
  const double k = cfg.gpe_cycles / (1.0 - cfg.gpe_stall_prob);
  return 1000 + 100 * static_cast<std::uint64_t>(cpg_c + k * (cfg.vtx_fifo_depth + 2) +
                                                  16 * cfg.int_latency * cfg.te_contexts);
}

double ratio(std::uint64_t a, std::uint64_t b) { return b == 0 ? 0.0 : static_cast<double>(a) / b; }

std::string percent(std::uint64_t part, std::uint64_t whole) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * ratio(part, whole));
  return buf;
}

// The run's counts from cycle 0 in the timeline's terms.
Timeline::Bucket run_totals(const Unit& unit, const Gpe& gpe) {
  Timeline::Bucket t;
  t.te = unit.te_class_cycles();
  const UnitCounters& s = unit.stats();
  for (std::uint64_t busy : s.int_busy_used()) t.int_busy += busy;
  t.cpg_busy = s.cpg[CpgClass::Busy];
  t.vertices = s.vertices_out;
  t.gpe = gpe.stats();
  return t;
}

WorkloadFactors workload_factors(const MeshSource& source) {
  WorkloadFactors w;
  const TessSettings* d3d11 = source.patterns().d3d11;
  if (d3d11) {
    w.uniform = false;
    w.pattern = d3d11->describe();
  }
  for (std::uint64_t t = source.first(); t < source.end(); ++t) {
    const int points = source.patch_points(t);
    if (points == 0) {
      ++w.culled;
      continue;
    }
    ++w.patches_with_vertices[points];
    w.vertices += static_cast<std::uint64_t>(points);
    if (d3d11) continue;
    const int L = source.factor(t);
    ++w.patches_with_factor[static_cast<std::size_t>(L)];
    if (L != source.factor(source.first())) w.uniform = false;
  }
  return w;
}

// The triangles of D3D11 patterns, built once per distinct set of factors (an adaptive mesh has
// a few hundred), for the patches handed to SimHooks::on_patch.
class TopologyCache {
 public:
  std::span<const std::uint32_t> indices(const TriangleFx& tri) {
    const std::array<std::int32_t, 5> key{static_cast<std::int32_t>(tri.pattern), tri.factors[0], tri.factors[1],
                                          tri.factors[2], tri.factors[3]};
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, d3d11_pattern(tri_setup(tri)).indices).first;
    return it->second;
  }

 private:
  std::map<std::array<std::int32_t, 5>, std::vector<std::uint32_t>> cache_;
};

}  // namespace

SimResult simulate(const Mesh& mesh, const UnitConfig& cfg, const SimHooks& hooks, MeshPatterns patterns) {
  return simulate_range(mesh, cfg, 0, mesh.triangle_count(), hooks, patterns);
}

SimResult simulate_range(const Mesh& mesh, const UnitConfig& cfg, std::uint64_t first, std::uint64_t end,
                         const SimHooks& hooks, MeshPatterns patterns) {
  const std::span<const std::uint8_t> factors = patterns.factors;
  if (!factors.empty() && factors.size() != mesh.triangle_count())
    throw std::logic_error("simulate: " + std::to_string(factors.size()) + " factors for " +
                           std::to_string(mesh.triangle_count()) + " triangles");
  if (patterns.d3d11 && cfg.format.bary_bits < 16)
    throw InputError("configuration", "bary_bits",
                     "the D3D11 pattern's points are 16.16: it needs bary_bits >= 16, not " +
                         std::to_string(cfg.format.bary_bits));
  if (first > end || end > mesh.triangle_count())
    throw std::logic_error("simulate: triangles " + std::to_string(first) + ".." + std::to_string(end) +
                           " of a mesh of " + std::to_string(mesh.triangle_count()));
  const auto t0 = std::chrono::steady_clock::now();
  check_convertible(mesh);
  SimResult r;
  r.mesh = mesh.source;
  r.config = cfg;
  r.triangles = end - first;
  r.scaling = host_scaling(mesh);

  Unit unit(cfg);
  const MeshSource source(mesh, r.scaling, cfg.format, cfg.tess_factor, patterns, cfg.cpg_tags, first, end);
  BasicTestbench<MeshSource> tb(source, cfg);
  r.cpg_cycles = unit.cpg_cycles();
  r.factors = workload_factors(source);
  const NumberFormat& fmt = cfg.format;
  const bool d3d11 = patterns.d3d11 != nullptr;
  TopologyCache topology;
  // The patch expected next: its id (the next triangle not culled), L (0: D3D11), vertices and,
  // for D3D11 patches handed to on_patch, its triangles.
  auto expect_id = static_cast<std::uint32_t>(first);
  int L = cfg.tess_factor, patch_vertices = 0;
  std::span<const std::uint32_t> patch_indices;
  auto expect_patch = [&](std::uint64_t from) {
    for (; from < end; ++from) {
      const int points = source.patch_points(from);
      if (points == 0) continue;
      expect_id = static_cast<std::uint32_t>(from);
      patch_vertices = points;
      L = d3d11 ? 0 : source.factor(from);
      if (d3d11 && hooks.on_patch) patch_indices = topology.indices(*source.triangle(from));
      return;
    }
    expect_id = static_cast<std::uint32_t>(end);
  };
  expect_patch(first);
  const std::uint64_t total = source.vertices();
  // A tagged triangle keeps the CPG longer: the watchdog allows for three tagged corners.
  TriangleFx all_tagged;
  for (TagsFx& t : all_tagged.tags) t.delta[0] = 1;
  const int tag_margin = cfg.cpg_tags ? cpg_tag_cycles(all_tagged, cfg.format, cfg.cpg) : 0;
  const std::uint64_t watchdog = watchdog_cycles(cfg, unit.cpg_cycles() + tag_margin);

  std::vector<glm::dvec3> patch_pos, patch_nrm;
  if (hooks.on_patch) {
    const int largest = d3d11 ? d3d11_setup(d3d11_host_factors({64.0f, 64.0f, 64.0f}, 64.0f, Partitioning::integer)).point_count
                              : pattern_vertex_count(factors.empty() ? cfg.tess_factor : kMaxTessFactor);
    patch_pos.resize(static_cast<std::size_t>(largest));
    patch_nrm.resize(static_cast<std::size_t>(largest));
  }
  std::vector<CycleObserver*> observers = hooks.observers;
  std::optional<MeshErrors> mesh_errors;
  std::optional<ArithmeticCheck> arithmetic;
  if (hooks.measure_errors) {
    mesh_errors.emplace(mesh, r.scaling, cfg, cfg.cpg_tags, patterns.d3d11);
    arithmetic.emplace(ArithmeticCheck::for_mesh(mesh, r.scaling, cfg, patterns));
  }

  // Expected next vertex: the stream is checked as it goes (patch order, pattern order), so a
  // model bug shows up as an internal error instead of a wrong mesh.
  int expect_index = 0;
  std::uint64_t accepted = 0;
  std::uint64_t last_progress = 0;
  std::uint64_t cycle = 0;
  // The TE's class counts at the end of the last accepting cycle: an interval's classes are the
  // counts at its end minus these.
  ClassCounts<TeClass> interval_start;
  bool interval_late = false;  // the GPE waited in this interval
  // The timeline reads the counters only at its bucket boundaries: one comparison per cycle.
  std::uint64_t timeline_end = r.timeline.next_boundary();

  const bool fast_forward = hooks.fast_forward && observers.empty();
  while (accepted < total) {
    // A cycle that accepted a vertex is followed by its retirement's refill: not worth asking.
    if (fast_forward && !tb.gpe_cycle().accepted) {
      // Quiet cycles at once, never past the cycle at which the watchdog would fire, nor past
      // the timeline's next boundary while the TE issues (its cycles are not all alike).
      const std::uint64_t n =
          tb.fast_forward(unit, watchdog + 1 - (cycle - last_progress), timeline_end - cycle);
      if (n > 0) {
        if (tb.gpe_cycle().spare && accepted > 0) {
          r.gpe_waited += n;
          interval_late = true;
        }
        cycle += n;
        // A stretch past a boundary is one of identical cycles (an issuing one ends there at most).
        if (cycle >= timeline_end) {
          const CycleActivity& a = unit.activity();
          r.timeline.close_within(run_totals(unit, tb.gpe()), cycle,
                                  Timeline::quiet_cycle(a.te, a.cpg, tb.gpe_cycle().cls));
          timeline_end = r.timeline.next_boundary();
        }
        if (cycle - last_progress > watchdog)
          throw std::logic_error("cycle model: no vertex accepted for " + std::to_string(watchdog) +
                                 " cycles (cycle " + std::to_string(cycle) + ")");
        continue;
      }
    }
    const UnitInputs& in = tb.inputs(unit);
    const GpeCycle& g = tb.gpe_cycle();
    if (g.accepted) {
      const VertexFx& v = unit.vtx();
      if (v.id != expect_id || v.index != expect_index || v.L != L ||
          (L > 0 && pattern_index(v.j, v.k, v.L) != expect_index) || v.last != (expect_index == patch_vertices - 1))
        throw std::logic_error("cycle model: vertex (" + std::to_string(v.id) + ", " +
                               std::to_string(v.j) + ", " + std::to_string(v.k) +
                               ") out of order at cycle " + std::to_string(cycle));
      if (expect_index == 0) {
        check_patch_flags(mesh, v.id, v.flags, fmt);
        if (v.flags & kFlagDivByZero) ++r.degenerate_patches;
      }
      if (v.nrm[0] == 0 && v.nrm[1] == 0 && v.nrm[2] == 0) ++r.zero_normals;
      if (hooks.on_vertex) hooks.on_vertex(v);
      if (mesh_errors) {
        mesh_errors->add(v);
        arithmetic->check(v);
      }
      if (hooks.on_patch) {
        patch_pos[static_cast<std::size_t>(expect_index)] = position_from_fixed(v.pos, r.scaling, fmt);
        patch_nrm[static_cast<std::size_t>(expect_index)] = normal_from_fixed(v.nrm, fmt);
        if (v.last) {
          const auto n = static_cast<std::size_t>(patch_vertices);
          hooks.on_patch(PatchOut{v.id, L, {patch_pos.data(), n}, {patch_nrm.data(), n}, patch_indices});
        }
      }
      if (v.last) {
        if (hooks.vertices_done)
          hooks.vertices_done->fetch_add(static_cast<std::uint64_t>(patch_vertices), std::memory_order_relaxed);
        if (hooks.cancel && hooks.cancel->load(std::memory_order_relaxed)) throw SimCancelled();
        expect_index = 0;
        expect_patch(std::uint64_t{expect_id} + 1);
      } else {
        ++expect_index;
      }
      ++accepted;
      last_progress = cycle;
    }
    const bool gpe_waited = g.spare && accepted > 0;  // GPE ready, no vertex, after its first
    unit.tick(in);
    if (gpe_waited) {
      ++r.gpe_waited;
      interval_late = true;
    }
    if (g.accepted) {
      const ClassCounts<TeClass>& now = unit.te_class_cycles();
      if (interval_late) r.te_late += now - interval_start;
      interval_start = now;
      interval_late = false;
    }
    if (!observers.empty()) {
      std::erase_if(observers, [&](CycleObserver* o) { return !o->on_cycle(unit, g); });
    }
    ++cycle;
    if (cycle == timeline_end) {
      r.timeline.close(run_totals(unit, tb.gpe()));
      timeline_end = r.timeline.next_boundary();
    }
    if (cycle - last_progress > watchdog)
      throw std::logic_error("cycle model: no vertex accepted for " + std::to_string(watchdog) +
                             " cycles (cycle " + std::to_string(cycle) + ")");
  }

  r.timeline.finish(run_totals(unit, tb.gpe()), cycle);
  r.unit = unit.stats();
  r.gpe = tb.gpe().stats();
  if (mesh_errors) r.errors = SimErrors{mesh_errors->result(), arithmetic->result()};
  r.cpg_tag_cycles = unit.cpg_tag_cycles();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

double throughput(const SimResult& r) { return ratio(r.unit.vertices_out, r.unit.cycles); }
double cycles_per_vertex(const SimResult& r) { return ratio(r.unit.cycles, r.unit.vertices_out); }

double int_utilisation(const SimResult& r) {
  std::uint64_t busy = 0;
  for (std::uint64_t b : r.unit.int_busy_used()) busy += b;
  return ratio(busy, r.unit.cycles * static_cast<std::uint64_t>(r.unit.int_blocks));
}

std::string bottleneck(const SimResult& r) {
  const std::uint64_t cycles = r.unit.cycles;
  if (cycles == 0) return "none (empty run)";
  const UnitConfig& c = r.config;
  char buf[320];
  // The GPE limits when it waited for a vertex no more often than the TE waited for it.
  if (r.gpe_waited <= r.unit.te[TeClass::BlockedByGpe]) {
    std::snprintf(buf, sizeof buf,
                  "GPE: waited for a vertex %.1f%% of cycles, TE blocked by GPE %.1f%% "
                  "(one vertex / %d cycles, busy %.1f%%)",
                  100 * ratio(r.gpe_waited, cycles), 100 * ratio(r.unit.te[TeClass::BlockedByGpe], cycles),
                  c.gpe_cycles, 100 * ratio(r.gpe[GpeClass::Busy], cycles));
    return buf;
  }
  // Otherwise the unit delivered vertices late: the stall class of the TE that dominates the late
  // vertex intervals.
  const ClassCounts<TeClass>& w = r.te_late;
  const double waited = static_cast<double>(w.total());
  const std::uint64_t context_limited = w[TeClass::ContextLimited], int_limited = w[TeClass::IntLimited],
                      starved_by_cpg = w[TeClass::StarvedByCpg];
  const std::uint64_t top = std::max({context_limited, int_limited, starved_by_cpg});
  if (top == 0) {
    std::snprintf(buf, sizeof buf,
                  "none dominant: GPE waited %.1f%% of cycles, no TE stall class in the late vertex "
                  "intervals (busy %.1f%%, pipeline %.1f%%)",
                  100 * ratio(r.gpe_waited, cycles), 100 * w[TeClass::Busy] / waited,
                  100 * w[TeClass::Pipeline] / waited);
  } else if (starved_by_cpg == top) {
    std::snprintf(buf, sizeof buf,
                  "CPG: TE starved by CPG in %.1f%% of the late vertex intervals (GPE waited %.1f%% of cycles; "
                  "%s mapping, C = %d cycles per triangle, %.4g vertices per patch)",
                  100 * starved_by_cpg / waited, 100 * ratio(r.gpe_waited, cycles),
                  to_string(c.cpg_mapping).c_str(), r.cpg_cycles, ratio(r.factors.vertices, r.triangles));
  } else if (int_limited == top) {
    std::snprintf(buf, sizeof buf,
                  "INT blocks: all %d busy with ready ops left in %.1f%% of the late vertex intervals "
                  "(GPE waited %.1f%% of cycles; utilisation %.1f%%, %.2f cycles/vertex at best)",
                  c.int_blocks, 100 * int_limited / waited, 100 * ratio(r.gpe_waited, cycles),
                  100 * int_utilisation(r), (c.normals == NormalMode::Linear ? 11.0 : 14.0) / c.int_blocks);
  } else {
    std::snprintf(buf, sizeof buf,
                  "TE contexts: oldest vertex waiting on its dependence chain in %.1f%% of the late vertex "
                  "intervals (GPE waited %.1f%% of cycles; %d contexts, INT latency %d, INT utilisation %.1f%%)",
                  100 * context_limited / waited, 100 * ratio(r.gpe_waited, cycles), c.te_contexts,
                  c.int_latency, 100 * int_utilisation(r));
  }
  return buf;
}

namespace {

// A block's classes by their keys (docs/statistics.md: "te", "cpg", "gpe", "limit.te_late").
template <class Class>
nlohmann::json classes_json(const ClassCounts<Class>& counts) {
  nlohmann::json j = nlohmann::json::object();
  for (Class c : all_of<Class>()) j[to_string(c)] = counts[c];
  return j;
}

// The summary's line of a block's classes: each class as a share of `cycles`.
template <class Class>
std::string classes_line(const ClassCounts<Class>& counts, std::uint64_t cycles) {
  const CounterBlockInfo& block = block_info(CounterEnum<Class>::block);
  char label[16];
  std::snprintf(label, sizeof label, "%-9s", block.label);
  std::string s = label;
  for (Class c : all_of<Class>())
    s += std::string(c == Class{} ? "" : "  ") + to_string(c) + " " + percent(counts[c], cycles);
  return s + "\n";
}

}  // namespace

namespace {

// Patches by vertex count in powers of two: 3, 4-7, 8-15, ..., 2048-4095 (L = 64 has 2145).
constexpr int kVertexBuckets = 11;
int vertex_bucket(int vertices) { return std::bit_width(static_cast<unsigned>(vertices)) - 2; }

nlohmann::json workload_json(const WorkloadFactors& w, std::uint64_t triangles) {
  std::array<std::uint64_t, kVertexBuckets> histogram{};
  for (const auto& [v, n] : w.patches_with_vertices) histogram[static_cast<std::size_t>(vertex_bucket(v))] += n;
  const int min_v = w.patches_with_vertices.empty() ? 0 : w.patches_with_vertices.begin()->first;
  const int max_v = w.patches_with_vertices.empty() ? 0 : w.patches_with_vertices.rbegin()->first;
  return {{"factors", w.uniform ? "uniform" : "per patch"},
          {"pattern", w.pattern.empty() ? "uniform" : w.pattern},
          {"culled_patches", w.culled},
          {"vertices_per_patch",
           {{"min", min_v}, {"mean", ratio(w.vertices, triangles - w.culled)}, {"max", max_v}}},
          {"vertices_per_patch_log2_histogram", histogram}};
}

nlohmann::json analytic_of(const SimResult& r) {
  // Scalar tags make C vary per triangle: the prediction takes the mean, rounded.
  const int cpg_c = r.cpg_cycles + static_cast<int>(std::lround(ratio(r.cpg_tag_cycles, r.triangles)));
  if (r.factors.uniform) return analytic_json(predict(r.config, cpg_c), r.config, r.triangles);
  const AnalyticPrediction p = predict(r.config, cpg_c, ratio(r.factors.vertices, r.triangles));
  nlohmann::json j = analytic_json(p, r.config, r.triangles);
  const VaryingWorkloadBounds b = varying_bounds(p, r.factors.patches_with_vertices);
  const auto v = static_cast<double>(r.factors.vertices);
  j["varying"] = {{"no_buffer_cycles", b.no_buffer_cycles},
                  {"full_buffer_cycles", b.full_buffer_cycles},
                  {"no_buffer_cycles_per_vertex", v > 0 ? b.no_buffer_cycles / v : 0.0},
                  {"full_buffer_cycles_per_vertex", v > 0 ? b.full_buffer_cycles / v : 0.0}};
  return j;
}

}  // namespace

nlohmann::json stats_units() {
  constexpr const char* kCycles = "cycles";
  constexpr const char* kShare = "fraction of cycles";
  constexpr const char* kDiagonal = "fraction of the mesh's bounding-box diagonal";
  nlohmann::json u = {
      {"schema_version", "format version of this JSON"},
      {"triangles", "triangles (of the mesh)"},
      {"cpg_cycles_per_triangle", "cycles/triangle"},
      {"cpg_tag_cycles", kCycles},
      {"throughput", "vertices/cycle"},
      {"cycles_per_vertex", "cycles/vertex"},
      {"int.blocks[].utilisation", kShare},
      {"int.busy", "cycles summed over the INT blocks (= operations issued)"},
      {"int.ops_per_vertex", "operations/vertex"},
      {"int.utilisation", "fraction of block-cycles"},
      {"gpe.vertices", "vertices"},
      {"limit.gpe_waited", kCycles},
      {"warnings.degenerate_patches", "patches"},
      {"warnings.zero_normals", "vertices"},
      {"workload.culled_patches", "patches"},
      {"workload.vertices_per_patch.min", "vertices"},
      {"workload.vertices_per_patch.mean", "vertices"},
      {"workload.vertices_per_patch.max", "vertices"},
      {"workload.vertices_per_patch_log2_histogram[]", "patches with 2^i..2^(i+1)-1 vertices"},
      {"analytic.cycles_per_vertex", "cycles/vertex"},
      {"analytic.bounds.cpg", "cycles/vertex"},
      {"analytic.bounds.dpg", "cycles/vertex"},
      {"analytic.bounds.gpe", "cycles/vertex"},
      {"analytic.bounds.int_issue", "cycles/vertex"},
      {"analytic.bounds.te_chain", "cycles/vertex"},
      {"analytic.chain_span", "cycles (one vertex's dependence chain alone)"},
      {"analytic.gpe_busy", kShare},
      {"analytic.int_utilisation", "fraction of block-cycles"},
      {"analytic.run_cycles", kCycles},
      {"analytic.run_cycles_per_vertex", "cycles/vertex"},
      {"analytic.throughput", "vertices/cycle"},
      {"analytic.varying.no_buffer_cycles", kCycles},
      {"analytic.varying.full_buffer_cycles", kCycles},
      {"analytic.varying.no_buffer_cycles_per_vertex", "cycles/vertex"},
      {"analytic.varying.full_buffer_cycles_per_vertex", "cycles/vertex"},
      {"wall_seconds", "seconds (wall clock of the simulation)"},
  };
  // Every counter of the registry (sim/blocks/counter_registry.hpp) where the JSON has it: the
  // run's counts at the top, an INT block's in int.blocks[], the classes in their block's object,
  // the TE's also over the late intervals, the TE's and the GPE's also per timeline bucket.
  for (const CounterRow& row : kCounterRegistry) {
    const std::string key = row.key;
    switch (row.block) {
      case CounterBlock::Run: u[key] = row.unit; break;
      case CounterBlock::Int: u["int.blocks[]." + key] = row.unit; break;
      case CounterBlock::Te:
        u["te." + key] = row.unit;
        u["limit.te_late." + key] = std::string(row.unit) + " (in the late vertex intervals)";
        u["timeline.te." + key + "[]"] = row.unit;
        break;
      case CounterBlock::Cpg: u["cpg." + key] = row.unit; break;
      case CounterBlock::Gpe:
        u["gpe." + key] = row.unit;
        u["timeline.gpe." + key + "[]"] = row.unit;
        break;
    }
  }
  for (const char* c : {"te_starved_by_cpg", "te_blocked_by_gpe", "gpe_starved_by_te"}) u[std::string("stalls.") + c] = kCycles;
  // --errors: against the mesh's float reference, and the arithmetic alone against its bound.
  for (const std::string prefix : {"errors.", "errors.arithmetic."}) {
    u[prefix + "vertices"] = "vertices";
    u[prefix + "normals_compared"] = "vertices";
    u[prefix + "position_max"] = kDiagonal;
    u[prefix + "position_rms"] = kDiagonal;
    u[prefix + "normal_angle_max"] = "radians";
    u[prefix + "normal_angle_rms"] = "radians";
  }
  // The timeline: per bucket, the same counts as above over that bucket's cycles.
  u["timeline.buckets"] = "buckets";
  u["timeline.bucket_cycles"] = "cycles (width of every bucket but the last)";
  u["timeline.cycles[]"] = kCycles;
  u["timeline.int_busy[]"] = "cycles summed over the INT blocks (= operations issued)";
  u["timeline.cpg_busy[]"] = kCycles;
  u["timeline.vertices_out[]"] = "vertices";
  // A chunked run (sim/chunked.hpp): its chunks and how far a single run's cycles can be.
  u["chunks.count"] = "chunks";
  u["chunks.cycles[]"] = kCycles;
  u["chunks.boundary_bound.longer"] = "cycles (per chunk boundary)";
  u["chunks.boundary_bound.shorter"] = "cycles (per chunk boundary)";
  u["chunks.single_run_cycles.min"] = kCycles;
  u["chunks.single_run_cycles.max"] = kCycles;
  u["errors.arithmetic.beyond_bound"] = "vertices";
  u["errors.arithmetic.saturated_vertices"] = "vertices";
  u["errors.arithmetic.scalar_tagged_vertices"] = "vertices";
  return u;
}

nlohmann::json stats_json(const SimResult& r) {
  using nlohmann::json;
  const UnitCounters& u = r.unit;
  json blocks = json::array();
  std::uint64_t busy_total = 0;
  for (int i = 0; i < u.int_blocks; ++i) {
    json b = {{"utilisation", ratio(u.int_busy[static_cast<std::size_t>(i)], u.cycles)}};
    for (std::size_t row = first_row(CounterBlock::Int); row < first_row(CounterBlock::Int) + row_count(CounterBlock::Int); ++row)
      b[kCounterRegistry[row].key] = counter_value(u, row, i);
    blocks.push_back(b);
    busy_total += u.int_busy[static_cast<std::size_t>(i)];
  }
  json j = {
      {"schema_version", kStatsSchemaVersion},
      {"tool", {{"name", "tessim"}, {"version", tool_version()}}},
      {"mesh", r.mesh},
      {"triangles", r.triangles},
      {"config", to_json(r.config)},
      {"cpg_cycles_per_triangle", r.cpg_cycles},
      {"cpg_tag_cycles", r.cpg_tag_cycles},
      {"throughput", throughput(r)},
      {"cycles_per_vertex", cycles_per_vertex(r)},
      {"int",
       {{"blocks", blocks},
        {"busy", busy_total},
        {"ops_per_vertex", ratio(busy_total, u.vertices_out)},
        {"utilisation", int_utilisation(r)}}},
      {"te", classes_json(u.te)},
      {"cpg", classes_json(u.cpg)},
      {"gpe", classes_json<GpeClass>(r.gpe)},
      {"limit", {{"gpe_waited", r.gpe_waited}, {"te_late", classes_json(r.te_late)}}},
      {"stalls",
       {{"te_starved_by_cpg", u.te[TeClass::StarvedByCpg]},
        {"te_blocked_by_gpe", u.te[TeClass::BlockedByGpe]},
        {"gpe_starved_by_te", r.gpe[GpeClass::Starved]}}},
      {"warnings", {{"degenerate_patches", r.degenerate_patches}, {"zero_normals", r.zero_normals}}},
      {"bottleneck", bottleneck(r)},
      {"workload", workload_json(r.factors, r.triangles)},
      {"analytic", analytic_of(r)},
      {"wall_seconds", r.wall_seconds},
      {"timeline", to_json(r.timeline)},
  };
  for (std::size_t row = first_row(CounterBlock::Run); row < first_row(CounterBlock::Run) + row_count(CounterBlock::Run); ++row)
    j[kCounterRegistry[row].key] = counter_value(u, row);
  j["gpe"]["vertices"] = r.gpe.vertices;
  if (r.errors) {
    j["errors"] = to_json(r.errors->mesh);
    j["errors"]["arithmetic"] = to_json(r.errors->arithmetic);
  }
  if (!r.chunk_cycles.empty()) {
    const ChunkBoundaryBound b = chunk_boundary_bound(r.config, r.factors.uniform);
    const std::uint64_t boundaries = r.chunk_cycles.size() - 1;
    j["chunks"] = {{"count", r.chunk_cycles.size()},
                   {"cycles", r.chunk_cycles},
                   {"boundary_bound", {{"longer", b.longer}, {"shorter", b.shorter}}},
                   {"single_run_cycles",
                    {{"min", u.cycles - std::min(u.cycles, boundaries * b.longer)}, {"max", u.cycles + boundaries * b.shorter}}},
                   {"bound", r.config.gpe_stall_prob > 0 ? "expected (random GPE stalls)" : "exact"}};
  }
  j["units"] = stats_units();
  return j;
}

std::string summary(const SimResult& r) {
  const UnitConfig& c = r.config;
  const UnitCounters& u = r.unit;
  const std::uint64_t n = u.cycles;
  std::ostringstream s;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "unit     N=%d INT (latency %d), V=%d contexts, FIFOs tri %d / vtx %d, Q%d.%d (W=%d) B=%d, "
                "CPG %s: %d cycles/triangle",
                c.int_blocks, c.int_latency, c.te_contexts, c.tri_fifo_depth, c.vtx_fifo_depth,
                c.format.coord_int_bits, c.format.coord_frac_bits, c.format.coord_width(), c.format.bary_bits,
                to_string(c.cpg_mapping).c_str(), r.cpg_cycles);
  s << buf;
  if (c.cpg_tags)
    s << " + scalar tags (" << r.cpg_tag_cycles << " cycles over the run, "
      << ratio(r.cpg_tag_cycles, r.triangles) << " per triangle)";
  s << "\n";
  std::string factors;
  if (!r.factors.pattern.empty()) {
    const int lo = r.factors.patches_with_vertices.empty() ? 0 : r.factors.patches_with_vertices.begin()->first;
    const int hi = r.factors.patches_with_vertices.empty() ? 0 : r.factors.patches_with_vertices.rbegin()->first;
    std::snprintf(buf, sizeof buf, "D3D11 pattern %s, %d..%d vertices/patch (%.1f on average)",
                  r.factors.pattern.c_str(), lo, hi, ratio(r.factors.vertices, r.triangles - r.factors.culled));
    if (r.factors.culled) std::snprintf(buf + std::strlen(buf), sizeof buf - std::strlen(buf), ", %llu culled",
                                        static_cast<unsigned long long>(r.factors.culled));
  } else if (r.factors.uniform) {
    const int L = r.triangles ? static_cast<int>(std::find_if(r.factors.patches_with_factor.begin() + 1,
                                                              r.factors.patches_with_factor.end(),
                                                              [](std::uint64_t n) { return n > 0; }) -
                                                 r.factors.patches_with_factor.begin())
                              : c.tess_factor;
    std::snprintf(buf, sizeof buf, "L=%d (%d vertices/patch)", L, pattern_vertex_count(L));
  } else {
    int lo = 0, hi = 0;
    for (int L = 1; L <= kMaxTessFactor; ++L)
      if (r.factors.patches_with_factor[static_cast<std::size_t>(L)]) {
        if (!lo) lo = L;
        hi = L;
      }
    std::snprintf(buf, sizeof buf, "L=%d..%d per patch (%.1f vertices/patch on average)", lo, hi,
                  ratio(r.factors.vertices, r.triangles));
  }
  factors = buf;
  std::snprintf(buf, sizeof buf, "workload %s: %llu triangles, %s, %s normals; GPE K=%d, stall %.2f, seed %llu\n",
                r.mesh.c_str(), static_cast<unsigned long long>(r.triangles), factors.c_str(),
                std::string(to_string(c.normals)).c_str(), c.gpe_cycles, c.gpe_stall_prob,
                static_cast<unsigned long long>(c.seed));
  s << buf;
  std::snprintf(buf, sizeof buf,
                "result   %llu cycles  %llu vertices  %.3f cycles/vertex  %.4f vertices/cycle\n",
                static_cast<unsigned long long>(n), static_cast<unsigned long long>(u.vertices_out),
                cycles_per_vertex(r), throughput(r));
  s << buf;
  s << "limit    " << bottleneck(r) << "\n";
  s << "INT      utilisation " << percent(static_cast<std::uint64_t>(int_utilisation(r) * 1e6), 1000000)
    << "  per block:";
  for (std::size_t i = 0; i < u.int_busy_used().size(); ++i) s << "  " << i << ":" << percent(u.int_busy[i], n);
  s << "\n";
  s << classes_line(u.te, n) << classes_line(u.cpg, n) << classes_line<GpeClass>(r.gpe, n);
  // The late intervals: the TE's three stall classes that name a limit, busy, and the rest.
  const ClassCounts<TeClass>& w = r.te_late;
  const std::uint64_t gw = w.total();
  s << "late     GPE waited " << percent(r.gpe_waited, n) << " of cycles; TE in the late intervals:";
  std::uint64_t other = gw;
  for (TeClass c : {TeClass::ContextLimited, TeClass::IntLimited, TeClass::StarvedByCpg, TeClass::Busy}) {
    s << (c == TeClass::ContextLimited ? " " : "  ") << to_string(c) << " " << percent(w[c], gw);
    other -= w[c];
  }
  s << "  other " << percent(other, gw) << "\n";
  if (r.errors) {
    const ErrorStats& m = r.errors->mesh;
    const ArithmeticErrors& a = r.errors->arithmetic;
    std::snprintf(buf, sizeof buf,
                  "errors   vs the mesh's float reference: position max %.3g rms %.3g of the diagonal, normal max "
                  "%.3g rms %.3g rad\n         arithmetic alone: position max %.3g of the diagonal, normal max %.3g "
                  "rad, %llu vertices beyond the derived bound\n",
                  m.position_max, m.position_rms, m.normal_angle_max, m.normal_angle_rms, a.stats.position_max,
                  a.stats.normal_angle_max, static_cast<unsigned long long>(a.beyond_bound));
    s << buf;
    if (a.beyond_bound) s << "         first beyond the bound: " << a.worst << "\n";
  }
  if (!r.chunk_cycles.empty()) {
    const ChunkBoundaryBound b = chunk_boundary_bound(c, r.factors.uniform);
    const std::uint64_t boundaries = r.chunk_cycles.size() - 1;
    std::snprintf(buf, sizeof buf,
                  "chunks   %zu chunks in parallel, each from reset: cycles are their sum; a single run: %llu..%llu "
                  "cycles (%llu longer .. %llu shorter per boundary%s)\n",
                  r.chunk_cycles.size(), static_cast<unsigned long long>(n - std::min(n, boundaries * b.longer)),
                  static_cast<unsigned long long>(n + boundaries * b.shorter), static_cast<unsigned long long>(b.longer),
                  static_cast<unsigned long long>(b.shorter), c.gpe_stall_prob > 0 ? ", on average: random stalls" : "");
    s << buf;
  }
  if (r.degenerate_patches > 0 || r.zero_normals > 0)
    s << "warning  " << r.degenerate_patches << " patches hit a zero divisor (zero-length edge or "
      << "vanishing mid-edge normal), " << r.zero_normals << " output normals vanished\n";
  return s.str();
}

ScheduleRecorder::ScheduleRecorder(int table_cycles, std::size_t max_vertices)
    : table_cycles_(table_cycles), max_vertices_(max_vertices) {
  rows_.reserve(static_cast<std::size_t>(table_cycles));
  retire_cycles_.reserve(max_vertices);
}

bool ScheduleRecorder::on_cycle(const Unit& unit, const GpeCycle&) {
  const CycleActivity& a = unit.activity();
  const bool started = !rows_.empty() || a.ops_issued > 0;
  if (started && rows_.size() < static_cast<std::size_t>(table_cycles_)) {
    Row row{a.cycle, {unit.issued_ops(), unit.issued_ops() + a.ops_issued}, a.allocated, a.retired,
            a.allocated_vertex, a.retired_vertex, a.te};
    rows_.push_back(std::move(row));
  }
  if (a.retired && retire_cycles_.size() < max_vertices_) retire_cycles_.push_back(a.cycle);
  return rows_.size() < static_cast<std::size_t>(table_cycles_) || retire_cycles_.size() < max_vertices_;
}

double ScheduleRecorder::steady_cycles_per_vertex() const {
  const std::size_t n = retire_cycles_.size();
  if (n < 16) return 0.0;
  // A window of whole periods: 2520 is a multiple of every period of up to 10 vertices.
  std::size_t window = (n / 2) / 2520 * 2520;
  if (window == 0) window = n / 2;
  const std::size_t hi = n - 1, lo = hi - window;
  return static_cast<double>(retire_cycles_[hi] - retire_cycles_[lo]) / static_cast<double>(hi - lo);
}

std::string ScheduleRecorder::table(int int_blocks) const {
  std::ostringstream s;
  char buf[64];
  s << "cycle ";
  for (int b = 0; b < int_blocks; ++b) {
    std::snprintf(buf, sizeof buf, " INT%-5d", b);
    s << buf;
  }
  s << " TE              events\n";
  for (const Row& row : rows_) {
    std::snprintf(buf, sizeof buf, "%5llu ", static_cast<unsigned long long>(row.cycle));
    s << buf;
    for (int b = 0; b < int_blocks; ++b) {
      char cell[32] = ".";
      if (static_cast<std::size_t>(b) < row.ops.size()) {
        const IssuedOp& op = row.ops[static_cast<std::size_t>(b)];
        std::snprintf(cell, sizeof cell, "v%llu.%d", static_cast<unsigned long long>(op.vertex), op.op);
      }
      std::snprintf(buf, sizeof buf, " %-8s", cell);
      s << buf;
    }
    std::snprintf(buf, sizeof buf, " %-15s", to_string(row.te));
    s << buf;
    if (row.allocated) s << " alloc v" << row.allocated_vertex;
    if (row.retired) s << " retire v" << row.retired_vertex;
    s << "\n";
  }
  return s.str();
}

}  // namespace tessim::sim
