#include "sim/report/report.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "sim/base/counter_registry.hpp"
#include "sim/config/analytic.hpp"
#include "sim/ge/ge_cost.hpp"
#include "sim/run/chunked.hpp"
#include "sim/values/unit_io.hpp"
#include "sim/version.hpp"

namespace tessim::sim {

namespace {

double ratio(std::uint64_t a, std::uint64_t b) { return b == 0 ? 0.0 : static_cast<double>(a) / b; }

// A block's classes by their keys (docs/statistics.md: "te", "cpg", "gpe", "limit.te_late").
template <class Class>
nlohmann::json classes_json(const ClassCounts<Class>& counts) {
  nlohmann::json j = nlohmann::json::object();
  for (Class c : all_of<Class>()) j[to_string(c)] = counts[c];
  return j;
}

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
  const UnitConfig cfg = with_ge_cost(r.config, r.ge);  // K with the GE's shader work
  if (r.factors.uniform) return analytic_json(predict(cfg, cpg_c), cfg, r.triangles);
  const AnalyticPrediction p = predict(cfg, cpg_c, ratio(r.factors.vertices, r.triangles));
  nlohmann::json j = analytic_json(p, cfg, r.triangles);
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
      {"workload.vertices_per_patch_log2_histogram[]", "patches with 2^(i+1)..2^(i+2)-1 vertices (i = 0: 3, single triangles)"},
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
      {"ge.cycles_per_vertex.base", "cycles/vertex (K)"},
      {"ge.cycles_per_vertex.evaluation", "cycles/vertex"},
      {"ge.cycles_per_vertex.displacement", "cycles/vertex"},
      {"ge.cycles_per_vertex.total", "cycles/vertex"},
      {"ge.shader_slots_per_vertex", "issue slots/vertex (evaluation and displacement)"},
      {"gpe.drain_cycles", "cycles (after the last acceptance, to the GE's last vertex finished)"},
      {"ge.core.lanes", "lanes"},
      {"ge.core.issue", "wave instructions/core cycle"},
      {"ge.core.core_mhz", "MHz"},
      {"ge.core.unit_mhz", "MHz"},
      {"ge.core.fifo", "vertices"},
      {"ge.core.program_slots_per_vertex", "issue slots/vertex (the GE's own work and the shader work)"},
      {"ge.core.wave_cycles", "core cycles/wave"},
      {"ge.core.cycles_per_vertex", "cycles/vertex (K derived: unit cycles at full waves)"},
      {"ge.core.core_cycles", "core cycles"},
      {"ge.core.issue_cycles", "core cycles"},
      {"ge.core.waves", "waves"},
      {"ge.core.lane_use", kShare},
      {"ge.core.fifo_peak", "vertices"},
      {"system.units[].triangles", "triangles"},
      {"system.units[].vertices", "vertices"},
      {"system.ports[].vertices", "vertices"},
      {"system.buffer.slots", "vertices"},
      {"system.buffer.max_occupancy", "vertices"},
      {"system.buffer.occupancy_histogram[]", "cycles with i..i+1 sixteenths of the slots taken (15: up to full)"},
      {"system.stalls.dispatch", "cycles (a triangle waited for its unit)"},
      {"system.stalls.units_blocked_by_buffer", "unit-cycles"},
      {"system.stalls.ports_waiting_for_unit", "port-cycles"},
      {"system.stalls.ports_waiting_for_stream", "port-cycles"},
      {"ge.displacement.amplitude", "mesh units"},
      {"ge.displacement.frequency", "radians per mesh unit"},
  };
  // Every counter of the registry (sim/base/counter_registry.hpp) where the JSON has it: the
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
        u["system.units[].te." + key] = row.unit;
        break;
      case CounterBlock::Cpg:
        u["cpg." + key] = row.unit;
        u["system.units[].cpg." + key] = row.unit;
        break;
      case CounterBlock::Gpe:
        u["gpe." + key] = row.unit;
        u["system.ports[]." + key] = row.unit;
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
  // A chunked run (sim/run/chunked.hpp): its chunks and how far a single run's cycles can be.
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
      {"ge",
       {{"cycles_per_vertex",
         {{"base", r.ge.base}, {"evaluation", r.ge.evaluation}, {"displacement", r.ge.displacement}, {"total", r.ge.total()}}},
        {"shader_slots_per_vertex", r.ge.shader_slots},
        {"displacement",
         {{"kind", to_string(r.displace.kind)}, {"amplitude", r.displace.amplitude}, {"frequency", r.displace.frequency}}}}},
  };
  for (std::size_t row = first_row(CounterBlock::Run); row < first_row(CounterBlock::Run) + row_count(CounterBlock::Run); ++row)
    j[kCounterRegistry[row].key] = counter_value(u, row);
  j["gpe"]["vertices"] = r.gpe.vertices;
  j["gpe"]["drain_cycles"] = r.gpe_drain_cycles;
  if (r.config.ge_core()) {
    const UnitConfig run = with_ge_cost(r.config, r.ge);
    const GeCoreStats& k = r.ge_core;
    j["ge"]["core"] = {{"lanes", run.ge_core_lanes},
                       {"issue", run.ge_core_issue},
                       {"core_mhz", run.ge_core_mhz},
                       {"unit_mhz", run.unit_mhz},
                       {"fifo", run.ge_core_fifo},
                       {"program_slots_per_vertex", core_program_slots(run)},
                       {"wave_cycles", core_wave_cycles(run)},
                       {"cycles_per_vertex", core_cycles_per_vertex(run)},
                       {"core_cycles", k.core_cycles},
                       {"issue_cycles", k.issue_cycles},
                       {"waves", k.waves},
                       {"lane_use", ratio(k.lanes_filled, k.waves * static_cast<std::uint64_t>(run.ge_core_lanes))},
                       {"fifo_peak", k.fifo_peak}};
  }
  if (r.system) {
    // A system of units: "cycles" is the system's; the unit blocks' classes above sum the units.
    const SystemStats& st = r.system->stats;
    j["cycles"] = st.cycles;
    json units = json::array();
    for (std::size_t i = 0; i < r.system->units.size(); ++i) {
      const UnitCounters& k = r.system->units[i];
      units.push_back({{"triangles", st.unit_triangles[i]}, {"vertices", st.unit_vertices[i]},
                       {"te", classes_json(k.te)}, {"cpg", classes_json(k.cpg)}});
    }
    json ports = json::array();
    for (const GpeStats& g : r.system->ports) {
      json p = classes_json<GpeClass>(g);
      p["vertices"] = g.vertices;
      ports.push_back(p);
    }
    j["system"] = {{"units", units},
                   {"ports", ports},
                   {"buffer",
                    {{"slots", r.config.reorder_slots},
                     {"max_occupancy", st.max_occupancy},
                     {"occupancy_histogram", st.occupancy_histogram}}},
                   {"stalls",
                    {{"dispatch", st.dispatch_stalls},
                     {"units_blocked_by_buffer", st.unit_blocked},
                     {"ports_waiting_for_unit", st.ports_waiting_unit},
                     {"ports_waiting_for_stream", st.ports_waiting_stream}}}};
  }
  if (r.errors) {
    j["errors"] = to_json(r.errors->mesh);
    j["errors"]["arithmetic"] = to_json(r.errors->arithmetic);
  }
  if (!r.chunk_cycles.empty()) {
    const ChunkBoundaryBound b = chunk_boundary_bound(with_ge_cost(r.config, r.ge), r.factors.uniform);
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

}  // namespace tessim::sim
