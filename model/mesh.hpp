// An indexed triangle mesh with one unit normal per vertex: the input of every form of the unit.
// (model/io/import.hpp and weld() in model/mesh_build.hpp also use it before welding, as
// their comments say; load_mesh returns it as described here.)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/vertex_tags.hpp"

namespace tessim {

struct Mesh {
  std::string source;                  // file it came from (for messages)
  std::vector<glm::dvec3> positions;   // welded: one entry per distinct position
  std::vector<glm::dvec3> normals;     // unit length, same size as positions
  std::vector<glm::uvec3> triangles;   // indices into positions; winding as in the file
  bool normals_from_file = false;      // false: computed (area- and angle-weighted)
  // Scalar tags (docs/stpn.md): empty for an untagged mesh, else one per position. Only the
  // float reference's tessellation uses them; load_mesh checks the tag rules.
  std::vector<VertexTags> tags;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  bool has_tags() const { return !tags.empty(); }
};

struct BoundingBox {
  glm::dvec3 lo{0.0};
  glm::dvec3 hi{0.0};
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return glm::length(hi - lo); }
};

BoundingBox bounding_box(const Mesh& mesh);

bool is_finite(const glm::dvec3& v);

// The zero-area test of the tessellator, shared with mesh statistics so that both report the
// same count: |e1 x e2| <= 1e-12 |e1| |e2| means the two edges are parallel up to rounding (or
// one of them has zero length).
bool is_zero_area(const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3);

// A vector as messages show it: "(x, y, z)" with 9 significant digits.
std::string format_vec(const glm::dvec3& v);

}  // namespace tessim
