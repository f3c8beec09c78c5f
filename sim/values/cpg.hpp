// Control-point generation (CPG) in fixed point: the values the unit's CPG datapath produces
// and the number of cycles it takes. The RTL's sequential CPG computes exactly these values,
// operation for operation (docs/microarchitecture.md §CPG).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "sim/values/d3d11_walk.hpp"
#include "model/normal_mode.hpp"
#include "sim/base/fixed.hpp"

namespace tessim::sim {

// The scalar tags of one vertex (docs/stpn.md) in the coordinate format: crease vector Δ
// (zero: untagged), sharpness σ, tension θ, bias β. All zero: a plain PN vertex.
struct TagsFx {
  FxVec delta{};
  std::int64_t sigma = 0, theta = 0, beta = 0;
  bool tagged() const { return delta[0] != 0 || delta[1] != 0 || delta[2] != 0; }
  bool neutral() const { return !tagged() && theta == 0; }  // changes nothing (model: VertexTags)
  bool operator==(const TagsFx&) const = default;
};

// The tessellation pattern of a patch (docs/microarchitecture.md §7): the uniform pattern with
// one factor L, or the Direct3D 11 pattern (docs/patterns.md) with per-edge factors. pow2 travels
// as integer: the host has rounded its factors to powers of two already.
enum class TriPattern : std::uint8_t { uniform = 0, integer = 1, fractional_odd = 2, fractional_even = 3 };

// The silhouette weight alpha of an edge as the host hands it over (docs/number-formats.md,
// Silhouette weight): unsigned with kAlphaFracBits fraction bits, 0..1, rounded by the host to
// the unit's alpha_bits A (its low 16 - A bits zero); the unit's input port carries its top
// A + 1 bits. 1 (kAlphaOne) is plain PN, 0 the flat triangle.
inline constexpr int kAlphaFracBits = 16;
inline constexpr std::uint32_t kAlphaOne = std::uint32_t{1} << kAlphaFracBits;
inline constexpr int kMaxAlphaBits = kAlphaFracBits;
// The width `tessim sim --silhouette` gives a unit configured without alpha: the rounding moves a
// tangent point by at most 2^-9 of its curve's offset (docs/number-formats.md).
inline constexpr int kDefaultAlphaBits = 8;
// round(alpha 2^A) / 2^A in the 16-bit transfer format: what the host sends for a float alpha.
std::uint32_t quantize_alpha(double alpha, int alpha_bits);
// The port value (A + 1 bits) of a transfer-format alpha.
inline std::uint32_t alpha_port_value(std::uint32_t alpha, int alpha_bits) {
  return alpha >> (kAlphaFracBits - alpha_bits);
}

// One input triangle as it crosses the unit's input stream.
struct TriangleFx {
  std::array<FxVec, 3> p{};  // P1, P2, P3
  std::array<FxVec, 3> n{};  // N1, N2, N3 (unit length before quantisation)
  int L = 1;                 // tessellation factor 1..64 of the uniform pattern
  TriPattern pattern = TriPattern::uniform;
  // D3D11 patterns: outer factors e0, e1, e2 and the inner factor, unsigned 16.16, as the host
  // hands them over: clamped to the partitioning's range and rounded (d3d11_host_factors()).
  std::array<Fixed16, 4> factors{};
  std::uint32_t id = 0;      // patch id, passed through to every output vertex
  // Scalar tags per corner; all neutral for plain PN. They cross the input stream only to a CPG
  // that takes them (cpg_tags; the RTL's CpgTags), which alone reads them.
  std::array<TagsFx, 3> tags{};
  // Silhouette weight of edge e (corners e -> e + 1), read only by a unit that takes alpha
  // (NumberFormat::alpha_bits > 0): the CPG blends the edge's tangent points between the flat
  // triangle (0) and PN (1, the default).
  std::array<std::uint32_t, 3> alpha{kAlphaOne, kAlphaOne, kAlphaOne};
};

// The partitioning a D3D11 triangle pattern stands for.
Partitioning tri_partitioning(TriPattern pattern);
// The D3D11 pattern's walk of a triangle (pattern != uniform): what the unit derives from its
// factors (d3d11_factors_from_fixed, d3d11_setup).
D3D11Setup tri_setup(const TriangleFx& tri);
// "L=4", or "fractional_odd 3.5,2.2,7.9 inner 4.4" (the factors as the unit receives them).
std::string describe_pattern(const TriangleFx& tri);
// Vertices the unit produces for the triangle: its pattern's points.
int patch_vertex_count(const TriangleFx& tri);
// The reason the unit cannot take the triangle's pattern and factors, empty if it can: L outside
// 1..64, a D3D11 factor outside the partitioning's range or not rounded as it requires, a
// fractional_odd inner factor of exactly 1 beside a larger outer one (docs/rtl.md, FSU).
std::string tri_pattern_problem(const TriangleFx& tri);
// The reason a unit with `fmt`'s alpha_bits cannot take the triangle's alpha, empty if it can:
// above 1, or not rounded to alpha_bits fraction bits. A unit without alpha ignores it.
std::string tri_alpha_problem(const TriangleFx& tri, const NumberFormat& fmt);
inline bool alpha_in_contract(const TriangleFx& tri, const NumberFormat& fmt) {
  if (!fmt.takes_alpha()) return true;
  const std::uint32_t low = (std::uint32_t{1} << (kAlphaFracBits - fmt.alpha_bits)) - 1;
  for (const std::uint32_t a : tri.alpha)
    if (a > kAlphaOne || (a & low) != 0) return false;
  return true;
}

// Contents of one control-point buffer (net layout of model/pn.hpp, net_index()).
// The normal net is stored at twice its Bernstein value (corners 2 Ni, mid-edges n_ij), which
// keeps one more bit of the mid-edge normals; the output normal is therefore 2 n(u,v) (the
// unit's normals are unnormalized; the consumer normalizes). In linear mode the corners hold
// N1, N2, N3 and the mid-edge entries are zero.
struct ControlPointsFx {
  std::array<FxVec, 10> b{};
  std::array<FxVec, 6> n{};
  std::uint8_t flags = 0;  // FxFlag bits raised while computing this patch
};

// The normal modes the hardware implements. `derivative` needs a per-vertex cross product
// (six multipliers behind the TE) whose precision falls as 1/L^2; it stays in the reference.
bool hardware_supports(NormalMode mode);

// Values of the dedicated CPG for one triangle. A triangle with non-neutral tags takes the
// scalar-tagged control points in fixed point (docs/number-formats.md, Scalar-tagged PN), the
// formulas of model/pn.hpp make_stpn_patch operation for operation; neutral corners take the
// plain PN formulas, so all-neutral tags give the plain control points bit for bit.
// A unit that takes alpha (fmt.alpha_bits > 0) blends each plain-PN tangent point with its
// edge's alpha: (2 Pn + Pf - round(alpha w) Nn) / 3, the product alpha w rounded to w's 2F
// fraction bits; alpha = 1 gives the PN point bit for bit. A scalar-tagged corner's tangent
// point is not blended.
ControlPointsFx compute_control_points(const TriangleFx& tri, NormalMode mode, const NumberFormat& fmt);

// The shape of the dedicated CPG's datapath (docs/microarchitecture.md §5): only its timing
// and cost depend on it, never a value.
struct CpgVariant {
  int lanes = 1;       // edge lanes: 1 walks the three edges in turn, 3 computes them at once
  int digit_bits = 1;  // r: quotient / root bits the dividers and the square root retire a cycle
  int copies = 1;      // CPGs taking successive triangles round robin (sim/blocks/cpg.hpp CpgArray)
  int product_reg = 0; // 1: the multipliers' products are registered (more cycles, a shorter path)
  bool operator==(const CpgVariant&) const = default;
};
inline constexpr int kMaxCpgDigitBits = 32;

// D: cycles of one division or square root, ceil(W / r).
int cpg_digit_steps(const NumberFormat& fmt, int digit_bits);
// Cycles the dedicated CPG spends on one edge (E) and on one triangle (C), accept cycle
// excluded (see the doc): the edges in turn (one lane) or at once (three lanes), then the
// centre point and the write. Registered products (product_reg) add steps to an edge (3 linear,
// 3 reflect, 4 quadratic) and a cycle to the centre point (rtl/tess_cpg_edge.sv lists both
// schedules). A CPG that takes alpha (fmt.alpha_bits > 0) scales each w by alpha in a step of
// its own, which lengthens only the linear edge with registered products (by one step).
int cpg_edge_cycles(NormalMode mode, const NumberFormat& fmt, int digit_bits = 1, bool product_reg = false);
int cpg_cycles(NormalMode mode, const NumberFormat& fmt, const CpgVariant& variant = {});
// Cycles a CPG that takes scalar tags adds for this triangle (0 when its tags are neutral;
// docs/microarchitecture.md §5): the face normal, per non-neutral corner its normalizations
// (N', Y and X for a tagged corner, X alone for a θ-only one), and four cycles per tangent point
// of a non-neutral corner. One lane takes the corners and edges in turn, three lanes one each at
// a time (rtl/tess_cpg.sv runs exactly this schedule).
int cpg_tag_cycles(const TriangleFx& tri, const NumberFormat& fmt, const CpgVariant& variant = {});

// Mode encoding on the unit's mode input and in the RTL package.
constexpr int mode_code(NormalMode m) {
  return m == NormalMode::Quadratic ? 0 : m == NormalMode::Reflect ? 1 : 2;  // linear = 2
}

}  // namespace tessim::sim
