// The uniform tessellation pattern (docs/mathematics.md §7): L segments per edge, domain points
// (u, v) = (j/L, k/L), j, k >= 0, j + k <= L. One order is used everywhere (reference, cycle
// model, RTL, output files): rows of increasing k, and within a row increasing j.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace tessim {

constexpr int kMaxTessFactor = 64;

constexpr int pattern_vertex_count(int L) { return (L + 1) * (L + 2) / 2; }
constexpr int pattern_triangle_count(int L) { return L * L; }

// Position of domain point (j, k) in the pattern order.
constexpr int pattern_index(int j, int k, int L) { return k * (L + 1) - k * (k - 1) / 2 + j; }

struct DomainPoint {
  int j = 0;  // u = j / L (weight of P2)
  int k = 0;  // v = k / L (weight of P3)
};

// All domain points in pattern order.
std::vector<DomainPoint> pattern_points(int L);

// The L^2 triangles as local vertex indices, with the input triangle's winding: for each
// cell (j, k) an "up" triangle (j,k) (j+1,k) (j,k+1) and, where j + k <= L - 2, a "down"
// triangle (j+1,k) (j+1,k+1) (j,k+1). Ordered by k, then j, up before down.
std::vector<glm::uvec3> pattern_triangles(int L);

}  // namespace tessim
