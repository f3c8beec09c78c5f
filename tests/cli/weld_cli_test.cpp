// tessim tessellate --weld and tessim sim -o --weld: the reference and the cycle model weld the
// same mesh to the same counts, and the files hold the welded meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <string>

#include "model/mesh_io.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kWuson);
  return mesh;
}

TEST(WeldCli, ReferenceAndCycleModelWeldToTheSameMesh) {
  testing::TempDir dir;
  const auto ref = dir.path() / "ref.ply", fx = dir.path() / "fx.obj";
  auto r = testing::run_tessim({"tessellate", kWuson, "-L", "3", "--weld", "-o", ref.string()}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const Mesh& mesh = wuson();
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const glm::uvec3& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[std::minmax(t[e], t[(e + 1) % 3])];
  const std::size_t expected = mesh.vertex_count() + 2 * edges.size() + mesh.triangle_count();
  EXPECT_NE(r.out.find("into " + std::to_string(expected) + " distinct vertices"), std::string::npos) << r.out;
  r = testing::run_tessim({"sim", kWuson, "-L", "3", "-o", fx.string(), "--weld"}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("into " + std::to_string(expected) + " distinct vertices"), std::string::npos) << r.out;
  // The files hold the welded meshes: the same vertex and triangle counts. (The OBJ is counted
  // line by line: load_mesh would weld it again by position alone, and a few vertices of the
  // fixed-point output share a position but not a normal.)
  const Mesh a = load_mesh(ref.string());
  EXPECT_EQ(a.vertex_count(), expected);
  EXPECT_EQ(a.triangle_count(), mesh.triangle_count() * 9);
  std::ifstream obj(fx);
  std::size_t v = 0, f = 0;
  for (std::string line; std::getline(obj, line);) {
    v += line.rfind("v ", 0) == 0;
    f += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(v, expected);
  EXPECT_EQ(f, mesh.triangle_count() * 9);
  // --weld without -o is a command-line error.
  r = testing::run_tessim({"sim", kWuson, "--weld"}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--weld"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tessim
