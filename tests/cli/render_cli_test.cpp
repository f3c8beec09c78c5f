// `tessim render` end to end: arguments refused before anything is written, the flat/PN
// comparison's panels, image formats, the heat maps of --color against what `tessim sim
// --errors` reports, the tagged mesh's panels and difference, colour options that cannot be
// measured.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/raster.hpp"
#include "tests/support/icosphere.hpp"
#include "tests/support/read_image.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace tessim::render;
using tessim::testing::read_back;
using tessim::testing::ReadBack;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;
using tessim::testing::TessimRun;

namespace {

const std::string kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
const std::string kCinema4D = "/usr/share/assimp/models/Collada/Cinema4D.dae";

using tessim::render::test_meshes::icosphere;

void write_obj(const RenderMesh& mesh, const fs::path& path) {
  std::ofstream out(path);
  for (const glm::dvec3& p : mesh.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const glm::dvec3& n : mesh.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
  for (const glm::uvec3& t : mesh.triangles)
    out << "f " << t.x + 1 << "//" << t.x + 1 << ' ' << t.y + 1 << "//" << t.y + 1 << ' ' << t.z + 1 << "//"
        << t.z + 1 << '\n';
}

// The "largest value" a heat-map render prints (its colour line), or NaN when missing.
double largest_value(const tessim::testing::TessimRun& run) {
  const auto at = run.out.find("largest value ");
  return at == std::string::npos ? std::nan("") : std::stod(run.out.substr(at + 14));
}

}  // namespace

TEST(RenderCommand, RejectsBadArgumentsBeforeWritingAnything) {
  TempDir dir;
  const fs::path mesh = dir.path() / "ball.obj";
  write_obj(icosphere(1), mesh);
  TempDir scratch;  // the captured streams
  const std::string out = (dir.path() / "out.png").string();
  const std::string ball = mesh.string();
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"render", ball, "--size", "0x10", "-o", out},
           {"render", ball, "--size", "10", "-o", out},
           {"render", ball, "--size", "9000x10", "-o", out},
           {"render", ball, "-L", "0", "-o", out},
           {"render", ball, "-L", "65", "-o", out},
           {"render", ball, "--normals", "cubic", "-o", out},
           {"render", ball, "--compare", "smooth", "-o", out},
           {"render", ball, "--elevation", "100", "-o", out},
           {"render", ball, "--up", "x", "-o", out},
           {"render", ball, "-o", (dir.path() / "out.bmp").string()},
           {"render", ball, "-o", (dir.path() / "no" / "out.png").string()},
           {"render", (dir.path() / "missing.obj").string(), "-o", out}}) {
    const TessimRun r = run_tessim(bad, scratch.path());
    const std::string line = bad[2] + " " + bad[3];
    EXPECT_EQ(r.status, 2) << line;
    EXPECT_NE(r.err.find("tessim: error:"), std::string::npos) << line << "\n" << r.err;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"ball.obj"}) << line;
  }
}

TEST(RenderCommand, CompareWritesFlatAndPnPanels) {
  TempDir dir;
  const fs::path mesh = dir.path() / "ball.obj";
  write_obj(icosphere(1), mesh);
  const fs::path png = dir.path() / "cmp.png";
  ASSERT_EQ(run_tessim({"render", mesh.string(), "-L", "3", "--compare", "flat", "--wireframe", "--size", "96x64",
                        "--no-caption", "-o", png.string()},
                       dir.path())
                .status,
            0);
  const ReadBack both = read_back(png);
  ASSERT_EQ(both.width, 2 * 96 + kSeparatorWidth);
  ASSERT_EQ(both.height, 64);
  // Same camera: the same silhouette (to within the PN bulge) in both panels, but different
  // shading inside it (facets on the left, smooth on the right).
  std::size_t left_covered = 0, right_covered = 0, differing = 0;
  const float background = both.rgb[0];  // the top left corner is empty
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x) {
      const float* l = &both.rgb[(static_cast<std::size_t>(y) * both.width + x) * 3];
      const float* r = &both.rgb[(static_cast<std::size_t>(y) * both.width + x + 96 + kSeparatorWidth) * 3];
      left_covered += std::abs(l[0] - background) > 0.02f;
      right_covered += std::abs(r[0] - background) > 0.02f;
      differing += std::abs(l[0] - r[0]) > 0.02f;
    }
  EXPECT_GT(left_covered, 96u * 64u / 4);
  EXPECT_NEAR(double(right_covered), double(left_covered), 0.15 * left_covered);
  EXPECT_GT(differing, left_covered / 4);

  const fs::path exr = dir.path() / "single.exr";
  ASSERT_EQ(run_tessim({"render", mesh.string(), "--normals", "derivative", "--size", "50x40", "--no-caption", "-o",
                        exr.string()},
                       dir.path())
                .status,
            0);
  const ReadBack single = read_back(exr);
  EXPECT_EQ(single.width, 50);
  EXPECT_EQ(single.height, 40);
}

TEST(RenderCommand, ErrorHeatMapMeasuresWhatSimErrorsReports) {
  TempDir dir;
  const fs::path png = dir.path() / "err.png", stats = dir.path() / "stats.json";
  const auto render = run_tessim({"render", kWuson, "-L", "3", "--color", "error-position", "--size", "200x150", "-o",
                                  png.string()},
                                 dir.path());
  ASSERT_EQ(render.status, 0) << render.err;
  const auto sim = run_tessim({"sim", kWuson, "-L", "3", "--errors", "--stats", stats.string()}, dir.path());
  ASSERT_EQ(sim.status, 0) << sim.err;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
  const double position_max = j.at("errors").at("position_max").get<double>();
  const double largest = largest_value(render);
  ASSERT_FALSE(std::isnan(largest)) << render.out;
  EXPECT_NEAR(largest, position_max, 1e-5 * position_max) << render.out;
  EXPECT_GT(largest, 0.0);

  const ReadBack image = read_back(png);
  ASSERT_EQ(image.width, 200);
  EXPECT_GT(image.height, 150 + 40);  // caption above, colour bar below
  // The normal heat map: angles in radians, far below a degree with 20 fraction bits.
  const auto normal = run_tessim({"render", kWuson, "-L", "3", "--color", "error-normal", "--size", "120x90", "-o",
                                  (dir.path() / "n.png").string()},
                                 dir.path());
  ASSERT_EQ(normal.status, 0) << normal.err;
  const double angle = largest_value(normal);
  EXPECT_GT(angle, 0.0);
  EXPECT_LT(angle, 0.0175);
}

TEST(RenderCommand, ColourScaleCanBeFixedAndClips) {
  TempDir dir;
  const auto r = run_tessim({"render", kWuson, "-L", "2", "--color", "pn-vs-flat", "--color-max", "1e-4", "--size",
                             "120x90", "-o", (dir.path() / "c.png").string()},
                            dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("0 .. 0.0001 "), std::string::npos) << r.out;
  const double largest = largest_value(r);
  EXPECT_GT(largest, 1e-4);  // PN bulges far more than 1e-4 of the diagonal somewhere
}

TEST(RenderCommand, TaggedMeshPanelsAndTheirDifference) {
  TempDir dir;
  const fs::path st = dir.path() / "c4d.ply";
  ASSERT_EQ(run_tessim({"stpn-import", kCinema4D, "-o", st.string()}, dir.path()).status, 0);
  const auto three = run_tessim({"render", st.string(), "-L", "4", "--compare", "flat,pn", "--size", "100x80",
                                 "--no-caption", "-o", (dir.path() / "three.png").string()},
                                dir.path());
  ASSERT_EQ(three.status, 0) << three.err;
  EXPECT_NE(three.out.find("STPN triangles"), std::string::npos) << three.out;
  EXPECT_NE(three.out.find("left: flat input | PN (tags ignored)"), std::string::npos) << three.out;
  const ReadBack image = read_back(dir.path() / "three.png");
  EXPECT_EQ(image.width, 3 * 100 + 2 * kSeparatorWidth);
  EXPECT_EQ(image.height, 80);

  const auto diff = run_tessim({"render", st.string(), "-L", "4", "--color", "stpn-vs-pn", "--size", "100x80", "-o",
                                (dir.path() / "diff.png").string()},
                               dir.path());
  ASSERT_EQ(diff.status, 0) << diff.err;
  // The cube's creases move the surface by a few percent of the diagonal; the sphere not at all.
  const double largest = largest_value(diff);
  EXPECT_GT(largest, 0.01);
  EXPECT_LT(largest, 0.2);
}

TEST(RenderCommand, ColourOptionsRejectWhatCannotBeMeasured) {
  TempDir dir;
  const std::string out = (dir.path() / "x.png").string();
  const std::vector<std::vector<std::string>> bad = {
      {"render", kWuson, "--color", "rainbow", "-o", out},
      {"render", kWuson, "--color", "pn-vs-flat", "--color-max", "-1", "-o", out},
      {"render", kWuson, "--color", "error-position", "--partitioning", "fractional_odd", "-o", out},
      {"render", kWuson, "--color", "error-normal", "--normals", "derivative", "-o", out},
      {"render", kWuson, "--color", "stpn-vs-pn", "-o", out},
      {"render", kWuson, "--compare", "pn", "-o", out},
      {"render", kWuson, "--compare", "flat,flat", "-o", out},
      {"render", kWuson, "--config", (dir.path() / "missing.json").string(), "-o", out},
      {"render", kWuson, "--color", "error-position", "--config", (dir.path() / "missing.json").string(), "-o", out},
  };
  for (const auto& args : bad) {
    const auto r = run_tessim(args, dir.path());
    std::string line;
    for (const auto& a : args) line += a + " ";
    EXPECT_EQ(r.status, 2) << line << r.err;
    EXPECT_NE(r.err.find("tessim: error:"), std::string::npos) << line << r.err;
    EXPECT_FALSE(fs::exists(out)) << line;
  }
}

namespace {

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

void write_lines(const fs::path& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const std::string& line : lines) out << line << '\n';
}

}  // namespace

// --view-path renders a frame per camera; --contours measures each. A uniform pattern ignores a
// frame's tessellation camera; an adaptive one follows it (the same camera twice is a plain
// frame, a far one changes the factors); the single-picture --contours agrees with the path's
// frame from the same camera; frames are written as numbered pictures.
TEST(RenderCommand, ViewPathFramesAndTheirContours) {
  TempDir dir;
  const std::string near = "eye=1.5,1.8,4.5,target=0,0.75,0,fov=40";
  const std::string side = "eye=4.6,1.2,0.5,target=0,0.75,0,fov=40";
  const std::string far = "eye=30,9,3,target=0,0.75,0,fov=40";
  const fs::path path = dir.path() / "views.path";
  write_lines(path, {"# a comment", near, "", side, side + " ; " + far, side + " ;" + side});
  const fs::path uniform = dir.path() / "uniform.json";
  const TessimRun u = run_tessim({"render", kWuson, "-L", "2", "--size", "160x120", "--view-path", path.string(),
                                  "--contours", uniform.string(), "-o", (dir.path() / "f%02d.png").string()},
                                 dir.path());
  ASSERT_EQ(u.status, 0) << u.err;
  EXPECT_NE(u.out.find("rendered 4 frames"), std::string::npos) << u.out;
  for (const char* name : {"f00.png", "f01.png", "f02.png", "f03.png"}) {
    const ReadBack image = read_back(dir.path() / name);
    EXPECT_EQ(image.width, 160) << name;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "f04.png"));
  const nlohmann::json doc = read_json(uniform);
  EXPECT_EQ(doc["format"], "tessim-contours");
  EXPECT_EQ(doc["samples_per_pixel"], 4);
  ASSERT_EQ(doc["frames"].size(), 4u);
  for (const auto& frame : doc["frames"]) {
    EXPECT_EQ(frame["triangles"], 3732 * 4);
    EXPECT_GT(frame["contour_samples"].get<int>(), 200);
    for (std::size_t i = 0; i < frame["contour"].size(); i += 2) {
      ASSERT_LT(frame["contour"][i].get<int>(), 160 * 4);
      ASSERT_LT(frame["contour"][i + 1].get<int>(), 120 * 4);
    }
  }
  EXPECT_NE(doc["frames"][0]["contour"], doc["frames"][1]["contour"]);  // another view
  EXPECT_EQ(doc["frames"][1]["contour"], doc["frames"][2]["contour"]);  // uniform: the same surface
  EXPECT_EQ(doc["frames"][1]["contour"], doc["frames"][3]["contour"]);

  const fs::path adaptive = dir.path() / "adaptive.json";
  const TessimRun a = run_tessim({"render", kWuson, "--adaptive", "silhouette", "--viewport", "160x120",
                                  "--outline-tolerance", "0.25", "--size", "160x120", "--view-path", path.string(),
                                  "--contours", adaptive.string()},
                                 dir.path());
  ASSERT_EQ(a.status, 0) << a.err;
  const nlohmann::json ad = read_json(adaptive);
  ASSERT_EQ(ad["frames"].size(), 4u);
  EXPECT_EQ(ad["frames"][1]["contour"], ad["frames"][3]["contour"]);    // its own camera twice
  EXPECT_EQ(ad["frames"][1]["triangles"], ad["frames"][3]["triangles"]);
  EXPECT_GT(ad["frames"][1]["triangles"].get<int>(), ad["frames"][2]["triangles"].get<int>());  // far: coarser
  EXPECT_NE(ad["frames"][1]["contour"], ad["frames"][2]["contour"]);    // the stale factors show
  EXPECT_EQ(ad["frames"][2]["camera"], ad["frames"][1]["camera"]);
  EXPECT_NE(ad["frames"][2]["tessellation_camera"], ad["frames"][1]["tessellation_camera"]);

  // One picture with --contours: the same map as the path's frame from that camera.
  const fs::path single = dir.path() / "single.json";
  const TessimRun s = run_tessim({"render", kWuson, "-L", "2", "--size", "160x120", "--view-camera", side, "--contours",
                                  single.string(), "-o", (dir.path() / "single.png").string()},
                                 dir.path());
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_EQ(read_json(single)["frames"][0]["contour"], doc["frames"][1]["contour"]);
}

TEST(RenderCommand, ViewPathRejectsBadFramesBeforeWritingAnything) {
  TempDir dir;
  const fs::path bad_line = dir.path() / "bad.path";
  write_lines(bad_line, {"eye=1,2,3", "eye=1,2", "eye=1,2,3"});
  const fs::path three = dir.path() / "three.path";
  write_lines(three, {"eye=1,2,3 ; eye=3,2,1 ; eye=0,0,5"});
  const fs::path empty = dir.path() / "empty.path";
  write_lines(empty, {"# nothing", ""});
  const fs::path good = dir.path() / "good.path";
  write_lines(good, {"eye=1.5,1.8,4.5,target=0,0.75,0"});
  TempDir scratch;
  const std::string json = (dir.path() / "c.json").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"--view-path", bad_line.string(), "--contours", json}, "bad.path: line 2"},
      {{"--view-path", three.string(), "--contours", json}, "more than two cameras"},
      {{"--view-path", empty.string(), "--contours", json}, "no camera"},
      {{"--view-path", (dir.path() / "missing.path").string(), "--contours", json}, "cannot be opened"},
      {{"--view-path", good.string()}, "needs -o"},
      {{"--view-path", good.string(), "-o", (dir.path() / "frame.png").string()}, "%d"},
      {{"--view-path", good.string(), "-o", (dir.path() / "f%d%d.png").string()}, "%d"},
      {{"--view-path", good.string(), "--contours", json, "--view-camera", "eye=1,2,3"}, "--view-camera"},
      {{"--view-path", good.string(), "--contours", json, "--compare", "flat"}, "--compare"},
      {{"--view-path", good.string(), "--contours", json, "--contour-samples", "0"}, "--contour-samples"},
      {{"--view-path", good.string(), "--contours", json, "--contour-depth-jump", "0"}, "--contour-depth-jump"},
      {{"--view-path", good.string(), "--contours", json, "--adaptive", "nyquist", "--displace", "sine",
        "--amplitude", "0.01", "--frequency", "5"},
       "nyquist"},
  };
  for (const auto& [extra, expected] : cases) {
    std::vector<std::string> argv{"render", kWuson, "--size", "64x48"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const TessimRun r = run_tessim(argv, scratch.path());
    EXPECT_EQ(r.status, 2) << expected << "\n" << r.out;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    std::vector<std::string> left = dir.entries();
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"bad.path", "empty.path", "good.path", "three.path"})) << expected;
  }
}
