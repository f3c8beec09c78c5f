// The properties every implementation of the D3D11 triangle-domain pattern has (docs/patterns.md):
// factor processing, counts, exact 16.16 positions of the tessellator, orientation, tiling and
// crack-free edges. A parameterised suite: tests/model/d3d11_pattern_test.cpp runs it on the
// float reference, tests/sim/d3d11_walk_test.cpp on the unit's integer walk.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "model/d3d11_types.hpp"

namespace tessim::d3d11_checks {

inline constexpr std::int64_t kOne = kFixed16One;
inline constexpr std::int64_t kTwiceDomainArea = kOne * kOne;  // 2 x 1/2, in 16.16 squared
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();


// Twice the signed area of triangle t in the (u, v) plane, exact.
inline std::int64_t twice_area(const D3D11Pattern& p, std::size_t t) {
  const FixedUV a = p.points[p.indices[3 * t]], b = p.points[p.indices[3 * t + 1]], c = p.points[p.indices[3 * t + 2]];
  return (std::int64_t{b.u} - a.u) * (std::int64_t{c.v} - a.v) - (std::int64_t{b.v} - a.v) * (std::int64_t{c.u} - a.u);
}

inline bool on_edge(const FixedUV& q, int edge) {
  if (edge == 0) return q.u == 0;
  if (edge == 1) return q.v == 0;
  return std::int64_t{q.u} + q.v == kOne;
}

// Parameter along edge `edge` in a direction shared by all three edges (v on u = 0, u on v = 0
// and on w = 0): equal factors must give equal sets.
inline Fixed16 edge_parameter(const FixedUV& q, int edge) { return edge == 0 ? q.v : q.u; }

inline std::vector<Fixed16> edge_parameters(const D3D11Pattern& p, int edge) {
  std::vector<Fixed16> params;
  for (const FixedUV& q : p.points)
    if (on_edge(q, edge)) params.push_back(edge_parameter(q, edge));
  std::sort(params.begin(), params.end());
  return params;
}

struct Shape {
  bool strict = true;  // no coincident points, no zero-area triangles
};

// Everything a valid pattern satisfies: points in the domain, all used; triangles all of one
// orientation summing to exactly the domain's area; every edge shared by two triangles in
// opposite directions except boundary edges, which are exactly the consecutive pairs of the
// points on the three domain edges, whose counts are the outer factors' point counts.
inline void expect_valid(const D3D11Pattern& p, Winding winding, Shape shape = {}) {
  ASSERT_FALSE(p.factors.culled);
  ASSERT_EQ(p.indices.size() % 3, 0u);
  const std::size_t n = p.points.size();
  for (const FixedUV& q : p.points) {
    EXPECT_GE(q.u, 0);
    EXPECT_GE(q.v, 0);
    EXPECT_LE(std::int64_t{q.u} + q.v, kOne);
  }
  std::vector<int> uses(n, 0);
  for (std::uint32_t i : p.indices) {
    ASSERT_LT(i, n);
    ++uses[i];
  }
  for (std::size_t i = 0; i < n; ++i) EXPECT_GT(uses[i], 0) << "point " << i << " unused";

  const int sign = winding == Winding::ccw ? 1 : -1;
  std::int64_t total = 0;
  for (std::size_t t = 0; t < p.triangle_count(); ++t) {
    const std::int64_t a = sign * twice_area(p, t);
    total += a;
    if (shape.strict)
      EXPECT_GT(a, 0) << "triangle " << t;
    else
      EXPECT_GE(a, 0) << "triangle " << t;
  }
  EXPECT_EQ(total, kTwiceDomainArea);

  if (shape.strict) {
    std::set<std::pair<Fixed16, Fixed16>> distinct;
    for (const FixedUV& q : p.points) distinct.insert({q.u, q.v});
    EXPECT_EQ(distinct.size(), n) << "coincident points";
  }

  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < p.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) ++directed[{p.indices[3 * t + c], p.indices[3 * t + (c + 1) % 3]}];
  std::array<std::vector<std::pair<Fixed16, Fixed16>>, 3> boundary;  // parameter pairs per edge
  std::size_t boundary_edges = 0;
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " repeated";
    if (directed.count({edge.second, edge.first})) continue;
    ++boundary_edges;
    const FixedUV a = p.points[edge.first], b = p.points[edge.second];
    int found = -1;
    for (int e = 0; e < 3; ++e)
      if (on_edge(a, e) && on_edge(b, e)) found = e;
    if (found < 0) {
      ADD_FAILURE() << "open edge " << edge.first << "-" << edge.second << " inside the domain";
      continue;
    }
    boundary[static_cast<std::size_t>(found)].push_back(std::minmax(edge_parameter(a, found), edge_parameter(b, found)));
  }
  for (int e = 0; e < 3; ++e) {
    std::vector<Fixed16> params = edge_parameters(p, e);
    if (!shape.strict) {
      // Points that coincide (an inner ring still on the boundary, a split too small for
      // 16.16) count once, and the zero-length boundary edges between them not at all.
      params.erase(std::unique(params.begin(), params.end()), params.end());
      std::erase_if(boundary[e], [](const auto& ab) { return ab.first == ab.second; });
      EXPECT_LE(static_cast<int>(params.size()), p.factors.outer_points[e]) << "edge " << e;
    } else {
      EXPECT_EQ(static_cast<int>(params.size()), p.factors.outer_points[e]) << "edge " << e;
    }
    std::vector<std::pair<Fixed16, Fixed16>> consecutive;
    for (std::size_t i = 0; i + 1 < params.size(); ++i) consecutive.emplace_back(params[i], params[i + 1]);
    std::sort(boundary[e].begin(), boundary[e].end());
    boundary[e].erase(std::unique(boundary[e].begin(), boundary[e].end()), boundary[e].end());
    EXPECT_EQ(boundary[e], consecutive) << "edge " << e << " not covered by its own subdivision";
  }
  // A triangulated disc: V - E + F = 1.
  const std::size_t edges = (3 * p.triangle_count() + boundary_edges) / 2;
  EXPECT_EQ(static_cast<std::int64_t>(n) - static_cast<std::int64_t>(edges) + static_cast<std::int64_t>(p.triangle_count()), 1);
}

// One implementation of the pattern: the float reference or the unit's integer walk.
struct D3D11Implementation {
  const char* name;
  D3D11Pattern (*pattern)(const std::array<float, 3>& outer, float inner, Partitioning partitioning, Winding winding);
};

inline std::string implementation_name(const ::testing::TestParamInfo<D3D11Implementation>& info) {
  return info.param.name;
}

class D3D11PatternProperties : public ::testing::TestWithParam<D3D11Implementation> {
 protected:
  D3D11Pattern make(float e0, float e1, float e2, float inner, Partitioning p, Winding w = Winding::ccw) const {
    return GetParam().pattern({e0, e1, e2}, inner, p, w);
  }
};

// All factors L, integer spacing: rings of 3(L - 2r) points, triangles 3(2n - 2) between
// rings of n and n - 2 segments per edge, plus the centre point (L even) or triangle (L odd).
inline std::size_t expected_points(int L) {
  const std::size_t m = static_cast<std::size_t>(L / 2);
  return L % 2 == 0 ? 3 * m * m + 3 * m + 1 : 3 * (m + 1) * (m + 1);
}
inline std::size_t expected_triangles(int L) {
  const auto l = static_cast<std::size_t>(L);
  return L % 2 == 0 ? 3 * l * l / 2 : (3 * l * l - 1) / 2;
}


TEST_P(D3D11PatternProperties, AllFactorsEqualIntegerCounts) {
  for (Partitioning part : {Partitioning::integer, Partitioning::fractional_odd, Partitioning::fractional_even}) {
    for (int L = 1; L <= 64; ++L) {
      if (part == Partitioning::fractional_odd && L % 2 == 0) continue;  // rounds up to odd
      if (part == Partitioning::fractional_even && L % 2 == 1) continue;
      if (part == Partitioning::fractional_odd && L == 64) continue;
      SCOPED_TRACE(::testing::Message() << partitioning_name(part) << " L=" << L);
      const float f = static_cast<float>(L);
      const D3D11Pattern p = make(f, f, f, f, part);
      EXPECT_EQ(p.points.size(), expected_points(L));
      EXPECT_EQ(p.triangle_count(), expected_triangles(L));
      expect_valid(p, Winding::ccw);
    }
  }
  EXPECT_EQ(expected_points(64), 3169u);
  EXPECT_EQ(expected_triangles(64), 6144u);
  EXPECT_EQ(expected_points(3), 12u);
  EXPECT_EQ(expected_triangles(3), 13u);
}

TEST_P(D3D11PatternProperties, FractionalAtAnIntegerOfItsParityIsTheIntegerPattern) {
  for (int L : {2, 3, 4, 7, 16, 33, 63}) {
    const Partitioning frac = L % 2 ? Partitioning::fractional_odd : Partitioning::fractional_even;
    const float f = static_cast<float>(L);
    const D3D11Pattern a = make(f, f, f, f, Partitioning::integer), b = make(f, f, f, f, frac);
    ASSERT_EQ(a.points.size(), b.points.size()) << L;
    for (std::size_t i = 0; i < a.points.size(); ++i) {
      EXPECT_EQ(a.points[i].u, b.points[i].u) << L << " point " << i;
      EXPECT_EQ(a.points[i].v, b.points[i].v) << L << " point " << i;
    }
    EXPECT_EQ(a.indices, b.indices) << L;
  }
}

TEST_P(D3D11PatternProperties, IntegerEdgePointsAreRoundedMultiplesOfTheReciprocalFromBothEnds) {
  for (int L = 1; L <= 64; ++L) {
    const D3D11Pattern p = make(static_cast<float>(L), 5, 6, 4, Partitioning::integer);
    const Fixed16 reciprocal = (kFixed16One + L / 2) / L;  // round(2^16 / L)
    std::vector<Fixed16> want;
    for (int k = 0; k <= L; ++k) {
      if (2 * k == L) want.push_back(0x8000);
      else if (2 * k < L) want.push_back(k * reciprocal);
      else want.push_back(kFixed16One - (L - k) * reciprocal);
    }
    EXPECT_EQ(edge_parameters(p, 0), want) << L;
  }
}

TEST_P(D3D11PatternProperties, OneThirdIsFixed0x5555) {
  const D3D11Pattern p = make(3, 3, 3, 3, Partitioning::integer);
  // Outer ring from v = 1 down the edge u = 0: 1 - 1/3 is formed as 1 - 0x5555.
  ASSERT_GE(p.points.size(), 3u);
  EXPECT_EQ(p.points[0].v, 0x10000);
  EXPECT_EQ(p.points[1].v, 0xaaab);
  EXPECT_EQ(p.points[2].v, 0x5555);
  // The inner triangle's distance from each edge is 2/3 of 0x5555, rounded: 0x38e3 (2/9).
  for (std::size_t i = 9; i < 12; ++i) {
    const FixedUV q = p.points[i];
    const Fixed16 w = kFixed16One - q.u - q.v;
    EXPECT_EQ(std::min({q.u, q.v, w}), 0x38e3) << i;
  }
  // L = 64: the innermost ring (r = 31) sits at (31 * 0x400 * 0xaaaa + 0x8000) >> 16 = 0x52aa
  // from each edge (0xaaab for 2/3 would give 0x52ab).
  const D3D11Pattern big = make(64, 64, 64, 64, Partitioning::integer);
  Fixed16 innermost = 0;
  for (std::size_t i = 0; i + 1 < big.points.size(); ++i) {  // all but the centre
    const FixedUV q = big.points[i];
    innermost = std::max(innermost, std::min({q.u, q.v, kFixed16One - q.u - q.v}));
  }
  EXPECT_EQ(innermost, 0x52aa);
  // An even pattern ends in the centre (0x5555, 0x5555).
  const D3D11Pattern even = make(4, 4, 4, 4, Partitioning::integer);
  EXPECT_EQ(even.points.back().u, 0x5555);
  EXPECT_EQ(even.points.back().v, 0x5555);
}

TEST_P(D3D11PatternProperties, DifferentFactorOnEachEdge) {
  for (Partitioning part : {Partitioning::integer, Partitioning::pow2}) {
    for (auto [e0, e1, e2, in] : std::vector<std::array<float, 4>>{
             {1, 2, 3, 4}, {7, 1, 64, 1}, {2, 9, 5, 13}, {64, 63, 1, 2}, {1, 1, 2, 1}, {1, 1, 1, 5}, {3, 8, 17, 30}}) {
      SCOPED_TRACE(::testing::Message() << partitioning_name(part) << " " << e0 << "," << e1 << "," << e2 << " / " << in);
      const D3D11Pattern p = make(e0, e1, e2, in, part);
      expect_valid(p, Winding::ccw);
      if (part == Partitioning::integer) {
        EXPECT_EQ(p.factors.outer_points[0], static_cast<int>(e0) + 1);
        EXPECT_EQ(p.factors.outer_points[1], static_cast<int>(e1) + 1);
        EXPECT_EQ(p.factors.outer_points[2], static_cast<int>(e2) + 1);
      }
    }
  }
  // Hand count: 1, 2, 5 segments on the edges and a single centre point (inner 1 counts as even).
  const D3D11Pattern p = make(1, 2, 5, 1, Partitioning::integer);
  EXPECT_EQ(p.points.size(), 1u + 2 + 5 + 1);
  EXPECT_EQ(p.triangle_count(), 8u);  // a fan from the centre
}

TEST_P(D3D11PatternProperties, EdgePointsDependOnlyOnTheEdgesFactor) {
  for (Partitioning part : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                            Partitioning::fractional_even}) {
    for (float f : {1.0f, 2.0f, 2.5f, 3.0f, 5.75f, 17.3f, 40.0f, 64.0f}) {
      SCOPED_TRACE(::testing::Message() << partitioning_name(part) << " factor " << f);
      const std::vector<Fixed16> on_u0 = edge_parameters(make(f, 3, 9.5f, 6, part), 0);
      EXPECT_EQ(edge_parameters(make(f, 12, 2, 31, part), 0), on_u0);
      EXPECT_EQ(edge_parameters(make(7, f, 2, 4, part), 1), on_u0);   // same factor on v = 0
      EXPECT_EQ(edge_parameters(make(2, 5, f, 60, part), 2), on_u0);  // and on w = 0
      // Symmetric about the edge's middle, so a neighbour walking the other way agrees.
      for (std::size_t i = 0; i < on_u0.size(); ++i) EXPECT_EQ(on_u0[i], kFixed16One - on_u0[on_u0.size() - 1 - i]);
    }
  }
}

TEST_P(D3D11PatternProperties, FractionalNearRoundingBoundaries) {
  struct Case {
    Partitioning part;
    float f;
    int edge_points;
    bool strict;  // no coincident points or zero-area triangles
  };
  for (const Case& c : std::vector<Case>{{Partitioning::fractional_odd, 2.999f, 4, true},
                                         {Partitioning::fractional_odd, 3.0f, 4, true},
                                         {Partitioning::fractional_odd, 3.001f, 6, true},
                                         {Partitioning::fractional_odd, 3.5f, 6, true},
                                         {Partitioning::fractional_even, 2.999f, 5, true},
                                         {Partitioning::fractional_even, 3.0f, 5, true},
                                         {Partitioning::fractional_even, 3.001f, 5, true},
                                         {Partitioning::fractional_even, 3.999f, 5, true},
                                         {Partitioning::fractional_even, 4.0f, 5, true},
                                         {Partitioning::fractional_even, 4.001f, 7, true},
                                         {Partitioning::fractional_even, 4.5f, 7, true}}) {
    SCOPED_TRACE(::testing::Message() << partitioning_name(c.part) << " " << c.f);
    const D3D11Pattern p = make(c.f, c.f, c.f, c.f, c.part);
    EXPECT_EQ(p.factors.outer_points, (std::array<int, 3>{c.edge_points, c.edge_points, c.edge_points}));
    EXPECT_EQ(p.factors.inner_points, c.edge_points);
    expect_valid(p, Winding::ccw, {c.strict});
  }
  // 2.999 and 3 (odd) differ only in where the points sit, not in the structure.
  const D3D11Pattern a = make(2.999f, 2.999f, 2.999f, 2.999f, Partitioning::fractional_odd);
  const D3D11Pattern b = make(3, 3, 3, 3, Partitioning::fractional_odd);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_NE(a.points[1].v, b.points[1].v);
}

// Fractional factors at least 0.01 from the integers of their parity: no coincident points.
TEST_P(D3D11PatternProperties, FractionalFactorsAwayFromTheirIntegersAreStrict) {
  std::uint32_t state = 12345;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  for (Partitioning part : {Partitioning::fractional_odd, Partitioning::fractional_even}) {
    const int parity = part == Partitioning::fractional_odd ? 1 : 0;
    auto factor = [&] {
      for (;;) {
        const float f = 1.0f + static_cast<float>(next() % 64000) / 1000.0f;
        const float nearest = 2.0f * std::round((f - static_cast<float>(parity)) / 2.0f) + static_cast<float>(parity);
        if (std::fabs(f - nearest) >= 0.01f && f >= 2.01f) return f;
      }
    };
    for (int i = 0; i < 300; ++i) {
      const float e0 = factor(), e1 = factor(), e2 = factor(), in = factor();
      SCOPED_TRACE(::testing::Message() << partitioning_name(part) << " " << e0 << "," << e1 << "," << e2 << " / " << in);
      expect_valid(make(e0, e1, e2, in, part), Winding::ccw);
    }
  }
}

TEST_P(D3D11PatternProperties, Limits) {
  // All ones: the domain triangle itself.
  for (Partitioning part : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd}) {
    const D3D11Pattern p = make(1, 1, 1, 1, part);
    EXPECT_TRUE(p.factors.single_triangle);
    ASSERT_EQ(p.points.size(), 3u);
    EXPECT_EQ(p.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    expect_valid(p, Winding::ccw);
  }
  // Below the minimum clamps up (not culled); fractional_even's minimum is 2.
  EXPECT_EQ(make(0.25f, 0.5f, 1, 0.1f, Partitioning::integer).points.size(), 3u);
  const D3D11Pattern even = make(1, 1, 1, 1, Partitioning::fractional_even);
  EXPECT_FALSE(even.factors.single_triangle);
  EXPECT_EQ(even.factors.outer, (std::array<float, 3>{2, 2, 2}));
  EXPECT_EQ(even.points.size(), 7u);
  // 64 is the maximum, 63 for fractional_odd; above clamps.
  for (Partitioning part : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_even}) {
    const D3D11Pattern at = make(64, 64, 64, 64, part), above = make(100, 65, 1e30f, 64.5f, part);
    EXPECT_EQ(above.factors.outer, (std::array<float, 3>{64, 64, 64}));
    EXPECT_EQ(above.factors.inner, 64.0f);
    EXPECT_EQ(above.indices, at.indices);
    EXPECT_EQ(above.points.size(), 3169u);
    expect_valid(above, Winding::ccw);
  }
  const D3D11Pattern odd = make(64, 100, std::numeric_limits<float>::infinity(), 70, Partitioning::fractional_odd);
  EXPECT_EQ(odd.factors.outer, (std::array<float, 3>{63, 63, 63}));
  EXPECT_EQ(odd.points.size(), expected_points(63));
}

TEST_P(D3D11PatternProperties, Culled) {
  for (Partitioning part : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                            Partitioning::fractional_even}) {
    for (std::array<float, 3> outer : std::vector<std::array<float, 3>>{
             {0, 4, 4}, {4, -1, 4}, {4, 4, kNaN}, {-0.0f, 1, 1}, {kNaN, kNaN, kNaN}}) {
      const D3D11Pattern p = GetParam().pattern(outer, 4, part, Winding::ccw);
      EXPECT_TRUE(p.factors.culled);
      EXPECT_TRUE(p.points.empty());
      EXPECT_TRUE(p.indices.empty());
    }
    // The inner factor never culls: NaN, 0 or negative clamp to the minimum.
    for (float in : {kNaN, 0.0f, -3.0f}) {
      const D3D11Pattern p = make(4, 4, 4, in, part);
      EXPECT_FALSE(p.factors.culled);
      expect_valid(p, Winding::ccw, {part != Partitioning::fractional_odd});
    }
  }
}

TEST_P(D3D11PatternProperties, InnerFactorWhenOuterFactorsAreOne) {
  // fractional_odd: once an outer edge is split the inner factor is kept just above 1, so an
  // inner ring exists; it starts on the boundary (zero-area triangles, coincident points).
  const D3D11Pattern frame = make(1, 1, 2, 1, Partitioning::fractional_odd);
  EXPECT_EQ(frame.factors.inner_fixed, 0x10001);
  EXPECT_FALSE(frame.factors.single_triangle);
  expect_valid(frame, Winding::ccw, {false});
  std::size_t zero = 0;
  for (std::size_t t = 0; t < frame.triangle_count(); ++t) zero += twice_area(frame, t) == 0;
  EXPECT_GT(zero, 0u);
  // Outer all 1, inner larger: rings inside an unsplit boundary.
  for (Partitioning part : {Partitioning::integer, Partitioning::fractional_odd}) {
    const D3D11Pattern p = make(1, 1, 1, 5, part);
    EXPECT_FALSE(p.factors.single_triangle);
    EXPECT_EQ(p.factors.outer_points, (std::array<int, 3>{2, 2, 2}));
    expect_valid(p, Winding::ccw);
  }
  // Integer: an inner factor of 1 with a split edge gives a fan about the centre.
  const D3D11Pattern fan = make(1, 1, 2, 1, Partitioning::integer);
  EXPECT_EQ(fan.points.size(), 5u);
  EXPECT_EQ(fan.triangle_count(), 4u);
  expect_valid(fan, Winding::ccw);
}

TEST_P(D3D11PatternProperties, Pow2RoundsUpToAPowerOfTwo) {
  const D3D11Pattern p = make(3, 5, 33, 9, Partitioning::pow2);
  EXPECT_EQ(p.factors.outer, (std::array<float, 3>{4, 8, 64}));
  EXPECT_EQ(p.factors.inner, 16.0f);
  const D3D11Pattern q = make(4, 8, 64, 16, Partitioning::integer);
  EXPECT_EQ(p.indices, q.indices);
  EXPECT_EQ(make(1.5f, 2, 1, 1, Partitioning::pow2).factors.outer, (std::array<float, 3>{2, 2, 1}));
  expect_valid(p, Winding::ccw);
}

TEST_P(D3D11PatternProperties, Windings) {
  for (auto [e0, e1, e2, in, part] : std::vector<std::tuple<float, float, float, float, Partitioning>>{
           {1, 1, 1, 1, Partitioning::integer},
           {5, 5, 5, 5, Partitioning::integer},
           {6, 2, 9, 3, Partitioning::integer},
           {3.3f, 7.7f, 1.6f, 5.2f, Partitioning::fractional_odd},
           {3.3f, 7.7f, 2.6f, 5.2f, Partitioning::fractional_even},
           {20, 3, 11, 40, Partitioning::pow2}}) {
    const D3D11Pattern ccw = make(e0, e1, e2, in, part, Winding::ccw);
    const D3D11Pattern cw = make(e0, e1, e2, in, part, Winding::cw);
    expect_valid(ccw, Winding::ccw);
    expect_valid(cw, Winding::cw);
    ASSERT_EQ(ccw.indices.size(), cw.indices.size());
    for (std::size_t i = 0; i < ccw.indices.size(); i += 3) {  // same triangles, last two corners swapped
      EXPECT_EQ(cw.indices[i], ccw.indices[i]);
      EXPECT_EQ(cw.indices[i + 1], ccw.indices[i + 2]);
      EXPECT_EQ(cw.indices[i + 2], ccw.indices[i + 1]);
    }
  }
}

TEST_P(D3D11PatternProperties, PointOrderStartsAtCornerVAndWalksTheRing) {
  const D3D11Pattern p = make(2, 2, 2, 2, Partitioning::integer);
  const std::vector<std::pair<Fixed16, Fixed16>> want = {
      {0, 0x10000}, {0, 0x8000}, {0, 0}, {0x8000, 0}, {0x10000, 0}, {0x8000, 0x8000}, {0x5555, 0x5555}};
  ASSERT_EQ(p.points.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(p.points[i].u, want[i].first) << i;
    EXPECT_EQ(p.points[i].v, want[i].second) << i;
  }
}

}  // namespace tessim::d3d11_checks
