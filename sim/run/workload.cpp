#include "sim/run/workload.hpp"

#include "sim/run/testbench.hpp"

namespace tessim::sim {

WorkloadFactors workload_factors(const MeshSource& source) {
  WorkloadFactors w;
  const TessSettings* d3d11 = source.patterns().d3d11;
  if (d3d11) {
    w.uniform = false;
    w.pattern = d3d11->describe();
  }
  for (std::uint64_t t = source.first(); t < source.end(); ++t) {
    const int points = source.patch_points(t);
    if (points == 0) {
      ++w.culled;
      continue;
    }
    ++w.patches_with_vertices[points];
    w.vertices += static_cast<std::uint64_t>(points);
    if (d3d11) continue;
    const int L = source.factor(t);
    ++w.patches_with_factor[static_cast<std::size_t>(L)];
    if (L != source.factor(source.first())) w.uniform = false;
  }
  return w;
}

}  // namespace tessim::sim
