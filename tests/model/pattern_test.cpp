// The uniform pattern (model/pattern.hpp, docs/mathematics.md §7): counts, order, topology.
#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "model/pattern.hpp"

namespace tessim {
namespace {

TEST(Pattern, VertexAndTriangleCounts) {
  for (int L = 1; L <= kMaxTessFactor; ++L) {
    EXPECT_EQ(pattern_vertex_count(L), (L + 1) * (L + 2) / 2);
    EXPECT_EQ(pattern_triangle_count(L), L * L);
    EXPECT_EQ(pattern_points(L).size(), static_cast<std::size_t>((L + 1) * (L + 2) / 2)) << "L=" << L;
    EXPECT_EQ(pattern_triangles(L).size(), static_cast<std::size_t>(L * L)) << "L=" << L;
  }
}

TEST(Pattern, PointsAreTheLatticeInRowOrder) {
  for (int L = 1; L <= kMaxTessFactor; ++L) {
    const std::vector<DomainPoint> pts = pattern_points(L);
    std::set<std::pair<int, int>> seen;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const DomainPoint& d = pts[i];
      ASSERT_GE(d.j, 0);
      ASSERT_GE(d.k, 0);
      ASSERT_LE(d.j + d.k, L);
      EXPECT_EQ(pattern_index(d.j, d.k, L), static_cast<int>(i)) << "L=" << L;
      EXPECT_TRUE(seen.emplace(d.j, d.k).second) << "duplicate point, L=" << L;
      // Rows of increasing k, and within a row increasing j.
      if (i > 0) {
        const DomainPoint& prev = pts[i - 1];
        EXPECT_TRUE(d.k > prev.k || (d.k == prev.k && d.j == prev.j + 1)) << "L=" << L << " i=" << i;
      }
    }
    EXPECT_EQ(pts.front().j, 0);
    EXPECT_EQ(pts.front().k, 0);
    EXPECT_EQ(pts.back().j, 0);
    EXPECT_EQ(pts.back().k, L);
  }
}

// Twice the signed area of a pattern triangle in (j, k) lattice units; positive means the
// winding of (P1, P2, P3), which sit at (0,0), (L,0), (0,L).
int twice_signed_area(const DomainPoint& a, const DomainPoint& b, const DomainPoint& c) {
  return (b.j - a.j) * (c.k - a.k) - (b.k - a.k) * (c.j - a.j);
}

bool on_boundary(const DomainPoint& a, const DomainPoint& b, int L) {
  return (a.k == 0 && b.k == 0) || (a.j == 0 && b.j == 0) || (a.j + a.k == L && b.j + b.k == L);
}

TEST(Pattern, TrianglesTileTheDomainWithOneOrientation) {
  for (int L = 1; L <= kMaxTessFactor; ++L) {
    const std::vector<DomainPoint> pts = pattern_points(L);
    const std::vector<glm::uvec3> tris = pattern_triangles(L);
    std::map<std::pair<unsigned, unsigned>, int> directed;  // (from, to) -> uses
    std::vector<int> used(pts.size(), 0);
    int total_area = 0;
    for (const glm::uvec3& t : tris) {
      for (int c = 0; c < 3; ++c) ASSERT_LT(t[c], pts.size());
      // Every triangle is a unit lattice triangle with the input's orientation.
      const int area = twice_signed_area(pts[t[0]], pts[t[1]], pts[t[2]]);
      EXPECT_EQ(area, 1) << "L=" << L;
      total_area += area;
      for (int c = 0; c < 3; ++c) {
        ++directed[{t[c], t[(c + 1) % 3]}];
        ++used[t[c]];
      }
    }
    // Unit triangles of total area L^2 / 2 inside the domain triangle cover it exactly.
    EXPECT_EQ(total_area, L * L);
    EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](int n) { return n > 0; })) << "L=" << L;

    // Consistent orientation: no directed edge twice. An interior edge is used once in each
    // direction (two triangles), a boundary edge once in total.
    int boundary_edges = 0;
    for (const auto& [edge, uses] : directed) {
      EXPECT_EQ(uses, 1) << "L=" << L;
      const bool boundary = on_boundary(pts[edge.first], pts[edge.second], L);
      const bool has_twin = directed.count({edge.second, edge.first}) > 0;
      EXPECT_EQ(has_twin, !boundary) << "L=" << L << " edge " << edge.first << "-" << edge.second;
      if (boundary) ++boundary_edges;
    }
    EXPECT_EQ(boundary_edges, 3 * L);
    // Euler: interior edges = (3 L^2 - 3 L) / 2, each seen twice above.
    EXPECT_EQ(directed.size(), static_cast<std::size_t>(3 * L + (3 * L * L - 3 * L)));
  }
}

TEST(Pattern, TriangleOrderIsRowsThenUpBeforeDown) {
  const int L = 3;
  auto idx = [](int j, int k) { return static_cast<unsigned>(pattern_index(j, k, L)); };
  const std::vector<glm::uvec3> expected = {
      {idx(0, 0), idx(1, 0), idx(0, 1)}, {idx(1, 0), idx(1, 1), idx(0, 1)},
      {idx(1, 0), idx(2, 0), idx(1, 1)}, {idx(2, 0), idx(2, 1), idx(1, 1)},
      {idx(2, 0), idx(3, 0), idx(2, 1)}, {idx(0, 1), idx(1, 1), idx(0, 2)},
      {idx(1, 1), idx(1, 2), idx(0, 2)}, {idx(1, 1), idx(2, 1), idx(1, 2)},
      {idx(0, 2), idx(1, 2), idx(0, 3)},
  };
  EXPECT_EQ(pattern_triangles(L), expected);
}

}  // namespace
}  // namespace tessim
