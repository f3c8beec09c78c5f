// `tessim sim --units M --threads T` (sim/system/system_threads.hpp): the mesh file and the
// statistics of a system of units are the same bytes whatever the thread count (the wall time
// aside), and the thread count is refused where it makes no sense.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(UnitsCli, SameMeshAndStatisticsOnAnyThreadCount) {
  testing::TempDir dir;
  // Uniform factors with a roomy buffer (the units run ahead), and adaptive ones with a small
  // buffer under random stalls (the run goes serial while the buffer is full).
  const std::vector<std::vector<std::string>> configs = {
      {"-L", "5", "--units", "4", "--ge-ports", "4", "--gpe-cycles", "1", "--reorder-slots", "4096"},
      {"--adaptive", "screen", "--camera", "eye=1.2,1.5,-2.2", "--units", "3", "--ge-ports", "2",
       "--reorder-slots", "64", "--gpe-stall-prob", "0.2", "--distribution", "least_loaded"}};
  for (const auto& config : configs) {
    std::string want_mesh;
    nlohmann::json want_stats;
    for (const std::string threads : {"1", "2", "3", "auto"}) {
      const auto mesh = dir.path() / ("out" + threads + ".ply");
      const auto stats = dir.path() / ("stats" + threads + ".json");
      std::vector<std::string> args = {"sim", kWuson, "--threads", threads, "-o", mesh.string(), "--stats", stats.string()};
      args.insert(args.end(), config.begin(), config.end());
      const auto r = testing::run_tessim(args, dir.path());
      ASSERT_EQ(r.status, 0) << r.err;
      std::ifstream in(stats);
      nlohmann::json j = nlohmann::json::parse(in);
      j.erase("wall_seconds");
      if (threads == "1") {
        want_mesh = slurp(mesh);
        want_stats = j;
        ASSERT_GT(want_mesh.size(), 10000u);
        EXPECT_TRUE(j.contains("system"));
      } else {
        EXPECT_EQ(slurp(mesh), want_mesh) << threads << " threads";
        EXPECT_EQ(j, want_stats) << threads << " threads";
      }
    }
  }
}

TEST(UnitsCli, RefusesAThreadCountOutOfRange) {
  testing::TempDir dir;
  for (const char* bad : {"0", "65", "two", "1.5"}) {
    const auto r = testing::run_tessim({"sim", kWuson, "-L", "2", "--units", "2", "--threads", bad}, dir.path());
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
  }
}

// Chunks of a system of units used to report every unit's cycles added together (1 793 360 for
// Wuson at --units 4 --chunks 2, against 448 090 unchunked): refused, with nothing written.
TEST(UnitsCli, RefusesChunksOfASystemOfUnits) {
  testing::TempDir dir;
  const auto r = testing::run_tessim(
      {"sim", kWuson, "-L", "2", "--units", "4", "--chunks", "2", "--stats", "s.json"}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--chunks: cannot be combined with --units 4"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "s.json"));
}

// A system's options with one unit used to be accepted, ignored and written into the statistics
// (config.ge_ports = 4 with one port's cycles).
TEST(UnitsCli, RefusesASystemsOptionsForOneUnit) {
  testing::TempDir dir;
  for (const std::vector<std::string>& option : std::vector<std::vector<std::string>>{
           {"--ge-ports", "4"}, {"--reorder-slots", "64"}, {"--distribution", "least_loaded"},
           {"--dispatch-batch", "2"}, {"--reassembly", "unordered"}}) {
    std::vector<std::string> args = {"sim", kWuson, "-L", "2", "--stats", "s.json"};
    args.insert(args.end(), option.begin(), option.end());
    const auto r = testing::run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << option[0] << ": " << r.err;
    EXPECT_NE(r.err.find(option[0] + ": has no effect on one unit"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "s.json"));
    args.insert(args.end(), {"--units", "2"});  // the same option for a system is taken
    EXPECT_EQ(testing::run_tessim(args, dir.path()).status, 0) << option[0];
  }
}

// The summary says what was measured: no line of zeros for late intervals a system does not
// classify, or that a GPE never had; dispatch stalls with their unit.
TEST(UnitsCli, SummaryLinesSayWhatWasMeasured) {
  testing::TempDir dir;
  const auto system = testing::run_tessim({"sim", kWuson, "-L", "2", "--units", "2"}, dir.path());
  ASSERT_EQ(system.status, 0) << system.err;
  EXPECT_EQ(system.out.find("\nlate "), std::string::npos) << system.out;
  EXPECT_NE(system.out.find("cycles of dispatch stalls"), std::string::npos) << system.out;
  const auto unit = testing::run_tessim({"sim", kWuson, "-L", "8", "--gpe-cycles", "40"}, dir.path());
  ASSERT_EQ(unit.status, 0) << unit.err;
  EXPECT_NE(unit.out.find("late     GPE never waited for a vertex"), std::string::npos) << unit.out;
}

TEST(UnitsCli, RefusesATraceWindowWithoutATrace) {
  testing::TempDir dir;
  const auto r = testing::run_tessim({"sim", kWuson, "-L", "2", "--trace-window", "0:100"}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--trace-window: needs --trace"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tessim
