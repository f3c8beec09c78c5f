// Test mesh for the renderer's tests (tests/render, tests/cli).
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "render/raster.hpp"

namespace tessim::render::test_meshes {

// Unit icosphere: the icosahedron with every triangle split in four `levels` times, vertices
// pushed onto the sphere; normals equal positions. Consistent outward (counter-clockwise) winding.
inline RenderMesh icosphere(int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  RenderMesh m;
  for (const glm::dvec3& p : {glm::dvec3(-1, t, 0), glm::dvec3(1, t, 0), glm::dvec3(-1, -t, 0), glm::dvec3(1, -t, 0),
                              glm::dvec3(0, -1, t), glm::dvec3(0, 1, t), glm::dvec3(0, -1, -t), glm::dvec3(0, 1, -t),
                              glm::dvec3(t, 0, -1), glm::dvec3(t, 0, 1), glm::dvec3(-t, 0, -1), glm::dvec3(-t, 0, 1)})
    m.positions.push_back(glm::normalize(p));
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
    auto midpoint = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      const auto index = static_cast<unsigned>(m.positions.size() - 1);
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<glm::uvec3> finer;
    for (const glm::uvec3& tri : m.triangles) {
      const unsigned ab = midpoint(tri.x, tri.y), bc = midpoint(tri.y, tri.z), ca = midpoint(tri.z, tri.x);
      finer.insert(finer.end(), {{tri.x, ab, ca}, {tri.y, bc, ab}, {tri.z, ca, bc}, {ab, bc, ca}});
    }
    m.triangles = std::move(finer);
  }
  m.normals = m.positions;
  return m;
}

}  // namespace tessim::render::test_meshes
