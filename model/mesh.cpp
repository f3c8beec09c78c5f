#include "model/mesh.hpp"

#include <cmath>
#include <sstream>

namespace tessim {

BoundingBox bounding_box(const Mesh& mesh) {
  BoundingBox box;  // an empty mesh has the degenerate box at the origin
  if (mesh.positions.empty()) return box;
  box.lo = box.hi = mesh.positions.front();
  for (const glm::dvec3& p : mesh.positions) {
    box.lo = glm::min(box.lo, p);
    box.hi = glm::max(box.hi, p);
  }
  return box;
}

bool is_finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool is_zero_area(const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3) {
  constexpr double kZeroArea = 1e-12;  // relative: rounding of the cross product, not a size
  const glm::dvec3 e1 = p2 - p1;
  const glm::dvec3 e2 = p3 - p1;
  return !(glm::length(glm::cross(e1, e2)) > kZeroArea * glm::length(e1) * glm::length(e2));
}

std::string format_vec(const glm::dvec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

}  // namespace tessim
