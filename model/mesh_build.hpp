// Turning triangles as read into the mesh the unit takes: exact welding, then vertex normals
// (the file's, averaged per position, or computed from the geometry). Each step takes and
// returns a Mesh and can be used on its own; load_mesh (model/mesh_io.hpp) chains them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/mesh.hpp"

namespace tessim {

// Names a vertex of weld()'s input in messages; the default says "vertex N".
using VertexNamer = std::function<std::string(std::uint32_t vertex)>;

// One vertex per distinct position, exactly (bit for bit in double, -0 equal to +0), in order
// of first occurrence; triangles are re-indexed, their winding kept. With normals_from_file,
// mesh.normals holds one normal per input vertex, of any length: the distinct directions found
// at a position are averaged, so that the result does not depend on how many corner copies the
// reader made of each (position, normal) pair. Zero-length normals carry no direction and are
// left out. Throws InputError if no normal at a position has a direction, if those at a
// position cancel, or if there are more than 2^32 - 1 distinct positions. Without
// normals_from_file, the result has no normals (compute_normals() gives them).
// Tags (mesh.tags, one per input vertex when present) are carried over: the copies welded into
// one vertex must have equal tags, else InputError naming two of them. `first_copies`, if
// given, receives the first input vertex of each welded vertex (for naming it in messages).
Mesh weld(const Mesh& mesh, const VertexNamer& name = {}, std::vector<std::uint32_t>* first_copies = nullptr);

// Sum over incident triangles of area x corner angle x unit face normal, normalized; +Z where
// that sum vanishes (only zero-area triangles around the vertex, or faces that cancel).
// `fallbacks`, if given, receives the number of such vertices.
std::vector<glm::dvec3> weighted_normals(const Mesh& mesh, std::size_t* fallbacks = nullptr);

// The mesh with weighted_normals() as its normals (normals_from_file = false).
Mesh compute_normals(Mesh mesh);

}  // namespace tessim
