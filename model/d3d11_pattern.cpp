// The D3D11 triangle-domain pattern (docs/patterns.md). Every step is integer arithmetic on
// 16.16 values, in the order the D3D11 tessellator does it, so that points come out
// bit-identical; the few float operations are those the tessellator performs on its inputs.
#include "model/d3d11_pattern.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

namespace tessim {

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

bool is_odd_integer(float x) { return (static_cast<int>(x) & 1) != 0; }

// Highest set bit cleared (0 stays 0).
int without_msb(int x) { return x == 0 ? 0 : x & ~static_cast<int>(std::bit_floor(static_cast<unsigned>(x))); }

// How one factor spreads its points along a unit edge. Points are placed on each half of the
// edge from its end towards the middle and mirrored; a fractional factor blends the positions
// of floor(half) and ceil(half) segments per half, the extra point splitting one segment
// chosen so that splits appear in ruler-function order as the factor grows.
struct Subdivision {
  bool odd = false;
  Fixed16 half_fraction = 0;  // fractional part of the (parity-adjusted) half factor
  int half_points = 0;        // points on one half, the end included and the middle excluded
  int split_point = 0;        // the point that only exists on the ceil(half) subdivision
  Fixed16 inv_floor_segments = 0;
  Fixed16 inv_ceil_segments = 0;
  int points = 0;  // on the whole edge, both ends included
};

Subdivision make_subdivision(Fixed16 factor, bool odd) {
  Subdivision s;
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
  s.points = odd ? (fixed_ceil(kHalf + (factor + 1) / 2) * 2) >> 16 : ((fixed_ceil((factor + 1) / 2) * 2) >> 16) + 1;
  return s;
}

// Position of point `index` (0 .. points - 1) along the edge, 16.16 in [0, 1].
Fixed16 place(const Subdivision& s, int index) {
  bool mirrored = false;
  if (index >= s.half_points) {
    index = 2 * s.half_points - index - (s.odd ? 1 : 0);
    mirrored = true;
  }
  // The middle is exact; the blend below could miss 0.5 by a unit.
  if (index == s.half_points) return kHalf;
  const std::uint64_t on_ceil = static_cast<std::uint64_t>(index) * static_cast<std::uint32_t>(s.inv_ceil_segments);
  const int floor_index = index > s.split_point ? index - 1 : index;
  const std::uint64_t on_floor = static_cast<std::uint64_t>(floor_index) * static_cast<std::uint32_t>(s.inv_floor_segments);
  const std::uint64_t f = static_cast<std::uint32_t>(s.half_fraction);
  const std::uint64_t blend = on_floor * (kFixed16One - f) + on_ceil * f;
  const auto position = static_cast<Fixed16>((blend + kHalf) >> 16);
  return mirrored ? kFixed16One - position : position;
}

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

}  // namespace

const char* partitioning_name(Partitioning p) {
  switch (p) {
    case Partitioning::integer: return "integer";
    case Partitioning::pow2: return "pow2";
    case Partitioning::fractional_odd: return "fractional_odd";
    case Partitioning::fractional_even: return "fractional_even";
  }
  return "?";
}

std::optional<Partitioning> parse_partitioning(std::string_view name) {
  for (Partitioning p : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                         Partitioning::fractional_even})
    if (name == partitioning_name(p)) return p;
  return std::nullopt;
}

const char* winding_name(Winding w) { return w == Winding::ccw ? "ccw" : "cw"; }

std::optional<Winding> parse_winding(std::string_view name) {
  if (name == "ccw") return Winding::ccw;
  if (name == "cw") return Winding::cw;
  return std::nullopt;
}

Fixed16 float_to_fixed16(float x) {
  const double scaled = static_cast<double>(x) * 65536.0;  // exact: 24 significant bits
  const double whole = std::floor(scaled), rest = scaled - whole;
  auto result = static_cast<Fixed16>(whole);
  if (rest > 0.5 || (rest == 0.5 && (result & 1))) ++result;
  return result;
}

Fixed16 fixed16_reciprocal(int n) { return n <= 0 ? 0 : (kFixed16One + n / 2) / n; }

D3D11Factors d3d11_tri_factors(const std::array<float, 3>& outer_in, float inner_in, Partitioning partitioning) {
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

  for (int e = 0; e < 3; ++e) {
    f.outer_odd[e] = integer_like(partitioning) ? is_odd_integer(f.outer[e]) : odd_partitioning;
    f.outer_fixed[e] = float_to_fixed16(f.outer[e]);
  }
  // An integer inner factor of 1 counts as even: the rings end in a centre point.
  f.inner_odd = integer_like(partitioning) ? is_odd_integer(f.inner) && f.inner != 1.0f : odd_partitioning;
  f.inner_fixed = float_to_fixed16(f.inner);

  if (partitioning != Partitioning::fractional_even && f.inner_fixed == kFixed16One &&
      std::all_of(f.outer_fixed.begin(), f.outer_fixed.end(), [](Fixed16 x) { return x == kFixed16One; })) {
    f.single_triangle = true;
    f.outer_points = {2, 2, 2};
    f.inner_points = 0;
    return f;
  }
  for (int e = 0; e < 3; ++e) f.outer_points[e] = make_subdivision(f.outer_fixed[e], f.outer_odd[e]).points;
  // At least one ring inside the outer one, even when the inner factor is 1.
  f.inner_points = std::max(f.inner_odd ? 4 : 3, make_subdivision(f.inner_fixed, f.inner_odd).points);
  return f;
}

D3D11Pattern d3d11_tri_pattern(const std::array<float, 3>& outer, float inner, Partitioning partitioning,
                               Winding winding) {
  D3D11Pattern pattern;
  pattern.factors = d3d11_tri_factors(outer, inner, partitioning);
  const D3D11Factors& f = pattern.factors;
  if (f.culled) return pattern;
  auto& points = pattern.points;
  auto& indices = pattern.indices;

  if (f.single_triangle) {
    points = {{0, kFixed16One}, {0, 0}, {kFixed16One, 0}};  // the corners v = 1, w = 1, u = 1
    emit_triangle(indices, winding, 0, 1, 2);
    return pattern;
  }

  std::array<Subdivision, 3> outer_sub;
  for (int e = 0; e < 3; ++e) outer_sub[e] = make_subdivision(f.outer_fixed[e], f.outer_odd[e]);
  const Subdivision inner_sub = make_subdivision(f.inner_fixed, f.inner_odd);
  const int n_inner = f.inner_points;

  // Outer ring from corner v = 1: down edge u = 0 to w = 1, along v = 0 to u = 1, back along
  // w = 0. Each edge lists its points without its last corner, the next edge's first.
  for (int e = 0; e < 3; ++e) {
    const int last = outer_sub[e].points - 1;
    for (int p = 0; p < last; ++p) {
      const Fixed16 t = place(outer_sub[e], e == 1 ? p : last - p);
      if (e == 0) points.push_back({0, t});
      else if (e == 1) points.push_back({t, 0});
      else points.push_back({t, kFixed16One - t});
    }
  }
  const auto outer_ring_points = static_cast<std::uint32_t>(points.size());

  // Inner rings, same walk. Ring r reuses points r .. n_inner - 1 - r of the inner factor's
  // edge subdivision t: its edges lie at barycentric distance d = 2/3 t_r from the outer
  // edges and a point's coordinate along the edge is t - d/2, which puts the ring's corners at
  // (d, d, 1 - 2d) where consecutive edges meet.
  for (int r = 1; r < n_inner / 2; ++r) {
    const int last = n_inner - 1 - r;
    const std::uint64_t scaled = static_cast<std::uint64_t>(place(inner_sub, r)) * kTwoThirds;
    const auto perp = static_cast<Fixed16>((scaled + kHalf) >> 16);
    const Fixed16 shift = (perp + 1) / 2;
    for (int e = 0; e < 3; ++e) {
      for (int p = r; p < last; ++p) {
        const Fixed16 t = place(inner_sub, e == 1 ? p : last - (p - r)) - shift;
        if (e == 0) points.push_back({perp, t});
        else if (e == 1) points.push_back({t, perp});
        else points.push_back({t, kFixed16One - t - perp});
      }
    }
  }
  if (!f.inner_odd) points.push_back({kOneThird, kOneThird});

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

}  // namespace tessim
