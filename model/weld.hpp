// Welded output: vertices that several patches share (corners and edge points of neighbouring
// patches) written once, the triangles re-indexed (tessim tessellate --weld, tessim sim -o
// --weld). Patches name each vertex by a key, and vertices with equal keys become one output
// vertex, the first one written:
// - the float reference keys a domain point by its place on the input mesh (domain_key): the
//   mesh vertices it lies between and its exact barycentric weights, so the two patches of an
//   edge name its points alike although their float64 positions may differ in the last bits;
// - the cycle model keys a vertex by the bits of its position and normal (bits_key), which the
//   two patches of an edge compute bit for bit alike.
// Memory grows with the distinct vertices (the writer holds the welded mesh until it writes).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "model/mesh.hpp"
#include "model/tessellate.hpp"

namespace tessim {

using WeldKey = std::array<std::uint64_t, 6>;

// The domain point with barycentric weights (w, u, v) = (wn, un, vn) / den on the input
// triangle's vertices (a, b, c): the vertices with a non-zero weight, in increasing index, each
// with its weight as a reduced fraction.
WeldKey domain_key(const glm::uvec3& triangle, std::uint64_t wn, std::uint64_t un, std::uint64_t vn,
                   std::uint64_t den);
// The keys of a reference patch's vertices (model/tessellate.hpp), in its order: uniform patterns
// by their lattice points (j/L, k/L), D3D11 patterns by their 16.16 points (docs/patterns.md),
// exact in a double.
void patch_weld_keys(const Mesh& mesh, const PatchView& patch, std::vector<WeldKey>& keys);
// The bits of a position and a normal.
WeldKey bits_key(const glm::dvec3& position, const glm::dvec3& normal);

class WeldingWriter {
 public:
  // A patch: its vertices, their keys and its triangles as local indices (three per triangle).
  void add_patch(std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals,
                 std::span<const WeldKey> keys, std::span<const std::uint32_t> indices);
  // Writes the welded mesh (PLY or OBJ, as MeshWriter), all or nothing.
  void write(const std::filesystem::path& path) const;

  std::uint64_t vertices_in() const { return vertices_in_; }
  std::uint64_t vertices_out() const { return positions_.size(); }
  std::uint64_t triangles() const { return indices_.size() / 3; }

 private:
  struct KeyHash {
    std::size_t operator()(const WeldKey& k) const;
  };
  std::unordered_map<WeldKey, std::uint32_t, KeyHash> index_;
  std::vector<glm::dvec3> positions_, normals_;
  std::vector<std::uint32_t> indices_;
  std::uint64_t vertices_in_ = 0;
};

}  // namespace tessim
