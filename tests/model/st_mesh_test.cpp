// Scalar-tagged meshes (docs/stpn.md): tags read from PLY vertex properties (ASCII, binary little
// and big endian) and written back, their checks (values, welding, the two rules of the format),
// tag statistics, and the import of meshes with hard edges (model/stpn_import.hpp), whose
// tessellation must stay closed: both patches of every edge put bit-identical points on it.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "model/base/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"
#include "model/st_mesh.hpp"
#include "model/stpn_import.hpp"
#include "model/tessellate.hpp"
#include "tests/support/prism_mesh.hpp"
#include "tests/support/rejects.hpp"
#include "tests/support/shared_edges.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::prism_obj;
using tessim::testing::rejects;
using tessim::testing::TempDir;

const fs::path kModels = "/usr/share/assimp/models";

// ---------------------------------------------------------------------------------------------
// Small tagged PLY files.

struct PlyVertex {
  glm::vec3 p;
  glm::vec3 n{0, 0, 1};
  VertexTags t{};
};

VertexTags tags(glm::dvec3 delta, double sigma, double theta = 0.0, double beta = 0.0) {
  VertexTags t;
  t.delta = delta;
  t.sigma = sigma;
  t.theta = theta;
  t.beta = beta;
  return t;
}

std::string ascii_ply(const std::vector<PlyVertex>& vertices, const std::vector<std::vector<unsigned>>& faces,
                      bool with_tags = true) {
  std::ostringstream s;
  s.precision(17);
  s << "ply\nformat ascii 1.0\nelement vertex " << vertices.size() << "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) s << "property float " << p << "\n";
  if (with_tags)
    for (const char* p : {"dx", "dy", "dz", "sigma", "theta", "beta"}) s << "property double " << p << "\n";
  s << "element face " << faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const PlyVertex& v : vertices) {
    s << v.p.x << " " << v.p.y << " " << v.p.z << " " << v.n.x << " " << v.n.y << " " << v.n.z;
    if (with_tags)
      s << " " << v.t.delta.x << " " << v.t.delta.y << " " << v.t.delta.z << " " << v.t.sigma << " " << v.t.theta << " "
        << v.t.beta;
    s << "\n";
  }
  for (const auto& f : faces) {
    s << f.size();
    for (unsigned i : f) s << " " << i;
    s << "\n";
  }
  return s.str();
}

template <class T>
void put(std::string& s, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian) std::reverse(bytes, bytes + sizeof(T));
  s.append(bytes, sizeof(T));
}

// Binary PLY with the tags in mixed types: Δ as doubles, σ θ β as floats (the test values are
// exact in float), a property Assimp does not know in between.
std::string binary_ply(const std::vector<PlyVertex>& vertices, const std::vector<std::vector<unsigned>>& faces,
                       bool big_endian) {
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") + " 1.0\n";
  s += "element vertex " + std::to_string(vertices.size()) + "\n";
  s += "property float x\nproperty float y\nproperty float z\nproperty float sigma\nproperty uchar quality\n"
       "property double dx\nproperty double dy\nproperty double dz\nproperty float nx\nproperty float ny\n"
       "property float nz\nproperty float theta\nproperty float beta\n";
  s += "element face " + std::to_string(faces.size()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (const PlyVertex& v : vertices) {
    for (int i = 0; i < 3; ++i) put<float>(s, v.p[i], big_endian);
    put<float>(s, static_cast<float>(v.t.sigma), big_endian);
    put<std::uint8_t>(s, 7, big_endian);
    for (int i = 0; i < 3; ++i) put<double>(s, v.t.delta[i], big_endian);
    for (int i = 0; i < 3; ++i) put<float>(s, v.n[i], big_endian);
    put<float>(s, static_cast<float>(v.t.theta), big_endian);
    put<float>(s, static_cast<float>(v.t.beta), big_endian);
  }
  for (const auto& f : faces) {
    put<std::uint8_t>(s, static_cast<std::uint8_t>(f.size()), big_endian);
    for (unsigned i : f) put<std::uint32_t>(s, i, big_endian);
  }
  return s;
}

// A strip of two triangles along x; vertices 0 and 1 tagged (a crease edge 0-1), vertex 3 with
// tension only.
std::vector<PlyVertex> strip_vertices() {
  return {
      {{0, 0, 0}, {0, 0, 1}, tags({0, 1.5, 0}, 0.5, 0.25, -0.75)},
      {{1, 0, 0}, {0, 0, 1}, tags({0, 0.5, 0}, 1.0, 0.0, 0.5)},
      {{0, 1, 0}, {0, 0, 1}, {}},
      {{1, 1, 0}, {0, 0, 1}, tags({0, 0, 0}, 0.0, 1.0, 0.0)},
  };
}
const std::vector<std::vector<unsigned>> kStripFaces = {{0, 1, 2}, {1, 3, 2}};

// A closed fan: centre 0, ring 1..6 in the plane z = 0.
std::vector<PlyVertex> fan_vertices() {
  std::vector<PlyVertex> v{{{0, 0, 0}}};
  for (int i = 0; i < 6; ++i) {
    const double a = i * 3.14159265358979323846 / 3.0;
    v.push_back({{static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f}});
  }
  return v;
}
const std::vector<std::vector<unsigned>> kFanFaces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 1}};


void expect_same_mesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.tags, b.tags);
}

// ---------------------------------------------------------------------------------------------
// Reading and writing tags.

TEST(TaggedPly, AsciiTagsAreReadExactly) {
  TempDir dir;
  const std::vector<PlyVertex> vertices = strip_vertices();
  const Mesh mesh = load_mesh(dir.write("strip.ply", ascii_ply(vertices, kStripFaces)));
  ASSERT_EQ(mesh.vertex_count(), 4u);
  ASSERT_TRUE(mesh.has_tags());
  ASSERT_EQ(mesh.tags.size(), 4u);
  for (std::size_t v = 0; v < 4; ++v) EXPECT_EQ(mesh.tags[v], vertices[v].t) << "vertex " << v;
  const TagStats s = tag_stats(mesh);
  EXPECT_TRUE(s.present);
  EXPECT_EQ(s.tagged, 2u);
  EXPECT_EQ(s.crease, 2u);
  EXPECT_EQ(s.softened, 0u);
  EXPECT_EQ(s.corner_like, 1u);
  EXPECT_EQ(s.tagged_edges, 1u);
  EXPECT_EQ(s.sigma_min, 0.5);
  EXPECT_EQ(s.sigma_max, 1.0);
  EXPECT_EQ(s.theta_min, 0.0);
  EXPECT_EQ(s.theta_max, 1.0);
  EXPECT_EQ(s.beta_min, -0.75);
  EXPECT_EQ(s.beta_max, 0.5);
  EXPECT_EQ(s.delta_min, 0.5);
  EXPECT_EQ(s.delta_max, 1.5);
}

TEST(TaggedPly, BinaryLittleAndBigEndianGiveTheAsciiMesh) {
  TempDir dir;
  const std::vector<PlyVertex> vertices = strip_vertices();
  const Mesh ascii = load_mesh(dir.write("a.ply", ascii_ply(vertices, kStripFaces)));
  const Mesh little = load_mesh(dir.write("le.ply", binary_ply(vertices, kStripFaces, false)));
  const Mesh big = load_mesh(dir.write("be.ply", binary_ply(vertices, kStripFaces, true)));
  expect_same_mesh(little, ascii);
  expect_same_mesh(big, ascii);
}

TEST(TaggedPly, QuadsAreTriangulatedWithTheirTags) {
  TempDir dir;
  const std::vector<PlyVertex> vertices = strip_vertices();
  const Mesh mesh = load_mesh(dir.write("quad.ply", ascii_ply(vertices, {{0, 1, 3, 2}})));
  ASSERT_EQ(mesh.triangle_count(), 2u);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    // Match by position: the tags travel with their vertex.
    const auto it = std::find_if(vertices.begin(), vertices.end(),
                                 [&](const PlyVertex& p) { return glm::dvec3(p.p) == mesh.positions[v]; });
    ASSERT_NE(it, vertices.end());
    EXPECT_EQ(mesh.tags[v], it->t);
  }
}

TEST(TaggedPly, ReadWriteReadIsExact) {
  TempDir dir;
  for (const bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary input" : "ASCII input");
    const std::vector<PlyVertex> vertices = strip_vertices();
    const fs::path input = dir.write(binary ? "in_b.ply" : "in_a.ply",
                                     binary ? binary_ply(vertices, kStripFaces, false) : ascii_ply(vertices, kStripFaces));
    const Mesh first = load_mesh(input);
    write_ply(first, dir.path() / "once.ply");
    const Mesh second = load_mesh(dir.path() / "once.ply");
    expect_same_mesh(second, first);
    EXPECT_TRUE(second.normals_from_file);
    // And the written file is a fixed point: writing the reread mesh gives the same bytes.
    write_ply(second, dir.path() / "twice.ply");
    std::ifstream a(dir.path() / "once.ply", std::ios::binary), b(dir.path() / "twice.ply", std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
  }
}

TEST(TaggedPly, UntaggedFilesHaveNoTags) {
  TempDir dir;
  const Mesh plain = load_mesh(dir.write("plain.ply", ascii_ply(strip_vertices(), kStripFaces, false)));
  EXPECT_FALSE(plain.has_tags());
  EXPECT_FALSE(tag_stats(plain).present);
  EXPECT_EQ(tag_stats(plain).tagged, 0u);
  // Written back without tag properties, read back without tags.
  write_ply(plain, dir.path() / "plain_out.ply");
  EXPECT_FALSE(load_mesh(dir.path() / "plain_out.ply").has_tags());
  // OBJ carries no tags.
  const Mesh obj = load_mesh(dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_FALSE(obj.has_tags());

  // One tag property alone: the others are zero, and the mesh is tagged (all neutral here).
  const std::string sigma_only =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float sigma\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0.5\n1 0 0 0\n0 1 0 0\n3 0 1 2\n";
  const Mesh partial = load_mesh(dir.write("sigma.ply", sigma_only));
  ASSERT_TRUE(partial.has_tags());
  EXPECT_EQ(partial.tags[0], tags({0, 0, 0}, 0.5));
  EXPECT_EQ(tag_stats(partial).tagged, 0u);
}

TEST(TaggedPly, WeldedCopiesMustAgree) {
  TempDir dir;
  // Vertex 3 repeats vertex 1's position: the same tags weld, different ones are an error.
  std::vector<PlyVertex> v = strip_vertices();
  v.push_back(v[1]);
  const std::vector<std::vector<unsigned>> faces = {{0, 4, 2}, {1, 3, 2}};
  const Mesh same = load_mesh(dir.write("same.ply", ascii_ply(v, faces)));
  EXPECT_EQ(same.vertex_count(), 4u);
  EXPECT_EQ(same.tags[1], v[1].t);
  v[4].t.sigma = 0.25;
  EXPECT_TRUE(rejects(dir.write("differ.ply", ascii_ply(v, faces)),
                      {"differ.ply: vertex 1: its tags", "differ from those of vertex 4", "welded"}));
}

TEST(TaggedPly, BadTagValuesAreRejected) {
  TempDir dir;
  struct Case {
    const char* name;
    VertexTags bad;
    std::vector<std::string> expected;
  };
  const double nan = std::nan(""), inf = INFINITY;
  const Case cases[] = {
      {"nan_sigma.ply", tags({0, 1, 0}, nan), {"vertex 0", "sigma is nan", "finite"}},
      {"inf_dx.ply", tags({inf, 1, 0}, 1), {"vertex 0", "dx is inf"}},
      {"nan_beta.ply", tags({0, 0, 0}, 0, 0, nan), {"vertex 0", "beta is nan"}},
      {"negative_sigma.ply", tags({0, 1, 0}, -0.5), {"vertex 0", "sigma -0.5 is negative"}},
      {"theta.ply", tags({0, 1, 0}, 1, 1.5), {"vertex 0", "theta 1.5 is outside [-1, 1]"}},
      {"beta.ply", tags({0, 1, 0}, 1, 0, -2), {"vertex 0", "beta -2 is outside [-1, 1]"}},
      // N + βΔ = 0: Y of docs/mathematics.md §9 has no direction.
      {"vanishing.ply", tags({0, 0, -2}, 0, 0, 0.5), {"vertex 0", "N + βΔ vanishes"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<PlyVertex> v = strip_vertices();
    v[0].t = c.bad;
    EXPECT_TRUE(rejects(dir.write(c.name, ascii_ply(v, kStripFaces)), c.expected));
    EXPECT_TRUE(rejects(dir.write(std::string("le_") + c.name, binary_ply(v, kStripFaces, false)), c.expected));
  }
  // The words "nan" and "inf" in an ASCII file.
  std::string text = ascii_ply(strip_vertices(), kStripFaces);
  const std::size_t at = text.find("0 1.5 0 0.5");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "0 1.5 0 nan");
  EXPECT_TRUE(rejects(dir.write("nan_word.ply", text), {"nan_word.ply: vertex 0: tag sigma is nan"}));
  // A tag declared as a list.
  const std::string list =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property list uchar float sigma\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1 0.5\n1 0 0 0\n0 1 0 0\n3 0 1 2\n";
  EXPECT_TRUE(rejects(dir.write("list.ply", list), {"list.ply", "property 'sigma'", "is a list"}));
}

TEST(TaggedPly, TaggedVertexWithThreeTaggedNeighboursIsRejected) {
  TempDir dir;
  std::vector<PlyVertex> v = fan_vertices();
  for (unsigned i : {0u, 1u, 3u, 5u}) v[i].t = tags({1, 0, 0}, 1);
  EXPECT_TRUE(rejects(dir.write("fan.ply", ascii_ply(v, kFanFaces)),
                      {"fan.ply: vertex 0: tagged, with 3 tagged neighbours (vertex 1, vertex 3, vertex 5)",
                       "at most 2"}));
  // Two tagged neighbours are allowed.
  v[5].t = {};
  EXPECT_NO_THROW(load_mesh(dir.write("fan_ok.ply", ascii_ply(v, kFanFaces))));
}

TEST(TaggedPly, TriangleWithThreeTaggedVerticesIsRejected) {
  TempDir dir;
  std::vector<PlyVertex> v = fan_vertices();
  for (unsigned i : {0u, 3u, 4u}) v[i].t = tags({1, 0, 0}, 1);
  EXPECT_TRUE(rejects(dir.write("tri.ply", ascii_ply(v, kFanFaces)),
                      {"tri.ply: triangle 2: all three of its vertices (vertex 0, vertex 3, vertex 4) are tagged",
                       "at most 2"}));
}

TEST(TaggedPly, EveryViolationIsListed) {
  TempDir dir;
  std::vector<PlyVertex> v = fan_vertices();
  for (PlyVertex& p : v) p.t = tags({1, 0, 0}, 1);  // everything tagged
  // Vertex 0 has 6 tagged neighbours, each ring vertex 3, every triangle three tagged vertices.
  EXPECT_TRUE(rejects(dir.write("all.ply", ascii_ply(v, kFanFaces)),
                      {"all.ply: vertex 0: tagged, with 6 tagged neighbours", "12 more violations of the tag rules at "
                       "vertex 1, vertex 2, vertex 3, vertex 4, vertex 5, vertex 6, triangle 0, triangle 1, triangle 2, "
                       "triangle 3, ..."}));
}

TEST(TaggedPly, ValidateTagsNamesVerticesAndChecksSizes) {
  Mesh mesh;
  mesh.source = "hand";
  mesh.positions = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
  mesh.normals.assign(3, glm::dvec3(0, 0, 1));
  mesh.triangles = {glm::uvec3(0, 1, 2)};
  EXPECT_NO_THROW(validate_tags(mesh));  // untagged
  mesh.tags.assign(2, VertexTags{});
  EXPECT_THROW(validate_tags(mesh), InputError);
  mesh.tags.assign(3, tags({1, 0, 0}, 1));
  try {
    validate_tags(mesh, [](std::uint32_t v) { return "corner " + std::to_string(v); });
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hand: triangle 0: all three of its vertices (corner 0, corner 1, corner 2)"),
              std::string::npos)
        << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Import and the closed tessellation.

struct EdgeComparison {
  std::size_t compared = 0;  // pairs of copies of a shared edge point
  std::size_t differing = 0;
  double worst = 0.0;
};

// Tessellates with the uniform pattern of factor L and compares, bit for bit, the copies of every
// point on an edge shared by two patches. With L a power of two the barycentrics of edge points
// are exact and the off-edge weight exactly 0, so equal edge control points give equal points.
EdgeComparison compare_shared_edges(const Mesh& mesh, int L, NormalMode mode = NormalMode::Quadratic) {
  std::map<testing::EdgePointKey, glm::dvec3> first_seen;
  EdgeComparison c;
  testing::for_each_edge_point(mesh, L, mode, [&](const PatchView& view, std::size_t i, const testing::EdgePointKey& key) {
    const glm::dvec3& p = view.positions[i];
    const auto [it, inserted] = first_seen.try_emplace(key, p);
    if (inserted) return;
    ++c.compared;
    if (p != it->second) ++c.differing;
    c.worst = std::max(c.worst, glm::length(p - it->second));
  });
  return c;
}

TEST(StpnImport, CubeCornersArePinnedAndTheCubeKeepsItsShape) {
  const fs::path file = kModels / "OBJ/box.obj";
  if (!fs::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
  const StImport st = import_st_mesh(file, {});
  const StImportSummary& s = st.summary;
  // Every vertex of an 8-vertex cube is a corner of three creases: the format's rules leave no
  // room for crease vertices there, only for pinned corners.
  EXPECT_EQ(s.vertices, 8u);
  EXPECT_EQ(s.crease_edges, 12u);
  EXPECT_TRUE(s.dihedral_test);
  EXPECT_EQ(s.crease_vertices, 0u);
  EXPECT_EQ(s.corners, 8u);
  EXPECT_EQ(s.corners_tagged, 0u);
  for (const VertexTags& t : st.mesh.tags) EXPECT_EQ(t, tags({0, 0, 0}, 0, 1.0));
  EXPECT_NO_THROW(validate_tags(st.mesh));

  // Plain PN rounds the cube off; with its corners pinned every tessellated point stays on the
  // cube's surface, and shared edges come out bit for bit the same.
  for (const bool tagged : {false, true}) {
    Mesh mesh = st.mesh;
    if (!tagged) mesh.tags.clear();
    double off_surface = 0.0;
    tessellate_mesh(mesh, 8, NormalMode::Quadratic, [&](const PatchView& view) {
      for (const glm::dvec3& p : view.positions)
        off_surface = std::max(off_surface, std::abs(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) - 0.5));
    });
    if (tagged) {
      EXPECT_EQ(off_surface, 0.0);  // docs/stpn.md §4.5
    } else {
      EXPECT_GT(off_surface, 0.15);  // 0.167 at L = 8
    }
    const EdgeComparison c = compare_shared_edges(mesh, 8);
    EXPECT_EQ(c.compared, 18u * 9u);  // 18 edges (12 of the cube, 6 diagonals), 9 points on each
    EXPECT_EQ(c.differing, 0u);
  }
}

// Vertices of the prism by where they are (load order is Assimp's order of first use).
bool is_centre(const glm::dvec3& p) { return p.x == 0.0 && p.y == 0.0; }
bool on_top_rim(const glm::dvec3& p) { return p.z == 1.0 && !is_centre(p); }
bool on_a_rim(const glm::dvec3& p) { return std::abs(p.z) == 1.0 && !is_centre(p); }

TEST(StpnImport, PrismRimsBecomeSharpCreases) {
  TempDir dir;
  const fs::path file = dir.write("prism.obj", prism_obj());
  const StImport st = import_st_mesh(file, {});
  const StImportSummary& s = st.summary;
  EXPECT_EQ(s.vertices, 50u);
  EXPECT_EQ(s.crease_edges, 32u);
  EXPECT_EQ(s.crease_vertices, 32u);
  EXPECT_EQ(s.tagged, 32u);
  EXPECT_EQ(s.softened, 0u);
  EXPECT_EQ(s.restricted, 0u);
  EXPECT_EQ(s.corners + s.crease_ends + s.non_manifold + s.folded, 0u);

  const Mesh& mesh = st.mesh;
  std::size_t rims = 0;
  for (std::uint32_t v = 0; v < 50; ++v) {
    const bool rim = on_a_rim(mesh.positions[v]);
    rims += rim;
    EXPECT_EQ(mesh.tags[v].tagged(), rim) << v;
    if (!rim) continue;
    EXPECT_EQ(mesh.tags[v].sigma, 1.0);
    EXPECT_GT(glm::length(mesh.tags[v].delta), 0.5);
    EXPECT_NEAR(glm::length(mesh.normals[v]), 1.0, 1e-15);
    EXPECT_NEAR(glm::dot(mesh.normals[v], mesh.tags[v].delta), 0.0, 1e-15);  // Δ ⊥ N
  }
  EXPECT_EQ(rims, 32u);

  // The reference reproduces both side normals at a rim vertex: the cap's normal in cap
  // patches, the side's in side patches (σ = 1).
  const glm::dvec3 top(0, 0, 1);
  std::size_t cap_corners = 0, side_corners = 0;
  tessellate_mesh(mesh, 4, NormalMode::Quadratic, [&](const PatchView& view) {
    const glm::uvec3 t = mesh.triangles[view.triangle];
    const int corner_point[3] = {pattern_index(0, 0, 4), pattern_index(4, 0, 4), pattern_index(0, 4, 4)};
    const bool cap = is_centre(mesh.positions[t[0]]) || is_centre(mesh.positions[t[1]]) || is_centre(mesh.positions[t[2]]);
    for (int c = 0; c < 3; ++c) {
      if (!on_top_rim(mesh.positions[t[c]])) continue;
      const glm::dvec3 n = view.normals[static_cast<std::size_t>(corner_point[c])];
      if (cap) {
        ++cap_corners;
        EXPECT_NEAR(glm::length(n - top), 0.0, 1e-14);
      } else {
        ++side_corners;
        EXPECT_NEAR(n.z, 0.0, 1e-14);  // horizontal: the side's normal
      }
    }
  });
  EXPECT_EQ(cap_corners, 32u);   // 16 rim vertices, 2 cap triangles each
  EXPECT_EQ(side_corners, 48u);  // 16 quads below the rim, 3 rim corners each

  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear, NormalMode::Derivative}) {
    const EdgeComparison c = compare_shared_edges(mesh, 4, mode);
    EXPECT_EQ(c.compared, 144u * 5u);  // 96 triangles, 144 edges, 5 points on each
    EXPECT_EQ(c.differing, 0u) << to_string(mode) << ", worst " << c.worst;
  }

  // Written and read back: the same ST-mesh, the same tessellation.
  write_ply(mesh, dir.path() / "prism_st.ply");
  const Mesh reread = load_mesh(dir.path() / "prism_st.ply");
  EXPECT_EQ(reread.positions, mesh.positions);
  EXPECT_EQ(reread.tags, mesh.tags);
  EXPECT_EQ(reread.triangles, mesh.triangles);
  double normal_change = 0.0;
  for (std::size_t v = 0; v < 50; ++v) normal_change = std::max(normal_change, glm::length(reread.normals[v] - mesh.normals[v]));
  EXPECT_LE(normal_change, 1e-7);  // through Assimp's single precision
  EXPECT_EQ(compare_shared_edges(reread, 4).differing, 0u);
}

TEST(StpnImport, SigmaAndCornerTensionAreTheOptions) {
  TempDir dir;
  const fs::path file = dir.write("prism.obj", prism_obj());
  StImportOptions options;
  options.sigma = 0.5;
  const StImport soft = import_st_mesh(file, options);
  EXPECT_EQ(soft.summary.tagged, 32u);
  for (std::uint32_t v = 0; v < 50; ++v)
    if (soft.mesh.tags[v].tagged()) {
      EXPECT_EQ(soft.mesh.tags[v].sigma, 0.5) << v;
    }
  EXPECT_EQ(compare_shared_edges(soft.mesh, 4).differing, 0u);

  // At 10° the sides' vertical edges (22.5°) are creases too: the rim vertices become corners
  // (three creases) and the middle ring crease vertices, whose vertical creases run into those
  // untagged corners: they are tagged but softened.
  options.crease_angle = 10.0;
  options.corner_tension = -0.25;
  const StImport st = import_st_mesh(file, options);
  EXPECT_EQ(st.summary.crease_edges, 32u + 32u);
  EXPECT_EQ(st.summary.corners, 32u);
  EXPECT_EQ(st.summary.crease_vertices, 16u);
  EXPECT_EQ(st.summary.tagged, 16u);
  EXPECT_EQ(st.summary.softened, 16u);
  EXPECT_EQ(st.summary.softened_ends, 16u);
  for (std::uint32_t v = 0; v < 50; ++v) {
    const glm::dvec3& p = st.mesh.positions[v];
    if (on_a_rim(p)) {
      EXPECT_EQ(st.mesh.tags[v], tags({0, 0, 0}, 0, -0.25)) << v;
    }
    if (p.z == 0.0) {
      EXPECT_TRUE(st.mesh.tags[v].tagged() && st.mesh.tags[v].sigma == 0.0) << v;
    }
  }
  EXPECT_EQ(compare_shared_edges(st.mesh, 4).differing, 0u);
}

// Real meshes with hard edges (assimp-testmodels): the ST-mesh passes the rules and its
// tessellation is closed. The counts are those recorded in docs/stpn.md.
TEST(StpnImport, RealHardEdgedMeshesStayClosed) {
  struct Case {
    const char* file;
    std::size_t crease_vertices, tagged, softened, corners;
  };
  const Case cases[] = {
      {"Collada/Cinema4D.dae", 36, 36, 0, 8},    // a cube, a cone and a sphere: normals split at hard edges
      {"OBJ/spider.obj", 152, 150, 6, 0},        // normals split at the joints of the legs
      {"X/BCN_Epileptic.X", 89, 77, 9, 4},       // a character with a few hard edges
      {"OFF/Wuson.off", 600, 488, 230, 149},     // no normals: faces meeting at more than 30°
  };
  for (const Case& c : cases) {
    const fs::path file = kModels / c.file;
    if (!fs::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
    SCOPED_TRACE(c.file);
    const StImport st = import_st_mesh(file, {});
    EXPECT_EQ(st.summary.crease_vertices, c.crease_vertices);
    EXPECT_EQ(st.summary.tagged, c.tagged);
    EXPECT_EQ(st.summary.softened, c.softened);
    EXPECT_EQ(st.summary.corners, c.corners);
    EXPECT_NO_THROW(validate_tags(st.mesh));
    const EdgeComparison e = compare_shared_edges(st.mesh, 4);
    EXPECT_GT(e.compared, st.mesh.triangle_count());
    EXPECT_EQ(e.differing, 0u) << "worst " << e.worst;
    RecordProperty(c.file, std::to_string(st.summary.crease_vertices) + " crease vertices, " +
                               std::to_string(st.summary.tagged - st.summary.softened) + " sharp");
  }
}

// Without the closing pass a crease running into an untagged vertex cracks: the two sides'
// coefficients differ. This is what softening prevents (and what the comparison detects).
TEST(StpnImport, ACreaseRunningIntoAnUntaggedVertexWouldCrack) {
  TempDir dir;
  const StImport st = import_st_mesh(dir.write("prism.obj", prism_obj()), {});
  Mesh broken = st.mesh;
  // Untag one top-rim vertex: its two rim neighbours keep σ = 1.
  const auto rim = std::find_if(broken.positions.begin(), broken.positions.end(), on_top_rim);
  broken.tags[static_cast<std::size_t>(rim - broken.positions.begin())] = VertexTags{};
  const EdgeComparison c = compare_shared_edges(broken, 4);
  EXPECT_GT(c.differing, 0u);
  EXPECT_GT(c.worst, 1e-6);
}

}  // namespace
}  // namespace tessim

namespace tessim {
namespace {

// stpn-import replaces a tagged file's tags, but a file whose tags break the format's rules is
// still refused, as every other command refuses it (docs/stpn.md).
TEST(StpnImport, RefusesAFileWhoseOwnTagsBreakTheRules) {
  const fs::path file = fs::temp_directory_path() / ("stpn_import_bad_tags_" + std::to_string(::getpid()) + ".ply");
  {
    std::ofstream out(file);
    out << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "property float dx\nproperty float dy\nproperty float dz\nproperty float sigma\nproperty float theta\n"
           "property float beta\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
           "0 0 0 0.5 0 0 1 0 0\n1 0 0 0.5 0 0 1 0 0\n0 1 0 0.5 0 0 1 0 0\n3 0 1 2\n";
  }
  try {
    (void)import_st_mesh(file, {});
    ADD_FAILURE() << "a triangle with three tagged vertices was imported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a triangle may have at most 2"), std::string::npos) << e.what();
  }
  fs::remove(file);
}

}  // namespace
}  // namespace tessim
