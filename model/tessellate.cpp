#include "model/tessellate.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "model/base/error.hpp"
#include "model/d3d11_pattern.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"

namespace tessim {

namespace {

// Everything that could make the stream fail is checked before the first patch reaches the
// sink, so a sink writing a file never sees a partial mesh followed by an error.
void validate(const Mesh& mesh, const TessSettings& settings) {
  const std::string& file = mesh.source.empty() ? std::string("mesh") : mesh.source;
  if (settings.kind == PatternKind::Uniform && (settings.L < 1 || settings.L > kMaxTessFactor))
    throw InputError(file, "tessellation factor",
                     std::to_string(settings.L) + " is outside 1.." + std::to_string(kMaxTessFactor));
  validate(settings, file);
  if (mesh.normals.size() != mesh.positions.size())
    throw InputError(file, "normals",
                     std::to_string(mesh.normals.size()) + " normals for " +
                         std::to_string(mesh.positions.size()) + " positions");
  if (mesh.has_tags() && mesh.tags.size() != mesh.positions.size())
    throw InputError(file, "tags",
                     std::to_string(mesh.tags.size()) + " tag sets for " + std::to_string(mesh.positions.size()) +
                         " positions");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!is_finite(mesh.positions[i]))
      throw InputError(file, "vertex " + std::to_string(i), "position is NaN or infinite");
    if (!is_finite(mesh.normals[i]))
      throw InputError(file, "vertex " + std::to_string(i), "normal is NaN or infinite");
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c)
      if (tri[c] >= mesh.positions.size())
        throw InputError(file, "triangle " + std::to_string(t),
                         "vertex index " + std::to_string(tri[c]) + " out of range (" +
                             std::to_string(mesh.positions.size()) + " vertices)");
  }
}


void add_basis(DomainPattern& p) {
  p.basis.reserve(p.points.size());
  for (const glm::dvec2& q : p.points) p.basis.push_back(basis_at(q.x, q.y));
}

DomainPattern uniform_pattern(int L) {
  DomainPattern p;
  p.uniform_L = L;
  const double segments = static_cast<double>(L);
  for (const DomainPoint& d : pattern_points(L)) p.points.emplace_back(d.j / segments, d.k / segments);
  for (const glm::uvec3& t : pattern_triangles(L)) p.indices.insert(p.indices.end(), {t.x, t.y, t.z});
  add_basis(p);
  return p;
}

DomainPattern d3d11_domain_pattern(const PatchFactors& f, Partitioning partitioning) {
  const D3D11Pattern d = d3d11_tri_pattern(f.outer, f.inner, partitioning, Winding::ccw);
  DomainPattern p;
  p.culled = d.factors.culled;
  p.points.reserve(d.points.size());
  for (const FixedUV& q : d.points) p.points.emplace_back(fixed16_to_double(q.u), fixed16_to_double(q.v));
  p.indices = d.indices;
  add_basis(p);
  return p;
}

// The factors as one key: their float bits.
std::array<std::uint32_t, 4> factor_key(const PatchFactors& f) {
  return {std::bit_cast<std::uint32_t>(f.outer[0]), std::bit_cast<std::uint32_t>(f.outer[1]),
          std::bit_cast<std::uint32_t>(f.outer[2]), std::bit_cast<std::uint32_t>(f.inner)};
}

}  // namespace

PatternCache::PatternCache(const TessSettings& settings) : settings_(settings) {
  if (settings.kind == PatternKind::Uniform) uniform_ = uniform_pattern(settings.L);
}

const DomainPattern& PatternCache::pattern(const Mesh& mesh, std::size_t triangle) {
  if (settings_.kind == PatternKind::Uniform) return uniform_;
  const PatchFactors f = patch_factors(settings_, mesh, triangle);
  const auto key = factor_key(f);
  auto it = by_factors_.find(key);
  if (it != by_factors_.end()) return it->second;
  // Bounded memory for any mesh: about 200 bytes per cached point (point, basis, triangles).
  if (cached_points_ > (std::size_t{1} << 20)) {
    by_factors_.clear();
    cached_points_ = 0;
  }
  it = by_factors_.emplace(key, d3d11_domain_pattern(f, settings_.partitioning)).first;
  cached_points_ += it->second.points.size();
  return it->second;
}

TessellationCounts count_tessellation(const Mesh& mesh, PatternCache& patterns) {
  TessellationCounts c;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const DomainPattern& p = patterns.pattern(mesh, t);
    if (p.culled) {
      ++c.culled;
      continue;
    }
    c.vertices += p.points.size();
    c.triangles += p.triangle_count();
  }
  return c;
}

TessellationSummary tessellate_mesh(const Mesh& mesh, int L, NormalMode mode, const PatchSink& sink) {
  TessSettings settings;
  settings.L = L;
  return tessellate_mesh(mesh, settings, mode, sink);
}

namespace {

// The patch of input triangle t: control points (scalar-tagged where the mesh has tags), then
// every domain point evaluated into positions/normals. Counts into `summary`. The evaluation is
// the Bernstein sum with the pattern's basis values: the same surface as de Casteljau in fewer
// operations (it differs from de Casteljau only in rounding, ~1e-16 relative); the INT
// operations counted are those the unit's de Casteljau performs.
// With silhouettes (`silhouette` given) the control points are the blended ones of
// make_silhouette_patch, on a tagged mesh with each face's sharp normals (docs/mathematics.md §11).
// With displacement on, each evaluated point is displaced along its unit normal (displace()).
void evaluate_patch(const Mesh& mesh, std::size_t t, const DomainPattern& domain, NormalMode mode,
                    const MeshSilhouette* silhouette, const DisplaceSettings& displacement, glm::dvec3* positions,
                    glm::dvec3* normals, TessellationSummary& summary) {
  const PnPatch patch = mesh_patch(mesh, t, mode, silhouette);
  const glm::uvec3& tri = mesh.triangles[t];
  summary.degenerate_edges += static_cast<std::uint64_t>(patch.degenerate_edges);
  if (is_zero_area(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]])) ++summary.degenerate_triangles;
  for (std::size_t i = 0; i < domain.basis.size(); ++i) {
    const PnVertex vertex = eval_bernstein(patch, domain.basis[i]);
    const DisplacedPoint point = displace(displacement, vertex.position, vertex.normal);
    positions[i] = point.position;
    normals[i] = point.normal;
  }
  summary.int_ops += domain.basis.size() * static_cast<std::uint64_t>(de_casteljau_ops(mode));
  ++summary.patches;
  summary.vertices += domain.points.size();
  summary.triangles += domain.triangle_count();
}

void add(TessellationSummary& into, const TessellationSummary& s) {
  into.patches += s.patches;
  into.culled += s.culled;
  into.vertices += s.vertices;
  into.triangles += s.triangles;
  into.int_ops += s.int_ops;
  into.degenerate_edges += s.degenerate_edges;
  into.degenerate_triangles += s.degenerate_triangles;
}

// The uniform pattern on several threads: workers evaluate batches of consecutive patches into
// a ring of buffers, the calling thread hands them to the sink in input order. The patches are
// independent, so the sink sees exactly what the sequential loop gives it, in the same order;
// memory stays a few batches whatever the mesh.
TessellationSummary tessellate_uniform_parallel(const Mesh& mesh, const DomainPattern& domain, NormalMode mode,
                                                const MeshSilhouette* silhouette, const DisplaceSettings& displacement,
                                                const PatchSink& sink, unsigned workers) {
  const std::size_t patch_vertices = domain.points.size();
  // About 64 Ki vertices per batch: large enough that handing batches over costs nothing.
  const std::size_t batch_patches = std::max<std::size_t>(1, (std::size_t{1} << 16) / patch_vertices);
  const std::size_t triangles = mesh.triangles.size();
  const std::size_t batches = (triangles + batch_patches - 1) / batch_patches;

  struct Slot {
    std::size_t batch = ~std::size_t{0};  // the batch it holds, once ready
    bool ready = false;
    std::vector<glm::dvec3> positions, normals;
    TessellationSummary summary;
  };
  std::vector<Slot> ring(2 * workers + 2);
  std::mutex mutex;
  std::condition_variable slot_ready, slot_free;
  std::size_t next_batch = 0;  // the next batch a worker takes
  std::size_t consumed = 0;    // batches the sink has seen
  bool stop = false;
  std::exception_ptr failure;

  auto work = [&] {
    for (;;) {
      std::size_t batch;
      {
        std::unique_lock lock(mutex);
        if (stop || next_batch >= batches) return;
        batch = next_batch++;
        // Its slot is free once the batch ring.size() before it has reached the sink.
        slot_free.wait(lock, [&] { return stop || batch < consumed + ring.size(); });
        if (stop) return;
      }
      Slot& slot = ring[batch % ring.size()];
      try {
        const std::size_t first = batch * batch_patches, end = std::min(triangles, first + batch_patches);
        slot.positions.resize((end - first) * patch_vertices);
        slot.normals.resize((end - first) * patch_vertices);
        slot.summary = {};
        for (std::size_t t = first; t < end; ++t)
          evaluate_patch(mesh, t, domain, mode, silhouette, displacement, &slot.positions[(t - first) * patch_vertices],
                         &slot.normals[(t - first) * patch_vertices], slot.summary);
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
        slot_ready.notify_all();
        slot_free.notify_all();
        return;
      }
      std::lock_guard lock(mutex);
      slot.batch = batch;
      slot.ready = true;
      slot_ready.notify_all();
    }
  };

  std::vector<std::thread> threads;
  for (unsigned i = 0; i < workers; ++i) threads.emplace_back(work);
  auto finish = [&] {
    {
      std::lock_guard lock(mutex);
      stop = true;
    }
    slot_ready.notify_all();
    slot_free.notify_all();
    for (std::thread& t : threads) t.join();
  };

  TessellationSummary summary;
  try {
    for (std::size_t batch = 0; batch < batches; ++batch) {
      Slot& slot = ring[batch % ring.size()];
      {
        std::unique_lock lock(mutex);
        slot_ready.wait(lock, [&] { return failure || (slot.ready && slot.batch == batch); });
        if (failure) std::rethrow_exception(failure);
      }
      const std::size_t first = batch * batch_patches, end = std::min(triangles, first + batch_patches);
      for (std::size_t t = first; t < end; ++t) {
        PatchView view;
        view.triangle = static_cast<std::uint32_t>(t);
        view.L = domain.uniform_L;
        view.positions = std::span<const glm::dvec3>(&slot.positions[(t - first) * patch_vertices], patch_vertices);
        view.normals = std::span<const glm::dvec3>(&slot.normals[(t - first) * patch_vertices], patch_vertices);
        view.domain = domain.points;
        view.indices = domain.indices;
        sink(view);
      }
      add(summary, slot.summary);
      std::lock_guard lock(mutex);
      slot.ready = false;
      ++consumed;
      slot_free.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  return summary;
}

}  // namespace

TessellationSummary tessellate_mesh(const Mesh& mesh, const TessSettings& given, NormalMode mode,
                                    const PatchSink& sink) {
  validate(mesh, given);
  TessSettings settings = given;
  bind_silhouette(settings, mesh);
  // The blend only with --silhouette (and not blend=off); the silhouette rule alone changes the
  // factors, not the patches.
  const MeshSilhouette* silhouette = settings.silhouette.blends() ? settings.silhouette_field.get() : nullptr;
  PatternCache patterns(settings);

  // The uniform pattern is one pattern for every patch: worth spreading over the cores when the
  // mesh has more than a batch or two of work.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (settings.kind == PatternKind::Uniform && cores > 1 && !mesh.triangles.empty() &&
      mesh.triangles.size() * patterns.pattern(mesh, 0).points.size() > (std::size_t{1} << 17))
    return tessellate_uniform_parallel(mesh, patterns.pattern(mesh, 0), mode, silhouette, settings.displace, sink,
                                       cores);

  // The two buffers every patch is written into: memory stays one patch, whatever the mesh.
  std::vector<glm::dvec3> positions, normals;
  TessellationSummary summary;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const DomainPattern& domain = patterns.pattern(mesh, t);
    if (domain.culled) {
      ++summary.culled;
      continue;
    }
    positions.resize(domain.points.size());
    normals.resize(domain.points.size());
    evaluate_patch(mesh, t, domain, mode, silhouette, settings.displace, positions.data(), normals.data(), summary);

    PatchView view;
    view.triangle = static_cast<std::uint32_t>(t);
    view.L = domain.uniform_L;
    view.positions = positions;
    view.normals = normals;
    view.domain = domain.points;
    view.indices = domain.indices;
    sink(view);
  }
  return summary;
}

}  // namespace tessim
