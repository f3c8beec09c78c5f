// Whole-mesh tessellation by the float64 reference, streamed patch by patch: memory is
// bounded by one patch, whatever the size of the output.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include <glm/glm.hpp>

#include "model/mesh.hpp"
#include "model/normal_mode.hpp"

namespace tessim {

// One tessellated input triangle: pattern_vertex_count(L) vertices in pattern order
// (model/pattern.hpp); the topology is pattern_triangles(L).
struct PatchView {
  std::uint32_t triangle = 0;  // index of the input triangle
  int L = 1;
  std::span<const glm::dvec3> positions;
  std::span<const glm::dvec3> normals;  // unit length
};

struct TessellationSummary {
  std::uint64_t patches = 0;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::uint64_t int_ops = 0;            // de Casteljau INT operations performed
  std::uint64_t degenerate_edges = 0;   // mid-edge normal fallbacks (zero-length edges)
  std::uint64_t degenerate_triangles = 0;  // zero-area input triangles
};

using PatchSink = std::function<void(const PatchView&)>;

// Tessellates every triangle of the mesh with uniform factor L (1..kMaxTessFactor) and hands
// each patch to the sink in input order. Throws InputError for L out of range.
TessellationSummary tessellate_mesh(const Mesh& mesh, int L, NormalMode mode, const PatchSink& sink);

}  // namespace tessim
