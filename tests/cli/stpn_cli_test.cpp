// Scalar-tagged meshes as a user meets them (docs/stpn.md): `tessim stpn-import` on a cube and on
// a prism with hard rims, `tessim info` showing the tags, `tessellate` using them, the cycle
// model warning that it does not, and bad options refused before anything is written.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/prism_mesh.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using testing::run_tessim;
using testing::TempDir;
using testing::TessimRun;

const fs::path kBox = "/usr/share/assimp/models/OBJ/box.obj";

struct Dirs {
  TempDir scratch;  // captured streams, inputs
  TempDir work;     // where commands write
  fs::path at(const std::string& name) const { return work.path() / name; }
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

nlohmann::json info_json(const fs::path& mesh, const Dirs& d) {
  const TessimRun r = run_tessim({"info", "--json", mesh.string()}, d.scratch.path());
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(StpnImportCli, CubeCornersArePinned) {
  if (!fs::exists(kBox)) FAIL() << kBox << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const TessimRun r = run_tessim({"stpn-import", kBox.string(), "-o", d.at("box.ply").string()}, d.scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "box.ply: 8 vertices, 12 triangles, 12 crease edges (faces meeting at more than 30 degrees)"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "crease vertices   0: 0 tagged")) << r.out;
  EXPECT_TRUE(contains(r.out, "corners           8 (theta 1)")) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;

  const nlohmann::json j = info_json(d.at("box.ply"), d);
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["tags"]["present"], true);
  EXPECT_EQ(j["tags"]["tagged"], 0);
  EXPECT_EQ(j["tags"]["corner_like"], 8);
  EXPECT_EQ(j["tags"]["theta"], nlohmann::json({1.0, 1.0}));
  const TessimRun text = run_tessim({"info", d.at("box.ply").string()}, d.scratch.path());
  EXPECT_TRUE(contains(text.out, "corner-like vertices  8 (untagged, theta > 0)")) << text.out;
}

TEST(StpnImportCli, PrismRimsAreTaggedAndTessellated) {
  Dirs d;
  const fs::path prism = d.scratch.write("prism.obj", testing::prism_obj());
  const TessimRun r = run_tessim({"stpn-import", prism.string(), "-o", d.at("prism.ply").string()}, d.scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "prism.ply: 50 vertices, 96 triangles, 32 crease edges")) << r.out;
  EXPECT_TRUE(contains(r.out, "crease vertices   32: 32 tagged, 0 untagged by the tag rules")) << r.out;
  EXPECT_TRUE(contains(r.out, "tagged          32 with sigma 1, 0 softened")) << r.out;

  const nlohmann::json j = info_json(d.at("prism.ply"), d);
  EXPECT_EQ(j["tags"]["tagged"], 32);
  EXPECT_EQ(j["tags"]["crease"], 32);
  EXPECT_EQ(j["tags"]["softened"], 0);
  EXPECT_EQ(j["tags"]["tagged_edges"], 32);
  EXPECT_EQ(j["tags"]["sigma"], nlohmann::json({1.0, 1.0}));
  const TessimRun text = run_tessim({"info", d.at("prism.ply").string()}, d.scratch.path());
  EXPECT_TRUE(contains(text.out, "tagged vertices       32 (crease vector non-zero; 32 edges between two of them)"))
      << text.out;
  EXPECT_TRUE(contains(text.out, "crease vertices       32 (tagged, sigma > 0), 0 softened")) << text.out;

  const TessimRun t =
      run_tessim({"tessellate", d.at("prism.ply").string(), "-L", "4", "-o", d.at("t.ply").string()}, d.scratch.path());
  EXPECT_EQ(t.status, 0) << t.err;
  EXPECT_TRUE(contains(t.out, "scalar-tagged PN: 32 tagged vertices")) << t.out;
  EXPECT_TRUE(fs::exists(d.at("t.ply")));

  // The cycle model computes plain PN: it says so rather than drop the tags silently.
  const TessimRun s = run_tessim({"sim", d.at("prism.ply").string(), "-L", "2"}, d.scratch.path());
  EXPECT_EQ(s.status, 0) << s.err;
  EXPECT_TRUE(contains(s.err, "tessim: warning: " + d.at("prism.ply").string() + ": tags: 32 vertices carry scalar tags"))
      << s.err;

  // Options reach the tags.
  const TessimRun soft = run_tessim({"stpn-import", prism.string(), "--sigma", "0.5", "-o", d.at("soft.ply").string()},
                                    d.scratch.path());
  ASSERT_EQ(soft.status, 0) << soft.err;
  EXPECT_EQ(info_json(d.at("soft.ply"), d)["tags"]["sigma"], nlohmann::json({0.5, 0.5}));
}

TEST(StpnImportCli, UntaggedMeshesSayNone) {
  if (!fs::exists(kBox)) FAIL() << kBox << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const TessimRun text = run_tessim({"info", kBox.string()}, d.scratch.path());
  EXPECT_TRUE(contains(text.out, "tags                  none (plain PN triangles)")) << text.out;
  EXPECT_EQ(info_json(kBox, d)["tags"]["present"], false);
  const TessimRun t = run_tessim({"tessellate", kBox.string(), "-o", d.at("t.ply").string()}, d.scratch.path());
  EXPECT_FALSE(contains(t.out, "scalar-tagged")) << t.out;
}

TEST(StpnImportCli, BadOptionsAndPathsWriteNothing) {
  if (!fs::exists(kBox)) FAIL() << kBox << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const std::string out = d.at("out.ply").string();
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"--sigma", "-1"}, {"command line: --sigma: -1 is outside 0..1000"}},
      {{"--sigma", "nan"}, {"command line: --sigma: 'nan' is not a finite number"}},
      {{"--sigma", "x"}, {"command line: --sigma: 'x' is not a number"}},
      {{"--crease-angle", "0"}, {"command line: --crease-angle: 0 is outside (0, 180) degrees"}},
      {{"--crease-angle", "180"}, {"command line: --crease-angle: 180 is outside (0, 180) degrees"}},
      {{"--corner-tension", "2"}, {"command line: --corner-tension: 2 is outside -1..1"}},
  };
  for (const auto& [options, expected] : cases) {
    std::vector<std::string> args = {"stpn-import", kBox.string(), "-o", out};
    args.insert(args.end(), options.begin(), options.end());
    SCOPED_TRACE(options.front() + " " + options.back());
    const TessimRun r = run_tessim(args, d.scratch.path());
    EXPECT_EQ(r.status, 2) << r.err;
    for (const std::string& part : expected) EXPECT_TRUE(contains(r.err, "tessim: error: " + part)) << r.err;
  }
  const TessimRun obj = run_tessim({"stpn-import", kBox.string(), "-o", d.at("out.obj").string()}, d.scratch.path());
  EXPECT_EQ(obj.status, 2);
  EXPECT_TRUE(contains(obj.err, "out.obj: output: unsupported extension '.obj' (an ST-mesh is written as .ply)")) << obj.err;
  const TessimRun dir = run_tessim({"stpn-import", kBox.string(), "-o", d.at("no/out.ply").string()}, d.scratch.path());
  EXPECT_EQ(dir.status, 2);
  EXPECT_TRUE(contains(dir.err, "-o: cannot open for writing")) << dir.err;
  const TessimRun missing = run_tessim({"stpn-import", d.at("none.obj").string(), "-o", out}, d.scratch.path());
  EXPECT_EQ(missing.status, 2);
  EXPECT_TRUE(contains(missing.err, "none.obj: file: does not exist")) << missing.err;
  EXPECT_TRUE(d.work.empty());
}

}  // namespace
}  // namespace tessim
