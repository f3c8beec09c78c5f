// Mesh import (OBJ, PLY, STL, OFF and the rest of Assimp's formats) and streamed export of
// tessellated meshes (PLY or OBJ, chosen by extension).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/mesh.hpp"

namespace tessim {

// Loads a triangle mesh. Faces are triangulated; identical positions are welded into one
// vertex. Normals from the file are kept when present (averaged over the welded copies and
// renormalized); otherwise area- and angle-weighted vertex normals are computed.
// Throws InputError naming the file, the element and the reason for: unreadable or malformed
// files, empty meshes, NaN/Inf coordinates, zero-length file normals, out-of-range indices,
// coordinates beyond what single precision resolves at the mesh's scale.
// What is read but left out (faces of 1 or 2 vertices among triangles) is a warning, each
// "FILE: ELEMENT: what was done": appended to `warnings`, or printed to stderr as
// "tessim: warning: ..." when `warnings` is null.
// A PLY file's vertex properties dx dy dz sigma theta beta are its scalar tags (mesh.tags,
// docs/stpn.md; empty when the file has none of them): copies welded together must agree, and
// the tagged mesh must pass validate_tags (model/st_mesh.hpp), else InputError.
Mesh load_mesh(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);

// Writes a whole mesh as binary little-endian PLY: double x y z nx ny nz, then dx dy dz sigma
// theta beta when it has tags, and uint triangles. load_mesh reads it back with the same
// triangles and, bit for bit, the same tags and positions (positions that single precision
// holds, as every position load_mesh returns); normals come back through single precision.
// Nothing reaches `path` unless the whole file was written (InputError otherwise).
void write_ply(const Mesh& mesh, const std::filesystem::path& path);

// Counts for `tessim info`.
struct MeshStats {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t degenerate_triangles = 0;  // zero area (repeated vertices, collinear points)
  std::size_t zero_length_edges = 0;  // triangle edges whose two ends coincide
  std::size_t edges = 0;  // distinct edges between distinct vertices (shared edges count once)
  // Computed normals only: vertices where the area x angle weighted face normals sum to zero
  // (only zero-area triangles around them, or faces that cancel); load_mesh gives them +Z.
  std::size_t normal_fallbacks = 0;
  BoundingBox bbox;
};
MeshStats mesh_stats(const Mesh& mesh);

// Streams a tessellated mesh to PLY (binary little-endian) or OBJ, chosen by the extension
// of `path`; anything else is an InputError. Vertex and triangle totals must be known up front
// (PLY's header needs them). Patches are appended one at a time; nothing reaches `path` until
// finish() succeeds (the file is written to a temporary and renamed). The path "-" is standard
// output, as binary PLY, written as it comes (a pipe cannot be taken back).
class MeshWriter {
 public:
  MeshWriter(const std::filesystem::path& path, std::uint64_t total_vertices,
             std::uint64_t total_triangles);
  ~MeshWriter();
  MeshWriter(const MeshWriter&) = delete;
  MeshWriter& operator=(const MeshWriter&) = delete;

  // Appends one patch of pattern_vertex_count(L) vertices in pattern order with
  // pattern_triangles(L) as its topology (indices offset by the vertices written so far).
  void add_patch(int L, const glm::dvec3* positions, const glm::dvec3* normals);
  // Appends one patch of any pattern: its vertices and its triangles as local indices.
  void add_patch(std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals,
                 std::span<const std::uint32_t> indices);
  void finish();  // checks the totals, flushes and renames into place

 private:
  // L > 0: a uniform patch of factor L (PLY keeps only the factor); 0: any other pattern.
  void append(int L, std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals,
              std::span<const std::uint32_t> indices);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Returns true if `path` has an extension MeshWriter accepts (.ply or .obj, any case), or is
// written directly (standard output "-", a device, a pipe: binary PLY, model/base/output_file.hpp).
bool is_supported_output(const std::filesystem::path& path);

}  // namespace tessim
