// Mesh import and export (model/mesh_io.hpp): real meshes (docs/verification.md) and bad input
// (docs/architecture.md, Bad input).
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "model/base/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "tests/support/rejects.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

using tessim::testing::rejects;
using tessim::testing::TempDir;


bool is_unit(const glm::dvec3& n) { return std::abs(glm::length(n) - 1.0) < 1e-12; }

// ---------------------------------------------------------------------------------------------

std::string le_bytes(const void* p, std::size_t n) { return std::string(static_cast<const char*>(p), n); }

// Binary little-endian PLY of a unit square (two triangles).
std::string square_binary_ply() {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n";
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  s += le_bytes(v, sizeof v);
  const std::uint32_t faces[2][3] = {{0, 1, 2}, {1, 3, 2}};
  for (const auto& f : faces) {
    const unsigned char n = 3;
    s += le_bytes(&n, 1) + le_bytes(f, sizeof f);
  }
  return s;
}

TEST(LoadMesh, BinaryPlyLoads) {
  TempDir dir;
  const Mesh mesh = load_mesh(dir.write("square.ply", square_binary_ply()));
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_FALSE(mesh.normals_from_file);
  for (const glm::dvec3& n : mesh.normals) EXPECT_EQ(n, glm::dvec3(0, 0, 1));  // flat square, +Z winding
}

// Every file of assimp-testmodels' invalid/ directory, each with what it must give.
TEST(LoadMesh, AssimpInvalidModels) {
  const fs::path dir = kModels / "invalid";
  if (!fs::exists(dir)) FAIL() << dir << " is missing: scripts/setup.sh installs assimp-testmodels";

  std::map<std::string, std::vector<std::string>> rejected = {
      // Header declares 353535235358 vertices: refused before Assimp allocates 16 GB for it.
      {"OutOfMemory.off", {"OutOfMemory.off", "OFF header", "353535235358"}},
      {"empty.3ds", {"empty.3ds", "is empty"}},
      {"empty.ase", {"empty.ase", "is empty"}},
      {"empty.lwo", {"empty.lwo", "is empty"}},
      {"empty.md5mesh", {"empty.md5mesh", "is empty"}},
      {"empty.obj", {"empty.obj", "is empty"}},
      {"empty.off", {"empty.off", "is empty"}},
      {"empty.ply", {"empty.ply", "is empty"}},
      {"empty.raw", {"empty.raw", "is empty"}},
      {"empty.smd", {"empty.smd", "is empty"}},
      {"empty.x", {"empty.x", "is empty"}},
      // Assimp's own error string is the reason.
      {"emptyIrrMesh.xml", {"emptyIrrMesh.xml", "import", "IRRMESH: Unable to read a mesh"}},
      // "f 4 12 2 1" with 8 vertices, on line 23 of the file.
      {"malformed.obj", {"malformed.obj", "face at line 23", "vertex index 12 out of range"}},
      {"readme.txt", {"readme.txt", "import", "No suitable reader"}},
  };
  std::set<std::string> seen;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    seen.insert(name);
    SCOPED_TRACE(name);
    if (name == "malformed2.obj") {
      // Its defects (an empty "f" line, a missing material) leave a valid open box: five of
      // the cube's six quads, read as 10 triangles over the 8 corners.
      const Mesh mesh = load_mesh(entry.path());
      EXPECT_EQ(mesh.vertex_count(), 8u);
      EXPECT_EQ(mesh.triangle_count(), 10u);
      EXPECT_FALSE(mesh.normals_from_file);
      const BoundingBox box = bounding_box(mesh);
      EXPECT_EQ(box.lo, glm::dvec3(-0.5));
      EXPECT_EQ(box.hi, glm::dvec3(0.5));
      for (const glm::dvec3& n : mesh.normals) EXPECT_TRUE(is_unit(n));
      continue;
    }
    const auto expected = rejected.find(name);
    ASSERT_NE(expected, rejected.end()) << "new file in " << dir << ": decide what it must give";
    EXPECT_TRUE(rejects(entry.path(), expected->second));
  }
  for (const auto& [name, parts] : rejected) EXPECT_TRUE(seen.count(name)) << name << " missing from " << dir;
}

TEST(LoadMesh, RejectsMalformedFilesNamingFileElementAndReason) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_TRUE(rejects(dir.path() / "missing.obj", {"missing.obj", "does not exist"}));
  EXPECT_TRUE(rejects(dir.write("empty.obj", ""), {"empty.obj", "is empty"}));
  EXPECT_TRUE(rejects(dir.write("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n"),
                      {"nan.obj", "vertex 2", "NaN or infinite"}));
  EXPECT_TRUE(rejects(dir.write("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"),
                      {"inf.obj", "vertex 1", "NaN or infinite"}));
  EXPECT_TRUE(rejects(dir.write("range.obj", tri + "f 1 2 3\nf 1 2 9\n"),
                      {"range.obj", "face at line 5", "vertex index 9 out of range"}));
  EXPECT_TRUE(rejects(dir.write("negative.obj", tri + "f -5 1 2\n"),
                      {"negative.obj", "face at line 4", "vertex index -5 out of range"}));
  EXPECT_TRUE(rejects(dir.write("points.obj", tri + "p 1 2 3\n"), {"points.obj", "faces", "no triangles (3 vertices, 3 point and 0 line primitives)"}));
  EXPECT_TRUE(rejects(dir.write("lines.obj", tri + "l 1 2\nl 2 3\n"), {"lines.obj", "no triangles (4 vertices, 0 point and 2 line primitives)"}));
  EXPECT_TRUE(rejects(dir.write("vertices.obj", tri), {"vertices.obj", "no triangles (3 vertices, 0 point and 0 line"}));
  // The only normal of vertex 2 is (0, 0, 0).
  EXPECT_TRUE(rejects(dir.write("zero_normal.obj", tri + "vn 0 0 1\nvn 0 0 0\nf 1//1 2//1 3//2\n"),
                      {"zero_normal.obj", "vertex 2", "normal in the file has zero length"}));
  EXPECT_TRUE(rejects(dir.write("nan_normal.obj", tri + "vn 0 0 1\nvn nan 0 1\nf 1//1 2//1 3//2\n"),
                      {"nan_normal.obj", "vertex 2", "normal in the file is NaN"}));
  // Two copies of one position whose normals are exactly opposite: no direction to average.
  EXPECT_TRUE(rejects(dir.write("cancel.obj", tri + "v 0 0 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 4//2 3//2 2//2\n"),
                      {"cancel.obj", "vertex", "cancel out"}));

  // PLY headers that declare things twice: Assimp 5.2's reader freed memory it did not allocate
  // on the first of these (found by fuzz/fuzz_mesh: two headers run together), so they are
  // rejected before it reads them.
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
  const std::string body = "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_TRUE(rejects(dir.write("two_headers.ply", header + "end_he\x04ply\n" + header + body),
                      {"two_headers.ply", "PLY header line 11", "a second format line"}));
  EXPECT_TRUE(rejects(dir.write("two_vertex_elements.ply", header + "element vertex 3\n" + body),
                      {"two_vertex_elements.ply", "PLY header line 9", "element 'vertex' declared twice"}));
  // PLY has only version 1.0 (Assimp reads any version as if it were 1.0).
  std::string future = header + body;
  future.replace(future.find("ascii 1.0"), 9, "ascii 9.9");
  EXPECT_TRUE(rejects(dir.write("version.ply", future), {"version.ply", "PLY header line 2", "format version '9.9'"}));
  std::string versionless = header + body;
  versionless.replace(versionless.find("ascii 1.0"), 9, "ascii");
  EXPECT_TRUE(rejects(dir.write("versionless.ply", versionless), {"versionless.ply", "format version ''"}));

  // PLY: truncated binary, truncated header, out-of-range face, non-numbers, Inf.
  const std::string ply = square_binary_ply();
  EXPECT_TRUE(rejects(dir.write("truncated.ply", ply.substr(0, ply.size() - 7)),
                      {"truncated.ply", "element 'face' 1 of 2", "truncated"}));
  EXPECT_TRUE(rejects(dir.write("truncated_vertices.ply", ply.substr(0, ply.find("end_header\n") + 11 + 20)),
                      {"truncated_vertices.ply", "element 'vertex' 1 of 4", "truncated"}));
  EXPECT_TRUE(rejects(dir.write("no_end_header.ply", ply.substr(0, ply.find("end_header"))),
                      {"no_end_header.ply", "PLY header", "no end_header"}));
  const std::string ascii_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_TRUE(rejects(dir.write("range.ply", ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
                      {"range.ply", "face 0", "vertex index 5 out of range (3 vertices)"}));
  EXPECT_TRUE(rejects(dir.write("word.ply", ascii_header + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"),
                      {"word.ply", "element 'vertex' 1 property 'y'", "'x' is not a number"}));
  EXPECT_TRUE(rejects(dir.write("inf.ply", ascii_header + "0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"),
                      {"inf.ply", "vertex 1", "NaN or infinite"}));
  EXPECT_TRUE(rejects(dir.write("short.ply", ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
                      {"short.ply", "element 'face' 0 of 1", "truncated"}));

  // OFF: counts beyond the data, out-of-range and oversized faces.
  EXPECT_TRUE(rejects(dir.write("counts.off", "OFF\n100000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                      {"counts.off", "OFF header", "declares 100000000 vertices"}));
  EXPECT_TRUE(rejects(dir.write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
                      {"range.off", "face 0", "vertex index 7 out of range (3 vertices)"}));
  EXPECT_TRUE(rejects(dir.write("coords.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
                      {"coords.off", "vertex 1", "expected 3 numbers"}));
  EXPECT_TRUE(rejects(dir.write("big.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n10 0 1 2 0 1 2 0 1 2 0\n"),
                      {"big.off", "face 0", "at most 9"}));

  EXPECT_TRUE(rejects(dir.write("garbage.xyz", "this is not a mesh\n"), {"garbage.xyz", "import", "Assimp cannot read it"}));
}

// A UV sphere of radius 1 around `centre` as ASCII PLY in double precision, with its normals.
std::string sphere_ply(const glm::dvec3& centre, int n = 8) {
  std::vector<glm::dvec3> unit;
  std::vector<glm::uvec3> faces;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double theta = M_PI * i / n, phi = M_PI * j / n;
      unit.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const unsigned a = static_cast<unsigned>(i * 2 * n + j), b = static_cast<unsigned>(i * 2 * n + (j + 1) % (2 * n));
      faces.emplace_back(a, a + 2 * n, b);
      faces.emplace_back(b, a + 2 * n, b + 2 * n);
    }
  std::ostringstream s;
  s.precision(17);
  s << "ply\nformat ascii 1.0\nelement vertex " << unit.size()
    << "\nproperty double x\nproperty double y\nproperty double z\nproperty double nx\nproperty double ny\n"
       "property double nz\nelement face "
    << faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const glm::dvec3& u : unit) {
    const glm::dvec3 p = centre + u;
    s << p.x << ' ' << p.y << ' ' << p.z << ' ' << u.x << ' ' << u.y << ' ' << u.z << '\n';
  }
  for (const glm::uvec3& f : faces) s << "3 " << f.x << ' ' << f.y << ' ' << f.z << '\n';
  return s.str();
}

// Faces of 1 or 2 vertices among triangles are left out with a warning naming the first.
TEST(LoadMesh, WarnsAboutPointAndLineFacesAmongTriangles) {
  TempDir dir;
  std::vector<std::string> warnings;
  const Mesh obj = load_mesh(dir.write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\nf 1 2\nf 4\n"),
                             &warnings);
  EXPECT_EQ(obj.triangle_count(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("mixed.obj: face 2: 2 faces of 1 or 2 vertices (points or lines) ignored"), std::string::npos)
      << warnings[0];

  warnings.clear();
  const Mesh off = load_mesh(dir.write("mixed.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 0 3\n3 0 1 2\n"), &warnings);
  EXPECT_EQ(off.triangle_count(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("mixed.off: face 0: 1 face of 1 or 2 vertices"), std::string::npos) << warnings[0];

  // Only triangles: no warning.
  warnings.clear();
  (void)load_mesh(dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), &warnings);
  EXPECT_TRUE(warnings.empty());
}

// Assimp drops every normal of a mesh with one normal index out of range (and the normals
// would be computed instead, silently): the file is refused like one with a bad vertex index.
TEST(LoadMesh, RejectsObjNormalIndicesOutOfRange) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n";
  EXPECT_TRUE(rejects(dir.write("normal.obj", tri + "f 1//1 2//1 3//5\n"),
                      {"normal.obj", "face at line 5", "normal index 5 out of range (1 in the file)"}));
  EXPECT_TRUE(rejects(dir.write("relative.obj", tri + "f 1//-1 2//-1 3//-2\n"),
                      {"relative.obj", "face at line 5", "normal index -2 out of range (1 defined before this line)"}));
  EXPECT_TRUE(rejects(dir.write("texture.obj", tri + "vt 0 0\nf 1/1/1 2/2/1 3/1/1\n"),
                      {"texture.obj", "face at line 6", "texture coordinate index 2 out of range"}));
  // A positive index may refer to an element defined further down, as Assimp reads it.
  const Mesh forward = load_mesh(dir.write("forward.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\nvn 0 0 1\n"));
  EXPECT_TRUE(forward.normals_from_file);
  EXPECT_EQ(forward.triangle_count(), 1u);
}

TEST(LoadMesh, RejectsTruncatedAsciiStl) {
  TempDir dir;
  const std::string facet =
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
      "    endloop\n  endfacet\n";
  const std::string whole = "solid t\n" + facet + facet + "endsolid t\n";
  EXPECT_EQ(load_mesh(dir.write("whole.stl", whole)).triangle_count(), 2u);
  // Cut between facets: Assimp loads one triangle without complaint.
  EXPECT_TRUE(rejects(dir.write("between.stl", "solid t\n" + facet),
                      {"between.stl", "endsolid", "truncated after 1 facet"}));
  // Cut inside a facet, and a facet with two vertices.
  const std::string cut = whole.substr(0, whole.find("vertex 1 0 0", whole.find("endfacet")));
  EXPECT_TRUE(rejects(dir.write("inside.stl", cut), {"inside.stl", "facet 1 (line 9)", "ends inside this facet"}));
  std::string two = whole;
  two.erase(two.find("      vertex 0 1 0\n"), 19);
  EXPECT_TRUE(rejects(dir.write("two.stl", two), {"two.stl", "facet 0 (line 2)", "2 vertices (a facet has 3)"}));
  EXPECT_TRUE(rejects(dir.write("word.stl", "solid t\n  facet normal 0 0 1\n    outer loop\n      vertex 0 x 0\n"),
                      {"word.stl", "facet 0", "expected 3 numbers"}));
  // The ASCII test models of assimp-testmodels (several solids, an empty one) still load.
  for (const char* name : {"Spider_ascii.stl", "sphereWithHole.stl", "triangle.stl", "triangle_with_empty_solid.stl",
                           "triangle_with_two_solids.stl", "Wuson.stl", "Spider_binary.stl"}) {
    const fs::path model = kModels / "STL" / name;
    if (!fs::exists(model)) continue;
    EXPECT_NO_THROW((void)load_mesh(model)) << model;
  }
}

// Assimp imports in single precision: a unit sphere 1e7 from the origin keeps a step of 1 and
// loses its shape (its normals then seem to cancel out). The message says what happened.
TEST(LoadMesh, RejectsCoordinatesSinglePrecisionCannotResolve) {
  TempDir dir;
  EXPECT_TRUE(rejects(dir.write("far.ply", sphere_ply(glm::dvec3(1e7, 0.0, 0.0))),
                      {"far.ply", "vertex coordinates", "x reaches 1e+07", "single precision", "steps of 1,",
                       "50 % of the mesh extent 2", "move the mesh near the origin"}));
  EXPECT_TRUE(rejects(dir.write("far_z.ply", sphere_ply(glm::dvec3(0.0, 0.0, -1e5))),
                      {"far_z.ply", "z reaches 100001", "single precision"}));
  // Near enough: the float32 step at 1000 is 6e-5 of a mesh 2 across.
  const Mesh near = load_mesh(dir.write("near.ply", sphere_ply(glm::dvec3(1000.0, 0.0, 0.0))));
  EXPECT_EQ(near.triangle_count(), 256u);
  // Everything at one point far out: kept (a degenerate mesh), with a warning.
  std::vector<std::string> warnings;
  const Mesh point = load_mesh(dir.write("point.obj", "v 1e7 1 1\nv 1e7 1 1\nv 1e7 1 1\nf 1 2 3\n"), &warnings);
  EXPECT_EQ(point.triangle_count(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("point.obj: vertex coordinates: all vertices import at one position"), std::string::npos)
      << warnings[0];
}

// Readers whose node graph lists meshes or children it does not hold (Assimp's RAW reader):
// read without a crash.
TEST(LoadMesh, RawModelsLoad) {
  for (const char* name : {"WithColor.raw", "WithTexture.raw"}) {
    const fs::path model = kModels / "RAW" / name;
    if (!fs::exists(model)) FAIL() << model << " is missing: scripts/setup.sh installs assimp-testmodels";
    const Mesh mesh = load_mesh(model);
    EXPECT_GT(mesh.triangle_count(), 0u) << model;
  }
}

// Files outside invalid/ that Assimp reads without complaint although they contradict their
// own headers.
TEST(LoadMesh, AssimpTestModelsThatContradictTheirHeaders) {
  const fs::path pond = kModels / "PLY/pond.0.ply", issue623 = kModels / "PLY/issue623.ply";
  if (!fs::exists(pond) || !fs::exists(issue623)) FAIL() << "assimp-testmodels is missing: scripts/setup.sh installs it";
  // 70051 vertices of 31 bytes declared; the last 23 bytes are missing.
  EXPECT_TRUE(rejects(pond, {"pond.0.ply", "element 'vertex' 70048 of 70051", "truncated"}));
  // The header puts a vertex_indices list on the vertex element and declares no faces.
  EXPECT_TRUE(rejects(issue623, {"issue623.ply", "element 'vertex' 0 property 'vertex_indices'",
                                 "'7.941797' is not a list length"}));
}

TEST(LoadMesh, WeldsSplitNormalCubeAndAveragesFileNormals) {
  TempDir dir;
  // A cube with one normal per face: every corner appears in three faces with three normals.
  const std::string cube =
      "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
      "f 1//1 4//1 3//1 2//1\nf 5//2 6//2 7//2 8//2\nf 1//3 2//3 6//3 5//3\n"
      "f 4//4 8//4 7//4 3//4\nf 1//5 5//5 8//5 4//5\nf 2//6 3//6 7//6 6//6\n";
  const Mesh mesh = load_mesh(dir.write("cube.obj", cube));
  ASSERT_EQ(mesh.vertex_count(), 8u);
  EXPECT_EQ(mesh.triangle_count(), 12u);
  EXPECT_TRUE(mesh.normals_from_file);
  ASSERT_EQ(mesh.normals.size(), 8u);
  for (std::size_t v = 0; v < 8; ++v) {
    const glm::dvec3 p = mesh.positions[v];
    EXPECT_EQ(glm::abs(p), glm::dvec3(1.0));
    // The three face normals at a corner average to its diagonal direction.
    EXPECT_LT(glm::length(mesh.normals[v] - p / std::sqrt(3.0)), 1e-15) << v;
  }
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0), 0.0) << "winding kept (outward)";
  }
}

TEST(LoadMesh, ZeroNormalCopyIgnoredWhereAnotherCopyHasADirection) {
  TempDir dir;
  // Vertex 3 appears twice: once with (0,0,0), once with +Z.
  const Mesh mesh = load_mesh(dir.write("mixed.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 0\n"
                                        "f 1//1 2//1 3//2\nf 2//1 4//1 3//1\n"));
  ASSERT_EQ(mesh.vertex_count(), 4u);
  for (const glm::dvec3& n : mesh.normals) EXPECT_EQ(n, glm::dvec3(0, 0, 1));
}

// Geodesic sphere: an icosahedron subdivided twice, projected to the unit sphere.
std::string icosphere_off(int subdivisions, glm::dvec3 center) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (glm::dvec3& p : v) p = glm::normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto midpoint = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      const auto [it, inserted] = mid.try_emplace(key, static_cast<unsigned>(v.size()));
      if (inserted) v.push_back(glm::normalize(v[a] + v[b]));
      return it->second;
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& tri : f) {
      const unsigned a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], a, c}, {tri[1], b, a}, {tri[2], c, b}, {a, b, c}});
    }
    f = next;
  }
  std::string s = "OFF\n" + std::to_string(v.size()) + " " + std::to_string(f.size()) + " 0\n";
  char line[128];
  for (const glm::dvec3& p : v) {
    const glm::dvec3 q = p + center;
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", q.x, q.y, q.z);
    s += line;
  }
  for (const glm::uvec3& tri : f) s += "3 " + std::to_string(tri[0]) + " " + std::to_string(tri[1]) + " " + std::to_string(tri[2]) + "\n";
  return s;
}

TEST(LoadMesh, ComputedNormalsOfAClosedConvexMeshPointOutward) {
  TempDir dir;
  const glm::dvec3 center(3.0, -2.0, 0.5);
  const Mesh mesh = load_mesh(dir.write("sphere.off", icosphere_off(2, center)));
  ASSERT_EQ(mesh.vertex_count(), 162u);
  ASSERT_EQ(mesh.triangle_count(), 320u);
  EXPECT_FALSE(mesh.normals_from_file);
  double worst = 1.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    ASSERT_TRUE(is_unit(mesh.normals[v]));
    worst = std::min(worst, glm::dot(mesh.normals[v], glm::normalize(mesh.positions[v] - center)));
  }
  // Outward, and close to the radial direction of the sphere the mesh approximates.
  EXPECT_GT(worst, 0.995);
  EXPECT_EQ(mesh_stats(mesh).normal_fallbacks, 0u);

  // The same sphere turned inside out (every face reversed) has inward normals.
  std::string inverted;
  {
    std::istringstream in(icosphere_off(2, center));
    std::string line;
    while (std::getline(in, line)) {
      int a, b, c;
      if (std::sscanf(line.c_str(), "3 %d %d %d", &a, &b, &c) == 3)
        line = "3 " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(b);
      inverted += line + "\n";
    }
  }
  const Mesh inside_out = load_mesh(dir.write("inverted.off", inverted));
  for (std::size_t v = 0; v < inside_out.vertex_count(); ++v)
    EXPECT_LT(glm::dot(inside_out.normals[v], inside_out.positions[v] - center), 0.0);
}

TEST(LoadMesh, ComputedNormalsAreAreaTimesAngleWeighted) {
  TempDir dir;
  // Vertex 0 is shared by a large triangle in the z = 0 plane (area 2, right angle at vertex 0)
  // and a small one in the x = 0 plane (area 1/8, angle 45 degrees at vertex 0).
  const Mesh mesh = load_mesh(dir.write("fan.obj",
                                        "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 0.5\nv 0 -0.5 0.5\n"
                                        "f 1 2 3\nf 1 4 5\n"));
  ASSERT_EQ(mesh.vertex_count(), 5u);
  const double pi = std::acos(-1.0);
  const glm::dvec3 expected = glm::normalize(2.0 * (pi / 2) * glm::dvec3(0, 0, 1) + 0.125 * (pi / 4) * glm::dvec3(1, 0, 0));
  EXPECT_LT(glm::length(mesh.normals[0] - expected), 1e-15);
}

TEST(LoadMesh, DegenerateTrianglesAreCountedAndGetADefinedNormal) {
  TempDir dir;
  // A good triangle, a separate collinear one (vertices 4-6) and one repeating a position
  // (vertex 7 coincides with vertex 1, so it welds and the triangle has a zero-length edge).
  const Mesh mesh = load_mesh(dir.write("degenerate.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                        "v 5 5 5\nv 6 6 6\nv 7 7 7\n"
                                        "v 0 0 0\n"
                                        "f 1 2 3\nf 4 5 6\nf 1 2 7\n"));
  ASSERT_EQ(mesh.vertex_count(), 6u);
  ASSERT_EQ(mesh.triangle_count(), 3u);
  const MeshStats stats = mesh_stats(mesh);
  EXPECT_EQ(stats.degenerate_triangles, 2u);
  EXPECT_EQ(stats.zero_length_edges, 1u);
  EXPECT_EQ(stats.normal_fallbacks, 3u);  // the three collinear vertices
  for (const glm::dvec3& n : mesh.normals) EXPECT_TRUE(is_unit(n));
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions[v].x >= 5.0) {
      EXPECT_EQ(mesh.normals[v], glm::dvec3(0, 0, 1));
    }
}

TEST(LoadMesh, MergesMeshesApplyingNodeTransforms) {
  TempDir dir;
  // glTF: one triangle mesh instanced by two nodes, the second translated by +10 in x and
  // rotated 90 degrees about z.
  const std::string gltf = R"({
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0}, {"mesh": 0, "matrix": [0,1,0,0, -1,0,0,0, 0,0,1,0, 10,0,0,1]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
    "buffers": [{"byteLength": 78, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAABAAIA"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 6}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}]
  })";
  const Mesh mesh = load_mesh(dir.write("two.gltf", gltf));
  ASSERT_EQ(mesh.vertex_count(), 6u);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_TRUE(mesh.normals_from_file);
  std::set<std::tuple<double, double, double>> positions;
  for (const glm::dvec3& p : mesh.positions) positions.insert({p.x, p.y, p.z});
  const std::set<std::tuple<double, double, double>> expected = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                                                 {10, 0, 0}, {10, 1, 0}, {9, 0, 0}};
  EXPECT_EQ(positions, expected);
  for (const glm::dvec3& n : mesh.normals) EXPECT_LT(glm::length(n - glm::dvec3(0, 0, 1)), 1e-7);
}

struct RealModel {
  const char* path;
  std::size_t vertices, triangles;
  bool normals_from_file;
};

TEST(LoadMesh, RealModelsLoadWithPlausibleCounts) {
  const RealModel models[] = {
      // Blender export with per-corner copies (11184 file vertices) of 2117 positions.
      {"PLY/Wuson.ply", 2117, 3732, true},
      // The same model, 3205 OFF vertices of which identical positions weld to 2117.
      {"OFF/Wuson.off", 2117, 3732, false},
      // 19 meshes merged; 762 'v' lines hold 722 distinct positions.
      {"OBJ/spider.obj", 722, 1368, true},
      // STL facet normals are per face, so vertex normals are computed.
      {"STL/sphereWithHole.stl", 146, 285, false},
  };
  for (const RealModel& m : models) {
    const fs::path file = kModels / m.path;
    if (!fs::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
    SCOPED_TRACE(m.path);
    const Mesh mesh = load_mesh(file);
    EXPECT_EQ(mesh.source, file.string());
    EXPECT_EQ(mesh.vertex_count(), m.vertices);
    EXPECT_EQ(mesh.triangle_count(), m.triangles);
    EXPECT_EQ(mesh.normals_from_file, m.normals_from_file);
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const glm::dvec3& n : mesh.normals) ASSERT_TRUE(is_unit(n));
    std::set<std::tuple<double, double, double>> distinct;
    for (const glm::dvec3& p : mesh.positions) distinct.insert({p.x, p.y, p.z});
    EXPECT_EQ(distinct.size(), mesh.vertex_count()) << "one vertex per distinct position";
    std::vector<bool> used(mesh.vertex_count(), false);
    for (const glm::uvec3& t : mesh.triangles)
      for (int c = 0; c < 3; ++c) {
        ASSERT_LT(t[c], mesh.vertex_count());
        used[t[c]] = true;
      }
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0) << "every vertex belongs to a triangle";
  }
}

// Blender's exported vertex normals (Wuson.ply) against the ones computed from the same model's
// geometry in other files: a plausibility check of the area x angle weighting on real data.
TEST(LoadMesh, WusonComputedNormalsAgreeWithTheExportedOnes) {
  const fs::path ply = kModels / "PLY/Wuson.ply", stl = kModels / "STL/Wuson.stl", off = kModels / "OFF/Wuson.off";
  if (!fs::exists(ply) || !fs::exists(stl) || !fs::exists(off)) FAIL() << "assimp-testmodels is missing: scripts/setup.sh installs it";
  const Mesh exported = load_mesh(ply);
  ASSERT_TRUE(exported.normals_from_file);
  const double diagonal = bounding_box(exported).diagonal();

  // Counts the computed normals within 26 degrees of (dot > 0.9) and opposite to (dot < -0.9)
  // the exported normal at the nearest exported position.
  auto compare = [&](const Mesh& computed, std::size_t& close, std::size_t& opposite) {
    close = opposite = 0;
    for (std::size_t v = 0; v < computed.vertex_count(); ++v) {
      std::size_t nearest = 0;
      double distance = INFINITY;
      for (std::size_t w = 0; w < exported.vertex_count(); ++w) {
        const double d = glm::length(exported.positions[w] - computed.positions[v]);
        if (d < distance) distance = d, nearest = w;
      }
      ASSERT_LT(distance, 1e-6 * diagonal) << "same model, same positions (up to STL's float rounding)";
      const double cosine = glm::dot(exported.normals[nearest], computed.normals[v]);
      close += cosine > 0.9;
      opposite += cosine < -0.9;
    }
  };
  std::size_t close = 0, opposite = 0;
  const Mesh from_stl = load_mesh(stl);
  ASSERT_FALSE(from_stl.normals_from_file);
  ASSERT_EQ(from_stl.vertex_count(), exported.vertex_count());
  compare(from_stl, close, opposite);
  // Measured: 2086 of 2117 (Blender weights the faces its own way).
  EXPECT_GT(close, from_stl.vertex_count() * 97 / 100) << close << " of " << from_stl.vertex_count();

  // Wuson.off lists every face in the opposite order (its face 0 is "3 2 0 1" where the PLY's
  // is the same corners as 0 1 2), so its computed normals follow its winding, inward.
  const Mesh from_off = load_mesh(off);
  ASSERT_FALSE(from_off.normals_from_file);
  compare(from_off, close, opposite);
  EXPECT_GT(opposite, from_off.vertex_count() * 97 / 100) << opposite << " of " << from_off.vertex_count();

  const MeshStats a = mesh_stats(exported), b = mesh_stats(from_off);
  EXPECT_EQ(a.bbox.lo, b.bbox.lo);
  EXPECT_EQ(a.bbox.hi, b.bbox.hi);
  EXPECT_NEAR(a.bbox.diagonal(), 3.697389, 1e-6);
}

TEST(MeshStats, CountsOnAHandBuiltMesh) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 0}};
  mesh.normals.assign(mesh.positions.size(), glm::dvec3(0, 0, 1));
  mesh.normals_from_file = true;
  mesh.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 4, 1}, {2, 2, 2}};
  const MeshStats stats = mesh_stats(mesh);
  EXPECT_EQ(stats.vertices, 5u);
  EXPECT_EQ(stats.triangles, 4u);
  EXPECT_EQ(stats.degenerate_triangles, 3u);  // collinear, repeated position, single point
  EXPECT_EQ(stats.zero_length_edges, 1u + 3u);
  // Distinct index pairs: 01 12 02 13 03 04 14 (01 counted once; 4 is not welded to 0 here;
  // the single-point triangle has no edge between distinct vertices).
  EXPECT_EQ(stats.edges, 7u);
  EXPECT_EQ(stats.normal_fallbacks, 0u);  // normals from a file never fall back
  EXPECT_EQ(stats.bbox.lo, glm::dvec3(0, 0, 0));
  EXPECT_EQ(stats.bbox.hi, glm::dvec3(2, 1, 0));
  EXPECT_DOUBLE_EQ(stats.bbox.diagonal(), std::sqrt(5.0));
}

// ---------------------------------------------------------------------------------------------
// Writer

// A curved patch of pattern_vertex_count(L) distinct points with unit normals.
void make_patch_data(int L, double offset, std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) {
  positions.clear();
  normals.clear();
  for (const DomainPoint& d : pattern_points(L)) {
    const double u = static_cast<double>(d.j) / L, v = static_cast<double>(d.k) / L;
    positions.emplace_back(offset + u + 0.1234567891234, v - 0.0000123456789, 0.3 * u * v + 1e-3 / 3.0);
    normals.push_back(glm::normalize(glm::dvec3(-0.3 * v, -0.3 * u, 1.0)));
  }
}

void round_trip(const std::string& extension) {
  TempDir dir;
  const fs::path file = dir.path() / ("patches" + extension);
  // Factors 2, 2, 3 exercise the PLY face list generated from runs of equal factors.
  const int factors[] = {2, 2, 3};
  std::vector<std::vector<glm::dvec3>> written_p, written_n;
  std::uint64_t total_v = 0, total_t = 0;
  for (int L : factors) {
    total_v += static_cast<std::uint64_t>(pattern_vertex_count(L));
    total_t += static_cast<std::uint64_t>(pattern_triangle_count(L));
  }
  {
    MeshWriter writer(file, total_v, total_t);
    for (std::size_t i = 0; i < std::size(factors); ++i) {
      written_p.emplace_back();
      written_n.emplace_back();
      make_patch_data(factors[i], 2.0 * static_cast<double>(i), written_p.back(), written_n.back());
      writer.add_patch(factors[i], written_p.back().data(), written_n.back().data());
    }
    EXPECT_FALSE(fs::exists(file)) << "nothing reaches the target before finish()";
    writer.finish();
  }
  ASSERT_TRUE(fs::exists(file));
  EXPECT_EQ(dir.entries().size(), 1u) << "no temporary left behind";

  const Mesh mesh = load_mesh(file);
  ASSERT_EQ(mesh.vertex_count(), total_v);  // all points distinct: nothing welds
  ASSERT_EQ(mesh.triangle_count(), total_t);
  EXPECT_TRUE(mesh.normals_from_file);

  // Assimp reads float32: compare within float precision.
  const double tol = 4.0 * std::ldexp(1.0, -24) * 8.0;  // |coordinates| < 8
  auto find = [&](const glm::dvec3& p) -> std::pair<std::size_t, std::size_t> {
    for (std::size_t patch = 0; patch < written_p.size(); ++patch)
      for (std::size_t i = 0; i < written_p[patch].size(); ++i)
        if (glm::length(written_p[patch][i] - p) <= tol) return {patch, i};
    return {SIZE_MAX, SIZE_MAX};
  };
  std::vector<std::pair<std::size_t, std::size_t>> source(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    source[v] = find(mesh.positions[v]);
    ASSERT_NE(source[v].first, SIZE_MAX) << "loaded vertex " << v << " matches no written vertex";
    EXPECT_LE(glm::length(mesh.normals[v] - written_n[source[v].first][source[v].second]), 4e-7);
  }
  // Topology: every loaded triangle is a pattern triangle of one patch, with its winding.
  std::set<std::tuple<std::size_t, unsigned, unsigned, unsigned>> expected, loaded;
  for (std::size_t patch = 0; patch < std::size(factors); ++patch)
    for (const glm::uvec3& t : pattern_triangles(factors[patch])) {
      // Rotate so the smallest index comes first: same triangle, same winding.
      glm::uvec3 r = t;
      while (r[0] != std::min({t[0], t[1], t[2]})) r = glm::uvec3(r[1], r[2], r[0]);
      expected.insert({patch, r[0], r[1], r[2]});
    }
  for (const glm::uvec3& t : mesh.triangles) {
    const auto a = source[t[0]], b = source[t[1]], c = source[t[2]];
    ASSERT_TRUE(a.first == b.first && b.first == c.first) << "triangle spans patches";
    glm::uvec3 r(a.second, b.second, c.second);
    const unsigned lowest = std::min({r[0], r[1], r[2]});
    while (r[0] != lowest) r = glm::uvec3(r[1], r[2], r[0]);
    loaded.insert({a.first, r[0], r[1], r[2]});
  }
  EXPECT_EQ(loaded, expected);
}

TEST(MeshWriter, PlyRoundTrip) { round_trip(".ply"); }
TEST(MeshWriter, ObjRoundTrip) { round_trip(".obj"); }
TEST(MeshWriter, ExtensionIsCaseInsensitive) {
  EXPECT_TRUE(is_supported_output("a/b.PLY"));
  EXPECT_TRUE(is_supported_output("b.Obj"));
  EXPECT_FALSE(is_supported_output("b.stl"));
  EXPECT_FALSE(is_supported_output("ply"));
  round_trip(".OBJ");
}

TEST(MeshWriter, ObjKeepsEveryDoubleExactly) {
  TempDir dir;
  const fs::path file = dir.path() / "exact.obj";
  std::vector<glm::dvec3> p, n;
  make_patch_data(4, 0.0, p, n);
  p[3] = glm::dvec3(1.0 / 3.0, -2.0e-300, 123456789.123456789);
  MeshWriter writer(file, p.size(), 16);
  writer.add_patch(4, p.data(), n.data());
  writer.finish();
  std::ifstream in(file);
  std::string kind;
  std::vector<glm::dvec3> vs, vns;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    s >> kind;
    glm::dvec3 x;
    if (kind == "v" || kind == "vn") {
      std::string a, b, c;
      s >> a >> b >> c;
      x = {std::strtod(a.c_str(), nullptr), std::strtod(b.c_str(), nullptr), std::strtod(c.c_str(), nullptr)};
      (kind == "v" ? vs : vns).push_back(x);
    }
  }
  ASSERT_EQ(vs.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(vs[i], p[i]);
    EXPECT_EQ(vns[i], n[i]);
  }
}

TEST(MeshWriter, FailedWritesLeaveNoFile) {
  TempDir dir;
  std::vector<glm::dvec3> p, n;
  make_patch_data(2, 0.0, p, n);

  // Unwritable target: a directory that does not exist.
  EXPECT_THROW(MeshWriter(dir.path() / "no_such_dir" / "out.ply", 6, 4), InputError);
  // Unsupported extension.
  EXPECT_THROW(MeshWriter(dir.path() / "out.stl", 6, 4), InputError);
  // Abandoned before finish() (an exception while tessellating, say).
  {
    MeshWriter writer(dir.path() / "abandoned.ply", 12, 8);
    writer.add_patch(2, p.data(), n.data());
  }
  // Fewer patches than declared: finish() refuses.
  {
    MeshWriter writer(dir.path() / "short.obj", 12, 8);
    writer.add_patch(2, p.data(), n.data());
    EXPECT_THROW(writer.finish(), std::logic_error);
  }
  // More patches than declared.
  {
    MeshWriter writer(dir.path() / "long.ply", 6, 4);
    writer.add_patch(2, p.data(), n.data());
    EXPECT_THROW(writer.add_patch(2, p.data(), n.data()), std::logic_error);
  }
  EXPECT_TRUE(dir.entries().empty()) << "left behind: " << ::testing::PrintToString(dir.entries());
}

TEST(MeshWriter, ReplacesAnExistingFileOnlyOnSuccess) {
  TempDir dir;
  const fs::path file = dir.write("out.ply", "previous contents");
  std::vector<glm::dvec3> p, n;
  make_patch_data(2, 0.0, p, n);
  {
    MeshWriter writer(file, 12, 8);
    writer.add_patch(2, p.data(), n.data());
  }
  std::ifstream in(file);
  std::string contents((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(contents, "previous contents");
}

}  // namespace
}  // namespace tessim
