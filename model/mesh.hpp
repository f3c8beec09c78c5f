// An indexed triangle mesh with one unit normal per vertex: the input of every form of the unit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tessim {

struct Mesh {
  std::string source;                  // file it came from (for messages)
  std::vector<glm::dvec3> positions;   // welded: one entry per distinct position
  std::vector<glm::dvec3> normals;     // unit length, same size as positions
  std::vector<glm::uvec3> triangles;   // indices into positions; winding as in the file
  bool normals_from_file = false;      // false: computed (area- and angle-weighted)

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
};

struct BoundingBox {
  glm::dvec3 lo{0.0};
  glm::dvec3 hi{0.0};
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return glm::length(hi - lo); }
};

BoundingBox bounding_box(const Mesh& mesh);

}  // namespace tessim
