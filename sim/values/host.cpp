#include "sim/values/host.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "model/base/error.hpp"
#include "model/silhouette.hpp"

namespace tessim::sim {

HostScaling host_scaling(const Mesh& mesh) {
  const BoundingBox box = bounding_box(mesh);
  HostScaling s;
  s.center = box.center();
  const glm::dvec3 half = 0.5 * (box.hi - box.lo);
  const double largest = std::max({half.x, half.y, half.z});
  s.half_extent = largest > 0.0 ? largest : 1.0;
  return s;
}

void check_convertible(const Mesh& mesh) {
  const std::string file = mesh.source.empty() ? std::string("mesh") : mesh.source;
  if (mesh.normals.size() != mesh.positions.size())
    throw InputError(file, "normals",
                     std::to_string(mesh.normals.size()) + " normals for " +
                         std::to_string(mesh.positions.size()) + " positions");
  auto finite = [](const glm::dvec3& x) { return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z); };
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!finite(mesh.positions[i]))
      throw InputError(file, "vertex " + std::to_string(i), "position is NaN or infinite");
    const double len = glm::length(mesh.normals[i]);
    if (!(std::abs(len - 1.0) <= 1e-3))
      throw InputError(file, "vertex " + std::to_string(i), "normal is not of unit length (" + std::to_string(len) + ")");
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      if (mesh.triangles[t][c] >= mesh.positions.size())
        throw InputError(file, "triangle " + std::to_string(t),
                         "vertex index " + std::to_string(mesh.triangles[t][c]) + " out of range");
}

std::int64_t quantize(double x, const NumberFormat& fmt) {
  return static_cast<std::int64_t>(std::floor(std::ldexp(x, fmt.coord_frac_bits) + 0.5));
}

FxVec quantize(const glm::dvec3& x, const NumberFormat& fmt) {
  return {quantize(x.x, fmt), quantize(x.y, fmt), quantize(x.z, fmt)};
}

glm::dvec3 dequantize(const FxVec& x, const NumberFormat& fmt) {
  const int F = fmt.coord_frac_bits;
  return {std::ldexp(static_cast<double>(x[0]), -F), std::ldexp(static_cast<double>(x[1]), -F),
          std::ldexp(static_cast<double>(x[2]), -F)};
}

PnInput dequantized_input(const TriangleFx& tri, const NumberFormat& fmt) {
  PnInput in;
  for (int i = 0; i < 3; ++i) {
    in.p[i] = dequantize(tri.p[i], fmt);
    in.n[i] = dequantize(tri.n[i], fmt);
  }
  return in;
}

TriangleFx to_fixed(const Mesh& mesh, std::size_t index, const HostScaling& scaling,
                    const NumberFormat& fmt, int L, bool with_tags) {
  const glm::uvec3& t = mesh.triangles[index];
  TriangleFx tri;
  for (int v = 0; v < 3; ++v) {
    tri.p[static_cast<std::size_t>(v)] = quantize(scaling.to_unit(mesh.positions[t[v]]), fmt);
    tri.n[static_cast<std::size_t>(v)] = quantize(mesh.normals[t[v]], fmt);
    if (!with_tags || !mesh.has_tags()) continue;
    const VertexTags& tags = mesh.tags[t[v]];
    // Δ (|components| <= 2), θ and β (in [-1, 1]) always fit; σ >= 0 is unbounded in the format.
    if (!(tags.sigma < std::ldexp(1.0, fmt.coord_int_bits)))
      throw InputError(mesh.source.empty() ? std::string("mesh") : mesh.source, "vertex " + std::to_string(t[v]),
                       "sigma " + std::to_string(tags.sigma) + " is beyond the unit's coordinate range (below " +
                           std::to_string(1 << fmt.coord_int_bits) + ")");
    TagsFx& q = tri.tags[static_cast<std::size_t>(v)];
    q.delta = quantize(tags.delta, fmt);
    q.sigma = quantize(tags.sigma, fmt);
    q.theta = quantize(tags.theta, fmt);
    q.beta = quantize(tags.beta, fmt);
  }
  tri.L = L;
  tri.id = static_cast<std::uint32_t>(index);
  return tri;
}

std::size_t tags_lost_in_fixed_point(const Mesh& mesh, const NumberFormat& fmt) {
  std::size_t lost = 0;
  for (const VertexTags& tags : mesh.tags) {
    const bool crease_lost = tags.tagged() && quantize(tags.delta, fmt) == FxVec{0, 0, 0};
    const bool tension_lost = tags.theta != 0.0 && quantize(tags.theta, fmt) == 0;
    if (crease_lost || tension_lost) ++lost;
  }
  return lost;
}

std::string tags_lost_warning(const Mesh& mesh, const NumberFormat& fmt) {
  const std::size_t lost = tags_lost_in_fixed_point(mesh, fmt);
  if (lost == 0) return {};
  return (mesh.source.empty() ? std::string("mesh") : mesh.source) + ": tags: " + std::to_string(lost) +
         " vertices carry a crease vector or tension below the fixed-point resolution 2^-" +
         std::to_string(fmt.coord_frac_bits) +
         ", which the unit receives as zero: it computes plain PN there (raise coord_frac_bits; docs/stpn.md)";
}

void set_d3d11_pattern(TriangleFx& tri, const D3D11Factors& f, Partitioning partitioning) {
  switch (partitioning) {
    case Partitioning::fractional_odd: tri.pattern = TriPattern::fractional_odd; break;
    case Partitioning::fractional_even: tri.pattern = TriPattern::fractional_even; break;
    default: tri.pattern = TriPattern::integer; break;
  }
  tri.factors = {f.outer_fixed[0], f.outer_fixed[1], f.outer_fixed[2], f.inner_fixed};
}

std::optional<TriangleFx> to_fixed(const Mesh& mesh, std::size_t index, const HostScaling& scaling,
                                   const NumberFormat& fmt, const TessSettings& settings, bool with_tags) {
  if (settings.kind == PatternKind::Uniform) return to_fixed(mesh, index, scaling, fmt, settings.L, with_tags);
  const PatchFactors f = patch_factors(settings, mesh, index);
  const D3D11Factors processed = d3d11_host_factors(f.outer, f.inner, settings.partitioning);
  if (processed.culled) return std::nullopt;
  TriangleFx tri = to_fixed(mesh, index, scaling, fmt, 1, with_tags);
  set_d3d11_pattern(tri, processed, settings.partitioning);
  return tri;
}

void set_silhouette_alpha(TriangleFx& tri, const MeshSilhouette& silhouette, std::size_t index,
                          const NumberFormat& fmt) {
  if (!fmt.takes_alpha()) return;
  const std::array<double, 3>& alpha = silhouette.alpha(index);
  for (std::size_t e = 0; e < 3; ++e) tri.alpha[e] = quantize_alpha(alpha[e], fmt.alpha_bits);
}

TriangleFx with_alpha(TriangleFx tri, const MeshPatterns& patterns, std::size_t index, const NumberFormat& fmt) {
  if (patterns.silhouette) set_silhouette_alpha(tri, *patterns.silhouette, index, fmt);
  return tri;
}

glm::dvec3 position_from_fixed(const FxVec& pos, const HostScaling& scaling, const NumberFormat& fmt) {
  return scaling.from_unit(dequantize(pos, fmt));
}

glm::dvec3 normal_from_fixed(const FxVec& nrm, const NumberFormat& fmt) {
  const glm::dvec3 n = dequantize(nrm, fmt);
  const double len = glm::length(n);
  return len > 0.0 ? n / len : glm::dvec3(0.0);
}

void check_patch_flags(const Mesh& mesh, std::uint32_t triangle, std::uint8_t flags,
                       const NumberFormat& fmt) {
  if ((flags & kFlagSaturated) == 0) return;
  throw InputError(mesh.source.empty() ? std::string("mesh") : mesh.source,
                   "triangle " + std::to_string(triangle),
                   "the fixed-point widths cannot hold the mesh: a control point saturated the " +
                       std::to_string(fmt.coord_width()) + "-bit coordinate format (I = " +
                       std::to_string(fmt.coord_int_bits) + ", F = " +
                       std::to_string(fmt.coord_frac_bits) + "); raise coord_int_bits");
}

}  // namespace tessim::sim
