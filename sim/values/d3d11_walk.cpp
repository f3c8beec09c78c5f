// The unit's D3D11 triangle-domain pattern (docs/patterns.md). Every step is integer arithmetic
// on 16.16 values, in the order the D3D11 tessellator does it, so that points come out
// bit-identical; the few float operations are those the tessellator performs on its inputs.
#include "sim/values/d3d11_walk.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

namespace tessim::sim {

namespace {

constexpr Fixed16 kHalf = 0x8000;
constexpr Fixed16 kTwoThirds = 0xaaaa;
constexpr Fixed16 kOneThird = 0x5555;
constexpr Fixed16 kIntegerMask = 0x7fff0000;
constexpr Fixed16 kFractionMask = 0x0000ffff;

constexpr float kMinOdd = 1.0f, kMaxOdd = 63.0f, kMinEven = 2.0f, kMaxEven = 64.0f;
constexpr float kFixedEpsilon = 1.0f / 65536.0f;  // the smallest positive 16.16 fraction

Fixed16 fixed_floor(Fixed16 x) { return x & kIntegerMask; }
Fixed16 fixed_ceil(Fixed16 x) { return (x & kFractionMask) ? fixed_floor(x) + kFixed16One : x; }

bool integer_like(Partitioning p) { return p == Partitioning::integer || p == Partitioning::pow2; }

// Clamp that maps NaN to the lower bound, as the tessellator's IEEE 754R min/max do.
float clamp_factor(float x, float lo, float hi) {
  if (std::isnan(x)) return lo;
  return std::min(hi, std::max(lo, x));
}

// The next power of two >= x (x >= 1): drop the mantissa and step the exponent.
float round_up_pow2(float x) {
  const auto bits = std::bit_cast<std::uint32_t>(x);
  if ((bits & 0x007fffffu) == 0) return x;
  return std::bit_cast<float>((bits & 0x7f800000u) + 0x00800000u);
}

// Highest set bit cleared (0 stays 0).
int without_msb(int x) { return x == 0 ? 0 : x & ~static_cast<int>(std::bit_floor(static_cast<unsigned>(x))); }

// Order in which the stitcher of the first ring visits positions on a half edge: 0, the
// middle (32), then 16, 8, 17, 4, 18, ...: entry k > 1 with k - 1 = 2^t (2j + 1) is 16/2^t + j.
// A position exists on a half edge of h points when it is < h.
constexpr std::array<int, 33> make_ruler_order() {
  std::array<int, 33> order{};
  order[0] = 0;
  order[1] = 32;
  for (int k = 2; k <= 32; ++k) {
    int x = k - 1, t = 0;
    while (x % 2 == 0) {
      x /= 2;
      ++t;
    }
    order[k] = (16 >> t) + (x - 1) / 2;
  }
  return order;
}
constexpr std::array<int, 33> kRulerOrder = make_ruler_order();

// Triangles are generated with positive area in the (u, v) plane; cw swaps the last two corners.
void emit_triangle(std::vector<std::uint32_t>& indices, Winding winding, std::uint32_t a, std::uint32_t b,
                   std::uint32_t c) {
  indices.push_back(a);
  indices.push_back(winding == Winding::ccw ? b : c);
  indices.push_back(winding == Winding::ccw ? c : b);
}

// Emits triangles between two rows of points: the inside row (a ring edge) and the outside
// row (the enclosing ring's edge). Callers map the row positions to point indices, which lets
// the third edge of a ring close onto its first point.
class Stitcher {
 public:
  template <class InsideFn, class OutsideFn>
  Stitcher(std::vector<std::uint32_t>& indices, Winding winding, InsideFn inside, OutsideFn outside)
      : indices_(indices), winding_(winding), inside_(inside), outside_(outside) {}

  // The first ring: outer edge and inner ring edge have unrelated factors and parities.
  void transition(int inside_half_points, bool inside_odd, int outside_half_points, bool outside_odd) {
    if (inside_odd) inside_half_points -= 1;
    if (outside_odd) outside_half_points -= 1;
    if (kRulerOrder[0] < outside_half_points) advance_outside();
    for (int k = 1; k <= 32; ++k) {
      if (kRulerOrder[k] < inside_half_points) advance_inside();
      if (kRulerOrder[k] < outside_half_points) advance_outside();
    }
    if (inside_odd != outside_odd || inside_odd) {
      if (inside_odd == outside_odd) {  // both odd: a quad across the middle
        tri(in(i_), out(o_), in(i_ + 1));
        tri(in(i_ + 1), out(o_), out(o_ + 1));
        ++i_;
        ++o_;
      } else if (!inside_odd) {  // a triangle pointing inwards
        tri(in(i_), out(o_), out(o_ + 1));
        ++o_;
      } else {  // a triangle pointing outwards
        tri(in(i_), out(o_), in(i_ + 1));
        ++i_;
      }
    }
    for (int k = 32; k >= 1; --k) {
      if (kRulerOrder[k] < outside_half_points) advance_outside();
      if (kRulerOrder[k] < inside_half_points) advance_inside();
    }
    if (kRulerOrder[0] < outside_half_points) advance_outside();
  }

  // Inner rings: the outside row has two points more than the inside row; diagonals mirror
  // about the edge's middle.
  void regular(int inside_points) {
    tri(out(o_), out(o_ + 1), in(i_));
    ++o_;
    int p = 0;
    for (; p < inside_points / 2; ++p, ++i_, ++o_) {
      tri(out(o_), in(i_ + 1), in(i_));
      tri(out(o_), out(o_ + 1), in(i_ + 1));
    }
    for (; p < inside_points - 1; ++p, ++i_, ++o_) {
      tri(in(i_), out(o_), out(o_ + 1));
      tri(in(i_), out(o_ + 1), in(i_ + 1));
    }
    tri(out(o_), out(o_ + 1), in(i_));
  }

 private:
  void advance_outside() {
    tri(out(o_), out(o_ + 1), in(i_));
    ++o_;
  }
  void advance_inside() {
    tri(in(i_), out(o_), in(i_ + 1));
    ++i_;
  }
  std::uint32_t in(int k) const { return inside_(k); }
  std::uint32_t out(int k) const { return outside_(k); }
  void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) { emit_triangle(indices_, winding_, a, b, c); }

  std::vector<std::uint32_t>& indices_;
  Winding winding_;
  std::function<std::uint32_t(int)> inside_, outside_;
  int i_ = 0, o_ = 0;
};

// The fields d3d11_factors_from_fixed() derives, into factors whose floats stay those given.
void processed_into(D3D11Factors& f, const D3D11Factors& processed) {
  f.single_triangle = processed.single_triangle;
  f.outer_odd = processed.outer_odd;
  f.inner_odd = processed.inner_odd;
  f.inner_fixed = processed.inner_fixed;
  f.outer_points = processed.outer_points;
  f.inner_points = processed.inner_points;
}

}  // namespace

D3D11Edge d3d11_edge(Fixed16 factor, bool odd) {
  D3D11Edge s;
  s.odd = odd;
  Fixed16 half = (factor + 1) / 2;
  // An even factor of 1 is handled as an odd one: half a segment cannot be centred.
  if (odd || half == kHalf) half += kHalf;
  const Fixed16 floor_half = fixed_floor(half), ceil_half = fixed_ceil(half);
  s.half_fraction = half - floor_half;
  s.half_points = ceil_half >> 16;
  const int floor_half_int = floor_half >> 16;
  if (ceil_half == floor_half)
    s.split_point = s.half_points + 1;  // no split: never reached
  else if (odd)
    s.split_point = floor_half == kFixed16One ? 0 : (without_msb(floor_half_int - 1) << 1) + 1;
  else
    s.split_point = (without_msb(floor_half_int) << 1) + 1;
  int floor_segments = (floor_half * 2) >> 16, ceil_segments = (ceil_half * 2) >> 16;
  if (odd) {
    floor_segments -= 1;
    ceil_segments -= 1;
  }
  s.inv_floor_segments = fixed16_reciprocal(floor_segments);
  s.inv_ceil_segments = fixed16_reciprocal(ceil_segments);
  const auto phi = static_cast<std::uint64_t>(s.half_fraction);
  s.floor_weight = static_cast<std::uint64_t>(s.inv_floor_segments) * (kFixed16One - phi);
  s.ceil_weight = static_cast<std::uint64_t>(s.inv_ceil_segments) * phi;
  s.points = odd ? (fixed_ceil(kHalf + (factor + 1) / 2) * 2) >> 16 : ((fixed_ceil((factor + 1) / 2) * 2) >> 16) + 1;
  return s;
}

Fixed16 d3d11_place(const D3D11Edge& s, int index) {
  bool mirrored = false;
  if (index >= s.half_points) {
    index = 2 * s.half_points - index - (s.odd ? 1 : 0);
    mirrored = true;
  }
  // The middle is exact; the blend below could miss 0.5 by a unit.
  if (index == s.half_points) return kHalf;
  // i' R(n_floor)(1 - φ) + i R(n_ceil) φ, rounded: the blend of the two placements i' / n_floor
  // and i / n_ceil, grouped so that the products of the factor alone are made once per edge.
  const int floor_index = index > s.split_point ? index - 1 : index;
  const std::uint64_t blend = static_cast<std::uint64_t>(floor_index) * s.floor_weight +
                              static_cast<std::uint64_t>(index) * s.ceil_weight;
  const auto position = static_cast<Fixed16>((blend + kHalf) >> 16);
  return mirrored ? kFixed16One - position : position;
}

D3D11Setup d3d11_setup(const D3D11Factors& f) {
  D3D11Setup s;
  s.factors = f;
  if (f.culled) return s;
  for (int e = 0; e < 3; ++e) {
    s.outer[static_cast<std::size_t>(e)] = d3d11_edge(f.outer_fixed[static_cast<std::size_t>(e)], f.outer_odd[static_cast<std::size_t>(e)]);
    s.point_count += f.outer_points[static_cast<std::size_t>(e)] - 1;
  }
  if (f.single_triangle) return s;
  s.inner = d3d11_edge(f.inner_fixed, f.inner_odd);
  const int n = f.inner_points;
  for (int r = 1; r < n / 2; ++r) s.point_count += 3 * (n - 1 - 2 * r);
  if (!f.inner_odd) s.point_count += 1;  // the centre
  return s;
}

void D3D11PointWalker::start(const D3D11Setup& setup) {
  ring_ = edge_ = p_ = index_ = 0;
  last_ = setup.point_count == 1;
}

void D3D11PointWalker::enter_ring(const D3D11Setup& setup, int ring) {
  ring_ = ring;
  edge_ = 0;
  p_ = ring;
  ring_last_ = setup.factors.inner_points - 1 - ring;
  // The ring's edges lie at barycentric distance 2/3 t_r from the outer ones; a point's
  // coordinate along the edge is t - (d + 2^-16) / 2, putting the corners at (d, d, 1 - 2d).
  const std::uint64_t scaled = static_cast<std::uint64_t>(d3d11_place(setup.inner, ring)) * kTwoThirds;
  perp_ = static_cast<Fixed16>((scaled + kHalf) >> 16);
  shift_ = (perp_ + 1) / 2;
}

FixedUV D3D11PointWalker::point(const D3D11Setup& setup) const {
  if (edge_ == 3) return {kOneThird, kOneThird};
  if (ring_ == 0) {
    const D3D11Edge& edge = setup.outer[static_cast<std::size_t>(edge_)];
    const int last = edge.points - 1;
    const Fixed16 t = d3d11_place(edge, edge_ == 1 ? p_ : last - p_);
    if (edge_ == 0) return {0, t};
    if (edge_ == 1) return {t, 0};
    return {t, kFixed16One - t};
  }
  const Fixed16 t = d3d11_place(setup.inner, edge_ == 1 ? p_ : ring_last_ - (p_ - ring_)) - shift_;
  if (edge_ == 0) return {perp_, t};
  if (edge_ == 1) return {t, perp_};
  return {t, kFixed16One - t - perp_};
}

void D3D11PointWalker::next(const D3D11Setup& setup) {
  ++index_;
  ++p_;
  last_ = index_ == setup.point_count - 1;
  const int edge_end = ring_ == 0 ? setup.outer[static_cast<std::size_t>(edge_)].points - 1 : ring_last_;
  if (edge_ == 3 || p_ < edge_end) return;
  p_ = ring_;
  if (++edge_ < 3) return;
  // Ring done: the next ring inwards, or the centre of an even pattern (a ring of its own).
  if (ring_ + 1 < setup.factors.inner_points / 2) enter_ring(setup, ring_ + 1);
  else ++ring_;
}

Fixed16 float_to_fixed16(float x) {
  const double scaled = static_cast<double>(x) * 65536.0;  // exact: 24 significant bits
  const double whole = std::floor(scaled), rest = scaled - whole;
  auto result = static_cast<Fixed16>(whole);
  if (rest > 0.5 || (rest == 0.5 && (result & 1))) ++result;
  return result;
}

Fixed16 fixed16_reciprocal(int n) { return n <= 0 ? 0 : (kFixed16One + n / 2) / n; }

D3D11Factors d3d11_host_factors(const std::array<float, 3>& outer_in, float inner_in, Partitioning partitioning) {
  D3D11Factors f;
  if (!(outer_in[0] > 0.0f) || !(outer_in[1] > 0.0f) || !(outer_in[2] > 0.0f)) {
    f.culled = true;
    return f;
  }
  const bool odd_partitioning = partitioning == Partitioning::fractional_odd;
  float lo = kMinOdd, hi = kMaxEven;
  if (partitioning == Partitioning::fractional_even) lo = kMinEven;
  if (odd_partitioning) hi = kMaxOdd;

  auto round_integer = [&](float x) {
    if (partitioning == Partitioning::pow2) x = round_up_pow2(x);
    return std::ceil(x);
  };
  for (int e = 0; e < 3; ++e) {
    f.outer[e] = clamp_factor(outer_in[e], lo, hi);
    if (integer_like(partitioning)) f.outer[e] = round_integer(f.outer[e]);
  }
  // fractional_odd: once an outer edge is subdivided, the inner ring must leave the boundary
  // ("picture frame"), so the inner factor is kept just above 1.
  float inner_lo = lo;
  if (odd_partitioning &&
      std::any_of(f.outer.begin(), f.outer.end(), [](float x) { return x > kMinOdd + kFixedEpsilon / 2; }))
    inner_lo = kMinOdd + kFixedEpsilon;
  f.inner = clamp_factor(inner_in, inner_lo, hi);
  if (integer_like(partitioning)) f.inner = round_integer(f.inner);

  for (int e = 0; e < 3; ++e) f.outer_fixed[e] = float_to_fixed16(f.outer[e]);
  const D3D11Factors processed = d3d11_factors_from_fixed(
      f.outer_fixed, float_to_fixed16(f.inner), partitioning == Partitioning::pow2 ? Partitioning::integer : partitioning);
  processed_into(f, processed);
  return f;
}

D3D11Factors d3d11_factors_from_fixed(const std::array<Fixed16, 3>& outer_fixed, Fixed16 inner_fixed,
                                      Partitioning partitioning) {
  D3D11Factors f;
  const bool odd_partitioning = partitioning == Partitioning::fractional_odd;
  f.outer_fixed = outer_fixed;
  f.inner_fixed = inner_fixed;
  for (int e = 0; e < 3; ++e) {
    f.outer[e] = static_cast<float>(fixed16_to_double(outer_fixed[e]));
    f.outer_odd[e] = integer_like(partitioning) ? ((outer_fixed[e] >> 16) & 1) != 0 : odd_partitioning;
  }
  f.inner = static_cast<float>(fixed16_to_double(inner_fixed));
  // An integer inner factor of 1 counts as even: the rings end in a centre point.
  f.inner_odd = integer_like(partitioning) ? ((inner_fixed >> 16) & 1) != 0 && inner_fixed != kFixed16One
                                           : odd_partitioning;

  if (partitioning != Partitioning::fractional_even && f.inner_fixed == kFixed16One &&
      std::all_of(f.outer_fixed.begin(), f.outer_fixed.end(), [](Fixed16 x) { return x == kFixed16One; })) {
    f.single_triangle = true;
    f.outer_points = {2, 2, 2};
    f.inner_points = 0;
    return f;
  }
  for (int e = 0; e < 3; ++e) f.outer_points[e] = d3d11_edge(f.outer_fixed[e], f.outer_odd[e]).points;
  // At least one ring inside the outer one, even when the inner factor is 1.
  f.inner_points = std::max(f.inner_odd ? 4 : 3, d3d11_edge(f.inner_fixed, f.inner_odd).points);
  return f;
}

D3D11Pattern d3d11_walk_pattern(const std::array<float, 3>& outer, float inner, Partitioning partitioning,
                                Winding winding) {
  return d3d11_pattern(d3d11_setup(d3d11_host_factors(outer, inner, partitioning)), winding);
}

D3D11Pattern d3d11_pattern(const D3D11Setup& setup, Winding winding) {
  D3D11Pattern pattern;
  pattern.factors = setup.factors;
  const D3D11Factors& f = pattern.factors;
  if (f.culled) return pattern;
  auto& points = pattern.points;
  auto& indices = pattern.indices;

  points.reserve(static_cast<std::size_t>(setup.point_count));
  for (D3D11PointWalker walk(setup);; walk.next(setup)) {
    points.push_back(walk.point(setup));
    if (walk.last()) break;
  }
  if (f.single_triangle) {  // the corners v = 1, w = 1, u = 1
    emit_triangle(indices, winding, 0, 1, 2);
    return pattern;
  }
  const std::array<D3D11Edge, 3>& outer_sub = setup.outer;
  const D3D11Edge& inner_sub = setup.inner;
  const int n_inner = f.inner_points;
  const auto outer_ring_points =
      static_cast<std::uint32_t>(f.outer_points[0] + f.outer_points[1] + f.outer_points[2] - 3);

  // Triangles, ring by ring from the outside, one edge at a time.
  std::array<int, 3> outside_points = f.outer_points;
  std::uint32_t outside_base = 0, inside_base = outer_ring_points;
  const int rings = (n_inner + 1) / 2;  // an even pattern's last "ring" is the centre point
  for (int r = 1; r < rings; ++r) {
    const int inside_points = n_inner - 2 * r;
    const std::uint32_t ring_outside_start = outside_base, ring_inside_start = inside_base;
    for (int e = 0; e < 3; ++e) {
      const bool closes_ring = e == 2;
      const int outside_count = outside_points[e];
      auto inside = [=](int k) {
        return closes_ring && k == inside_points - 1 ? ring_inside_start : inside_base + static_cast<std::uint32_t>(k);
      };
      auto outside = [=](int k) {
        return closes_ring && k == outside_count - 1 ? ring_outside_start : outside_base + static_cast<std::uint32_t>(k);
      };
      Stitcher stitch(indices, winding, inside, outside);
      if (r == 1)
        stitch.transition(inner_sub.half_points, f.inner_odd, outer_sub[e].half_points, f.outer_odd[e]);
      else
        stitch.regular(inside_points);
      outside_base += static_cast<std::uint32_t>(outside_count - 1);
      inside_base += static_cast<std::uint32_t>(inside_points - 1);
      outside_points[e] = inside_points;
    }
  }
  if (f.inner_odd) {  // the innermost ring is a single triangle
    emit_triangle(indices, winding, outside_base, outside_base + 1, outside_base + 2);
  }
  return pattern;
}

}  // namespace tessim::sim
