// Reading a mesh file through Assimp, with the checks Assimp does not make. The result is not
// yet welded; load_mesh (model/mesh_io.hpp) welds it and settles its normals.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "model/mesh.hpp"

namespace tessim::io {

struct ImportedMesh {
  // The triangles of every node instance, after its transform (faces of a mirroring transform
  // reversed to keep them outward). One vertex per (instance, source vertex used by a triangle),
  // in order of first use. With normals_from_file, normals are the file's after the normal
  // matrix, not renormalized (zero-length ones included); STL's facet normals are not taken.
  // A PLY file's scalar tags (docs/stpn.md) are in mesh.tags, one per vertex, their values
  // checked (tag_value_problem, model/st_mesh.hpp); empty for every other file.
  Mesh mesh;
  // With normals_from_file or tags: (Assimp mesh, vertex in it) of every vertex, for messages.
  std::vector<std::pair<unsigned, unsigned>> origin;
  bool several_meshes = false;
  // What was read but not used, each as "FILE: ELEMENT: what was done" (faces of 1 or 2
  // vertices, left out); load_mesh prints them as warnings.
  std::vector<std::string> warnings;

  std::string vertex_name(std::uint32_t vertex) const;  // "vertex 7" or "mesh 2 vertex 7"
};

// Throws InputError naming the file, the element and the reason for: missing, empty,
// unreadable or malformed files, no triangles, NaN/Inf coordinates or normals, unusable tags,
// out-of-range indices, ASCII STL files without 'endsolid' or with incomplete facets, and coordinates that
// single precision (Assimp's) cannot resolve at the scale of the mesh.
ImportedMesh import_mesh(const std::filesystem::path& path);

}  // namespace tessim::io
