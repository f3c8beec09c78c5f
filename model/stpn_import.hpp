// Turning a mesh with hard edges into a scalar-tagged mesh (ST-mesh, docs/stpn.md): find its
// creases, give each crease vertex the average normal N and the crease vector Δ of its two
// sides, and resolve what the rules of the format forbid. `tessim stpn-import` runs it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/mesh.hpp"

namespace tessim {

constexpr double kDefaultCreaseAngle = 30.0;  // degrees
// The file's normals of a vertex in two faces further apart than this split it: a hard edge.
constexpr double kNormalSplitAngle = 1.0;  // degrees

struct StImportOptions {
  // Edges whose faces' normals are more than this many degrees apart are creases. Unset: 30°
  // for a mesh without normals in the file (or with flat ones: every corner's normal its face's
  // normal); a mesh with them takes its creases from where the normals split, and this test is
  // made only when the angle is given.
  std::optional<double> crease_angle;
  double sigma = 1.0;           // σ of every tagged vertex: 1 reproduces the two side normals
  double corner_tension = 1.0;  // θ of corners (three or more creases meet): 1 keeps them pointed
};

// Every vertex falls in one class (docs/stpn.md, stpn-import).
struct StImportSummary {
  std::size_t vertices = 0, triangles = 0;
  std::size_t crease_edges = 0;     // hard edges found (two faces each)
  bool dihedral_test = false;       // creases from the angle between faces (crease_angle used)
  bool normal_splits = false;       // creases from where the file's normals split
  bool faceted_normals = false;     // the file's normals are its face normals: no crease information
  double crease_angle = 0.0;        // degrees, when dihedral_test
  std::size_t crease_vertices = 0;  // fan cut in two sides by creases: tagged unless counted below
  std::size_t tagged = 0;           // crease vertices carrying Δ (σ as asked, or 0 if softened)
  std::size_t softened = 0;         // tagged, but σ = 0 to keep the surface closed, because ...
  std::size_t softened_ends = 0;    // ... a crease runs from it into an untagged vertex
  std::size_t softened_sides = 0;   // ... the side test puts one of its faces on the other side
  std::size_t restricted = 0;       // crease vertices left untagged by the two rules of the format
  std::size_t folded = 0;           // crease vertices whose two sides have no average: untagged
  std::size_t corners = 0;          // three or more sides: θ = corner_tension, ...
  std::size_t corners_tagged = 0;   // ... tagged with σ = 0 where a crease from a tagged vertex ends there
  std::size_t crease_ends = 0;      // one side, a crease ending here: ...
  std::size_t crease_ends_tagged = 0;  // ... tagged with σ = 0 where a crease from a tagged vertex ends there
  std::size_t non_manifold = 0;     // on an edge of 3+ faces, or where separate fans touch: untagged
};

struct StImport {
  Mesh mesh;  // the ST-mesh: positions and triangles of the input, tags, N at tagged vertices
  StImportSummary summary;
};

// Makes an ST-mesh of a welded mesh with unit normals. `corner_normals`: the file's normal of
// each triangle corner (3 per triangle, any length; zero-length ones are ignored) or empty when
// the file has none. The result passes validate_tags (model/st_mesh.hpp) and is crack-free:
// both patches of every edge compute the same boundary curve (docs/stpn.md says why).
StImport make_st_mesh(const Mesh& mesh, std::span<const glm::dvec3> corner_normals, const StImportOptions& options);

// Loads a mesh file as load_mesh does (any tags in it are replaced) and makes it an ST-mesh.
// Warnings as load_mesh's.
StImport import_st_mesh(const std::filesystem::path& path, const StImportOptions& options,
                        std::vector<std::string>* warnings = nullptr);

}  // namespace tessim
