// Host side of the unit: a float mesh into the unit's fixed-point input stream and the
// fixed-point output stream back into the mesh's own coordinates (docs/number-formats.md §3).
//
// Scaling: positions are centred at the bounding-box centre and divided by the largest
// half-extent, so every coordinate lies in [-1, 1]; normals are quantized as they are (unit
// length, components in [-1, 1]). Quantization rounds to nearest, ties up: q = floor(x 2^F + 1/2).
// The inverse multiplies back; output normals are normalized (the unit's are not).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <span>
#include <vector>
#include <cstddef>

#include <glm/glm.hpp>

#include "model/factors.hpp"
#include "model/mesh.hpp"
#include "model/pn.hpp"
#include "sim/base/fixed.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

struct HostScaling {
  glm::dvec3 center{0.0};  // bounding-box centre of the mesh
  double half_extent = 1.0;  // largest half-extent of the bounding box (1 for a point)

  // Mesh coordinates -> unit coordinates in [-1, 1] and back.
  glm::dvec3 to_unit(const glm::dvec3& p) const { return (p - center) / half_extent; }
  glm::dvec3 from_unit(const glm::dvec3& q) const { return q * half_extent + center; }
};

HostScaling host_scaling(const Mesh& mesh);

// Checks what the conversion relies on: finite positions, unit normals (to 1e-3), one normal
// per position, vertex indices in range. Throws InputError naming the mesh and the element.
void check_convertible(const Mesh& mesh);

// Round to nearest (ties towards +inf) to F fraction bits. |x| must be well inside the range.
std::int64_t quantize(double x, const NumberFormat& fmt);
FxVec quantize(const glm::dvec3& x, const NumberFormat& fmt);
glm::dvec3 dequantize(const FxVec& x, const NumberFormat& fmt);
// The triangle's positions and normals as the float reference takes them: the values the unit
// received (its quantized input), not the mesh's.
PnInput dequantized_input(const TriangleFx& tri, const NumberFormat& fmt);

// Input triangle `index` of the mesh, scaled and quantized, with factor L and id = index.
// With `with_tags` the mesh's scalar tags come along (Δ, σ, θ, β quantized like normals;
// the fixed-point scalar-tagged arithmetic, docs/number-formats.md); InputError naming the
// vertex when σ exceeds the coordinate range.
TriangleFx to_fixed(const Mesh& mesh, std::size_t index, const HostScaling& scaling,
                    const NumberFormat& fmt, int L, bool with_tags = false);

// Vertices whose scalar tags act in float64 but vanish in the fixed-point input: a crease
// vector Δ that quantizes to zero (every component below half of 2^-F), or a tension θ that
// does. The unit then computes plain PN there; the caller warns (tessim sim --cpg-tags 1).
std::size_t tags_lost_in_fixed_point(const Mesh& mesh, const NumberFormat& fmt);
// The warning about them, "FILE: tags: N vertices ..." (empty when there are none), as the CLI
// prints it after "tessim: warning: " and the Python module raises it as a UserWarning.
std::string tags_lost_warning(const Mesh& mesh, const NumberFormat& fmt);

// Gives the triangle the D3D11 pattern with factors `f` as the tessellator processes them
// (d3d11_host_factors: clamped, rounded, 16.16); pow2 travels as integer. `f` must not be culled:
// a culled patch has no points and the host does not send it.
void set_d3d11_pattern(TriangleFx& tri, const D3D11Factors& f, Partitioning partitioning);

// Input triangle `index` with the pattern `settings` gives its patch: the uniform pattern with
// settings.L, or the D3D11 pattern with the patch's factors (fixed or adaptive, model/factors.hpp).
// std::nullopt when the factors cull the patch (an outer factor <= 0 or NaN): it is not sent.
std::optional<TriangleFx> to_fixed(const Mesh& mesh, std::size_t index, const HostScaling& scaling,
                                   const NumberFormat& fmt, const TessSettings& settings, bool with_tags = false);

// The pattern of each triangle of a mesh run through the unit: one factor for all (the
// configuration's L), one uniform factor per triangle, or the D3D11 pattern with fixed or
// adaptive factors (model/factors.hpp), which the unit takes per patch.
struct MeshPatterns {
  std::span<const std::uint8_t> factors;  // uniform: one per triangle of the mesh, or empty
  const TessSettings* d3d11 = nullptr;    // D3D11 settings (kept by reference), or none
  // The silhouette weights alpha the host sends with each triangle (tessim sim --silhouette), or
  // none (every alpha 1). Only a unit that takes alpha (alpha_bits > 0) reads them.
  const MeshSilhouette* silhouette = nullptr;
  // Procedural displacement the geometry engine applies to every output vertex (tessim sim
  // --displace): in float, after the unit, at the cost of sim/ge/ge_cost.hpp per vertex.
  DisplaceSettings displace;

  MeshPatterns() = default;
  MeshPatterns(std::span<const std::uint8_t> f) : factors(f) {}
  MeshPatterns(const std::vector<std::uint8_t>& f) : factors(f) {}
  MeshPatterns(const TessSettings* s) : d3d11(s && s->kind == PatternKind::D3D11 ? s : nullptr) {}
  bool per_patch() const { return d3d11 || !factors.empty(); }
};

// Gives the triangle (mesh triangle `index`) the silhouette weights of `silhouette`, rounded to
// the unit's alpha_bits (quantize_alpha); nothing for a unit without alpha.
void set_silhouette_alpha(TriangleFx& tri, const MeshSilhouette& silhouette, std::size_t index,
                          const NumberFormat& fmt);
// `tri` with the alpha of `patterns` (set_silhouette_alpha) when it has a silhouette.
TriangleFx with_alpha(TriangleFx tri, const MeshPatterns& patterns, std::size_t index, const NumberFormat& fmt);

// Output vertex data back in the mesh's coordinates. The normal is normalized; a vanished
// normal (all components zero) is returned as the zero vector and reported by the caller.
glm::dvec3 position_from_fixed(const FxVec& pos, const HostScaling& scaling, const NumberFormat& fmt);
glm::dvec3 normal_from_fixed(const FxVec& nrm, const NumberFormat& fmt);

// Throws InputError(mesh, "triangle <id>", ...) when a patch's control-point computation
// saturated: the coordinate widths cannot hold the mesh.
void check_patch_flags(const Mesh& mesh, std::uint32_t triangle, std::uint8_t flags,
                       const NumberFormat& fmt);

}  // namespace tessim::sim
