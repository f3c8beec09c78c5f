// `tessim power` (sim/report/power.hpp, docs/silicon.md, Energy): the report's blocks add up to
// its totals, its energy follows the run's actions, clock gating leaves an idle unit its leakage
// alone, and a configuration without a characterization is refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

nlohmann::json power(testing::TempDir& dir, std::vector<std::string> extra, const std::string& name) {
  const auto out = dir.path() / (name + ".json");
  std::vector<std::string> args = {"power", kWuson, "--json", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = testing::run_tessim(args, dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  std::ifstream in(out);
  return nlohmann::json::parse(in);
}

double sum(const nlohmann::json& blocks, const char* key) {
  double s = 0;
  for (const auto& b : blocks) s += b[key].get<double>();
  return s;
}

TEST(PowerCli, BlocksAddUpToTheUnit) {
  testing::TempDir dir;
  const nlohmann::json r = power(dir, {"-L", "8"}, "l8");
  for (const char* key : {"area_mm2", "clock_mhz", "power_mw", "energy_nj_per_vertex", "int_blocks", "blocks",
                          "idle_power_mw", "mvertices_per_s"})
    EXPECT_TRUE(r.contains(key)) << key;
  EXPECT_EQ(r["int_blocks"], 2);
  EXPECT_NEAR(sum(r["blocks"], "area_mm2"), r["area_mm2"].get<double>(), 1e-9);
  EXPECT_NEAR(sum(r["blocks"], "power_mw"), r["power_mw"].get<double>(), 1e-9 * r["power_mw"].get<double>());
  EXPECT_NEAR(sum(r["blocks"], "energy_nj_per_vertex"), r["energy_nj_per_vertex"].get<double>(),
              1e-9 * r["energy_nj_per_vertex"].get<double>());
  int ints = 0;
  for (const auto& b : r["blocks"]) {
    for (const char* key : {"name", "area_mm2", "power_mw", "energy_nj_per_vertex"}) EXPECT_TRUE(b.contains(key));
    if (b["name"].get<std::string>().rfind("int", 0) == 0) {
      ++ints;
      EXPECT_GT(b["data_energy_nj"].get<double>(), 0) << b["name"];  // every INT block issued
    }
  }
  EXPECT_EQ(ints, 2);
  // Power is energy over time at the configuration's clock.
  const double seconds = r["cycles"].get<double>() / (r["clock_mhz"].get<double>() * 1e6);
  EXPECT_NEAR(r["power_mw"].get<double>() * 1e-3 * seconds * 1e9 / r["vertices"].get<double>(),
              r["energy_nj_per_vertex"].get<double>(), 1e-6 * r["energy_nj_per_vertex"].get<double>());
}

TEST(PowerCli, EnergyFollowsTheRunsActions) {
  testing::TempDir dir;
  const nlohmann::json l8 = power(dir, {"-L", "8"}, "l8");
  const nlohmann::json l2 = power(dir, {"-L", "2"}, "l2");
  auto block = [](const nlohmann::json& r, const std::string& name) {
    for (const auto& b : r["blocks"])
      if (b["name"] == name) return b;
    return nlohmann::json();
  };
  // Eight segments a side issue more INT operations and retire more vertices than two; the
  // INT blocks' data energy grows with their operations.
  EXPECT_GT(block(l8, "int0")["actions"].get<double>(), block(l2, "int0")["actions"].get<double>());
  EXPECT_GT(block(l8, "int0")["data_energy_nj"].get<double>(), block(l2, "int0")["data_energy_nj"].get<double>());
  EXPECT_GT(l8["data_mw"].get<double>(), 0.0);
}

TEST(PowerCli, ClockGatingLeavesAnIdleUnitItsLeakage) {
  testing::TempDir dir;
  const nlohmann::json plain = power(dir, {"-L", "8"}, "plain");
  const nlohmann::json gated = power(dir, {"-L", "8", "--clock-gating"}, "gated");
  double leakage = 0;
  for (const auto& b : gated["blocks"]) leakage += b["leakage_mw"].get<double>();
  EXPECT_NEAR(gated["idle_power_mw"].get<double>(), leakage, 1e-12);
  EXPECT_GT(plain["idle_power_mw"].get<double>(), 10 * plain["leakage_mw"].get<double>());  // the clock runs
  EXPECT_LT(gated["energy_nj_per_vertex"].get<double>(), plain["energy_nj_per_vertex"].get<double>());
  EXPECT_GT(gated["area_mm2"].get<double>(), plain["area_mm2"].get<double>());  // the gates' cells
  EXPECT_GT(gated["clock_gates"].get<double>(), 0);
}

TEST(PowerCli, UncharacterizedConfigurationIsRefusedByName) {
  testing::TempDir dir;
  const auto r = testing::run_tessim({"power", kWuson, "--int-blocks", "5"}, dir.path());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("no energy characterization"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("scripts/energy.py"), std::string::npos) << r.err;
  const auto units = testing::run_tessim({"power", kWuson, "--units", "2"}, dir.path());
  EXPECT_NE(units.status, 0);
  EXPECT_NE(units.err.find("--units"), std::string::npos) << units.err;
}

// At another clock the same run takes another time: power scales with the clock, the dynamic
// energy per vertex does not; a clock of zero or less is refused.
TEST(PowerCli, ClockOptionScalesPowerNotDynamicEnergy) {
  testing::TempDir dir;
  const nlohmann::json own = power(dir, {"-L", "4"}, "own");
  const nlohmann::json slow = power(dir, {"-L", "4", "--clock-mhz", "10"}, "slow");
  EXPECT_DOUBLE_EQ(slow["clock_mhz"].get<double>(), 10.0);
  const double ratio = own["clock_mhz"].get<double>() / 10.0;
  EXPECT_NEAR((own["clock_mw"].get<double>() + own["data_mw"].get<double>()) / ratio,
              slow["clock_mw"].get<double>() + slow["data_mw"].get<double>(), 1e-9 * own["power_mw"].get<double>());
  EXPECT_NEAR(own["leakage_mw"].get<double>(), slow["leakage_mw"].get<double>(), 1e-12);
  for (const char* bad : {"0", "-5"}) {
    const auto r = testing::run_tessim({"power", kWuson, "--clock-mhz", bad}, dir.path());
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--clock-mhz"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace tessim
