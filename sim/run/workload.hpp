// The per-patch load of a run (SimResult::factors): the factors of its patches and the vertices
// they make, counted from the triangle source before the run.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "model/pattern.hpp"

namespace tessim::sim {

class MeshSource;

struct WorkloadFactors {
  bool uniform = true;  // every patch has the configuration's factor (uniform pattern)
  std::array<std::uint64_t, kMaxTessFactor + 1> patches_with_factor{};  // uniform pattern: index L
  std::map<int, std::uint64_t> patches_with_vertices;  // vertices per patch -> patches
  std::uint64_t vertices = 0;
  std::uint64_t culled = 0;  // D3D11 patches their factors cull: never sent to the unit
  std::string pattern;       // D3D11: the settings (TessSettings::describe); empty: uniform
};

// The load of the triangles [source.first(), source.end()).
WorkloadFactors workload_factors(const MeshSource& source);

}  // namespace tessim::sim
