// Points counted as one when within a distance of each other (grid cells of that size,
// neighbours searched): the spatial weld the crack-free tests compare with.
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

namespace tessim::testing {

// Welds points within `tolerance` (grid cells of that size, neighbours searched).
inline std::size_t distinct_points(const std::vector<glm::dvec3>& points, double tolerance) {
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      // Unsigned: the products wrap by definition (signed overflow would be undefined).
      return static_cast<std::size_t>(static_cast<std::uint64_t>(k.x) * 73856093u ^
                                      static_cast<std::uint64_t>(k.y) * 19349663u ^
                                      static_cast<std::uint64_t>(k.z) * 83492791u);
    }
  };
  std::unordered_map<Key, std::vector<glm::dvec3>, Hash> cells;
  std::size_t distinct = 0;
  for (const glm::dvec3& p : points) {
    const Key k{static_cast<std::int64_t>(std::floor(p.x / tolerance)), static_cast<std::int64_t>(std::floor(p.y / tolerance)),
                static_cast<std::int64_t>(std::floor(p.z / tolerance))};
    bool found = false;
    for (std::int64_t dx = -1; dx <= 1 && !found; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && !found; ++dy)
        for (std::int64_t dz = -1; dz <= 1 && !found; ++dz) {
          auto it = cells.find(Key{k.x + dx, k.y + dy, k.z + dz});
          if (it == cells.end()) continue;
          for (const glm::dvec3& q : it->second)
            if (glm::length(p - q) <= tolerance) found = true;
        }
    if (!found) {
      cells[k].push_back(p);
      ++distinct;
    }
  }
  return distinct;
}

}  // namespace tessim::testing
