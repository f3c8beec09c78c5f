#include "model/mesh.hpp"

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

}  // namespace tessim
