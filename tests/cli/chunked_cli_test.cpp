// `tessim sim --chunks` (sim/run/chunked.hpp, docs/statistics.md "Chunked runs"): the same mesh
// file as a single run, the chunks' statistics, and a refusal of what it cannot merge.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim::sim {
namespace {

const char* const kSphere = "/usr/share/assimp/models/STL/sphereWithHole.stl";
const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(ChunkedCli, SameMeshFileAndChunkStatistics) {
  testing::TempDir dir;
  const auto out = dir.path() / "out";
  std::filesystem::create_directories(out);
  for (const char* weld : {"", "--weld"}) {
    const std::string ext = *weld ? ".obj" : ".ply";
    const auto a = out / ("single" + ext), b = out / ("chunked" + ext);
    std::vector<std::string> args = {"sim", kWuson, "-L", "3", "-o", a.string()};
    if (*weld) args.push_back(weld);
    ASSERT_EQ(testing::run_tessim(args, dir.path()).status, 0);
    args[5] = b.string();
    args.insert(args.end(), {"--chunks", "3", "--stats", (out / "s.json").string()});
    const auto r = testing::run_tessim(args, dir.path());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("chunks   3 chunks"), std::string::npos) << r.out;
    EXPECT_EQ(slurp(a), slurp(b)) << weld;
  }
  std::ifstream in(out / "s.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["chunks"]["count"], 3);
  EXPECT_EQ(j["chunks"]["cycles"].size(), 3u);
  EXPECT_EQ(j["schema_version"], kStatsSchemaVersion);
  // Nothing left behind but the outputs.
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(out)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"chunked.obj", "chunked.ply", "s.json", "single.obj", "single.ply"}));
}

TEST(ChunkedCli, RefusedWhereItCannotApply) {
  testing::TempDir dir;
  const auto out = dir.path() / "out";
  std::filesystem::create_directories(out);
  const std::string o = (out / "m.ply").string(), s = (out / "s.json").string(), t = (out / "t.json").string();
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--chunks", "2", "--trace", t}, {"--chunks", "auto", "--schedule"}, {"--chunks", "0"},
        {"--chunks", "33"}, {"--chunks", "two"}, {"--chunks", "4000"}}) {
    std::vector<std::string> args = {"sim", kSphere, "-L", "2", "-o", o, "--stats", s};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = testing::run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << extra[1];
    EXPECT_NE(r.err.find("--chunks"), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::is_empty(out)) << extra[1];
  }
  // More chunks than triangles.
  const auto one = dir.path() / "one.obj";
  {
    std::ofstream f(one);
    f << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.2\nf 1 2 3\nf 2 4 3\n";
  }
  const auto r = testing::run_tessim({"sim", one.string(), "--chunks", "3", "-o", o}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("2 triangles"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(out));
  EXPECT_EQ(testing::run_tessim({"sim", one.string(), "--chunks", "auto", "-o", o}, dir.path()).status, 0);
}

}  // namespace
}  // namespace tessim::sim
