// The unit's output stream checked as the geometry engine accepts it: the patches in stream
// order (culled ones skipped), each one's vertices in pattern order with its id, L and last
// flag, and its patch flags against the mesh. A model bug thereby shows up as an internal error
// (std::logic_error) at the cycle it happens instead of as a wrong mesh. The warnings of the
// statistics (degenerate patches, vanished normals) are counted on the way.
#pragma once

#include <cstdint>

#include "model/mesh.hpp"
#include "sim/base/fixed.hpp"
#include "sim/run/testbench.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

class OutputCheck {
 public:
  // The triangles [source.first(), source.end()); `d3d11`: their patterns are D3D11 ones.
  OutputCheck(const Mesh& mesh, const MeshSource& source, const NumberFormat& format, bool d3d11);

  // The vertex accepted in `cycle`; throws std::logic_error unless it is the one expected.
  void check(const VertexFx& v, std::uint64_t cycle);
  // Of the vertex check() took: its place in its patch's pattern order, its patch's vertices and
  // the patch's uniform factor (0: a D3D11 pattern).
  int index() const { return index_; }
  int patch_vertices() const { return patch_vertices_; }
  int L() const { return L_; }
  // Expect the vertex after the one check() took (once every consumer has seen that one).
  void next();

  std::uint64_t degenerate_patches() const { return degenerate_patches_; }  // with the divide-by-zero flag
  std::uint64_t zero_normals() const { return zero_normals_; }  // output vertices whose normal vanished

 private:
  // The patch expected next: the first triangle from `from` on that is not culled.
  void expect_patch(std::uint64_t from);

  const Mesh& mesh_;
  const MeshSource& source_;
  NumberFormat format_;
  bool d3d11_;
  std::uint32_t id_ = 0;  // the patch expected (end: none left)
  int L_ = 1, patch_vertices_ = 0, index_ = 0;
  bool last_ = false;
  std::uint64_t degenerate_patches_ = 0, zero_normals_ = 0;
};

}  // namespace tessim::sim
