// `tessellate|render --displace sine --amplitude A --frequency F` (docs/mathematics.md §12): the
// per-patch output is the displaced surface of the model, and bad settings are input errors with
// nothing written.
#include <filesystem>
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

}  // namespace
}  // namespace tessim
