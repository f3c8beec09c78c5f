// `tessellate|render --displace sine --amplitude A --frequency F` (docs/mathematics.md §12): the
// per-patch output is the displaced surface of the model, and bad settings are input errors with
// nothing written. `--adaptive nyquist|screen+nyquist|silhouette+nyquist` and
// `--samples-per-wavelength S` (docs/patterns.md §9): factors from the displacement's wavelength,
// the same vertices from `tessellate` and `sim`, and their misuse refused.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/displace.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "tests/support/nearest_points.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

TEST(DisplaceCli, TessellateWritesTheDisplacedSurface) {
  TempDir dir;
  const fs::path out = dir.path() / "d.ply";
  const auto r = run_tessim({"tessellate", kWuson, "-L", "3", "--displace", "sine", "--amplitude", "0.02",
                             "--frequency", "30", "-o", out.string()},
                            dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("displaced by 0.02 sin(30 |P|)"), std::string::npos) << r.out;
  const Mesh mesh = load_mesh(kWuson);
  TessSettings s;
  s.L = 3;
  s.displace = {DisplaceKind::Sine, 0.02, 30.0};
  std::vector<glm::dvec3> expected;
  tessellate_mesh(mesh, s, NormalMode::Quadratic, [&](const PatchView& v) {
    expected.insert(expected.end(), v.positions.begin(), v.positions.end());
  });
  // The mesh reader welds equal positions and reads single precision: every written position is
  // one of the model's, within float rounding.
  const Mesh written = load_mesh(out);
  const double tolerance = 1e-6 * bounding_box(mesh).diagonal();
  EXPECT_LE(tessim::testing::farthest_from(written.positions, expected, tolerance), tolerance);
  // Not the plain surface.
  const fs::path plain = dir.path() / "p.ply";
  ASSERT_EQ(run_tessim({"tessellate", kWuson, "-L", "3", "-o", plain.string()}, dir.path()).status, 0);
  EXPECT_NE(load_mesh(plain).positions, written.positions);
}

TEST(DisplaceCli, BadSettingsAreInputErrors) {
  TempDir dir;
  const std::string out = (dir.path() / "x.ply").string();
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  const Case cases[] = {
      {{"tessellate", kWuson, "-o", out, "--displace", "sine", "--amplitude", "nan", "--frequency", "1"},
       "--amplitude: 'nan' is not a finite number"},
      {{"tessellate", kWuson, "-o", out, "--displace", "sine", "--amplitude", "1", "--frequency", "-2"}, "is negative"},
      {{"tessellate", kWuson, "-o", out, "--displace", "sine", "--amplitude", "1", "--frequency", "inf"},
       "--frequency: 'inf' is not a finite number"},
      {{"tessellate", kWuson, "-o", out, "--displace", "wave", "--amplitude", "1", "--frequency", "1"}, "is not sine"},
      {{"tessellate", kWuson, "-o", out, "--displace", "sine", "--amplitude", "1"}, "needs --amplitude A and --frequency F"},
      {{"tessellate", kWuson, "-o", out, "--frequency", "1"}, "--frequency: needs --displace sine"},
      {{"render", kWuson, "-o", out + ".png", "--displace", "sine", "--amplitude", "0.1", "--frequency", "3", "--color",
        "error-position"},
       "measures the unit, which does not displace"},
  };
  for (const Case& c : cases) {
    const auto r = run_tessim(c.args, dir.path());
    EXPECT_EQ(r.status, 2) << c.message << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".png"));
  }
}

// The count in "<file>: P patches, V vertices, ..." (tessellate) or "result ... V vertices" (sim).
std::uint64_t printed_vertices(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("([0-9]+) +vertices"))) return 0;
  return std::stoull(m[1].str());
}

const std::vector<std::string> kSine{"--displace", "sine", "--amplitude", "0.02", "--frequency", "60"};

std::vector<std::string> with_sine(std::vector<std::string> args) {
  args.insert(args.end(), kSine.begin(), kSine.end());
  return args;
}

TEST(DisplaceCli, NyquistFactorsFollowTheSamplesPerWavelength) {
  TempDir dir;
  const fs::path out4 = dir.path() / "n4.ply", out8 = dir.path() / "n8.ply";
  const auto r4 = run_tessim(with_sine({"tessellate", kWuson, "--adaptive", "nyquist", "-o", out4.string()}), dir.path());
  ASSERT_EQ(r4.status, 0) << r4.err;
  EXPECT_NE(r4.out.find("nyquist-adaptive (4 samples per wavelength)"), std::string::npos) << r4.out;
  const auto r8 = run_tessim(
      with_sine({"tessellate", kWuson, "--adaptive", "nyquist", "--samples-per-wavelength", "8", "-o", out8.string()}),
      dir.path());
  ASSERT_EQ(r8.status, 0) << r8.err;
  EXPECT_NE(r8.out.find("nyquist-adaptive (8 samples per wavelength)"), std::string::npos) << r8.out;
  const std::uint64_t v4 = printed_vertices(r4.out), v8 = printed_vertices(r8.out);
  EXPECT_GT(v4, 0u) << r4.out;
  EXPECT_GT(v8, v4) << r8.out;
  // The written meshes: twice the samples, more points (the reader welds shared ones).
  EXPECT_GT(load_mesh(out8).vertex_count(), load_mesh(out4).vertex_count());
  // The factors the model computes (model/factors.hpp), counted the writer's way.
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.rule = AdaptiveRule::Nyquist;
  s.displace = {DisplaceKind::Sine, 0.02, 60.0};
  const Mesh mesh = load_mesh(kWuson);
  PatternCache cache(s);
  EXPECT_EQ(count_tessellation(mesh, cache).vertices, v4);

  // sim: the host computes the same factors, the unit tessellates, the GE displaces.
  const fs::path sim = dir.path() / "s.ply";
  const auto rs = run_tessim(with_sine({"sim", kWuson, "--adaptive", "nyquist", "-o", sim.string()}), dir.path());
  ASSERT_EQ(rs.status, 0) << rs.err;
  EXPECT_NE(rs.out.find("nyquist-adaptive (4 samples per wavelength)"), std::string::npos) << rs.out;
  EXPECT_TRUE(fs::exists(sim));
  const std::size_t result = rs.out.find("\nresult");
  ASSERT_NE(result, std::string::npos) << rs.out;
  EXPECT_EQ(printed_vertices(rs.out.substr(result)), v4) << rs.out;
}

// An edge that needs more than 64 segments is clamped and still aliases: the run says so, once,
// with the count, and still writes its output; at a frequency the factors can follow, no warning.
// One right triangle with legs of 1: noise at f asks S·f·ℓ segments, 80 and 113.1 at f = 20.
TEST(DisplaceCli, NyquistClampIsWarned) {
  TempDir dir;
  const fs::path mesh = dir.path() / "tri.obj", out = dir.path() / "n.ply";
  std::ofstream(mesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  auto noise = [&](const char* command, const char* f) {
    return run_tessim({command, mesh.string(), "--adaptive", "nyquist", "-o", out.string(), "--displace", "noise",
                       "--amplitude", "0.01", "--frequency", f},
                      dir.path());
  };
  for (const char* command : {"tessellate", "sim"}) {
    const auto r = noise(command, "20");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string warning = "3 edges need more than 64 segments for 4 samples per wavelength (up to 114)";
    const std::size_t at = r.err.find(warning);
    EXPECT_NE(at, std::string::npos) << command << ": " << r.err;
    EXPECT_EQ(r.err.find(warning, at + 1), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("still aliases"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out));
    fs::remove(out);
    const auto low = noise(command, "10");  // 40 and 56.6 segments
    ASSERT_EQ(low.status, 0) << low.err;
    EXPECT_EQ(low.err.find("warning"), std::string::npos) << low.err;
  }
}

TEST(DisplaceCli, NyquistMisuseIsAnInputError) {
  TempDir dir;
  const std::string out = (dir.path() / "x.ply").string();
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  const Case cases[] = {
      {{"tessellate", kWuson, "-o", out, "--adaptive", "nyquist"},
       "--adaptive: the nyquist rule samples a displacement: it needs --displace sine|noise"},
      {{"tessellate", kWuson, "-o", out, "--adaptive", "screen+nyquist", "--camera", "eye=0,0,3"},
       "--adaptive: the nyquist rule samples a displacement: it needs --displace sine|noise"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--camera", "eye=0,0,3"}),
       "--camera: --adaptive nyquist takes no camera (screen+nyquist does)"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--viewport", "100x100"}),
       "--viewport: --adaptive nyquist takes no camera (screen+nyquist does)"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--pixels-per-segment", "3"}),
       "--pixels-per-segment: is the screen rule's; --adaptive nyquist alone takes --samples-per-wavelength only"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--outline-tolerance", "3"}),
       "--outline-tolerance: is the silhouette rule's; --adaptive nyquist alone takes --samples-per-wavelength only"},
      {with_sine({"tessellate", kWuson, "-o", out, "--samples-per-wavelength", "8"}),
       "--samples-per-wavelength: needs --adaptive nyquist, screen+nyquist, silhouette+nyquist or contour+nyquist"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "screen", "--samples-per-wavelength", "8", "--camera",
                  "eye=0,0,3"}),
       "--samples-per-wavelength: needs --adaptive nyquist, screen+nyquist, silhouette+nyquist or contour+nyquist"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--samples-per-wavelength", "0.5"}),
       "--samples-per-wavelength: 0.5 is not a finite number >= 1"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--samples-per-wavelength", "nan"}),
       "--samples-per-wavelength: 'nan' is not a finite number"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "nyquist", "--samples-per-wavelength", "inf"}),
       "--samples-per-wavelength: 'inf' is not a finite number"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "screen+nyquist"}),
       "--camera: --adaptive screen+nyquist needs --camera eye=x,y,z"},
      {with_sine({"tessellate", kWuson, "-o", out, "--adaptive", "silhouette+nyquist"}),
       "--camera: --adaptive silhouette+nyquist needs --camera eye=x,y,z"},
      {with_sine({"sim", kWuson, "-o", out, "--adaptive", "nyquist", "--camera", "eye=0,0,3"}),
       "--camera: --adaptive nyquist takes no camera (screen+nyquist does)"},
      {{"sim", kWuson, "-o", out, "--adaptive", "nyquist"},
       "--adaptive: the nyquist rule samples a displacement: it needs --displace sine|noise"},
      {with_sine({"render", kWuson, "-o", out + ".png", "--adaptive", "nyquist", "--samples-per-wavelength", "0.5"}),
       "--samples-per-wavelength: 0.5 is not a finite number >= 1"},
  };
  for (const Case& c : cases) {
    const auto r = run_tessim(c.args, dir.path());
    EXPECT_EQ(r.status, 2) << c.message << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("tessim: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(out)) << c.message;
    EXPECT_FALSE(fs::exists(out + ".png")) << c.message;
  }
}

}  // namespace
}  // namespace tessim

namespace tessim {
namespace {

// The interface of `tessim sim --displace`: the unit's output displaced by the geometry engine is
// the float reference's displaced surface within 1e-5 of the diagonal (both ways: every point
// of each near one of the other), and `--evaluation gpe --cpg-mapping host` gives the reference's.
TEST(DisplaceCli, SimWritesTheUnitsOutputDisplacedWithinOneHundredThousandthOfTheDiagonal) {
  TempDir dir;
  const std::vector<std::string> displace{"--displace", "sine", "--amplitude", "0.03", "--frequency", "50"};
  auto with = [](std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  const fs::path reference = dir.path() / "t.ply", unit = dir.path() / "s.ply", ge = dir.path() / "g.ply";
  ASSERT_EQ(run_tessim(with({"tessellate", kWuson, "-L", "5", "-o", reference.string()}, displace), dir.path()).status, 0);
  const auto r = run_tessim(with({"sim", kWuson, "-L", "5", "-o", unit.string(), "--quiet"}, displace), dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("GE       20 cycles/vertex: K=8 + 12 displacing (sine, amplitude 0.03, frequency 50)"),
            std::string::npos)
      << r.out;
  const auto g = run_tessim(with({"sim", kWuson, "-L", "5", "-o", ge.string(), "--quiet", "--evaluation", "gpe",
                                  "--cpg-mapping", "host"},
                                 displace),
                            dir.path());
  ASSERT_EQ(g.status, 0) << g.err;
  const Mesh want = load_mesh(reference.string()), got = load_mesh(unit.string()), on_ge = load_mesh(ge.string());
  const double tolerance = 1e-5 * bounding_box(load_mesh(kWuson)).diagonal();
  // (The reader welds equal single-precision positions, so the counts may differ by a few.)
  EXPECT_LE(tessim::testing::farthest_from(got.positions, want.positions, tolerance), tolerance);
  EXPECT_LE(tessim::testing::farthest_from(want.positions, got.positions, tolerance), tolerance);
  // The host's control points on the GE: the reference's points up to the DPG's 16-bit weights
  // and the reader's single precision.
  const double close = 1e-6 * bounding_box(load_mesh(kWuson)).diagonal();
  EXPECT_LE(tessim::testing::farthest_from(on_ge.positions, want.positions, close), close);
}

}  // namespace
}  // namespace tessim
