// The scalar tags of one vertex of a scalar-tagged PN mesh (docs/mathematics.md §9,
// docs/stpn.md): what make_stpn_patch (model/pn.hpp) takes per corner and Mesh::tags holds.
#pragma once

#include <glm/glm.hpp>

namespace tessim {

// Crease vector Δ = N⁺ − N⁻ (zero: the vertex is untagged; its normal N is then
// normalize(N⁺ + N⁻)), sharpness σ >= 0, tension θ in [-1, 1], bias β in [-1, 1].
struct VertexTags {
  glm::dvec3 delta{0.0};
  double sigma = 0.0, theta = 0.0, beta = 0.0;
  bool tagged() const { return delta != glm::dvec3(0.0); }
  // No tag changes anything: untagged and no tension (σ and β act only with Δ != 0).
  bool neutral() const { return !tagged() && theta == 0.0; }
  bool operator==(const VertexTags&) const = default;
};

}  // namespace tessim
