// The patches of a run handed out whole (SimHooks::on_patch): the accepted vertices of a patch
// collected and converted back into the mesh's coordinates, with the triangles of its D3D11
// pattern, once its last vertex is accepted.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "sim/base/fixed.hpp"
#include "sim/run/hooks.hpp"
#include "sim/run/testbench.hpp"
#include "sim/values/host.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

class PatchAssembly {
 public:
  // The patches of `source`, whose triangles have `tess_factor` where they have no factor of
  // their own; `on_patch` (which must outlive this) receives each one, its spans valid during the
  // call only.
  PatchAssembly(const MeshSource& source, const HostScaling& scaling, const NumberFormat& format, int tess_factor,
                const std::function<void(const PatchOut&)>& on_patch);

  // Vertex `index` of a patch of `vertices` vertices and uniform factor L (0: D3D11).
  void add(const VertexFx& v, int index, int L, int vertices);
  // The same for a vertex already in float in the mesh's coordinates (evaluation gpe), of the
  // patch of triangle `id`; `last`: the patch's last vertex.
  void add(const glm::dvec3& position, const glm::dvec3& normal, std::uint32_t id, bool last, int index, int L,
           int vertices);

 private:
  // The triangles of a D3D11 pattern, built once per distinct set of factors (an adaptive mesh
  // has a few hundred).
  std::span<const std::uint32_t> indices(const TriangleFx& tri);

  const MeshSource& source_;
  HostScaling scaling_;
  NumberFormat format_;
  const std::function<void(const PatchOut&)>& on_patch_;
  std::vector<glm::dvec3> positions_, normals_;
  std::map<std::array<std::int32_t, 5>, std::vector<std::uint32_t>> topology_;
};

}  // namespace tessim::sim
