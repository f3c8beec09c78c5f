// The D3D11 triangle-domain pattern in double arithmetic (docs/patterns.md). The tessellator
// computes in 16.16 fixed point; here every quantity is a double in natural units (1.0 is one),
// and the points where the tessellator's integer arithmetic drops bits are explicit roundings
// to the 2^-16 grid. Every value is a multiple of 2^-32 below 2^7, so a double holds it exactly
// and only those roundings round: the result is the tessellator's, bit for bit.
#include "model/d3d11_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace tessim {

namespace {

constexpr double kGrid = 65536.0;        // 16.16: steps of 1 / kGrid
constexpr double kStep = 1.0 / kGrid;    // the smallest positive 16.16 value
constexpr double kTwoThirds = 0xaaaa / kGrid;  // the definition's 2/3: truncated to the grid
constexpr double kOneThird = 0x5555 / kGrid;   // and 1/3

// The three roundings of the definition: a float factor to the grid (nearest, ties to even,
// the default rounding mode); a sum rounded by adding half a step and truncating; a truncation.
double to_grid_nearest_even(double x) { return std::nearbyint(x * kGrid) / kGrid; }
double to_grid_half_up(double x) { return std::floor(x * kGrid + 0.5) / kGrid; }
double to_grid_down(double x) { return std::floor(x * kGrid) / kGrid; }

Fixed16 as_fixed16(double x) { return static_cast<Fixed16>(x * kGrid); }  // x is on the grid

// 1/n on the grid, nearest (the definition's reciprocal table: 1/3 is 0x5555, 1/6 0x2aab).
double reciprocal(int n) { return n > 0 ? to_grid_half_up(1.0 / n) : 0.0; }

// x without its highest power of two (0 for 0): the ruler-order index of a split.
int without_highest_power_of_two(int x) {
  int power = 1;
  while (power * 2 <= x) power *= 2;
  return x >= 1 ? x - power : 0;
}

// The smallest power of two >= x (x >= 1).
float next_power_of_two(float x) {
  int exponent = 0;
  const float mantissa = std::frexp(x, &exponent);  // x = mantissa 2^exponent, mantissa in [0.5, 1)
  return mantissa == 0.5f ? x : std::ldexp(1.0f, exponent);
}

bool is_odd_integer(float x) { return std::fmod(x, 2.0f) == 1.0f; }

// One factor's points along a unit edge (docs/patterns.md §2): each half, from its end to the
// middle, blends the placements of floor(H) and ceil(H) segments by the fraction of H.
struct Subdivision {
  bool odd = false;
  double fraction = 0.0;     // of the half factor H
  int half_points = 0;       // ceil(H): a half's points, its end included, the middle not
  int split = 0;             // past this point the floor(H) placement has one point fewer
  double floor_step = 0.0;   // 1 / segments of floor(H), on the grid
  double ceil_step = 0.0;    // 1 / segments of ceil(H)
  int points = 0;            // the whole edge's, both ends included

  Subdivision(double factor, bool odd_parity) : odd(odd_parity) {
    double half = to_grid_down((factor + kStep) / 2);
    // An even factor of 1 is taken as odd: half a segment cannot be centred.
    if (odd || half == 0.5) half += 0.5;
    const double floor_half = std::floor(half), ceil_half = std::ceil(half);
    fraction = half - floor_half;
    half_points = static_cast<int>(ceil_half);
    const int whole = static_cast<int>(floor_half);
    if (floor_half == ceil_half) split = half_points + 1;  // no split
    else if (odd) split = whole == 1 ? 0 : 2 * without_highest_power_of_two(whole - 1) + 1;
    else split = 2 * without_highest_power_of_two(whole) + 1;
    const int odd_less = odd ? 1 : 0;
    floor_step = reciprocal(2 * whole - odd_less);
    ceil_step = reciprocal(2 * half_points - odd_less);
    points = 2 * half_points + (odd ? 0 : 1);
  }

  // Point i (0 .. points - 1) from the edge's start.
  double place(int i) const {
    const bool mirrored = i >= half_points;
    if (mirrored) i = 2 * half_points - i - (odd ? 1 : 0);
    if (i == half_points) return 0.5;  // the middle, exactly
    const int on_floor = i > split ? i - 1 : i;
    const double t = to_grid_half_up(on_floor * floor_step * (1.0 - fraction) + i * ceil_step * fraction);
    return mirrored ? 1.0 - t : t;
  }
};

struct Point {
  double u, v;
};

// The definition's "clockwise" triangle is ccw in the (u, v) plane; cw swaps two corners.
void add_triangle(std::vector<std::uint32_t>& out, Winding winding, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (winding == Winding::cw) std::swap(b, c);
  out.insert(out.end(), {a, b, c});
}

// Positions along a half edge in the order the stitcher of the first ring reaches them (the
// definition's table: 0, the middle, then by halves, quarters, eighths, ...).
constexpr int kRulerPositions[33] = {0,  32, 16, 8,  17, 4,  18, 9,  19, 2,  20, 10, 21, 5,  22, 11, 23,
                                     1,  24, 12, 25, 6,  26, 13, 27, 3,  28, 14, 29, 7,  30, 15, 31};

// Triangles between a row of a ring's edge (inside) and the enclosing ring's edge (outside),
// each row given as its points' indices from the edge's start to its end.
class Rows {
 public:
  Rows(std::vector<std::uint32_t>& out, Winding winding, const std::vector<std::uint32_t>& inside,
       const std::vector<std::uint32_t>& outside)
      : out_(out), winding_(winding), inside_(inside), outside_(outside) {}

  // Outer ring to ring 1: unrelated counts and parities.
  void transition(int inside_half, bool inside_odd, int outside_half, bool outside_odd) {
    if (inside_odd) --inside_half;
    if (outside_odd) --outside_half;
    if (kRulerPositions[0] < outside_half) step_outside();
    for (int k = 1; k < 33; ++k) {
      if (kRulerPositions[k] < inside_half) step_inside();
      if (kRulerPositions[k] < outside_half) step_outside();
    }
    if (inside_odd && outside_odd) {  // a quad across the middle
      triangle(in(0), out(0), in(1));
      triangle(in(1), out(0), out(1));
      ++i_;
      ++o_;
    } else if (outside_odd) {  // inside even: a triangle pointing inwards
      triangle(in(0), out(0), out(1));
      ++o_;
    } else if (inside_odd) {  // a triangle pointing outwards
      triangle(in(0), out(0), in(1));
      ++i_;
    }
    for (int k = 32; k >= 1; --k) {
      if (kRulerPositions[k] < outside_half) step_outside();
      if (kRulerPositions[k] < inside_half) step_inside();
    }
    if (kRulerPositions[0] < outside_half) step_outside();
  }

  // Ring r to ring r + 1 (outside two points longer): a corner triangle at each end, and
  // between them diagonals mirrored about the middle.
  void regular() {
    const int n = static_cast<int>(inside_.size());
    step_outside();
    int p = 0;
    for (; p < n / 2; ++p, ++i_, ++o_) {
      triangle(out(0), in(1), in(0));
      triangle(out(0), out(1), in(1));
    }
    for (; p < n - 1; ++p, ++i_, ++o_) {
      triangle(in(0), out(0), out(1));
      triangle(in(0), out(1), in(1));
    }
    step_outside();
  }

 private:
  void step_outside() {
    triangle(out(0), out(1), in(0));
    ++o_;
  }
  void step_inside() {
    triangle(in(0), out(0), in(1));
    ++i_;
  }
  std::uint32_t in(int ahead) const { return inside_[static_cast<std::size_t>(i_ + ahead)]; }
  std::uint32_t out(int ahead) const { return outside_[static_cast<std::size_t>(o_ + ahead)]; }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { add_triangle(out_, winding_, a, b, c); }

  std::vector<std::uint32_t>& out_;
  Winding winding_;
  const std::vector<std::uint32_t>& inside_;
  const std::vector<std::uint32_t>& outside_;
  int i_ = 0, o_ = 0;
};

// The three edge rows of a ring whose points start at `first` and whose edges have `counts`
// points each (both corners included): edge e starts where edge e - 1 ends, and edge 2 ends at
// the ring's first point. A ring of one point (an even pattern's centre) is that point thrice.
std::array<std::vector<std::uint32_t>, 3> ring_rows(std::uint32_t first, const std::array<int, 3>& counts) {
  const int size = counts[0] + counts[1] + counts[2] - 3;
  std::array<std::vector<std::uint32_t>, 3> rows;
  int start = 0;
  for (int e = 0; e < 3; ++e) {
    for (int j = 0; j < counts[e]; ++j)
      rows[e].push_back(first + static_cast<std::uint32_t>(size > 0 ? (start + j) % size : 0));
    start += counts[e] - 1;
  }
  return rows;
}

}  // namespace

D3D11Factors d3d11_tri_factors(const std::array<float, 3>& outer, float inner, Partitioning partitioning) {
  D3D11Factors f;
  if (!(outer[0] > 0.0f && outer[1] > 0.0f && outer[2] > 0.0f)) {  // NaN too
    f.culled = true;
    return f;
  }
  const bool integral = partitioning == Partitioning::integer || partitioning == Partitioning::pow2;
  const bool odd = partitioning == Partitioning::fractional_odd;
  const float lo = partitioning == Partitioning::fractional_even ? 2.0f : 1.0f;
  const float hi = odd ? 63.0f : 64.0f;
  // fmax/fmin return the number when the other operand is NaN: NaN clamps to the lower bound.
  auto clamp = [&](float x, float low) { return std::fmin(hi, std::fmax(low, x)); };
  auto round = [&](float x) {
    if (partitioning == Partitioning::pow2) x = next_power_of_two(x);
    return integral ? std::ceil(x) : x;
  };
  for (int e = 0; e < 3; ++e) f.outer[e] = round(clamp(outer[e], lo));
  // fractional_odd: a split outer edge (above 1 once on the grid) needs an inner ring to stitch
  // to, so the inner factor's lower bound becomes the grid's next value above 1.
  const float above_one = 1.0f + static_cast<float>(kStep / 2);
  const bool frame = odd && std::any_of(f.outer.begin(), f.outer.end(), [&](float x) { return x > above_one; });
  f.inner = round(clamp(inner, frame ? 1.0f + static_cast<float>(kStep) : lo));

  std::array<double, 3> outer_grid{};
  for (int e = 0; e < 3; ++e) {
    outer_grid[e] = to_grid_nearest_even(f.outer[e]);
    f.outer_fixed[e] = as_fixed16(outer_grid[e]);
    f.outer_odd[e] = integral ? is_odd_integer(f.outer[e]) : odd;
  }
  const double inner_grid = to_grid_nearest_even(f.inner);
  f.inner_fixed = as_fixed16(inner_grid);
  // An integer inner factor of 1 counts as even: the rings end in a centre point.
  f.inner_odd = integral ? is_odd_integer(f.inner) && f.inner != 1.0f : odd;

  if (partitioning != Partitioning::fractional_even && inner_grid == 1.0 &&
      std::all_of(outer_grid.begin(), outer_grid.end(), [](double x) { return x == 1.0; })) {
    f.single_triangle = true;
    f.outer_points = {2, 2, 2};
    return f;
  }
  for (int e = 0; e < 3; ++e) f.outer_points[e] = Subdivision(outer_grid[e], f.outer_odd[e]).points;
  // At least one ring inside the outer one, even when the inner factor is 1.
  f.inner_points = std::max(f.inner_odd ? 4 : 3, Subdivision(inner_grid, f.inner_odd).points);
  return f;
}

D3D11Pattern d3d11_tri_pattern(const std::array<float, 3>& outer, float inner, Partitioning partitioning,
                               Winding winding) {
  D3D11Pattern pattern;
  pattern.factors = d3d11_tri_factors(outer, inner, partitioning);
  const D3D11Factors& f = pattern.factors;
  if (f.culled) return pattern;
  std::vector<Point> points;
  std::vector<std::uint32_t>& triangles = pattern.indices;
  if (f.single_triangle) {  // the domain itself: corners v = 1, w = 1, u = 1
    points = {{0.0, 1.0}, {0.0, 0.0}, {1.0, 0.0}};
    add_triangle(triangles, winding, 0, 1, 2);
  } else {
    const std::array<Subdivision, 3> edges{Subdivision(f.outer_fixed[0] * kStep, f.outer_odd[0]),
                                           Subdivision(f.outer_fixed[1] * kStep, f.outer_odd[1]),
                                           Subdivision(f.outer_fixed[2] * kStep, f.outer_odd[2])};
    const Subdivision rings(f.inner_fixed * kStep, f.inner_odd);
    const int n = f.inner_points;

    // The outer ring from the corner v = 1: down u = 0 (v falling), along v = 0 (u rising),
    // back along w = 0; each edge without its last corner, which starts the next edge.
    for (int e = 0; e < 3; ++e) {
      const int last = edges[e].points - 1;
      for (int p = 0; p < last; ++p) {
        const double t = edges[e].place(e == 1 ? p : last - p);
        points.push_back(e == 0 ? Point{0.0, t} : e == 1 ? Point{t, 0.0} : Point{t, 1.0 - t});
      }
    }
    // Ring r uses the inner subdivision's points r .. n - 1 - r, its edges 2/3 t_r in from the
    // outer ones and its points shifted back by half that, so that its corners are (d, d).
    std::vector<std::uint32_t> ring_first{0};
    for (int r = 1; r < n / 2; ++r) {
      ring_first.push_back(static_cast<std::uint32_t>(points.size()));
      const double d = to_grid_half_up(rings.place(r) * kTwoThirds);
      const double shift = to_grid_down((d + kStep) / 2);
      const int last = n - 1 - r;
      for (int e = 0; e < 3; ++e)
        for (int p = r; p < last; ++p) {
          const double t = rings.place(e == 1 ? p : last - (p - r)) - shift;
          points.push_back(e == 0 ? Point{d, t} : e == 1 ? Point{t, d} : Point{t, 1.0 - t - d});
        }
    }
    if (!f.inner_odd) {  // the centre closes an even pattern
      ring_first.push_back(static_cast<std::uint32_t>(points.size()));
      points.push_back({kOneThird, kOneThird});
    }

    // Each ring to the next inwards, edge by edge: the first pair by the transition, the others
    // regularly; the innermost ring of an odd pattern is one triangle.
    std::array<int, 3> outside_counts = f.outer_points;
    auto outside = ring_rows(0, outside_counts);
    for (std::size_t r = 1; r < ring_first.size(); ++r) {
      const int count = n - 2 * static_cast<int>(r);
      const std::array<int, 3> inside_counts{count, count, count};
      const auto inside = ring_rows(ring_first[r], inside_counts);
      for (int e = 0; e < 3; ++e) {
        Rows rows(triangles, winding, inside[e], outside[e]);
        if (r == 1) rows.transition(rings.half_points, f.inner_odd, edges[e].half_points, f.outer_odd[e]);
        else rows.regular();
      }
      outside = inside;
    }
    if (f.inner_odd) {
      const std::uint32_t c = ring_first.back();
      add_triangle(triangles, winding, c, c + 1, c + 2);
    }
  }
  pattern.points.reserve(points.size());
  for (const Point& q : points) pattern.points.push_back({as_fixed16(q.u), as_fixed16(q.v)});
  return pattern;
}

}  // namespace tessim
