#include "sim/run/patch_assembly.hpp"

#include "model/pattern.hpp"
#include "sim/values/d3d11_walk.hpp"

namespace tessim::sim {

PatchAssembly::PatchAssembly(const MeshSource& source, const HostScaling& scaling, const NumberFormat& format,
                             int tess_factor, const std::function<void(const PatchOut&)>& on_patch)
    : source_(source), scaling_(scaling), format_(format), on_patch_(on_patch) {
  // Room for the largest patch the run can have.
  const MeshPatterns& patterns = source.patterns();
  const int largest =
      patterns.d3d11 ? d3d11_setup(d3d11_host_factors({64.0f, 64.0f, 64.0f}, 64.0f, Partitioning::integer)).point_count
                     : pattern_vertex_count(patterns.factors.empty() ? tess_factor : kMaxTessFactor);
  positions_.resize(static_cast<std::size_t>(largest));
  normals_.resize(static_cast<std::size_t>(largest));
}

std::span<const std::uint32_t> PatchAssembly::indices(const TriangleFx& tri) {
  const std::array<std::int32_t, 5> key{static_cast<std::int32_t>(tri.pattern), tri.factors[0], tri.factors[1],
                                        tri.factors[2], tri.factors[3]};
  auto it = topology_.find(key);
  if (it == topology_.end()) it = topology_.emplace(key, d3d11_pattern(tri_setup(tri)).indices).first;
  return it->second;
}

void PatchAssembly::add(const VertexFx& v, int index, int L, int vertices) {
  add(position_from_fixed(v.pos, scaling_, format_), normal_from_fixed(v.nrm, format_), v.id, v.last, index, L,
      vertices);
}

void PatchAssembly::add(const glm::dvec3& position, const glm::dvec3& normal, std::uint32_t id, bool last, int index,
                        int L, int vertices) {
  positions_[static_cast<std::size_t>(index)] = position;
  normals_[static_cast<std::size_t>(index)] = normal;
  if (!last) return;
  const auto n = static_cast<std::size_t>(vertices);
  const std::span<const std::uint32_t> triangles =
      L == 0 ? indices(*source_.triangle(id)) : std::span<const std::uint32_t>{};
  on_patch_(PatchOut{id, L, {positions_.data(), n}, {normals_.data(), n}, triangles});
}

}  // namespace tessim::sim
