// Silhouettes on the command line (docs/mathematics.md §11, docs/patterns.md): `tessellate
// --silhouette` writes the per-patch output of the blended patches, `info --silhouette` counts
// the edges by α, `--adaptive silhouette` refines near the outline only, and bad eyes or widths
// are input errors with nothing written.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/silhouette.hpp"
#include "model/tessellate.hpp"
#include "tests/support/nearest_points.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::farthest_from;
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
  const double tolerance = 1e-6 * bounding_box(mesh).diagonal();
  EXPECT_LE(farthest_from(written.positions, expected, tolerance), tolerance);
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
  // The contour rule refines the patches the view contour can cross as well: more than the
  // per-edge rule at the same tolerance.
  const auto contour = triangles("contour", "--outline-tolerance", "0.5");
  EXPECT_GT(contour, silhouette);
  RecordProperty("screen", static_cast<int>(screen));
  RecordProperty("silhouette", static_cast<int>(silhouette));
  RecordProperty("contour", static_cast<int>(contour));
}

// The unit's output (`sim --silhouette`, the interface the checks use): per patch, in the order of
// `tessellate --silhouette`, each position within the unit's derived bound plus the host's
// rounding of alpha to A bits (docs/number-formats.md §7) of the float reference.
TEST(SilhouetteCli, SimWritesTheUnitsBlendedOutputWithinItsBound) {
  TempDir dir;
  const Mesh mesh = load_mesh(kWuson);
  double longest = 0;
  for (const glm::uvec3& t : mesh.triangles)
    for (int e = 0; e < 3; ++e)
      longest = std::max(longest, glm::length(mesh.positions[t[(e + 1) % 3]] - mesh.positions[t[e]]));
  const double diagonal = bounding_box(mesh).diagonal();
  const fs::path ref = dir.path() / "ref.ply";
  ASSERT_EQ(run_tessim({"tessellate", kWuson, "-L", "3", "--silhouette", "eye=3,1,-3,beta=0.3", "-o", ref.string()},
                       dir.path()).status, 0);
  const Mesh expected = load_mesh(ref);
  for (const int bits : {0, 3, 16}) {  // 0: the configuration has no alpha, sim takes the default 8
    const fs::path out = dir.path() / ("unit" + std::to_string(bits) + ".ply");
    std::vector<std::string> args{"sim", kWuson, "-L", "3", "--silhouette", "eye=3,1,-3,beta=0.3", "-o", out.string()};
    if (bits) args.insert(args.end(), {"--alpha-bits", std::to_string(bits)});
    const auto r = run_tessim(args, dir.path());
    ASSERT_EQ(r.status, 0) << r.err;
    const int a = bits ? bits : 8;
    EXPECT_EQ(r.err.find("alpha_bits 8 (the configuration had 0)") != std::string::npos, bits == 0) << r.err;
    const Mesh unit = load_mesh(out);
    // Arithmetic (about 1e-6 of the diagonal) and single-precision files, then |delta alpha| |w| / 3.
    const double bound = 2e-6 * diagonal + std::ldexp(1.0, -(a + 1)) * longest / 3.0;
    const double worst = std::max(farthest_from(unit.positions, expected.positions, bound),
                                  farthest_from(expected.positions, unit.positions, bound));
    EXPECT_LE(worst, bound) << "alpha_bits " << a;
    if (a == 3) {
      EXPECT_GT(worst, 2e-6 * diagonal) << "3-bit alpha shows beside the arithmetic";
    }
  }
  // Without --silhouette the unit's output is plain PN: the blend changed it.
  const fs::path plain = dir.path() / "plain.ply";
  ASSERT_EQ(run_tessim({"sim", kWuson, "-L", "3", "-o", plain.string()}, dir.path()).status, 0);
  EXPECT_NE(load_mesh(plain).positions, load_mesh(dir.path() / "unit16.ply").positions);
}

// The silhouette rule's factors on the unit: the patches the reference makes, and crack-free (the
// welded output has as many vertices as the reference's).
class SilhouetteRules : public ::testing::TestWithParam<std::string> {};

TEST_P(SilhouetteRules, SimTakesTheRulesFactors) {
  TempDir dir;
  const std::vector<std::string> view{"--adaptive", GetParam(), "--camera", "eye=2.6,1.3,-2.9,target=0,0.6,-0.2",
                                      "--silhouette", "camera"};
  // The element counts of the written (welded) file: the mesh reader would weld again by position.
  auto run = [&](const char* cmd, const char* name) {
    std::vector<std::string> args{cmd, kWuson, "-o", (dir.path() / name).string(), "--weld"};
    args.insert(args.end(), view.begin(), view.end());
    const auto r = run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    std::ifstream in(dir.path() / name, std::ios::binary);
    std::string line, counts;
    while (std::getline(in, line) && line != "end_header")
      if (line.rfind("element ", 0) == 0) counts += line + "; ";
    return counts;
  };
  const std::string unit = run("sim", "unit.ply");
  // Every shared point welded as in the crack-free reference: as many vertices and triangles.
  EXPECT_EQ(unit, run("tessellate", "ref.ply"));
}

INSTANTIATE_TEST_SUITE_P(PerEdgeAndContour, SilhouetteRules, ::testing::Values("silhouette", "contour"));

// A feature end (a crease through vertex 0 between the two faces of edge 0-1) is the reference's:
// the unit refuses the mesh, naming the vertex, and writes nothing.
TEST(SilhouetteCli, SimRefusesAFeatureEndNamingItsVertex) {
  TempDir dir;
  const fs::path mesh = dir.path() / "crease.ply";
  {
    std::FILE* f = std::fopen(mesh.string().c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
               "property float dx\nproperty float dy\nproperty float dz\nproperty float sigma\nproperty float theta\n"
               "property float beta\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0 0 -1 1 1 0 0\n1 0 0 0 0 0 0 0 0\n0.5 1 0 0 0 0 0 0 0\n0.5 -0.5 1 0 0 0 0 0 0\n3 0 1 2\n3 1 0 3\n",
               f);
    std::fclose(f);
  }
  const fs::path out = dir.path() / "o.ply";
  const auto r = run_tessim({"sim", mesh.string(), "--silhouette", "eye=0,0,5", "-o", out.string()}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("crease.ply: vertex 0: a feature end of the silhouette"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // The reference computes it.
  const auto t = run_tessim({"tessellate", mesh.string(), "--silhouette", "eye=0,0,5", "-o", out.string()}, dir.path());
  EXPECT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.out.find("1 feature ends"), std::string::npos) << t.out;
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
      {{"tessellate", kWuson, "-o", out, "--silhouette", ""}, "--silhouette: has an empty value"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "camera"}, "'camera' takes the eye of --adaptive"},
      {{"render", kWuson, "-o", out + ".png", "--silhouette", "eye=0,0,5,beta=0"}, "must be a positive finite number"},
      {{"render", kWuson, "-o", out + ".png", "--color", "silhouette"}, "silhouette needs --silhouette"},
      {{"info", kWuson, "--silhouette", "camera"}, "info has no camera"},
      {{"tessellate", kWuson, "-o", out, "--silhouette", "eye=0,0,5,blend=maybe"}, "is not on or off"},
      {{"sim", kWuson, "-o", out, "--silhouette", "eye=0,0,5,beta=0"}, "must be a positive finite number"},
      {{"sim", kWuson, "-o", out, "--silhouette", "camera"}, "'camera' takes the eye of --adaptive"},
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
