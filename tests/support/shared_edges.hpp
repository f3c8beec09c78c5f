// The points on the edges of a uniformly tessellated mesh, named alike by the two patches that
// share an edge: the crack-free checks of the reference (pn_test, st_mesh_test).
#pragma once

#include <tuple>

#include "model/mesh.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"

namespace tessim::testing {

// Domain-point index of the point `step` segments from the start of edge e of a patch (0: P1->P2,
// 1: P2->P3, 2: P3->P1).
inline int edge_point(int edge, int step, int L) {
  switch (edge) {
    case 0: return pattern_index(step, 0, L);
    case 1: return pattern_index(L - step, step, L);
    default: return pattern_index(0, L - step, L);
  }
}

using EdgePointKey = std::tuple<unsigned, unsigned, int>;  // lower vertex, upper vertex, steps from the lower

// Tessellates with the uniform pattern of factor L and calls fn(view, index, key) for every point
// on an edge of every patch (zero-length edges left out).
template <class Fn>
void for_each_edge_point(const Mesh& mesh, int L, NormalMode mode, Fn fn) {
  tessellate_mesh(mesh, L, mode, [&](const PatchView& view) {
    const glm::uvec3 t = mesh.triangles[view.triangle];
    for (int e = 0; e < 3; ++e) {
      const unsigned a = t[e], b = t[(e + 1) % 3];
      if (a == b) continue;
      for (int step = 0; step <= L; ++step) {
        const EdgePointKey key = a < b ? std::make_tuple(a, b, step) : std::make_tuple(b, a, L - step);
        fn(view, static_cast<std::size_t>(edge_point(e, step, L)), key);
      }
    }
  });
}

}  // namespace tessim::testing
