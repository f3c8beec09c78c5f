#include "model/factors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/base/error.hpp"
#include "model/pattern.hpp"

namespace tessim {

namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

std::string TessSettings::describe() const {
  if (kind == PatternKind::Uniform) return "L=" + std::to_string(L);
  std::string s = partitioning_name(partitioning);
  if (source == FactorSource::Fixed) {
    s += " outer " + number(outer[0]) + "," + number(outer[1]) + "," + number(outer[2]) + " inner " + number(inner);
  } else {
    s += " adaptive (eye " + format_vec(camera.eye) + ", fov " + number(camera.fov_deg) + " deg, " +
         std::to_string(camera.width) + "x" + std::to_string(camera.height) + ", " + number(pixels_per_segment) +
         " pixels per segment)";
  }
  return s;
}

float adaptive_edge_factor(const ScreenCamera& camera, double pixels_per_segment, const glm::dvec3& a,
                           const glm::dvec3& b) {
  const double focal_pixels = 0.5 * camera.height / std::tan(0.5 * camera.fov_deg * M_PI / 180.0);
  const glm::dvec3 mid = 0.5 * (a + b);
  const double length = glm::length(a - b);
  // An edge through the eye would be infinitely long on screen; its factor is the maximum.
  const double distance = std::max(glm::length(mid - camera.eye), 1e-300);
  const double segments = length * focal_pixels / (distance * pixels_per_segment);
  return static_cast<float>(std::clamp(segments, 1.0, static_cast<double>(kMaxTessFactor)));
}

PatchFactors patch_factors(const TessSettings& settings, const Mesh& mesh, std::size_t t) {
  if (settings.kind == PatternKind::Uniform) {
    const auto L = static_cast<float>(settings.L);
    return {{L, L, L}, L};
  }
  if (settings.source == FactorSource::Fixed) return {settings.outer, settings.inner};
  const glm::uvec3& tri = mesh.triangles[t];
  const glm::dvec3& p0 = mesh.positions[tri[0]];
  const glm::dvec3& p1 = mesh.positions[tri[1]];
  const glm::dvec3& p2 = mesh.positions[tri[2]];
  auto edge = [&](const glm::dvec3& a, const glm::dvec3& b) {
    return adaptive_edge_factor(settings.camera, settings.pixels_per_segment, a, b);
  };
  PatchFactors f;
  f.outer = {edge(p0, p2), edge(p0, p1), edge(p1, p2)};
  f.inner = std::max({f.outer[0], f.outer[1], f.outer[2]});
  return f;
}

void validate(const TessSettings& s, const std::string& source) {
  if (s.kind == PatternKind::Uniform) {
    if (s.L < 1 || s.L > kMaxTessFactor)
      throw InputError(source, "-L", "tessellation factor " + std::to_string(s.L) + " is outside 1.." +
                                         std::to_string(kMaxTessFactor));
    return;
  }
  // Fixed factors are all valid: the tessellator clamps them, and one <= 0 or NaN culls.
  if (s.source == FactorSource::Fixed) return;
  const ScreenCamera& c = s.camera;
  if (!is_finite(c.eye) || !is_finite(c.target))
    throw InputError(source, "--camera", "eye and target must be finite");
  if (c.eye == c.target) throw InputError(source, "--camera", "the eye is the target: no direction of view");
  if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0))
    throw InputError(source, "--camera", "fov " + number(c.fov_deg) + " is outside (0, 180) degrees");
  if (c.width < 1 || c.height < 1) throw InputError(source, "--viewport", "width and height must be at least 1");
  if (!(s.pixels_per_segment > 0.0) || std::isinf(s.pixels_per_segment))
    throw InputError(source, "--pixels-per-segment", "must be a positive finite number");
}

}  // namespace tessim
