#include "sim/run/chunked.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "model/pattern.hpp"
#include "sim/config/analytic.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

std::vector<std::uint64_t> chunk_starts(std::uint64_t triangles, int chunks) {
  if (chunks < 1 || static_cast<std::uint64_t>(chunks) > std::max<std::uint64_t>(triangles, 1))
    throw std::logic_error("chunk_starts: " + std::to_string(chunks) + " chunks of " + std::to_string(triangles) +
                           " triangles");
  const auto k = static_cast<std::uint64_t>(chunks);
  std::vector<std::uint64_t> starts;
  for (std::uint64_t i = 0; i <= k; ++i) starts.push_back(triangles / k * i + std::min(i, triangles % k));
  return starts;
}

UnitConfig chunk_config(const UnitConfig& cfg, int chunk) {
  UnitConfig c = cfg;
  if (chunk > 0) {
    // Distinct, reproducible streams: the seed mixed with the chunk index.
    SplitMix64 mix(cfg.seed ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(chunk)));
    c.seed = mix.next();
  }
  return c;
}

namespace {

// Root mean squares over two disjoint sets: sqrt((n_a rms_a^2 + n_b rms_b^2) / (n_a + n_b)).
double merged_rms(double a, std::uint64_t na, double b, std::uint64_t nb) {
  if (na + nb == 0) return 0.0;
  return std::sqrt((static_cast<double>(na) * a * a + static_cast<double>(nb) * b * b) / static_cast<double>(na + nb));
}

void add(ErrorStats& a, const ErrorStats& b) {
  a.position_rms = merged_rms(a.position_rms, a.vertices, b.position_rms, b.vertices);
  a.normal_angle_rms = merged_rms(a.normal_angle_rms, a.normals_compared, b.normal_angle_rms, b.normals_compared);
  a.vertices += b.vertices;
  a.normals_compared += b.normals_compared;
  a.position_max = std::max(a.position_max, b.position_max);
  a.normal_angle_max = std::max(a.normal_angle_max, b.normal_angle_max);
}

}  // namespace

SimResult merge_chunks(std::span<const SimResult> parts, const UnitConfig& cfg) {
  if (parts.empty()) throw std::logic_error("merge_chunks: no chunks");
  SimResult r;
  const SimResult& first = parts.front();
  r.mesh = first.mesh;
  r.factors.pattern = first.factors.pattern;
  r.config = cfg;
  r.cpg_cycles = first.cpg_cycles;
  r.scaling = first.scaling;
  r.ge = first.ge;
  r.displace = first.displace;
  r.unit.int_blocks = first.unit.int_blocks;
  std::vector<Timeline> timelines;
  timelines.reserve(parts.size());
  for (const SimResult& p : parts) {
    r.triangles += p.triangles;
    r.cpg_tag_cycles += p.cpg_tag_cycles;
    add(r.unit, p.unit);
    r.gpe += p.gpe;
    r.gpe.cycles += p.gpe.cycles;
    r.gpe.vertices += p.gpe.vertices;
    r.gpe_waited += p.gpe_waited;
    r.te_late += p.te_late;
    r.degenerate_patches += p.degenerate_patches;
    r.zero_normals += p.zero_normals;
    for (std::size_t L = 0; L < r.factors.patches_with_factor.size(); ++L)
      r.factors.patches_with_factor[L] += p.factors.patches_with_factor[L];
    for (const auto& [points, n] : p.factors.patches_with_vertices) r.factors.patches_with_vertices[points] += n;
    r.factors.vertices += p.factors.vertices;
    r.factors.culled += p.factors.culled;
    if (p.errors) {
      if (!r.errors) {
        r.errors = p.errors;
      } else {
        add(r.errors->mesh, p.errors->mesh);
        ArithmeticErrors& a = r.errors->arithmetic;
        add(a.stats, p.errors->arithmetic.stats);
        a.beyond_bound += p.errors->arithmetic.beyond_bound;
        a.saturated += p.errors->arithmetic.saturated;
        a.scalar_tagged += p.errors->arithmetic.scalar_tagged;
        if (a.worst.empty()) a.worst = p.errors->arithmetic.worst;  // the first in stream order
      }
    }
    timelines.push_back(p.timeline);
    r.chunk_cycles.push_back(p.unit.cycles);
  }
  r.factors.uniform = r.factors.pattern.empty() &&
                      std::count_if(r.factors.patches_with_factor.begin(), r.factors.patches_with_factor.end(),
                                    [](std::uint64_t n) { return n > 0; }) <= 1;
  r.timeline = Timeline::concatenate(timelines);
  return r;
}

SimResult simulate_chunked(const Mesh& mesh, const UnitConfig& cfg, int chunks, const ChunkCallbacks& callbacks,
                           MeshPatterns patterns) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::uint64_t> starts = chunk_starts(mesh.triangle_count(), chunks);
  const auto k_chunks = static_cast<std::size_t>(chunks);
  // A failing chunk stops only the chunks after it: one before it may still hold the error a
  // single run would report (the first in stream order).
  std::vector<std::atomic<bool>> cancel(k_chunks);
  const auto cancel_after = [&](std::size_t failed) {
    for (std::size_t k = failed + 1; k < k_chunks; ++k) cancel[k] = true;
  };
  std::vector<SimHooks> hooks(k_chunks);
  for (std::size_t k = 0; k < k_chunks; ++k) {
    if (callbacks.hooks) hooks[k] = callbacks.hooks(static_cast<int>(k));
    if (!hooks[k].observers.empty()) throw std::logic_error("simulate_chunked: observers watch one run");
    hooks[k].cancel = &cancel[k];
  }

  std::vector<std::optional<SimResult>> results(k_chunks);
  std::vector<std::exception_ptr> errors(k_chunks);
  std::vector<char> finished(k_chunks, 0);
  std::mutex mutex;
  std::condition_variable changed;
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < k_chunks;) {
      try {
        if (cancel[k].load()) throw SimCancelled();
        results[k] = simulate_range(mesh, chunk_config(cfg, static_cast<int>(k)), starts[k], starts[k + 1], hooks[k],
                                    patterns);
      } catch (...) {
        errors[k] = std::current_exception();
        cancel_after(k);
      }
      {
        const std::lock_guard lock(mutex);
        finished[k] = 1;
      }
      changed.notify_all();
    }
  };
  unsigned threads = callbacks.threads > 0 ? static_cast<unsigned>(callbacks.threads)
                                           : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, static_cast<unsigned>(chunks));
  std::exception_ptr failure;
  {
    std::vector<std::jthread> pool;
    for (unsigned i = 0; i < threads; ++i) pool.emplace_back(work);
    // The chunks' outputs in stream order, each as soon as it and those before it are done.
    for (std::size_t k = 0; k < k_chunks && !failure; ++k) {
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return finished[k] != 0; });
      }
      if (errors[k]) break;
      try {
        if (callbacks.done) callbacks.done(static_cast<int>(k));
      } catch (...) {
        failure = std::current_exception();
        for (std::atomic<bool>& c : cancel) c = true;
      }
    }
    if (!failure)
      for (std::size_t k = 0; k < k_chunks; ++k)
        if (errors[k]) cancel_after(k);
  }  // joins the workers
  // The first chunk's own error in stream order (a cancelled chunk comes after a failed one).
  for (const std::exception_ptr& e : errors) {
    if (!e) continue;
    try {
      std::rethrow_exception(e);
    } catch (const SimCancelled&) {
      continue;
    }
  }
  if (failure) std::rethrow_exception(failure);

  std::vector<SimResult> parts;
  parts.reserve(k_chunks);
  for (std::optional<SimResult>& r : results) parts.push_back(std::move(*r));
  SimResult merged = merge_chunks(parts, cfg);
  merged.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return merged;
}

ChunkBoundaryBound chunk_boundary_bound(const UnitConfig& cfg, bool uniform_factors) {
  // C of the slowest triangle: scalar tags lengthen the CPG's work on a tagged triangle.
  TriangleFx all_tagged;
  for (TagsFx& t : all_tagged.tags) t.delta[0] = 1;
  const int cpg_c = Unit(cfg).cpg_cycles() + (cfg.cpg_tags ? cpg_tag_cycles(all_tagged, cfg.format, cfg.cpg) : 0);
  const AnalyticPrediction p = predict(cfg, cpg_c);
  // F: reset to the first acceptance of an empty unit: the first control points (fill), the
  // first vertex's dependence chain, its last result, retirement, acceptance.
  const double first_vertex = p.fill_cycles + p.chain_span + cfg.int_latency + 2;
  // One CPG copy's cycles per patch (C + 1 dedicated; the compute steps and two more in the gpe
  // mapping): a patch's own control points never come sooner, however many copies there are.
  const double per_patch_cpg = p.cpg * p.patch_vertices * cfg.cpg.copies;
  ChunkBoundaryBound b;
  b.longer = static_cast<std::uint64_t>(std::ceil(uniform_factors ? first_vertex : first_vertex + 2 * per_patch_cpg));
  // The single run's geometry engine is busy K - 1 cycles after the last vertex before the
  // boundary; a dedicated CPG's first vertex never comes before C + 3 cycles.
  const bool gpe_idle_by_then = cfg.cpg_mapping == CpgMapping::Dedicated && cfg.gpe_cycles - 1 <= cpg_c + 3;
  b.shorter = gpe_idle_by_then ? 0 : static_cast<std::uint64_t>(cfg.gpe_cycles - 1);
  return b;
}

}  // namespace tessim::sim
