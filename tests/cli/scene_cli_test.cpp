// tessim sim SCENE.scene.json (docs/scenes.md): every frame's draws through the unit and its
// geometry engine. A frame is the sum of its draws; a tessellated draw is exactly the per-mesh
// run of `tessim sim` (uniform or adaptive from the frame's camera), so the draws' vertices add up
// to the per-mesh runs'; an untessellated draw costs the unit nothing and the geometry engine K
// cycles per vertex; bad scenes are input errors naming the file and the element, with nothing
// written; the shipped scenes run.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;
using tessim::testing::TessimRun;

const std::string kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
const std::string kSphere = "/usr/share/assimp/models/STL/sphereWithHole.stl";
const std::string kCube = "/usr/share/assimp/models/PLY/cube.ply";

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

void write_json(const fs::path& path, const nlohmann::json& j) { std::ofstream(path) << j.dump(1); }

nlohmann::json mesh_stats(const TempDir& dir, const std::vector<std::string>& args) {
  const fs::path stats = dir.path() / "mesh.json";
  std::vector<std::string> argv{"sim"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--int-blocks", "2", "--gpe-cycles", "8", "--stats", stats.string(), "--quiet"});
  const TessimRun r = run_tessim(argv, dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  return read_json(stats);
}

const std::string kNear = "eye=1.5,1.8,4.5,target=0,0.75,0,fov=40";
const std::string kFar = "eye=9,6,14,target=0,0.75,0,fov=40";

nlohmann::json small_scene() {
  return {{"format", "tessim-scene"},
          {"version", 1},
          {"clock_mhz", 50},
          {"viewport", {640, 480}},
          {"draws",
           {{{"name", "ground"}, {"mesh", kCube}, {"tessellation", "none"},
             {"instances", {{{"translate", {-5, -0.1, -5}}, {"scale", {10, 0.1, 10}}}}}},
            {{"name", "wuson"}, {"mesh", kWuson}, {"tessellation", "uniform"}, {"L", 4}},
            {{"name", "blobs"}, {"mesh", kSphere}, {"tessellation", "uniform"}, {"L", 3},
             {"instances", {{{"translate", {3, 0, 0}}}, {{"translate", {-3, 0, 0}}, {"scale", 0.5}, {"rotate_y_deg", 30}}}}},
            {{"name", "near wuson"}, {"mesh", kWuson}, {"tessellation", "adaptive"}, {"rule", "screen"},
             {"pixels_per_segment", 12}}}},
          {"camera_path",
           {{{"eye", {1.5, 1.8, 4.5}}, {"target", {0, 0.75, 0}}, {"fov_deg", 40}},
            {{"eye", {9, 6, 14}}, {"target", {0, 0.75, 0}}, {"fov_deg", 40}}}}};
}

TEST(SceneCli, FramesAreTheirDrawsAndDrawsArePerMeshRuns) {
  TempDir dir;
  const fs::path scene = dir.path() / "small.scene.json";
  write_json(scene, small_scene());
  const fs::path stats = dir.path() / "s.json";
  const TessimRun r = run_tessim({"sim", scene.string(), "--int-blocks", "2", "--gpe-cycles", "8", "--stats",
                                  stats.string()},
                                 dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frame   1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frames per second at 50 MHz"), std::string::npos) << r.out;
  const nlohmann::json doc = read_json(stats);
  ASSERT_EQ(doc["frames"].size(), 2u);

  const nlohmann::json wuson = mesh_stats(dir, {kWuson, "-L", "4"});
  const nlohmann::json sphere = mesh_stats(dir, {kSphere, "-L", "3"});
  const nlohmann::json near = mesh_stats(dir, {kWuson, "--adaptive", "screen", "--camera", kNear, "--viewport", "640x480",
                                               "--pixels-per-segment", "12"});
  const nlohmann::json far = mesh_stats(dir, {kWuson, "--adaptive", "screen", "--camera", kFar, "--viewport", "640x480",
                                              "--pixels-per-segment", "12"});
  for (std::size_t k = 0; k < 2; ++k) {
    const nlohmann::json& frame = doc["frames"][k];
    ASSERT_EQ(frame["draws"].size(), 5u);  // ground, wuson, two blobs, near wuson
    std::uint64_t cycles = 0, vertices = 0, idle = 0;
    for (const auto& d : frame["draws"]) {
      cycles += d["cycles"].get<std::uint64_t>();
      vertices += d["vertices"].get<std::uint64_t>();
      if (d["tessellation"] == "none") idle += d["cycles"].get<std::uint64_t>();
    }
    EXPECT_EQ(frame["cycles"], cycles);
    EXPECT_EQ(frame["vertices"], vertices);
    EXPECT_EQ(frame["unit_idle_cycles"], idle);
    EXPECT_DOUBLE_EQ(frame["ms"].get<double>(), cycles / 50e3);
    // Untessellated: the unit does nothing, the geometry engine K cycles per distinct vertex.
    const auto& ground = frame["draws"][0];
    EXPECT_EQ(ground["unit_cycles"], 0);
    EXPECT_EQ(ground["vertices"], 8);  // the cube's corners
    EXPECT_EQ(ground["cycles"], 8 * 8);
    // Tessellated: each instance is the per-mesh run, whatever its placement; the draw ends when
    // the geometry engine has finished the last vertex (the rest of its K).
    auto expect_run = [](const nlohmann::json& draw, const nlohmann::json& run) {
      EXPECT_EQ(draw["vertices"], run["vertices_out"]);
      EXPECT_EQ(draw["unit_cycles"], run["cycles"]);
      EXPECT_EQ(run["gpe"]["drain_cycles"], 7);
      EXPECT_EQ(draw["cycles"], run["cycles"].get<std::uint64_t>() + 7);
    };
    expect_run(frame["draws"][1], wuson);
    for (int i : {2, 3}) {
      SCOPED_TRACE(i);
      expect_run(frame["draws"][i], sphere);
    }
    SCOPED_TRACE(k);
    expect_run(frame["draws"][4], k == 0 ? near : far);
    const nlohmann::json& adaptive = k == 0 ? near : far;
    EXPECT_EQ(frame["tessellated_vertices"],
              wuson["vertices_out"].get<std::uint64_t>() + 2 * sphere["vertices_out"].get<std::uint64_t>() +
                  adaptive["vertices_out"].get<std::uint64_t>());
  }
  EXPECT_GT(near["vertices_out"].get<std::uint64_t>(), far["vertices_out"].get<std::uint64_t>());
  EXPECT_EQ(doc["summary"]["worst_cycles"], std::max(doc["frames"][0]["cycles"].get<std::uint64_t>(),
                                                      doc["frames"][1]["cycles"].get<std::uint64_t>()));
}

// With a shader-core geometry engine: K is derived and printed, the frame's clock is unit_mhz,
// an untessellated draw costs full waves of the core's own program, and a tessellated one the
// per-mesh run with the same core plus the core's drain.
TEST(SceneCli, AShaderCoreDerivesKAndRunsOnItsOwnClock) {
  TempDir dir;
  const fs::path scene = dir.path() / "small.scene.json";
  write_json(scene, small_scene());
  const fs::path stats = dir.path() / "s.json";
  const std::vector<std::string> core{"--ge-core-lanes", "8", "--ge-core-mhz", "100", "--unit-mhz", "40"};
  std::vector<std::string> argv{"sim", scene.string(), "--int-blocks", "2", "--stats", stats.string()};
  argv.insert(argv.end(), core.begin(), core.end());
  const TessimRun r = run_tessim(argv, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  // K = 65 slots a wave / 8 lanes × 40 / 100 = 3.25 unit cycles per vertex.
  EXPECT_NE(r.out.find("GE core 8 lanes at 100 MHz: K = 3.250"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("frame times at unit_mhz 40"), std::string::npos) << r.err;  // not the scene's 50
  const nlohmann::json doc = read_json(stats);
  EXPECT_DOUBLE_EQ(doc["summary"]["ge_cycles_per_vertex"].get<double>(), 3.25);
  std::vector<std::string> mesh_args{"sim", kWuson, "-L", "4", "--int-blocks", "2", "--stats",
                                     (dir.path() / "m.json").string(), "--quiet"};
  mesh_args.insert(mesh_args.end(), core.begin(), core.end());
  ASSERT_EQ(run_tessim(mesh_args, dir.path()).status, 0);
  const nlohmann::json wuson = read_json(dir.path() / "m.json");
  EXPECT_EQ(wuson["ge"]["core"]["lanes"], 8);
  EXPECT_GT(wuson["gpe"]["drain_cycles"].get<std::uint64_t>(), 0u);
  for (const auto& frame : doc["frames"]) {
    const auto& ground = frame["draws"][0];
    EXPECT_EQ(ground["unit_cycles"], 0);
    EXPECT_EQ(ground["cycles"], 26);  // one wave of 8 corners: 65 core cycles = 26 unit cycles
    EXPECT_EQ(frame["draws"][1]["unit_cycles"], wuson["cycles"]);
    EXPECT_EQ(frame["draws"][1]["cycles"],
              wuson["cycles"].get<std::uint64_t>() + wuson["gpe"]["drain_cycles"].get<std::uint64_t>());
    EXPECT_DOUBLE_EQ(frame["ms"].get<double>(), frame["cycles"].get<double>() / 40e3);
  }
}

TEST(SceneCli, BadScenesAreInputErrorsAndWriteNothing) {
  TempDir dir;
  auto with = [](auto change) {
    nlohmann::json j = small_scene();
    change(j);
    return j;
  };
  const std::vector<std::pair<nlohmann::json, std::string>> cases{
      {with([](nlohmann::json& j) { j["colour"] = 1; }), "colour: unknown key"},
      {with([](nlohmann::json& j) { j["format"] = "scene"; }), "format"},
      {with([](nlohmann::json& j) { j["draws"][1]["L"] = 65; }), "draws[1].L"},
      {with([](nlohmann::json& j) { j["draws"][0]["L"] = 4; }), "draws[0].L: only uniform"},
      {with([](nlohmann::json& j) { j["draws"][1]["tessellation"] = "fine"; }), "draws[1].tessellation"},
      {with([](nlohmann::json& j) { j["draws"][3]["rule"] = "nyquist"; }), "draws[3].rule"},
      {with([](nlohmann::json& j) { j["draws"][3]["outline_tolerance"] = 1; }), "draws[3].outline_tolerance"},
      {with([](nlohmann::json& j) { j["draws"][2]["instances"][0]["scale"] = 0; }), "draws[2].instances[0].scale"},
      {with([](nlohmann::json& j) { j["draws"][1]["mesh"] = "missing.ply"; }), "draws[1].mesh"},
      {with([](nlohmann::json& j) { j["camera_path"] = nlohmann::json::array(); }), "camera_path"},
      {with([](nlohmann::json& j) { j["camera_path"][1]["eye"] = {0, 0.75, 0}; }), "camera_path[1]: eye and target"},
  };
  const fs::path stats = dir.path() / "s.json";
  for (const auto& [scene, expected] : cases) {
    const fs::path file = dir.path() / "bad.scene.json";
    write_json(file, scene);
    const TessimRun r = run_tessim({"sim", file.string(), "--stats", stats.string()}, dir.path());
    EXPECT_EQ(r.status, 2) << expected;
    EXPECT_NE(r.err.find("bad.scene.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(stats)) << expected;
  }
  const fs::path good = dir.path() / "good.scene.json";
  write_json(good, small_scene());
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"-L", "8"}, {"--adaptive", "screen", "--camera", kNear}, {"-o", (dir.path() / "o.ply").string()},
           {"--units", "2"}, {"--chunks", "2"}}) {
    std::vector<std::string> argv{"sim", good.string(), "--stats", stats.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const TessimRun r = run_tessim(argv, dir.path());
    EXPECT_EQ(r.status, 2) << extra[0];
    EXPECT_NE(r.err.find(extra[0]), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(stats)) << extra[0];
  }
}

TEST(SceneCli, ShippedScenesRun) {
  TempDir dir;
  for (const char* name : {"herd", "figures"}) {
    const fs::path scene = fs::path(TESSIM_SOURCE_DIR) / "scenes" / (std::string(name) + ".scene.json");
    const fs::path stats = dir.path() / (std::string(name) + ".json");
    const TessimRun r = run_tessim({"sim", scene.string(), "--stats", stats.string(), "--quiet"}, dir.path());
    ASSERT_EQ(r.status, 0) << name << "\n" << r.err;
    const nlohmann::json doc = read_json(stats);
    const nlohmann::json source = read_json(scene);
    ASSERT_EQ(doc["frames"].size(), source["camera_path"].size()) << name;
    std::size_t instances = 0;
    for (const auto& d : source["draws"]) instances += d.contains("instances") ? d["instances"].size() : 1;
    for (const auto& frame : doc["frames"]) {
      EXPECT_EQ(frame["draws"].size(), instances) << name;
      EXPECT_GT(frame["unit_idle_cycles"].get<std::uint64_t>(), 0u) << name;  // the ground and the props
      EXPECT_GT(frame["tessellated_vertices"].get<std::uint64_t>(), 0u) << name;
    }
    EXPECT_GT(doc["summary"]["sustained_fps"].get<double>(), 0.0) << name;
  }
}

}  // namespace
