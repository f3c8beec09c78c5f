#include "sim/simulate.hpp"

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

#include "model/base/error.hpp"
#include "sim/late_intervals.hpp"
#include "sim/output_check.hpp"
#include "sim/patch_assembly.hpp"
#include "sim/testbench.hpp"
#include "sim/timeline_recorder.hpp"
#include "sim/watchdog.hpp"

namespace tessim::sim {

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
  const std::uint64_t total = source.vertices();

  // The run's concerns besides stepping the unit, each fed what it watches.
  OutputCheck output(mesh, source, cfg.format, patterns.d3d11 != nullptr);
  std::optional<PatchAssembly> patches;
  if (hooks.on_patch) patches.emplace(source, r.scaling, cfg.format, cfg.tess_factor, hooks.on_patch);
  std::optional<MeshErrors> mesh_errors;
  std::optional<ArithmeticCheck> arithmetic;
  if (hooks.measure_errors) {
    mesh_errors.emplace(mesh, r.scaling, cfg, cfg.cpg_tags, patterns.d3d11, patterns.silhouette);
    arithmetic.emplace(ArithmeticCheck::for_mesh(mesh, r.scaling, cfg, patterns));
  }
  LateIntervals late;
  TimelineRecorder timeline(r.timeline);
  Watchdog watchdog(cfg, unit.cpg_cycles());
  std::vector<CycleObserver*> observers = hooks.observers;

  std::uint64_t accepted = 0;
  std::uint64_t cycle = 0;
  const bool fast_forward = hooks.fast_forward && observers.empty();
  while (accepted < total) {
    // A cycle that accepted a vertex is followed by its retirement's refill: not worth asking.
    if (fast_forward && !tb.gpe_cycle().accepted) {
      // Quiet cycles at once, never past the cycle at which the watchdog would fire, nor past
      // the timeline's next boundary while the TE issues (its cycles are not all alike).
      const std::uint64_t n =
          tb.fast_forward(unit, watchdog.cycles_left(cycle), timeline.next_boundary() - cycle);
      if (n > 0) {
        if (tb.gpe_cycle().spare && accepted > 0) late.waited(n);
        cycle += n;
        timeline.stretch_done(cycle, unit, tb.gpe(), tb.gpe_cycle().cls);
        watchdog.check(cycle);
        continue;
      }
    }
    const UnitInputs& in = tb.inputs(unit);
    const GpeCycle& g = tb.gpe_cycle();
    if (g.accepted) {
      const VertexFx& v = unit.vtx();
      output.check(v, cycle);
      if (hooks.on_vertex) hooks.on_vertex(v);
      if (mesh_errors) {
        mesh_errors->add(v);
        arithmetic->check(v);
      }
      if (patches) patches->add(v, output.index(), output.L(), output.patch_vertices());
      if (v.last) {
        if (hooks.vertices_done)
          hooks.vertices_done->fetch_add(static_cast<std::uint64_t>(output.patch_vertices()),
                                         std::memory_order_relaxed);
        if (hooks.cancel && hooks.cancel->load(std::memory_order_relaxed)) throw SimCancelled();
      }
      output.next();
      ++accepted;
      watchdog.progress(cycle);
    }
    const bool gpe_waited = g.spare && accepted > 0;  // GPE ready, no vertex, after its first
    unit.tick(in);
    if (gpe_waited) late.waited(1);
    if (g.accepted) late.accepted(unit.te_class_cycles());
    if (!observers.empty()) {
      std::erase_if(observers, [&](CycleObserver* o) { return !o->on_cycle(unit, g); });
    }
    ++cycle;
    timeline.cycle_done(cycle, unit, tb.gpe());
    watchdog.check(cycle);
  }

  timeline.finish(cycle, unit, tb.gpe());
  r.unit = unit.stats();
  r.gpe = tb.gpe().stats();
  r.gpe_waited = late.gpe_waited();
  r.te_late = late.te_late();
  r.degenerate_patches = output.degenerate_patches();
  r.zero_normals = output.zero_normals();
  if (mesh_errors) r.errors = SimErrors{mesh_errors->result(), arithmetic->result()};
  r.cpg_tag_cycles = unit.cpg_tag_cycles();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace tessim::sim
