// Distances between two point sets: how far a written mesh's points lie from the expected ones
// (the CLI tests, whose mesh reader welds and reads single precision, so points match only
// within a tolerance and not in order).
#pragma once

#include <algorithm>
#include <vector>

#include <glm/glm.hpp>

namespace tessim::testing {

// The largest distance from a point of `a` to its nearest point of `b`, searched within `reach`
// (a point with none within reach counts as 2 reach).
inline double farthest_from(const std::vector<glm::dvec3>& a, std::vector<glm::dvec3> b, double reach) {
  std::sort(b.begin(), b.end(), [](const glm::dvec3& p, const glm::dvec3& q) { return p.x < q.x; });
  double worst = 0;
  for (const glm::dvec3& p : a) {
    double nearest = 2 * reach;
    auto it = std::lower_bound(b.begin(), b.end(), p.x - reach, [](const glm::dvec3& q, double x) { return q.x < x; });
    for (; it != b.end() && it->x <= p.x + reach; ++it) nearest = std::min(nearest, glm::length(*it - p));
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace tessim::testing
