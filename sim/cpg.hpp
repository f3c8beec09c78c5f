// Control-point generation (CPG) in fixed point: the values the unit's CPG datapath produces
// and the number of cycles it takes. The RTL's sequential CPG computes exactly these values,
// operation for operation (docs/microarchitecture.md §CPG).
#pragma once

#include <array>
#include <cstdint>

#include "model/normal_mode.hpp"
#include "sim/fixed.hpp"

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

// One input triangle as it crosses the unit's input stream.
struct TriangleFx {
  std::array<FxVec, 3> p{};  // P1, P2, P3
  std::array<FxVec, 3> n{};  // N1, N2, N3 (unit length before quantisation)
  int L = 1;                 // tessification factor 1..64
  std::uint32_t id = 0;      // patch id, passed through to every output vertex
  // Scalar tags per corner; all neutral for plain PN. They cross the input stream only to a CPG
  // that takes them (cpg_tags; the RTL's CpgTags), which alone reads them.
  std::array<TagsFx, 3> tags{};
};

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
ControlPointsFx compute_control_points(const TriangleFx& tri, NormalMode mode, const NumberFormat& fmt);

// The shape of the dedicated CPG's datapath (docs/microarchitecture.md §5): only its timing
// and cost depend on it, never a value.
struct CpgVariant {
  int lanes = 1;       // edge lanes: 1 walks the three edges in turn, 3 computes them at once
  int digit_bits = 1;  // r: quotient / root bits the dividers and the square root retire a cycle
  bool operator==(const CpgVariant&) const = default;
};
inline constexpr int kMaxCpgDigitBits = 32;

// D: cycles of one division or square root, ceil(W / r).
int cpg_digit_steps(const NumberFormat& fmt, int digit_bits);
// Cycles the dedicated CPG spends on one edge (E) and on one triangle (C), accept cycle
// excluded (see the doc): the edges in turn (one lane) or at once (three lanes), then the
// centre point and the write.
int cpg_edge_cycles(NormalMode mode, const NumberFormat& fmt, int digit_bits = 1);
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
