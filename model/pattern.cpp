#include "model/pattern.hpp"

namespace tessim {

std::vector<DomainPoint> pattern_points(int L) {
  std::vector<DomainPoint> pts;
  pts.reserve(static_cast<std::size_t>(pattern_vertex_count(L)));
  for (int k = 0; k <= L; ++k)
    for (int j = 0; j + k <= L; ++j) pts.push_back({j, k});
  return pts;
}

std::vector<glm::uvec3> pattern_triangles(int L) {
  std::vector<glm::uvec3> tris;
  tris.reserve(static_cast<std::size_t>(pattern_triangle_count(L)));
  auto idx = [L](int j, int k) { return static_cast<unsigned>(pattern_index(j, k, L)); };
  for (int k = 0; k < L; ++k) {
    for (int j = 0; j + k < L; ++j) {
      tris.emplace_back(idx(j, k), idx(j + 1, k), idx(j, k + 1));
      if (j + k <= L - 2) tris.emplace_back(idx(j + 1, k), idx(j + 1, k + 1), idx(j, k + 1));
    }
  }
  return tris;
}

}  // namespace tessim
