// Procedural displacement of the tessellated surface (docs/mathematics.md §12): each evaluated
// point moves along its unit shading normal by h(P) = a·sin(f‖P‖), and its normal is perturbed
// with the analytic gradient of h (Blinn). Applied by tessellate_mesh after the patch is
// evaluated, so it works with every pattern, normal mode and the silhouette blend.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace tessim {

enum class DisplaceKind { None, Sine };

struct DisplaceSettings {
  DisplaceKind kind = DisplaceKind::None;
  double amplitude = 0.0;  // a, in the mesh's own units
  double frequency = 0.0;  // f, radians per unit of ‖P‖ (the mesh's own coordinates); >= 0
  bool enabled() const { return kind != DisplaceKind::None; }
};

struct DisplacedPoint {
  glm::dvec3 position;
  glm::dvec3 normal;  // unit length
};

// P' = P + h N with h = a sin(f‖P‖), and N' = normalize(N − (g − (g·N) N)) with the gradient
// g = a f cos(f‖P‖) P/‖P‖ (n: the unit shading normal). At P = 0 the gradient of ‖P‖ is
// undefined: g = 0 there, so N' = N. N' never vanishes: N minus a vector orthogonal to it has
// length ≥ 1.
DisplacedPoint displace(const DisplaceSettings& d, const glm::dvec3& p, const glm::dvec3& n);

// InputError(source, option, reason) for a non-finite amplitude or frequency, a negative
// frequency, or a product a·f beyond the double range.
void validate(const DisplaceSettings& d, const std::string& source);

}  // namespace tessim
