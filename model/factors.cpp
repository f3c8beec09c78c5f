#include "model/factors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

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
  std::string s;
  if (kind == PatternKind::Uniform) {
    s = "L=" + std::to_string(L);
  } else if (source == FactorSource::Fixed) {
    s = partitioning_name(partitioning);
    s += " outer " + number(outer[0]) + "," + number(outer[1]) + "," + number(outer[2]) + " inner " + number(inner);
  } else if (rule == AdaptiveRule::Nyquist) {
    s = partitioning_name(partitioning);
    s += " nyquist-adaptive (" + number(samples_per_wavelength) + " samples per wavelength)";
  } else {
    s = partitioning_name(partitioning);
    const bool by_outline = this->by_outline();
    s += std::string(rule == AdaptiveRule::Contour ? " contour-adaptive (eye "
                     : by_outline                  ? " silhouette-adaptive (eye "
                                                   : " adaptive (eye ") +
         format_vec(camera.eye) +
         ", fov " + number(camera.fov_deg) + " deg, " + std::to_string(camera.width) + "x" +
         std::to_string(camera.height) + ", " +
         (by_outline ? "outline tolerance " + number(outline_tolerance) + " pixels)"
                     : number(pixels_per_segment) + " pixels per segment)");
    if (with_nyquist) s += " and nyquist (" + number(samples_per_wavelength) + " samples per wavelength)";
  }
  if (silhouette.enabled) {
    s += silhouette.eye_from_camera ? std::string(", silhouettes from the camera's eye")
                                    : ", silhouettes from eye " + format_vec(silhouette.eye);
    s += " (beta " + number(silhouette.beta) + (silhouette.blend ? ")" : ", factors only)");
  }
  if (displace.enabled())
    s += ", displaced by " + number(displace.amplitude) +
         (displace.kind == DisplaceKind::Noise ? " noise(" + number(displace.frequency) + " P)"
                                               : " sin(" + number(displace.frequency) + " |P|)");
  return s;
}

namespace {

// What both rules project with: the focal length in pixels of the viewport's height, and the
// distance from the eye to the edge's midpoint. An edge through the eye would be infinitely
// large on screen; its factor is then the maximum.
struct Projection {
  double focal_pixels, distance;
};
Projection project(const ScreenCamera& camera, const glm::dvec3& a, const glm::dvec3& b) {
  const double focal_pixels = 0.5 * camera.height / std::tan(0.5 * camera.fov_deg * M_PI / 180.0);
  const glm::dvec3 mid = 0.5 * (a + b);
  return {focal_pixels, std::max(glm::length(mid - camera.eye), 1e-300)};
}

double clamp_factor(double segments) { return std::clamp(segments, 1.0, static_cast<double>(kMaxTessFactor)); }

}  // namespace

float adaptive_edge_factor(const ScreenCamera& camera, double pixels_per_segment, const glm::dvec3& a,
                           const glm::dvec3& b) {
  const Projection p = project(camera, a, b);
  const double length = glm::length(a - b);
  return static_cast<float>(clamp_factor(length * p.focal_pixels / (p.distance * pixels_per_segment)));
}

float silhouette_edge_factor(const ScreenCamera& camera, double outline_tolerance, double alpha, double deviation,
                             const glm::dvec3& a, const glm::dvec3& b) {
  const Projection p = project(camera, a, b);
  const double offset_pixels = alpha * deviation * (p.focal_pixels / p.distance);
  return static_cast<float>(clamp_factor(kChordErrorFactor * std::sqrt(offset_pixels / outline_tolerance)));
}

double nyquist_segments(const DisplaceSettings& displace, double samples_per_wavelength, const glm::dvec3& a,
                        const glm::dvec3& b) {
  if (!displace.enabled()) return 0.0;
  // The ends in lexicographic order: the same operations whichever patch asks.
  const bool swap = std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z);
  const glm::dvec3& p = swap ? b : a;
  const glm::dvec3& q = swap ? a : b;
  const glm::dvec3 chord = q - p;
  const double length = glm::length(chord);
  if (!(length > 0.0)) return 0.0;
  double cycles = displace.frequency * length;  // noise: one wavelength per lattice cell
  if (displace.kind == DisplaceKind::Sine) {
    const glm::dvec3 e = chord / length;
    auto rate = [&](const glm::dvec3& x) {
      const double r = glm::length(x);
      return r > 0.0 ? std::abs(glm::dot(x, e)) / r : 1.0;
    };
    cycles *= std::min(1.0, std::max(rate(p), rate(q))) / (2.0 * M_PI);
  }
  return samples_per_wavelength * cycles;
}

float nyquist_edge_factor(const DisplaceSettings& displace, double samples_per_wavelength, const glm::dvec3& a,
                          const glm::dvec3& b) {
  return static_cast<float>(clamp_factor(nyquist_segments(displace, samples_per_wavelength, a, b)));
}

NyquistShortfall nyquist_shortfall(const TessSettings& s, const Mesh& mesh) {
  NyquistShortfall shortfall;
  const bool nyquist = s.kind == PatternKind::D3D11 && s.source == FactorSource::Adaptive &&
                       (s.rule == AdaptiveRule::Nyquist || s.with_nyquist);
  if (!nyquist) return shortfall;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * mesh.triangle_count());
  for (const glm::uvec3& tri : mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = tri[i], b = tri[(i + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, b] : edges) {
    const double segments = nyquist_segments(s.displace, s.samples_per_wavelength, mesh.positions[a], mesh.positions[b]);
    if (segments > static_cast<double>(kMaxTessFactor)) ++shortfall.edges;
    shortfall.most_segments = std::max(shortfall.most_segments, segments);
  }
  return shortfall;
}

void bind_silhouette(TessSettings& s, const Mesh& mesh) {
  if (!s.uses_silhouette() || s.silhouette_field) return;
  const bool adaptive = s.kind == PatternKind::D3D11 && s.source == FactorSource::Adaptive;
  const std::string source = mesh.source.empty() ? std::string("mesh") : mesh.source;
  validate(s.silhouette, source);
  if (s.silhouette.enabled && s.silhouette.eye_from_camera && !adaptive)
    throw InputError(source, "--silhouette", "'camera' takes the eye of --adaptive ... --camera, which is not given");
  // Without --silhouette the silhouette rule takes α from the camera's eye with the default β
  // (and the patches stay plain PN); with it, the rule and the blend share its α.
  const bool own_eye = s.silhouette.enabled && !s.silhouette.eye_from_camera;
  const glm::dvec3 eye = own_eye ? s.silhouette.eye : s.camera.eye;
  auto field = std::make_shared<MeshSilhouette>(mesh, eye, s.silhouette.beta);
  if (adaptive && s.rule == AdaptiveRule::Contour) field->mark_contour_patches(mesh, s.silhouette.blends());
  s.silhouette_field = std::move(field);
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
  PatchFactors f;
  if (settings.rule == AdaptiveRule::Nyquist) {
    f.outer = {1.0f, 1.0f, 1.0f};
  } else if (settings.by_outline()) {
    if (!settings.silhouette_field) throw std::logic_error("patch_factors: the silhouette rule needs bind_silhouette()");
    const MeshSilhouette& field = *settings.silhouette_field;
    const std::array<double, 3>& alpha = field.alpha(t);  // edges 01, 12, 20
    const std::array<double, 3>& deviation = field.deviation(t);
    const bool contour = settings.rule == AdaptiveRule::Contour;
    auto edge = [&](int e, const glm::dvec3& p, const glm::dvec3& q) {
      const double a = contour && field.contour_edge(t, e) ? 1.0 : alpha[static_cast<std::size_t>(e)];
      return silhouette_edge_factor(settings.camera, settings.outline_tolerance, a, deviation[static_cast<std::size_t>(e)],
                                    p, q);
    };
    f.outer = {edge(2, p0, p2), edge(0, p0, p1), edge(1, p1, p2)};
  } else {
    auto edge = [&](const glm::dvec3& a, const glm::dvec3& b) {
      return adaptive_edge_factor(settings.camera, settings.pixels_per_segment, a, b);
    };
    f.outer = {edge(p0, p2), edge(p0, p1), edge(p1, p2)};
  }
  if (settings.rule == AdaptiveRule::Nyquist || settings.with_nyquist) {
    auto edge = [&](const glm::dvec3& a, const glm::dvec3& b) {
      return nyquist_edge_factor(settings.displace, settings.samples_per_wavelength, a, b);
    };
    const std::array<float, 3> nyquist{edge(p0, p2), edge(p0, p1), edge(p1, p2)};
    for (std::size_t i = 0; i < 3; ++i) f.outer[i] = std::max(f.outer[i], nyquist[i]);
  }
  f.inner = std::max({f.outer[0], f.outer[1], f.outer[2]});
  return f;
}

void validate(const TessSettings& s, const std::string& source) {
  validate(s.silhouette, source);
  validate(s.displace, source);
  if (s.kind == PatternKind::Uniform) {
    if (s.L < 1 || s.L > kMaxTessFactor)
      throw InputError(source, "-L", "tessellation factor " + std::to_string(s.L) + " is outside 1.." +
                                         std::to_string(kMaxTessFactor));
    return;
  }
  // Fixed factors are all valid: the tessellator clamps them, and one <= 0 or NaN culls.
  if (s.source == FactorSource::Fixed) return;
  if (s.rule == AdaptiveRule::Nyquist || s.with_nyquist) {
    if (!s.displace.enabled())
      throw InputError(source, "--adaptive", "the nyquist rule samples a displacement: it needs --displace sine|noise");
    if (!(s.samples_per_wavelength >= 1.0) || std::isinf(s.samples_per_wavelength))
      throw InputError(source, "--samples-per-wavelength",
                       number(s.samples_per_wavelength) + " is not a finite number >= 1");
    if (s.rule == AdaptiveRule::Nyquist) return;  // no camera
  }
  const ScreenCamera& c = s.camera;
  if (!is_finite(c.eye) || !is_finite(c.target))
    throw InputError(source, "--camera", "eye and target must be finite");
  if (c.eye == c.target) throw InputError(source, "--camera", "the eye is the target: no direction of view");
  if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0))
    throw InputError(source, "--camera", "fov " + number(c.fov_deg) + " is outside (0, 180) degrees");
  if (c.width < 1 || c.height < 1) throw InputError(source, "--viewport", "width and height must be at least 1");
  if (!(s.pixels_per_segment > 0.0) || std::isinf(s.pixels_per_segment))
    throw InputError(source, "--pixels-per-segment", "must be a positive finite number");
  if (!(s.outline_tolerance > 0.0) || std::isinf(s.outline_tolerance))
    throw InputError(source, "--outline-tolerance", "must be a positive finite number");
}

}  // namespace tessim
