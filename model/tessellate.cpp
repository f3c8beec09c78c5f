#include "model/tessellate.hpp"

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
void validate(const Mesh& mesh, int L) {
  const std::string& file = mesh.source.empty() ? std::string("mesh") : mesh.source;
  if (L < 1 || L > kMaxTessFactor)
    throw InputError(file, "tessellation factor",
                     std::to_string(L) + " is outside 1.." + std::to_string(kMaxTessFactor));
  if (mesh.normals.size() != mesh.positions.size())
    throw InputError(file, "normals",
                     std::to_string(mesh.normals.size()) + " normals for " +
                         std::to_string(mesh.positions.size()) + " positions");
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

}  // namespace

TessellationSummary tessellate_mesh(const Mesh& mesh, int L, NormalMode mode, const PatchSink& sink) {
  validate(mesh, L);

  const std::vector<DomainPoint> domain = pattern_points(L);
  const double segments = static_cast<double>(L);
  // The two buffers every patch is written into: memory stays one patch, whatever the mesh.
  std::vector<glm::dvec3> positions(domain.size());
  std::vector<glm::dvec3> normals(domain.size());

  TessellationSummary summary;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    PnInput input;
    for (int c = 0; c < 3; ++c) {
      input.p[c] = mesh.positions[tri[c]];
      input.n[c] = mesh.normals[tri[c]];
    }
    const PnPatch patch = make_patch(input, mode);
    summary.degenerate_edges += static_cast<std::uint64_t>(patch.degenerate_edges);
    if (is_zero_area(input.p[0], input.p[1], input.p[2])) ++summary.degenerate_triangles;

    for (std::size_t i = 0; i < domain.size(); ++i) {
      const PnVertex vertex =
          eval_de_casteljau(patch, domain[i].j / segments, domain[i].k / segments, &summary.int_ops);
      positions[i] = vertex.position;
      normals[i] = vertex.normal;
    }

    PatchView view;
    view.triangle = static_cast<std::uint32_t>(t);
    view.L = L;
    view.positions = positions;
    view.normals = normals;
    sink(view);

    ++summary.patches;
    summary.vertices += domain.size();
    summary.triangles += static_cast<std::uint64_t>(pattern_triangle_count(L));
  }
  return summary;
}

}  // namespace tessim
