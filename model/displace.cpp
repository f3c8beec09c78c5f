#include "model/displace.hpp"

#include <cmath>

#include "model/base/error.hpp"

namespace tessim {

DisplacedPoint displace(const DisplaceSettings& d, const glm::dvec3& p, const glm::dvec3& n) {
  if (!d.enabled()) return {p, n};
  const double r = glm::length(p);
  const double h = d.amplitude * std::sin(d.frequency * r);
  glm::dvec3 g(0.0);
  if (r > 0.0) g = (d.amplitude * d.frequency * std::cos(d.frequency * r) / r) * p;
  const glm::dvec3 tangential = g - glm::dot(g, n) * n;
  return {p + h * n, glm::normalize(n - tangential)};
}

void validate(const DisplaceSettings& d, const std::string& source) {
  if (!d.enabled()) return;
  if (!std::isfinite(d.amplitude))
    throw InputError(source, "--amplitude", std::to_string(d.amplitude) + " is not a finite number");
  if (!std::isfinite(d.frequency))
    throw InputError(source, "--frequency", std::to_string(d.frequency) + " is not a finite number");
  if (d.frequency < 0.0)
    throw InputError(source, "--frequency", std::to_string(d.frequency) + " is negative (radians per unit of |P|)");
  if (!std::isfinite(d.amplitude * d.frequency))
    throw InputError(source, "--amplitude", "amplitude x frequency is beyond the double range");
}

}  // namespace tessim
