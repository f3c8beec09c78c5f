// Whole-mesh tessellation by the float64 reference, streamed patch by patch: memory is
// bounded by one patch (and the distinct patterns), whatever the size of the output. Each
// patch gets the uniform pattern or the D3D11 pattern of its factors (model/factors.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <map>
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "model/factors.hpp"
#include "model/mesh.hpp"
#include "model/normal_mode.hpp"
#include "model/pn.hpp"

namespace tessim {

// The domain pattern of one patch: points (u, v) (w = 1 - u - v) and its triangles as local
// indices, three per triangle, in the input triangle's winding.
struct DomainPattern {
  int uniform_L = 0;  // > 0: the uniform pattern of that factor (model/pattern.hpp)
  bool culled = false;
  std::vector<glm::dvec2> points;
  std::vector<BasisAtPoint> basis;  // the Bernstein basis at each point, shared by every patch
  std::vector<std::uint32_t> indices;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// The pattern of every patch of a mesh under some settings, built once per distinct set of
// factors (an adaptive mesh has a few hundred).
class PatternCache {
 public:
  explicit PatternCache(const TessSettings& settings);
  const DomainPattern& pattern(const Mesh& mesh, std::size_t triangle);
  const TessSettings& settings() const { return settings_; }

 private:
  TessSettings settings_;
  DomainPattern uniform_;
  std::map<std::array<std::uint32_t, 4>, DomainPattern> by_factors_;
  std::size_t cached_points_ = 0;  // points of the patterns in by_factors_ (bounds its memory)
};

// One tessellated input triangle: its pattern's points evaluated on the PN patch, in the
// pattern's order.
struct PatchView {
  std::uint32_t triangle = 0;  // index of the input triangle
  int L = 1;                   // the uniform pattern's factor; 0 for a D3D11 pattern
  std::span<const glm::dvec3> positions;
  std::span<const glm::dvec3> normals;  // unit length
  std::span<const glm::dvec2> domain;   // (u, v) of each vertex
  std::span<const std::uint32_t> indices;  // triangles, local indices
};

struct TessellationSummary {
  std::uint64_t patches = 0;            // patches handed to the sink
  std::uint64_t culled = 0;             // patches a factor <= 0 or NaN culled
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::uint64_t int_ops = 0;            // INT operations the unit's de Casteljau performs for them
  std::uint64_t degenerate_edges = 0;   // mid-edge normal fallbacks (zero-length edges)
  std::uint64_t degenerate_triangles = 0;  // zero-area input triangles
};

using PatchSink = std::function<void(const PatchView&)>;

// Tessellates every triangle of the mesh with the pattern the settings give it and hands each
// patch that is not culled to the sink in input order. A mesh with tags is tessellated as
// scalar-tagged PN triangles (make_stpn_patch, docs/stpn.md), one without as plain PN. Throws InputError for invalid settings
// or mesh, before the first patch.

TessellationSummary tessellate_mesh(const Mesh& mesh, const TessSettings& settings, NormalMode mode,
                                    const PatchSink& sink);
// The uniform pattern with factor L (1..kMaxTessFactor).
TessellationSummary tessellate_mesh(const Mesh& mesh, int L, NormalMode mode, const PatchSink& sink);

// Vertices and triangles tessellate_mesh will produce (for writers that need them up front).
struct TessellationCounts {
  std::uint64_t vertices = 0, triangles = 0, culled = 0;
};
TessellationCounts count_tessellation(const Mesh& mesh, PatternCache& patterns);

}  // namespace tessim
