// The pattern options of `tessim tessellate` and `tessim render` (docs/patterns.md §7): the
// uniform default is unchanged, fixed and adaptive D3D11 factors give the patterns the model
// computes, and conflicting or malformed options are input errors with nothing written.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "model/d3d11_pattern.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;

const char* const kSphere = "/usr/share/assimp/models/STL/sphereWithHole.stl";

TEST(FactorsCli, FixedFactorsWriteThePatternOfTheModel) {
  TempDir dir;
  const fs::path out = dir.path() / "f.obj";
  const auto r = run_tessim({"tessellate", kSphere, "--outer", "2,3.5,5", "--inner", "4", "--partitioning",
                             "fractional_even", "-o", out.string()},
                            dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const D3D11Pattern p = d3d11_tri_pattern({2.0f, 3.5f, 5.0f}, 4.0f, Partitioning::fractional_even);
  const Mesh mesh = load_mesh(kSphere);
  const Mesh written = load_mesh(out);
  EXPECT_EQ(written.triangle_count(), mesh.triangle_count() * p.triangle_count());
  EXPECT_NE(r.out.find("fractional_even outer 2,3.5,5 inner 4"), std::string::npos) << r.out;
}

TEST(FactorsCli, AdaptiveCountsAreThoseOfTheModel) {
  TempDir dir;
  const fs::path out = dir.path() / "a.ply";
  const auto r = run_tessim({"tessellate", kSphere, "--adaptive", "screen", "--camera", "eye=0,0,40,fov=30",
                             "--pixels-per-segment", "6", "-o", out.string()},
                            dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.camera.eye = {0, 0, 40};
  s.camera.fov_deg = 30;
  s.pixels_per_segment = 6;
  const Mesh mesh = load_mesh(kSphere);
  PatternCache cache(s);
  const TessellationCounts c = count_tessellation(mesh, cache);
  EXPECT_NE(r.out.find(std::to_string(c.vertices) + " vertices, " + std::to_string(c.triangles) + " triangles"),
            std::string::npos)
      << r.out;
  EXPECT_GT(c.triangles, mesh.triangle_count());  // some edges are refined...
  EXPECT_LT(c.triangles, mesh.triangle_count() * 64 * 64);  // ...not all to the limit
}

TEST(FactorsCli, BadPatternOptionsAreInputErrors) {
  TempDir dir;
  const std::string out = (dir.path() / "x.ply").string();
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  const Case cases[] = {
      {{"--inner", "3"}, "--inner: needs --outer"},
      {{"--outer", "1,2"}, "expected 3 comma-separated factors"},
      {{"--outer", "1,x,2"}, "'x' is not a number"},
      {{"--partitioning", "odd"}, "is not one of integer, pow2, fractional_odd, fractional_even"},
      {{"--camera", "eye=1,2,3"}, "--camera: needs --adaptive screen"},
      {{"--adaptive", "screen"}, "needs --camera eye=x,y,z"},
      {{"--adaptive", "world", "--camera", "eye=1,2,3"}, "'world' is not screen, silhouette, contour, nyquist"},
      {{"--adaptive", "screen", "--camera", "eye=0,0,0"}, "the eye is the target"},
      {{"--adaptive", "screen", "--camera", "eye=1,2"}, "needs three coordinates"},
      {{"--adaptive", "screen", "--camera", "eye=1,2,3,fov=180"}, "outside (0, 180)"},
      // An unknown key after the eye is named, not read as a fourth coordinate.
      {{"--adaptive", "screen", "--camera", "eye=0,0,5,foo=1"}, "unknown key 'foo' (eye, target, fov)"},
      {{"--adaptive", "screen", "--camera", "eye=1,2,3", "--outer", "1,2,3"}, "--outer: cannot be combined with --adaptive"},
      // --inner alone is named as itself (it used to be reported as --outer).
      {{"--adaptive", "screen", "--camera", "eye=1,2,3", "--inner", "3"}, "--inner: cannot be combined with --adaptive"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"tessellate", kSphere, "-o", out};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto r = run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << c.message << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("tessim: error: "), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.message;
  }
}

// A factor's text is rounded once, straight to a float: 1.00000005960464478 is just above
// 1 + 2^-24, the midpoint between 1 and the next float, so it is 1 + 2^-23 (through a double it
// would round to the midpoint first and then, ties to even, to 1). Integer partitioning rounds
// 1 + 2^-23 up to 2: three points on that edge, five in all (the D3D11 tessellator's count).
TEST(FactorsCli, FactorTextIsRoundedOnceToAFloat) {
  TempDir dir;
  const auto r = run_tessim({"pattern", "--outer", "1.00000005960464478,1,1", "--inner", "1", "--partitioning",
                             "integer", "--json"},
                            dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["outer"][0].get<double>(), 2.0);
  EXPECT_EQ(j["points"].size(), 5u) << r.out;
  // Signs, spaces and hexadecimal floats are read as before.
  const auto hex = run_tessim({"pattern", "--outer", "+2, 0x1p1 ,2e0", "--inner", "1", "--partitioning", "integer",
                               "--json"},
                              dir.path());
  ASSERT_EQ(hex.status, 0) << hex.err;
  EXPECT_EQ(nlohmann::json::parse(hex.out)["outer_fixed"], nlohmann::json::parse("[131072, 131072, 131072]"));
}

// Fixed factors cull all patches or none: culling all is an empty run, refused as bad input
// (every command alike: tests/cli/input_policy_test.cpp).
TEST(FactorsCli, FactorsThatCullEveryPatchAreRefused) {
  TempDir dir;
  const fs::path out = dir.path() / "c.ply";
  const auto r = run_tessim({"tessellate", kSphere, "--outer", "0,3,3", "-o", out.string()}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("command line: --outer: '0,3,3': every patch is culled"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// -L sets the factors of the uniform pattern and of --partitioning alone; beside --outer or
// --adaptive each patch takes its factors from those, so an -L given would be ignored: refused by
// name, in the reference commands and in the unit's, and nothing written.
TEST(FactorsCli, FactorBesideOuterOrAdaptiveIsRefused) {
  TempDir dir;
  const fs::path out = dir.path() / "o.ply";
  const std::string camera = "eye=0,0,6";
  const std::vector<std::vector<std::string>> refused = {
      {"tessellate", kSphere, "-L", "8", "--outer", "2,2,2", "-o", out.string()},
      {"tessellate", kSphere, "-L", "8", "--adaptive", "screen", "--camera", camera, "-o", out.string()},
      {"sim", kSphere, "-L", "3", "--outer", "2,2,2", "-o", out.string()},
      {"sim", kSphere, "--tess-factor", "3", "--adaptive", "screen", "--camera", camera, "-o", out.string()},
      {"power", kSphere, "-L", "3", "--outer", "2,2,2"},
  };
  for (const auto& args : refused) {
    const auto r = run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << args[0] << " " << args[3] << ": " << r.err;
    EXPECT_NE(r.err.find("-L: has no effect with --"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << args[0];
  }
  // Still accepted: -L with --partitioning alone (every factor L), and --outer or --adaptive alone.
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sim", kSphere, "-L", "3", "--partitioning", "fractional_odd"},
        std::vector<std::string>{"sim", kSphere, "--outer", "2,2,2"},
        std::vector<std::string>{"tessellate", kSphere, "--adaptive", "screen", "--camera", camera, "-o",
                                 out.string()}}) {
    const auto r = run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 0) << args[2] << ": " << r.err;
  }
}

}  // namespace
}  // namespace tessim
