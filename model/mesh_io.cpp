// load_mesh chains the steps: import (model/io/import.hpp: Assimp and the checks it does not
// make), exact welding, then normals (model/mesh_build.hpp), then the tag rules
// (model/st_mesh.hpp). The writers are in model/io/write_mesh.cpp.
#include "model/mesh_io.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <utility>
#include <vector>

#include "model/base/error.hpp"
#include "model/io/import.hpp"
#include "model/mesh_build.hpp"
#include "model/st_mesh.hpp"

namespace tessim {

Mesh load_mesh(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  const io::ImportedMesh imported = io::import_mesh(path);
  for (const std::string& w : imported.warnings) {
    if (warnings) warnings->push_back(w);
    else std::fprintf(stderr, "tessim: warning: %s\n", printable_text(w, 960).c_str());
  }
  std::vector<std::uint32_t> first_copies;
  Mesh mesh = weld(imported.mesh, [&](std::uint32_t v) { return imported.vertex_name(v); }, &first_copies);
  if (!mesh.normals_from_file) mesh = compute_normals(std::move(mesh));
  validate_tags(mesh, [&](std::uint32_t v) { return imported.vertex_name(first_copies[v]); });
  return mesh;
}

MeshStats mesh_stats(const Mesh& mesh) {
  MeshStats stats;
  stats.vertices = mesh.vertex_count();
  stats.triangles = mesh.triangle_count();
  stats.bbox = bounding_box(mesh);
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3& p1 = mesh.positions[t[0]];
    const glm::dvec3& p2 = mesh.positions[t[1]];
    const glm::dvec3& p3 = mesh.positions[t[2]];
    if (is_zero_area(p1, p2, p3)) ++stats.degenerate_triangles;  // the tessellator's test
    stats.zero_length_edges += (p1 == p2) + (p2 == p3) + (p3 == p1);
  }
  // Welded, so equal positions are equal indices: an edge is an unordered pair of indices.
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const glm::uvec3& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t a = t[i], b = t[(i + 1) % 3];
      if (a != b) edges.push_back(std::min(a, b) << 32 | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  stats.edges = static_cast<std::size_t>(std::unique(edges.begin(), edges.end()) - edges.begin());
  if (!mesh.normals_from_file) weighted_normals(mesh, &stats.normal_fallbacks);
  return stats;
}

}  // namespace tessim
