#include "sim/run/simulate.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <unordered_map>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "model/base/error.hpp"
#include "model/tessellate.hpp"
#include "sim/ge/ge_evaluation.hpp"
#include "sim/run/late_intervals.hpp"
#include "sim/run/output_check.hpp"
#include "sim/run/patch_assembly.hpp"
#include "sim/run/testbench.hpp"
#include "sim/run/timeline_recorder.hpp"
#include "sim/run/watchdog.hpp"
#include "sim/system/system.hpp"
#include "sim/system/system_threads.hpp"

namespace tessim::sim {

std::function<void(const PatchOut&)> displaced(std::function<void(const PatchOut&)> on_patch,
                                               const DisplaceSettings& displace) {
  // The buffers live as long as the returned function: no allocation per patch once they have
  // grown to the largest patch.
  auto positions = std::make_shared<std::vector<glm::dvec3>>();
  auto normals = std::make_shared<std::vector<glm::dvec3>>();
  return [on_patch = std::move(on_patch), displace, positions, normals](const PatchOut& p) {
    positions->assign(p.positions.begin(), p.positions.end());
    normals->assign(p.normals.begin(), p.normals.end());
    for (std::size_t i = 0; i < positions->size(); ++i) {
      glm::dvec3& n = (*normals)[i];
      // A vanished normal (counted in warnings.zero_normals) gives no direction: the point stays.
      if (n == glm::dvec3(0.0)) continue;
      const DisplacedPoint d = tessim::displace(displace, (*positions)[i], n);
      (*positions)[i] = d.position;
      n = d.normal;
    }
    on_patch(PatchOut{p.triangle, p.L, *positions, *normals, p.indices});
  };
}

namespace {

// The float patch the GE evaluates from a control-point buffer the CPG filled: dequantized, back in
// the mesh's coordinates (the normal net is stored at twice its value; a uniform scale leaves the
// normals' directions).
PnPatch patch_from_fixed(const ControlPointsFx& cp, NormalMode mode, const NumberFormat& fmt, const HostScaling& scaling) {
  PnPatch p;
  p.mode = mode;
  for (std::size_t i = 0; i < p.b.size(); ++i) p.b[i] = scaling.from_unit(dequantize(cp.b[i], fmt));
  for (std::size_t i = 0; i < p.n_bern.size(); ++i) p.n_bern[i] = 0.5 * dequantize(cp.n[i], fmt);
  // Linear mode: the corners of the net hold N1, N2, N3 as they are.
  constexpr std::array<int, 3> kCorners{net_index(0, 0, 2), net_index(2, 0, 2), net_index(0, 2, 2)};
  for (std::size_t c = 0; c < 3; ++c) p.n_corner[c] = dequantize(cp.n[static_cast<std::size_t>(kCorners[c])], fmt);
  return p;
}

// What a run does with each vertex the geometry engine accepts, the same for one unit and for a
// system: the stream-order check, the hooks, the error measurement and the patches handed out.
class AcceptedVertices {
 public:
  AcceptedVertices(const Mesh& mesh, const MeshSource& source, const UnitConfig& cfg, const SimHooks& hooks,
                   const MeshPatterns& patterns, const HostScaling& scaling)
      : hooks_(hooks),
        output_(mesh, source, cfg.format, patterns.d3d11 != nullptr),
        on_patch_(patch_sink(hooks, patterns)) {
    if (on_patch_) patches_.emplace(source, scaling, cfg.format, cfg.tess_factor, on_patch_);
    if (hooks.measure_errors) {
      mesh_errors_.emplace(mesh, scaling, cfg, cfg.cpg_tags, patterns.d3d11, patterns.silhouette);
      arithmetic_.emplace(ArithmeticCheck::for_mesh(mesh, scaling, cfg, patterns));
    }
  }

  // The vertex `v`, accepted in `cycle`. Throws SimCancelled at a patch's end when asked to.
  void take(const VertexFx& v, std::uint64_t cycle) {
    output_.check(v, cycle);
    if (hooks_.on_vertex) hooks_.on_vertex(v);
    if (mesh_errors_) {
      mesh_errors_->add(v);
      arithmetic_->check(v);
    }
    if (patches_) patches_->add(v, output_.index(), output_.L(), output_.patch_vertices());
    if (v.last) {
      if (hooks_.vertices_done)
        hooks_.vertices_done->fetch_add(static_cast<std::uint64_t>(output_.patch_vertices()), std::memory_order_relaxed);
      if (hooks_.cancel && hooks_.cancel->load(std::memory_order_relaxed)) throw SimCancelled();
    }
    output_.next();
  }

  // The run's warnings and errors into `r`.
  void finish(SimResult& r) const {
    r.degenerate_patches = output_.degenerate_patches();
    r.zero_normals = output_.zero_normals();
    if (mesh_errors_) r.errors = SimErrors{mesh_errors_->result(), arithmetic_->result()};
  }

  // hooks.on_patch, behind the GE's displacement when the run displaces.
  static std::function<void(const PatchOut&)> patch_sink(const SimHooks& hooks, const MeshPatterns& patterns) {
    return patterns.displace.enabled() && hooks.on_patch ? displaced(hooks.on_patch, patterns.displace) : hooks.on_patch;
  }

 private:
  const SimHooks& hooks_;
  OutputCheck output_;
  std::function<void(const PatchOut&)> on_patch_;  // PatchAssembly keeps a reference to it
  std::optional<PatchAssembly> patches_;
  std::optional<MeshErrors> mesh_errors_;
  std::optional<ArithmeticCheck> arithmetic_;
};

// The loop a configuration runs: one unit, a system of units (cfg.units > 1) or the unit without
// TE of evaluation gpe (validate() admits a system only with evaluation unit).
enum class Loop { Unit, System, GeEvaluation };

Loop loop_of(const UnitConfig& cfg) {
  if (cfg.evaluation == Evaluation::Gpe) return Loop::GeEvaluation;
  return cfg.units > 1 ? Loop::System : Loop::Unit;
}

// The setup the three loops share, in the order they have always done it: the arguments checked,
// the result as far as it is known before the first cycle, what the loop cannot do with the hooks
// refused, the configuration the testbench and the watchdog see, and the run's triangles in stream
// order. A loop builds its unit, calls started() and returns finish().
struct RunSetup {
  RunSetup(const Mesh& mesh, const UnitConfig& cfg, std::uint64_t first, std::uint64_t end, const SimHooks& hooks,
           const MeshPatterns& patterns)
      : mesh(mesh),
        cfg(cfg),
        hooks(hooks),
        patterns(patterns),
        loop(loop_of(cfg)),
        r(start(first, end)),
        run_cfg(with_ge_cost(cfg, r.ge)),
        source(mesh, r.scaling, cfg.format, cfg.tess_factor, patterns, with_tags(cfg), first, end),
        total(source.vertices()) {
    r.factors = workload_factors(source);
  }

  // The loop's unit is built: its C goes into the result, and the watchdog allows `waits` times
  // what that unit's waits can take.
  Watchdog started(int cpg_cycles, int waits = 1) {
    r.cpg_cycles = cpg_cycles;
    return Watchdog(run_cfg, cpg_cycles * waits);
  }

  // The result, with the run's wall time.
  SimResult finish() {
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::move(r);
  }

  const Mesh& mesh;
  const UnitConfig& cfg;
  const SimHooks& hooks;
  const MeshPatterns& patterns;
  const Loop loop;
  std::chrono::steady_clock::time_point t0;
  SimResult r;
  const UnitConfig run_cfg;  // the geometry engine as the run sees it: K plus its shader work per vertex
  MeshSource source;
  const std::uint64_t total;  // the vertices the geometry engine accepts over the run

 private:
  // The mesh's scalar tags go along when the loop's CPG takes them: in evaluation gpe, only a
  // dedicated CPG does.
  static bool with_tags(const UnitConfig& cfg) {
    return cfg.evaluation == Evaluation::Gpe ? cfg.cpg_tags && cfg.cpg_mapping == CpgMapping::Dedicated
                                             : cfg.cpg_tags != 0;
  }

  // Everything before the run's triangles; t0 is taken once the arguments have passed.
  SimResult start(std::uint64_t first, std::uint64_t end) {
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
    t0 = std::chrono::steady_clock::now();
    check_convertible(mesh);
    SimResult result;
    result.mesh = mesh.source;
    result.config = cfg;
    result.triangles = end - first;
    result.scaling = host_scaling(mesh);
    validate(patterns.displace, "displacement");
    result.displace = patterns.displace;
    result.ge = ge_vertex_cost(cfg, patterns.displace.kind);
    if (loop == Loop::GeEvaluation && !hooks.observers.empty())
      throw InputError("configuration", "evaluation", "gpe has no TE to trace or schedule (--trace, --schedule)");
    if (loop == Loop::GeEvaluation && (hooks.measure_errors || hooks.on_vertex))
      throw InputError("configuration", "evaluation",
                       "gpe evaluates in float on the geometry engine: --errors measures the unit's fixed-point output");
    if (loop == Loop::System && !hooks.observers.empty())
      throw InputError("command line", "--units", "a trace or schedule follows one unit: not a system of several");
    return result;
  }
};

// evaluation gpe: the DPG's points evaluated by the geometry engine (sim/ge/ge_evaluation.hpp),
// cycle by cycle.
SimResult simulate_ge_evaluation(RunSetup& setup) {
  const Mesh& mesh = setup.mesh;
  const UnitConfig& cfg = setup.cfg;
  const SimHooks& hooks = setup.hooks;
  const MeshPatterns& patterns = setup.patterns;
  SimResult& r = setup.r;
  GeEvaluationUnit unit(cfg);
  BasicTestbench<MeshSource> tb(setup.source, setup.run_cfg);
  Watchdog watchdog = setup.started(unit.cpg_cycles());
  const std::uint64_t total = setup.total;
  std::optional<PatchAssembly> patches;
  const std::function<void(const PatchOut&)> on_patch = AcceptedVertices::patch_sink(hooks, patterns);
  if (on_patch) patches.emplace(setup.source, r.scaling, cfg.format, cfg.tess_factor, on_patch);
  // The host's control points (cpg_mapping host): the float reference's, once per patch.
  PnPatch host_patch;
  std::uint32_t host_patch_id = UINT32_MAX;
  std::uint64_t accepted = 0, cycle = 0;
  while (accepted < total) {
    const UnitInputs& in = tb.inputs(unit);
    const GpeCycle& g = tb.gpe_cycle();
    if (g.accepted) {
      const GePoint& v = unit.vtx();
      const ControlPointBuffer::Entry& e = unit.entry(v.buffer);
      if (patches) {
        const double one = static_cast<double>(cfg.format.bary_one());
        const double u = static_cast<double>(v.point.u) / one, w_v = static_cast<double>(v.point.v) / one;
        PnVertex out;
        if (cfg.cpg_mapping == CpgMapping::Host) {
          if (host_patch_id != v.id) {
            host_patch = mesh_patch(mesh, v.id, cfg.normals, patterns.silhouette);
            host_patch_id = v.id;
          }
          out = eval_bernstein(host_patch, u, w_v);
        } else {
          out = eval_bernstein(patch_from_fixed(e.cp, cfg.normals, cfg.format, r.scaling), u, w_v);
        }
        const bool uniform = e.pattern == TriPattern::uniform;
        patches->add(out.position, out.normal, v.id, v.point.last, v.point.index, uniform ? e.L : 0,
                     uniform ? pattern_vertex_count(e.L) : e.d3d11.point_count);
      }
      if (v.point.last && hooks.vertices_done)
        hooks.vertices_done->fetch_add(static_cast<std::uint64_t>(v.point.index + 1), std::memory_order_relaxed);
      if (v.point.last && hooks.cancel && hooks.cancel->load(std::memory_order_relaxed)) throw SimCancelled();
      ++accepted;
      watchdog.progress(cycle);
    }
    unit.tick(in);
    ++cycle;
    watchdog.check(cycle);
  }
  // No timeline: its buckets follow the TE's classes, and there is no TE.
  r.unit = unit.stats();
  r.gpe = tb.gpe().stats();
  r.gpe_drain_cycles = tb.gpe().drain_cycles();
  r.ge_core = tb.gpe().core_stats();
  r.cpg_tag_cycles = unit.cpg_tag_cycles();
  return setup.finish();
}

// The patches of an unordered system, held until every earlier patch has been handed on.
class StreamOrder {
 public:
  void dispatched(std::uint32_t id) { order_.push_back(id); }
  // `emit` gets the vertices in stream order, as soon as every earlier one has come.
  template <class Emit>
  void take(const VertexFx& v, Emit&& emit) {
    if (!order_.empty() && v.id == order_.front() && held_.find(v.id) == held_.end()) {
      emit(v);  // the oldest patch, nothing of it held: straight through
      if (v.last) {
        order_.pop_front();
        release(emit);
      }
      return;
    }
    held_[v.id].push_back(v);
  }

 private:
  template <class Emit>
  void release(Emit&& emit) {
    while (!order_.empty()) {
      auto it = held_.find(order_.front());
      if (it == held_.end()) return;
      for (const VertexFx& w : it->second) emit(w);
      if (!it->second.back().last) {
        it->second.clear();  // the rest comes straight through
        held_.erase(it);
        return;
      }
      held_.erase(it);
      order_.pop_front();
    }
  }

  std::deque<std::uint32_t> order_;
  std::unordered_map<std::uint32_t, std::vector<VertexFx>> held_;
};

// cfg.units > 1: the system of sim/system/system.hpp, cycle by cycle.
SimResult simulate_system(RunSetup& setup) {
  const UnitConfig& cfg = setup.cfg;
  const SimHooks& hooks = setup.hooks;
  SimResult& r = setup.r;
  MeshSource& source = setup.source;  // popped here: no testbench stands between it and the system
  UnitSystem system(cfg, r.ge.total());
  // A system's vertex can wait behind another unit's patches: the watchdog allows M times a unit's.
  Watchdog watchdog = setup.started(system.unit(0).cpg_cycles(), cfg.units);
  const std::uint64_t total = setup.total;
  AcceptedVertices accepted_vertices(setup.mesh, source, cfg, hooks, setup.patterns, r.scaling);
  std::uint64_t accepted = 0, cycle = 0;
  // Unordered reassembly: what the ports took is put back in stream order for everything after
  // the run (order check, hooks, output file). The simulator's buffer, not the hardware's.
  const bool unordered = cfg.reassembly == Reassembly::Unordered;
  StreamOrder stream_order;
  // Fast-forward as one unit does (docs/microarchitecture.md §11), asked after a cycle in which no
  // port took a vertex.
  const bool fast_forward = hooks.fast_forward;
  auto run = [&](auto&& tick, auto&& skip) {
    while (accepted < total) {
      if (fast_forward && system.emitted().empty()) {
        const std::uint64_t n = skip(source.available(), source.front(), watchdog.cycles_left(cycle));
        if (n > 0) {
          cycle += n;
          watchdog.check(cycle);
          continue;
        }
      }
      const bool tri_valid = source.available();
      if (tick(tri_valid, source.front())) {
        if (unordered) stream_order.dispatched(source.front().id);
        source.pop();
      }
      for (const VertexFx& v : system.emitted()) {
        if (unordered)
          stream_order.take(v, [&](const VertexFx& w) { accepted_vertices.take(w, cycle); });
        else
          accepted_vertices.take(v, cycle);
        ++accepted;
        watchdog.progress(cycle);
      }
      ++cycle;
      watchdog.check(cycle);
    }
  };
  const int threads = std::min(hooks.system_threads, cfg.units);
  if (threads > 1) {
    ThreadedSystem threaded(system, threads);
    run([&](bool tri_valid, const TriangleFx& tri) { return threaded.tick(tri_valid, tri); },
        [&](bool tri_valid, const TriangleFx& tri, std::uint64_t limit) {
          return threaded.fast_forward(tri_valid, tri, limit);
        });
    threaded.finish();
  } else {
    run([&](bool tri_valid, const TriangleFx& tri) { return system.tick(tri_valid, tri); },
        [&](bool tri_valid, const TriangleFx& tri, std::uint64_t limit) {
          return system.fast_forward(tri_valid, tri, limit);
        });
  }
  SystemResult sys;
  sys.stats = system.stats();
  for (int u = 0; u < system.units(); ++u) {
    sys.units.push_back(system.unit(u).stats());
    add(r.unit, sys.units.back());
    r.cpg_tag_cycles += system.unit(u).cpg_tag_cycles();
  }
  r.unit.int_blocks = cfg.int_blocks;
  for (int p = 0; p < system.ports(); ++p) {
    sys.ports.push_back(system.port(p).stats());
    r.gpe += sys.ports.back();
    r.gpe.cycles += sys.ports.back().cycles;
    r.gpe.vertices += sys.ports.back().vertices;
  }
  r.system = std::move(sys);
  accepted_vertices.finish(r);
  return setup.finish();
}

// One unit, cycle by cycle: the observers, fast-forward, the limit line and the timeline.
SimResult simulate_unit(RunSetup& setup) {
  const UnitConfig& cfg = setup.cfg;
  const SimHooks& hooks = setup.hooks;
  SimResult& r = setup.r;
  Unit unit(cfg);
  BasicTestbench<MeshSource> tb(setup.source, setup.run_cfg);
  Watchdog watchdog = setup.started(unit.cpg_cycles());
  const std::uint64_t total = setup.total;

  // The run's concerns besides stepping the unit, each fed what it watches.
  AcceptedVertices accepted_vertices(setup.mesh, setup.source, cfg, hooks, setup.patterns, r.scaling);
  LateIntervals late;
  TimelineRecorder timeline(r.timeline);
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
      accepted_vertices.take(unit.vtx(), cycle);
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
  r.gpe_drain_cycles = tb.gpe().drain_cycles();
  r.ge_core = tb.gpe().core_stats();
  r.gpe_waited = late.gpe_waited();
  r.te_late = late.te_late();
  accepted_vertices.finish(r);
  r.cpg_tag_cycles = unit.cpg_tag_cycles();
  return setup.finish();
}

}  // namespace

SimResult simulate(const Mesh& mesh, const UnitConfig& cfg, const SimHooks& hooks, MeshPatterns patterns) {
  return simulate_range(mesh, cfg, 0, mesh.triangle_count(), hooks, patterns);
}

SimResult simulate_range(const Mesh& mesh, const UnitConfig& cfg, std::uint64_t first, std::uint64_t end,
                         const SimHooks& hooks, MeshPatterns patterns) {
  RunSetup setup(mesh, cfg, first, end, hooks, patterns);
  switch (setup.loop) {
    case Loop::GeEvaluation: return simulate_ge_evaluation(setup);
    case Loop::System: return simulate_system(setup);
    case Loop::Unit: break;
  }
  return simulate_unit(setup);
}

}  // namespace tessim::sim
