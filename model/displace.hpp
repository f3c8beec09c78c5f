// Procedural displacement of the tessellated surface (docs/mathematics.md §12): each evaluated
// point moves along its unit shading normal by h(P) = a·sin(f‖P‖) or a·noise(f P) (gradient
// noise, below), and its normal is perturbed with the analytic gradient of h (Blinn). Applied by tessellate_mesh after the patch is
// evaluated, so it works with every pattern, normal mode and the silhouette blend.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace tessim {

enum class DisplaceKind { None, Sine, Noise };

inline const char* to_string(DisplaceKind k) {
  switch (k) {
    case DisplaceKind::None: return "none";
    case DisplaceKind::Sine: return "sine";
    case DisplaceKind::Noise: return "noise";
  }
  return "?";
}

struct DisplaceSettings {
  DisplaceKind kind = DisplaceKind::None;
  double amplitude = 0.0;  // a, in the mesh's own units
  double frequency = 0.0;  // f, radians per unit of ‖P‖ (the mesh's own coordinates); >= 0
  bool enabled() const { return kind != DisplaceKind::None; }
};

// Gradient noise in the manner of Perlin's improved noise (docs/mathematics.md §12): at each
// integer lattice point one of the 12 directions (±1, ±1, 0) and permutations, chosen by a fixed
// permutation of 0..255; the value at x blends the eight corners' planes g_c·(x − c) with the
// quintic fade 6t⁵ − 15t⁴ + 10t³, so value and gradient are continuous. Zero at lattice points,
// about [−1, 1]. The gradient is the analytic one.
struct NoiseSample {
  double value = 0.0;
  glm::dvec3 gradient{0.0};
};
NoiseSample gradient_noise(const glm::dvec3& x);

struct DisplacedPoint {
  glm::dvec3 position;
  glm::dvec3 normal;  // unit length
};

// P' = P + h N and N' = normalize(N − (g − (g·N) N)), g the gradient of h (n: the unit shading
// normal). Sine: h = a sin(f‖P‖), g = a f cos(f‖P‖) P/‖P‖; at P = 0 the gradient of ‖P‖ is
// undefined: g = 0 there, so N' = N. Noise: h = a noise(f P), g = a f ∇noise(f P). N' never
// vanishes: N minus a vector orthogonal to it has length ≥ 1.
DisplacedPoint displace(const DisplaceSettings& d, const glm::dvec3& p, const glm::dvec3& n);

// InputError(source, option, reason) for a non-finite amplitude or frequency, a negative
// frequency, or a product a·f beyond the double range.
void validate(const DisplaceSettings& d, const std::string& source);

}  // namespace tessim
