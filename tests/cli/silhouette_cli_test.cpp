// Silhouettes on the command line (docs/mathematics.md §11, docs/patterns.md): `tessellate
// --silhouette` writes the per-patch output of the blended patches, `info --silhouette` counts
// the edges by α, `--adaptive silhouette` refines near the outline only, and bad eyes or widths
// are input errors with nothing written.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/silhouette.hpp"
#include "model/tessellate.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

TEST(SilhouetteCli, TessellateWritesTheBlendedPatchesOfTheModel) {
  TempDir dir;
  const fs::path out = dir.path() / "s.ply";
  const auto r = run_tessim({"tessellate", kWuson, "-L", "3", "--silhouette", "eye=3,1,-3,beta=0.3", "-o", out.string()},
                            dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const Mesh mesh = load_mesh(kWuson);
  TessSettings s;
  s.L = 3;
  s.silhouette.enabled = true;
  s.silhouette.eye = {3, 1, -3};
  s.silhouette.beta = 0.3;
  std::vector<glm::dvec3> expected;
  tessellate_mesh(mesh, s, NormalMode::Quadratic, [&](const PatchView& v) {
    expected.insert(expected.end(), v.positions.begin(), v.positions.end());
  });
  // Per-patch output: every patch's 10 points (the summary counts them), each written position
  // one of the model's (the mesh reader welds equal positions and reads single precision).
  EXPECT_NE(r.out.find(std::to_string(mesh.triangle_count() * 10) + " vertices"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("silhouettes from eye (3, 1, -3) (beta 0.3)"), std::string::npos) << r.out;
  const Mesh written = load_mesh(out);
  std::sort(expected.begin(), expected.end(), [](const glm::dvec3& a, const glm::dvec3& b) { return a.x < b.x; });
  const double tolerance = 1e-6 * bounding_box(mesh).diagonal();
  for (const glm::dvec3& p : written.positions) {
    auto it = std::lower_bound(expected.begin(), expected.end(), p.x - tolerance,
                               [](const glm::dvec3& a, double x) { return a.x < x; });
    bool found = false;
    for (; it != expected.end() && it->x <= p.x + tolerance && !found; ++it) found = glm::length(*it - p) <= tolerance;
    ASSERT_TRUE(found) << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_GT(written.vertex_count(), mesh.vertex_count());
  // The plain PN output differs: the silhouette flattened what faces the eye.
  const fs::path plain = dir.path() / "p.ply";
  ASSERT_EQ(run_tessim({"tessellate", kWuson, "-L", "3", "-o", plain.string()}, dir.path()).status, 0);
  EXPECT_NE(fs::file_size(plain), 0u);
  const Mesh plain_mesh = load_mesh(plain);
  EXPECT_NE(plain_mesh.positions, written.positions);
}

TEST(SilhouetteCli, InfoCountsEdgesByAlphaAsTheModelDoes) {
  TempDir dir;
  const auto r = run_tessim({"info", kWuson, "--silhouette", "eye=3,1,-3", "--json"}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const MeshSilhouette model(load_mesh(kWuson), glm::dvec3(3, 1, -3), kDefaultSilhouetteBeta);
  const SilhouetteCounts& c = model.counts();
  EXPECT_EQ(j["silhouette"]["flat"].get<std::uint64_t>(), c.flat);
  EXPECT_EQ(j["silhouette"]["blended"].get<std::uint64_t>(), c.blended);
  EXPECT_EQ(j["silhouette"]["curved"].get<std::uint64_t>(), c.curved);
  EXPECT_EQ(j["silhouette"]["edges"].get<std::uint64_t>(), c.flat + c.blended + c.curved);
  EXPECT_EQ(j["silhouette"]["beta"].get<double>(), 0.25);
  const auto text = run_tessim({"info", kWuson, "--silhouette", "eye=3,1,-3"}, dir.path());
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("edges alpha = 0     " + std::to_string(c.flat)), std::string::npos) << text.out;
}

TEST(SilhouetteCli, AdaptiveSilhouetteSpendsFewerTrianglesThanTheScreenRule) {
  TempDir dir;
  auto triangles = [&](const std::string& rule, const std::string& knob, const std::string& value) {
    const auto r = run_tessim({"tessellate", kWuson, "--adaptive", rule, "--camera", "eye=2.6,1.3,-2.9,target=0,0.6,-0.2",
                               knob, value, "-o", (dir.path() / (rule + ".ply")).string()},
                              dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    const std::size_t at = r.out.find(" triangles,");
    const std::size_t start = r.out.rfind(' ', at - 1) + 1;
    return std::stoull(r.out.substr(start, at - start));
  };
  const auto screen = triangles("screen", "--pixels-per-segment", "6");
  const auto silhouette = triangles("silhouette", "--outline-tolerance", "0.5");
  EXPECT_LT(silhouette, screen / 2);
  EXPECT_GT(silhouette, load_mesh(kWuson).triangle_count());
}

TEST(SilhouetteCli, BadSilhouettesAreInputErrors) {
  TempDir dir;
  const std::string out = (dir.path() / "x.ply").string();
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  const Case cases[] = {
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=0,0,5,beta=0"}, "beta 0 must be a positive finite number"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=0,0,5,beta=nan"}, "must be a positive finite number"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=0,0,5,beta=-2"}, "must be a positive finite number"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=nan,0,5"}, "is not finite"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=inf,0,5"}, "is not finite"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=1,2"}, "needs three coordinates"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", ""}, "is not eye=x,y,z[,beta=B][,blend=off] or camera[,beta=B][,blend=off]"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "camera"}, "'camera' takes the eye of --adaptive"},
      {{"render", kWuson, "-o", out + ".png", "--silhouette", "eye=0,0,5,beta=0"}, "must be a positive finite number"},
      {{"render", kWuson, "-o", out + ".png", "--color", "silhouette"}, "silhouette needs --silhouette"},
      {{"info", kWuson, "--silhouette", "camera"}, "info has no camera"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=0,0,5,blend=maybe"}, "is not on or off"},
      {{"sim", kWuson, "-o", out, "--adaptive", "silhouette", "--camera", "eye=0,0,5"},
       "the unit's triangle interface does not carry"},
      {{"tessellate", kWuson, "-o", out, "--adaptive", "silhouette", "--camera", "eye=0,0,5", "--pixels-per-segment", "4"},
       "is the screen rule's"},
      {{"tessellate", kWuson, "-o", out, "--adaptive", "screen", "--camera", "eye=0,0,5", "--outline-tolerance", "1"},
       "--outline-tolerance: needs --adaptive silhouette"},
      {{"tessellate", kWuson, "-o", out, "--outline-tolerance", "1"}, "--outline-tolerance: needs --adaptive silhouette"},
      {{"tessellate", kWuson, "-o", out, "--adaptive", "silhouette", "--camera", "eye=0,0,5", "--outline-tolerance", "0"},
       "--outline-tolerance: must be a positive finite number"},
  };
  for (const Case& c : cases) {
    const auto r = run_tessim(c.args, dir.path());
    EXPECT_EQ(r.status, 2) << c.message << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("tessim: error: "), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.message;
    EXPECT_FALSE(fs::exists(out + ".png")) << c.message;
  }
  // An eye exactly on an edge's midpoint: that edge is curved (α = 1), never a NaN.
  const Mesh mesh = load_mesh(kWuson);
  const glm::uvec3 t = mesh.triangles[0];
  const glm::dvec3 mid = 0.5 * (mesh.positions[t[0]] + mesh.positions[t[1]]);
  char eye[128];
  std::snprintf(eye, sizeof eye, "eye=%.17g,%.17g,%.17g", mid.x, mid.y, mid.z);
  const auto r = run_tessim({"tessellate", kWuson, "-L", "2", "--silhouette", eye, "-o", out}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const Mesh written = load_mesh(out);
  for (const glm::dvec3& p : written.positions) ASSERT_TRUE(is_finite(p));
  const MeshSilhouette s(mesh, mid, kDefaultSilhouetteBeta);
  EXPECT_EQ(s.alpha(0)[0], 1.0);
}

}  // namespace
}  // namespace tessim
