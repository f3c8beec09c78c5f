#include "sim/values/cpg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "model/pattern.hpp"
#include "model/pn.hpp"

namespace tessim::sim {

namespace {

FxVec sub(const FxVec& a, const FxVec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
FxVec add(const FxVec& a, const FxVec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

struct EdgeSlots {
  int a, b;          // vertex indices: the edge runs from a to b
  int near_a, near_b;  // geometry net slots of the tangent points near a and near b
  int mid;           // normal net slot of the mid-edge normal
};

// Edge order of the CPG schedule: P1->P2, P2->P3, P3->P1.
constexpr std::array<EdgeSlots, 3> kEdges{{
    {0, 1, net_index(1, 0, 3), net_index(2, 0, 3), net_index(1, 0, 2)},  // b210 b120 n110
    {1, 2, net_index(2, 1, 3), net_index(1, 2, 3), net_index(1, 1, 2)},  // b021 b012 n011
    {2, 0, net_index(0, 2, 3), net_index(0, 1, 3), net_index(0, 1, 2)},  // b102 b201 n101
}};

// (2 Pn + Pf - w Nn) / 3 with w = (Pf - Pn).Nn, for the tangent point near Pn on edge Pn->Pf.
// `w_ex` is the exact dot product (2F fraction bits) and `sign` its orientation: the edge
// vector d is computed once per edge (b - a), so the far end uses -d.
FxVec tangent_point(const FxVec& pn, const FxVec& pf, const FxVec& nn, i128 w_ex, int sign,
                    const NumberFormat& f, std::uint8_t& flags) {
  const int F = f.coord_frac_bits;
  FxVec r{};
  for (int c = 0; c < 3; ++c) {
    const i128 chord = (i128{2} * pn[c] + pf[c]) << (2 * F);  // 3F fraction bits
    const i128 num = chord - sign * w_ex * nn[c];
    r[c] = mul_const(num, 3 * F, one_third(f), f, flags);
  }
  return r;
}

// normalize(v) as the CPG computes it: v / floor(sqrt(v.v)), each component a truncated
// division (F fraction bits). A zero vector raises kFlagDivByZero and gives zero.
FxVec normalize_fx(const FxVec& v, const NumberFormat& f, std::uint8_t& flags) {
  const int F = f.coord_frac_bits;
  const i128 norm = static_cast<i128>(isqrt(static_cast<u128>(dot_exact(v, v))));  // F fraction bits
  FxVec r{};
  for (int c = 0; c < 3; ++c) r[c] = div_trunc(i128{v[c]} << F, norm, f, flags);
  return r;
}

// round(a + k b) per component, k a scalar with F fraction bits: a + k b is exact with 2F
// fraction bits and rounded once.
FxVec add_scaled(const FxVec& a, std::int64_t k, const FxVec& b, const NumberFormat& f, std::uint8_t& flags) {
  const int F = f.coord_frac_bits;
  FxVec r{};
  for (int c = 0; c < 3; ++c) r[c] = saturate(round_shift((i128{a[c]} << F) + i128{k} * b[c], F), f, flags);
  return r;
}

// Scalar-tagged tangent coefficient nearest Pj on edge j -> k (docs/mathematics.md §9):
//   d = Pj + (1 - θj)/3 (Pk - Pj),  b = d + Π(Pj, n, d) m,  Π(p, n, q) = -n.(q - p)
// with (n, m) = (Xj, Xj) off a crease and (Nj, Yj) on one (both ends tagged). d is rounded
// once; Π is exact (2F fraction bits) and b rounds d + Π m once.
FxVec stpn_tangent(const FxVec& pj, const FxVec& pk, std::int64_t theta, const FxVec& n, const FxVec& m,
                   const NumberFormat& f, std::uint8_t& flags) {
  const int F = f.coord_frac_bits;
  const i128 one = i128{1} << F;
  FxVec d{}, dj{};
  for (int c = 0; c < 3; ++c) {
    const i128 step = (one - theta) * (i128{pk[c]} - pj[c]);  // 2F fraction bits, exact
    d[c] = saturate(i128{pj[c]} + mul_const(step, 2 * F, one_third(f), f, flags), f, flags);
    dj[c] = d[c] - pj[c];
  }
  const i128 project = -dot_exact(n, dj);  // 2F fraction bits
  FxVec b{};
  for (int c = 0; c < 3; ++c) b[c] = saturate(i128{d[c]} + round_shift(project * m[c], 2 * F), f, flags);
  return b;
}

}  // namespace

bool hardware_supports(NormalMode mode) { return mode != NormalMode::Derivative; }

ControlPointsFx compute_control_points(const TriangleFx& tri, NormalMode mode, const NumberFormat& f) {
  if (!hardware_supports(mode)) throw std::invalid_argument("normal mode not implemented by the unit");
  const int F = f.coord_frac_bits;
  ControlPointsFx cp;
  std::uint8_t& flags = cp.flags;

  cp.b[net_index(0, 0, 3)] = tri.p[0];
  cp.b[net_index(3, 0, 3)] = tri.p[1];
  cp.b[net_index(0, 3, 3)] = tri.p[2];

  // Scalar tags: the sharp normal N'_i = normalize(Ni + s σi Δi) of each tagged corner, on the
  // side s of its crease this triangle's face normal lies on (exact sign), replaces Ni in the
  // normal field; X_i and Y_i steer the tangents of non-neutral corners.
  std::array<FxVec, 3> field = tri.n;
  std::array<FxVec, 3> x_dir{}, y_dir{};
  const bool stpn = !(tri.tags[0].neutral() && tri.tags[1].neutral() && tri.tags[2].neutral());
  if (stpn) {
    const FxVec e1 = sub(tri.p[1], tri.p[0]), e2 = sub(tri.p[2], tri.p[0]);
    const std::array<i128, 3> face{i128{e1[1]} * e2[2] - i128{e1[2]} * e2[1], i128{e1[2]} * e2[0] - i128{e1[0]} * e2[2],
                                   i128{e1[0]} * e2[1] - i128{e1[1]} * e2[0]};  // exact, 2F fraction bits
    for (int v = 0; v < 3; ++v) {
      const TagsFx& t = tri.tags[v];
      if (t.neutral()) continue;
      if (t.tagged()) {
        const i128 side = face[0] * t.delta[0] + face[1] * t.delta[1] + face[2] * t.delta[2];
        const std::int64_t signed_sigma = side >= 0 ? t.sigma : -t.sigma;
        field[v] = normalize_fx(add_scaled(tri.n[v], signed_sigma, t.delta, f, flags), f, flags);
        y_dir[v] = normalize_fx(add_scaled(tri.n[v], t.beta, t.delta, f, flags), f, flags);
      }
      // X = normalize((1 - σ) N + σ N'), rounded once before the normalization.
      FxVec blend{};
      const i128 one = i128{1} << F;
      for (int c = 0; c < 3; ++c)
        blend[c] = saturate(round_shift((one - t.sigma) * tri.n[v][c] + i128{t.sigma} * field[v][c], F), f, flags);
      x_dir[v] = normalize_fx(blend, f, flags);
    }
  }

  const std::array<int, 3> corner_n{net_index(0, 0, 2), net_index(2, 0, 2), net_index(0, 2, 2)};
  for (int v = 0; v < 3; ++v) {
    for (int c = 0; c < 3; ++c) {
      cp.n[corner_n[v]][c] = mode == NormalMode::Linear ? field[v][c]
                                                         : saturate(i128{2} * field[v][c], f, flags);
    }
  }

  i128 sum_t[3] = {0, 0, 0};
  for (const EdgeSlots& e : kEdges) {
    const FxVec& pa = tri.p[e.a];
    const FxVec& pb = tri.p[e.b];
    const FxVec& na = tri.n[e.a];
    const FxVec& nb = tri.n[e.b];
    const FxVec d = sub(pb, pa);  // exact, W+1 bits
    i128 wa_ex = dot_exact(d, na);
    i128 wb_ex = dot_exact(d, nb);
    if (f.takes_alpha()) {  // the silhouette blend: w <- round(alpha w), 2F fraction bits
      const std::int64_t alpha = alpha_port_value(tri.alpha[static_cast<std::size_t>(e.a)], f.alpha_bits);
      wa_ex = round_shift(alpha * wa_ex, f.alpha_bits);
      wb_ex = round_shift(alpha * wb_ex, f.alpha_bits);
    }
    // A corner's tangent: plain PN when its tags are neutral, else the scalar-tagged rule (its
    // crease rule when both ends are tagged).
    auto tangent = [&](int near, int far, const FxVec& pn, const FxVec& pf, const FxVec& nn, i128 w_ex, int sign) {
      const TagsFx& t = tri.tags[near];
      if (t.neutral()) return tangent_point(pn, pf, nn, w_ex, sign, f, flags);
      if (t.tagged() && tri.tags[far].tagged()) return stpn_tangent(pn, pf, t.theta, nn, y_dir[near], f, flags);
      return stpn_tangent(pn, pf, t.theta, x_dir[near], x_dir[near], f, flags);
    };
    cp.b[e.near_a] = tangent(e.a, e.b, pa, pb, na, wa_ex, +1);
    cp.b[e.near_b] = tangent(e.b, e.a, pb, pa, nb, wb_ex, -1);
    for (int c = 0; c < 3; ++c) sum_t[c] += i128{cp.b[e.near_a][c]} + cp.b[e.near_b][c];

    if (mode == NormalMode::Linear) continue;
    // Mid-edge normal from the field's corner normals (the sharp ones of tagged corners):
    // m = s - k proj_d(s), proj_d(s)_c = d_c (d.s) / (d.d), per component so that every
    // quotient is bounded by |s| whatever the edge length.
    const FxVec s = add(field[e.a], field[e.b]);  // exact, W+1 bits
    const i128 p_ex = dot_exact(d, s);
    const i128 q_ex = dot_exact(d, d);
    const int k = mode == NormalMode::Quadratic ? 2 : 4;
    FxVec m{};
    for (int c = 0; c < 3; ++c) {
      const std::int64_t t = div_trunc(i128{d[c]} * p_ex, q_ex, f, flags);
      m[c] = saturate(i128{s[c]} - i128{k} * t, f, flags);
    }
    if (mode == NormalMode::Reflect) {
      cp.n[e.mid] = m;  // n_ij itself: twice its Bernstein value
      continue;
    }
    const i128 mm_ex = dot_exact(m, m);
    const i128 norm = static_cast<i128>(isqrt(static_cast<u128>(mm_ex)));  // F fraction bits
    for (int c = 0; c < 3; ++c) cp.n[e.mid][c] = div_trunc(i128{m[c]} << F, norm, f, flags);
  }

  // b111 = E + (E - V)/2 = (3 sum(tangents) - 2 sum(corners)) / 12
  for (int c = 0; c < 3; ++c) {
    const i128 corners = i128{tri.p[0][c]} + tri.p[1][c] + tri.p[2][c];
    cp.b[net_index(1, 1, 3)][c] = mul_const(3 * sum_t[c] - 2 * corners, F, one_twelfth(f), f, flags);
  }
  return cp;
}

int cpg_digit_steps(const NumberFormat& f, int digit_bits) {
  if (digit_bits < 1) throw std::invalid_argument("CPG digit bits must be at least 1");
  return (f.coord_width() + digit_bits - 1) / digit_bits;
}

int cpg_edge_cycles(NormalMode mode, const NumberFormat& f, int digit_bits, bool product_reg) {
  const int D = cpg_digit_steps(f, digit_bits);
  // Geometry: d and s; the dot products d.Na, d.Nb, d.s, d.d; the two tangent points (6 steps).
  // Registered products (rtl/tess_cpg_edge.sv): a step of its own for d, every product used a
  // step after it is issued and a tangent point's division by 3 a step after its numerator, so
  // the tangent point near b leaves in step 7 and reaches b111's sum in step 8; the first
  // division starts in step 10 instead of 7 (d's step, the sum of d.d, the dividend's product).
  const int wait = product_reg ? 1 : 0;  // from a product's issue to its use
  const int first_division = product_reg ? 10 : 7;
  switch (mode) {
    // alpha w takes the step after w; with registered products the tangent point near b leaves
    // a step later (rtl/tess_cpg_edge.sv), without them the steps are reordered at no cost.
    case NormalMode::Linear: return product_reg ? 9 + (f.takes_alpha() ? 1 : 0) : 6;
    // + D-cycle division (3 slices), m = s - k t
    case NormalMode::Reflect: return first_division + D + 1;
    // + m.m (and its sum), D-cycle square root, D-cycle division (3 slices)
    case NormalMode::Quadratic: return first_division + D + 1 + 1 + wait + D + D;
    case NormalMode::Derivative: break;
  }
  throw std::invalid_argument("normal mode not implemented by the unit");
}

int cpg_tag_cycles(const TriangleFx& tri, const NumberFormat& f, const CpgVariant& v) {
  const int D = cpg_digit_steps(f, v.digit_bits);
  const int normalization = 2 + 2 * D;  // scale and add, dot product, square root, division
  // A tangent point: (1 - θ)(Pk - Pj), its third, the projection's dot product, d + Π m (one
  // multiplication a cycle, rtl/tess_cpg_tag.sv).
  constexpr int kFaceNormal = 2, kSide = 1, kTangent = 4;
  int corners = 0, slowest_corner = 0, any_tagged = 0;
  for (const TagsFx& t : tri.tags) {
    if (t.neutral()) continue;
    const int c = t.tagged() ? kSide + 3 * normalization : normalization;
    corners += c;
    slowest_corner = std::max(slowest_corner, c);
    any_tagged |= t.tagged();
  }
  if (corners == 0) return 0;
  int tangents = 0, slowest_edge = 0;
  for (int e = 0; e < 3; ++e) {
    const int ends = !tri.tags[e].neutral() + !tri.tags[(e + 1) % 3].neutral();
    tangents += kTangent * ends;
    slowest_edge = std::max(slowest_edge, kTangent * ends);
  }
  const bool in_turn = v.lanes == 1;
  return (any_tagged ? kFaceNormal : 0) + (in_turn ? corners + tangents : slowest_corner + slowest_edge);
}

int cpg_cycles(NormalMode mode, const NumberFormat& f, const CpgVariant& v) {
  if (v.lanes != 1 && v.lanes != 3) throw std::invalid_argument("CPG lanes must be 1 or 3");
  // the edges (in turn or at once), then one cycle for b111 (two with registered products) and
  // one for the write into the control-point buffer
  const int edges_in_turn = v.lanes == 1 ? 3 : 1;
  return edges_in_turn * cpg_edge_cycles(mode, f, v.digit_bits, v.product_reg != 0) + (v.product_reg ? 3 : 2);
}

Partitioning tri_partitioning(TriPattern pattern) {
  switch (pattern) {
    case TriPattern::fractional_odd: return Partitioning::fractional_odd;
    case TriPattern::fractional_even: return Partitioning::fractional_even;
    default: return Partitioning::integer;
  }
}

D3D11Setup tri_setup(const TriangleFx& tri) {
  return d3d11_setup(
      d3d11_factors_from_fixed({tri.factors[0], tri.factors[1], tri.factors[2]}, tri.factors[3], tri_partitioning(tri.pattern)));
}

std::string describe_pattern(const TriangleFx& tri) {
  if (tri.pattern == TriPattern::uniform) return "L=" + std::to_string(tri.L);
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s %.6g,%.6g,%.6g inner %.6g", partitioning_name(tri_partitioning(tri.pattern)),
                fixed16_to_double(tri.factors[0]), fixed16_to_double(tri.factors[1]), fixed16_to_double(tri.factors[2]),
                fixed16_to_double(tri.factors[3]));
  return buf;
}

std::uint32_t quantize_alpha(double alpha, int alpha_bits) {
  if (alpha_bits < 1 || alpha_bits > kMaxAlphaBits) throw std::invalid_argument("alpha bits outside 1..16");
  const double a = std::clamp(alpha, 0.0, 1.0);  // NaN -> 1: the reference's rule (model/silhouette.hpp)
  const double steps = std::floor(std::ldexp(std::isnan(alpha) ? 1.0 : a, alpha_bits) + 0.5);
  return static_cast<std::uint32_t>(steps) << (kAlphaFracBits - alpha_bits);
}

std::string tri_alpha_problem(const TriangleFx& tri, const NumberFormat& fmt) {
  if (alpha_in_contract(tri, fmt)) return {};
  const std::uint32_t low = (std::uint32_t{1} << (kAlphaFracBits - fmt.alpha_bits)) - 1;
  for (int e = 0; e < 3; ++e) {
    const std::uint32_t a = tri.alpha[static_cast<std::size_t>(e)];
    const char* reason = a > kAlphaOne ? "above 1" : (a & low) != 0 ? "not rounded to alpha_bits fraction bits" : nullptr;
    if (reason) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "alpha of edge %d 0x%x (16 fraction bits) %s", e, static_cast<unsigned>(a), reason);
      return buf;
    }
  }
  return {};
}

int patch_vertex_count(const TriangleFx& tri) {
  return tri.pattern == TriPattern::uniform ? pattern_vertex_count(tri.L) : tri_setup(tri).point_count;
}

std::string tri_pattern_problem(const TriangleFx& tri) {
  if (tri.pattern == TriPattern::uniform) {
    if (tri.L < 1 || tri.L > kMaxTessFactor)
      return "tessellation factor " + std::to_string(tri.L) + " outside 1.." + std::to_string(kMaxTessFactor);
    return {};
  }
  if (static_cast<int>(tri.pattern) > 3) return "pattern code " + std::to_string(static_cast<int>(tri.pattern));
  // The ranges of docs/patterns.md §1, in 16.16.
  const Fixed16 one = kFixed16One;
  Fixed16 lo = one, hi = 64 * one;
  if (tri.pattern == TriPattern::fractional_odd) hi = 63 * one;
  if (tri.pattern == TriPattern::fractional_even) lo = 2 * one;
  static constexpr const char* kNames[] = {"outer factor 0", "outer factor 1", "outer factor 2", "inner factor"};
  for (int i = 0; i < 4; ++i) {
    const Fixed16 f = tri.factors[static_cast<std::size_t>(i)];
    const char* reason = nullptr;
    if (f < lo || f > hi) reason = "outside the partitioning's range";
    else if (tri.pattern == TriPattern::integer && (f & 0xffff) != 0) reason = "not an integer (integer partitioning)";
    if (reason) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s 0x%x (16.16) %s", kNames[i], static_cast<unsigned>(f), reason);
      return buf;
    }
  }
  // fractional_odd: an inner factor of exactly 1 is the single triangle's alone. Beside a larger
  // outer factor it has no ring to cut (its edge has 2 points where the ring needs 4): the host
  // raises it to 1 + 2^-16 (d3d11_host_factors), and the unit's contract excludes it.
  if (tri.pattern == TriPattern::fractional_odd && tri.factors[3] == one &&
      (tri.factors[0] != one || tri.factors[1] != one || tri.factors[2] != one))
    return "inner factor 0x10000 (16.16) is 1 beside an outer factor above 1 (fractional_odd: the host sends 1 + 2^-16)";
  return {};
}

}  // namespace tessim::sim
