// `tessim cosim` on the command line (built with TESSIM_BUILD_RTL): wave options refused before
// the run, the coverage file accumulating across invocations, the configuration file selecting
// the RTL build, the tally of several seeds, int_blocks without an RTL build as bad input.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rtl/verilated/rtl_unit.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim::cosim {
namespace {

TEST(CosimWave, BadWaveOptionsAreInputErrorsBeforeTheRun) {
  tessim::testing::TempDir dir;
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  for (const Case& c : {Case{{"--wave", (dir.path() / "w.txt").string()}, "--wave: "},
                        Case{{"--wave", (dir.path() / "w.fst").string(), "--wave-window", "50:10"}, "--wave-window: "},
                        Case{{"--wave", (dir.path() / "w.fst").string(), "--wave-window", "10:50", "--seeds", "2"},
                             "--wave-window: "},
                        Case{{"--wave", (dir.path() / "w.fst").string(), "--wave-window", "0"}, "--wave-window: "},
                        Case{{"--wave", (dir.path() / "missing" / "w.vcd").string()}, "--wave: "}}) {
    std::vector<std::string> args{"cosim", "--random", "4"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto r = tessim::testing::run_tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "") << "nothing runs";
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "w.fst"));
}

// On the command line the file accumulates across invocations; a file that is not coverage is
// bad input, reported before anything runs.
TEST(CosimCli, CoverageAccumulatesInItsFile) {
  tessim::testing::TempDir dir;
  const std::string file = (dir.path() / "cov.json").string();
  const std::vector<std::string> cmd{"cosim", "--random", "4", "--random-max-L", "2", "--coverage", file};
  auto r = tessim::testing::run_tessim(cmd, dir.path());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("functional coverage: "), std::string::npos) << r.out;
  const auto cycles = [&] {
    std::ifstream in(file);
    const nlohmann::json j = nlohmann::json::parse(in);
    std::uint64_t n = 0;
    for (const auto& [bin, hits] : j["bins"].items())
      if (bin.rfind("te.ops_issued/", 0) == 0) n += hits.get<std::uint64_t>();
    return n;
  };
  const std::uint64_t once = cycles();
  EXPECT_GT(once, 0u);
  r = tessim::testing::run_tessim(cmd, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(cycles(), 2 * once);
  const auto bad = dir.write("bad.json", R"({"bins": {"te.class/busy": -3}})");
  r = tessim::testing::run_tessim({"cosim", "--random", "4", "--coverage", bad.string()}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(bad.string() + ": bins.te.class/busy: "), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

// `tessim cosim` on the command line: the configuration file's values hold unless a flag is
// given (the --int default used to overwrite the file's int_blocks), and an int_blocks without
// an RTL build is bad input naming the builds that exist (it used to be an internal error).
TEST(CosimCli, ConfigFileIntBlocksSelectTheBuild) {
  tessim::testing::TempDir dir;
  const auto cfg = dir.write("n1.json", R"({"int_blocks": 1, "gpe_cycles": 2})");
  auto r = tessim::testing::run_tessim({"cosim", "--random", "6", "--random-max-L", "3", "--config", cfg.string()},
                                       dir.path());
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("RTL n1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("config: N=1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("K=2 "), std::string::npos) << r.out;
  // A flag given overrides the file, under its canonical name and its alias.
  for (const char* flag : {"--int", "--int-blocks"}) {
    r = tessim::testing::run_tessim(
        {"cosim", "--random", "6", "--random-max-L", "3", "--config", cfg.string(), flag, "3"}, dir.path());
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("RTL n3 "), std::string::npos) << r.out;
  }
}

// Several seeds end with a tally; a failing run does not claim that everything was within the
// bound (it stopped at the divergence), and the tally says where it stopped.
TEST(CosimCli, SeedsEndWithATallyAndAFailureIsNotCalledClean) {
  tessim::testing::TempDir dir;
  auto r = tessim::testing::run_tessim({"cosim", "--random", "6", "--random-max-L", "2", "--seeds", "2"}, dir.path());
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("seeds: 2 of 2 run, 2 passed, 0 failed; "), std::string::npos) << r.out;
  r = tessim::testing::run_tessim(
      {"cosim", "--random", "12", "--random-max-L", "4", "--variant", "n2_bug1", "--seeds", "3", "--gpe-cycles", "1"},
      dir.path());
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_EQ(r.out.find("all within the derived bound"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("before the divergence within the derived bound"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("seeds: 1 of 3 run, 0 passed, 1 failed (stopped at the first failure)"), std::string::npos)
      << r.out;
}

TEST(CosimCli, IntBlocksWithoutAnRtlBuildIsAnInputError) {
  tessim::testing::TempDir dir;
  const auto r = tessim::testing::run_tessim({"cosim", "--random", "4", "--int", "5"}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err.rfind("tessim: error: command line: int_blocks: ", 0), 0u) << r.err;
  for (const std::string& v : rtl::rtl_variants()) EXPECT_NE(r.err.find(v), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  // From a file, the file is named; an unknown --variant is bad input too.
  const auto cfg = dir.write("n6.json", R"({"int_blocks": 6})");
  const auto f = tessim::testing::run_tessim({"cosim", "--random", "4", "--config", cfg.string()}, dir.path());
  EXPECT_EQ(f.status, 2) << f.err;
  EXPECT_EQ(f.err.rfind("tessim: error: " + cfg.string() + ": int_blocks: ", 0), 0u) << f.err;
  const auto v = tessim::testing::run_tessim({"cosim", "--random", "4", "--variant", "n9"}, dir.path());
  EXPECT_EQ(v.status, 2) << v.err;
  EXPECT_NE(v.err.find("--variant: no RTL build 'n9'; the RTL builds are n1, "), std::string::npos) << v.err;
}

}  // namespace
}  // namespace tessim::cosim
