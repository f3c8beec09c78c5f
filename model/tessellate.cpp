#include "model/tessellate.hpp"

#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include "model/error.hpp"
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


DomainPattern uniform_pattern(int L) {
  DomainPattern p;
  p.uniform_L = L;
  const double segments = static_cast<double>(L);
  for (const DomainPoint& d : pattern_points(L)) p.points.emplace_back(d.j / segments, d.k / segments);
  for (const glm::uvec3& t : pattern_triangles(L)) p.indices.insert(p.indices.end(), {t.x, t.y, t.z});
  return p;
}

DomainPattern d3d11_domain_pattern(const PatchFactors& f, Partitioning partitioning) {
  const D3D11Pattern d = d3d11_tri_pattern(f.outer, f.inner, partitioning, Winding::ccw);
  DomainPattern p;
  p.culled = d.factors.culled;
  p.points.reserve(d.points.size());
  for (const FixedUV& q : d.points) p.points.emplace_back(fixed16_to_double(q.u), fixed16_to_double(q.v));
  p.indices = d.indices;
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
  if (by_factors_.size() > 4096) by_factors_.clear();  // bounded memory for any mesh
  auto it = by_factors_.find(key);
  if (it == by_factors_.end()) it = by_factors_.emplace(key, d3d11_domain_pattern(f, settings_.partitioning)).first;
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

TessellationSummary tessellate_mesh(const Mesh& mesh, const TessSettings& settings, NormalMode mode,
                                    const PatchSink& sink) {
  validate(mesh, settings);
  PatternCache patterns(settings);
  // The two buffers every patch is written into: memory stays one patch, whatever the mesh.
  std::vector<glm::dvec3> positions, normals;

  TessellationSummary summary;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const DomainPattern& domain = patterns.pattern(mesh, t);
    if (domain.culled) {
      ++summary.culled;
      continue;
    }
    const glm::uvec3& tri = mesh.triangles[t];
    PnInput input;
    std::array<VertexTags, 3> tags{};
    for (int c = 0; c < 3; ++c) {
      input.p[c] = mesh.positions[tri[c]];
      input.n[c] = mesh.normals[tri[c]];
      if (mesh.has_tags()) tags[c] = mesh.tags[tri[c]];
    }
    // A tagged mesh takes the scalar-tagged control points (plain PN where tags are neutral).
    const PnPatch patch = mesh.has_tags() ? make_stpn_patch(input, tags, mode) : make_patch(input, mode);
    summary.degenerate_edges += static_cast<std::uint64_t>(patch.degenerate_edges);
    if (is_zero_area(input.p[0], input.p[1], input.p[2])) ++summary.degenerate_triangles;

    positions.resize(domain.points.size());
    normals.resize(domain.points.size());
    for (std::size_t i = 0; i < domain.points.size(); ++i) {
      const PnVertex vertex = eval_de_casteljau(patch, domain.points[i].x, domain.points[i].y, &summary.int_ops);
      positions[i] = vertex.position;
      normals[i] = vertex.normal;
    }

    PatchView view;
    view.triangle = static_cast<std::uint32_t>(t);
    view.L = domain.uniform_L;
    view.positions = positions;
    view.normals = normals;
    view.domain = domain.points;
    view.indices = domain.indices;
    sink(view);

    ++summary.patches;
    summary.vertices += domain.points.size();
    summary.triangles += domain.triangle_count();
  }
  return summary;
}

}  // namespace tessim
