// The statistics as a data product: every number of `tessim sim --stats` has a unit, the file
// names its format version and the tool, and `tessim compare` puts two runs side by side.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

using nlohmann::json;

const char* const kMesh = "/usr/share/assimp/models/STL/sphereWithHole.stl";

json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

// Numbers by their unit-table path ("int.blocks[].busy"), configuration and units left out.
void numeric_paths(const json& j, const std::string& path, std::set<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      if (path.empty() && (k == "config" || k == "units")) continue;
      numeric_paths(v, path.empty() ? k : path + "." + k, out);
    }
  } else if (j.is_array()) {
    for (const auto& v : j) numeric_paths(v, path + "[]", out);
  } else if (j.is_number()) {
    out.insert(path);
  }
}

TEST(StatsJson, EveryNumberHasAUnitAndEveryUnitANumber) {
  testing::TempDir dir;
  const auto plain = dir.path() / "plain.json", rich = dir.path() / "rich.json";
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "3", "--stats", plain.string()}, dir.path()).status, 0);
  // --errors, adaptive factors and chunks add the error, varying-workload and chunk figures.
  const auto r = testing::run_tessim({"sim", kMesh, "--errors", "--adaptive", "screen", "--camera",
                                      "eye=1.5,1.5,5,target=1.5,1.5,1.5", "--chunks", "2", "--stats", rich.string()},
                                     dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  // A system of units adds its own figures.
  const auto system = dir.path() / "system.json";
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "2", "--units", "2", "--ge-ports", "2", "--stats", system.string()},
                                dir.path())
                .status,
            0);
  // A shader-core geometry engine adds the core's figures.
  const auto core = dir.path() / "core.json";
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "2", "--ge-core-lanes", "8", "--stats", core.string()}, dir.path())
                .status,
            0);
  const json units = sim::stats_units();
  std::set<std::string> seen;
  for (const auto& p : {plain, rich, system, core}) {
    const json j = read_json(p);
    EXPECT_EQ(j["schema_version"], sim::kStatsSchemaVersion);
    EXPECT_EQ(j["tool"]["name"], "tessim");
    EXPECT_FALSE(j["tool"]["version"].get<std::string>().empty());
    EXPECT_EQ(j["units"], units);
    std::set<std::string> paths;
    numeric_paths(j, "", paths);
    for (const std::string& path : paths) EXPECT_TRUE(units.contains(path)) << path << " has no unit";
    seen.insert(paths.begin(), paths.end());
  }
  for (const auto& [path, unit] : units.items()) EXPECT_TRUE(seen.contains(path)) << path << " is in no statistics";
  // `tessim schema` lists the same table.
  const auto s = testing::run_tessim({"schema"}, dir.path());
  ASSERT_EQ(s.status, 0);
  EXPECT_EQ(json::parse(s.out)["statistics"]["units"], units);
}

TEST(CompareCli, TwoRunsSideBySideWithRatios) {
  testing::TempDir dir;
  const auto a = dir.path() / "a.json", b = dir.path() / "b.json";
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "4", "--stats", a.string()}, dir.path()).status, 0);
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "4", "--cpg-lanes", "3", "--stats", b.string()}, dir.path()).status,
            0);
  const json ja = read_json(a), jb = read_json(b);
  auto r = testing::run_tessim({"compare", a.string(), b.string()}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("config.cpg_lanes"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("config.int_blocks"), std::string::npos) << "only differing configuration keys";
  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.4f", jb["cycles"].get<double>() / ja["cycles"].get<double>());
  const std::size_t line = r.out.find("\ncycles ");
  ASSERT_NE(line, std::string::npos) << r.out;
  const std::string cycles_line = r.out.substr(line + 1, r.out.find('\n', line + 1) - line - 1);
  EXPECT_NE(cycles_line.find(std::to_string(ja["cycles"].get<std::uint64_t>())), std::string::npos) << cycles_line;
  EXPECT_NE(cycles_line.find(std::to_string(jb["cycles"].get<std::uint64_t>())), std::string::npos) << cycles_line;
  EXPECT_NE(cycles_line.find(ratio), std::string::npos) << cycles_line;
  EXPECT_NE(cycles_line.find("cycles"), std::string::npos);

  r = testing::run_tessim({"compare", a.string(), b.string(), "--csv"}, dir.path());
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("key,a,b,ratio_b_over_a,unit\n", 0), 0u);
  EXPECT_NE(r.out.find("\ncycles," + std::to_string(ja["cycles"].get<std::uint64_t>()) + "," +
                       std::to_string(jb["cycles"].get<std::uint64_t>()) + "," + ratio + ",cycles\n"),
            std::string::npos)
      << r.out;

  // Not statistics: bad input, named.
  const auto bad = dir.write("bad.json", R"({"x": 1})");
  r = testing::run_tessim({"compare", a.string(), bad.string()}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(bad.string() + ": statistics: "), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

// The first column of each row of compare's table, in order.
std::vector<std::string> row_keys(const std::string& out) {
  std::vector<std::string> keys;
  std::size_t start = out.find("\nstatistic ");
  while (start != std::string::npos && start + 1 < out.size()) {
    const std::size_t end = out.find('\n', start + 1);
    const std::string line = out.substr(start + 1, end == std::string::npos ? std::string::npos : end - start - 1);
    if (!line.empty() && line[0] != ' ') keys.push_back(line.substr(0, line.find(' ')));
    start = end;
  }
  if (!keys.empty()) keys.erase(keys.begin());  // the header
  return keys;
}

TEST(CompareCli, IntegersExactKeysInNaturalOrderAndFilters) {
  testing::TempDir dir;
  const auto a = dir.path() / "a.json", b = dir.path() / "b.json";
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "2", "--stats", a.string()}, dir.path()).status, 0);
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "9", "--stats", b.string()}, dir.path()).status, 0);
  // A long run's count, stored as a double as the analytic figures are.
  json jb = read_json(b);
  jb["analytic"]["run_cycles"] = 1343771.0;
  { std::ofstream(b) << jb.dump(1); }

  auto r = testing::run_tessim({"compare", a.string(), b.string()}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t at = r.out.find("\nanalytic.run_cycles ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string line = r.out.substr(at + 1, r.out.find('\n', at + 1) - at - 1);
  EXPECT_NE(line.find(" 1343771 "), std::string::npos) << line;
  EXPECT_EQ(line.find("e+06"), std::string::npos) << line;
  r = testing::run_tessim({"compare", a.string(), b.string(), "--csv"}, dir.path());
  EXPECT_NE(r.out.find("\nanalytic.run_cycles,"), std::string::npos);
  EXPECT_NE(r.out.find(",1343771,"), std::string::npos) << r.out;

  // Histogram bins 0, 1, 2, ..., 9, 10: in natural order, not 0, 1, 10, 2.
  r = testing::run_tessim({"compare", a.string(), b.string()}, dir.path());
  const std::vector<std::string> keys = row_keys(r.out);
  const std::string bins = "workload.vertices_per_patch_log2_histogram.";
  std::vector<int> order;
  for (const std::string& k : keys)
    if (k.rfind(bins, 0) == 0) order.push_back(std::stoi(k.substr(bins.size())));
  ASSERT_GT(order.size(), 10u) << r.out;
  for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], static_cast<int>(i)) << r.out;

  // --key: only keys with the prefix; --changed: only figures that differ.
  r = testing::run_tessim({"compare", a.string(), b.string(), "--key", "analytic.", "--key", "gpe."}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> some = row_keys(r.out);
  ASSERT_FALSE(some.empty()) << r.out;
  for (const std::string& k : some)
    EXPECT_TRUE(k.rfind("analytic.", 0) == 0 || k.rfind("gpe.", 0) == 0) << k;
  // The configuration keys that differ still say what the two runs are.
  EXPECT_EQ(r.out.find("configuration: the same"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nconfig.tess_factor "), std::string::npos) << r.out;
  r = testing::run_tessim({"compare", a.string(), b.string(), "--changed", "--csv"}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("\nschema_version,"), std::string::npos) << r.out;  // the same in both
  EXPECT_NE(r.out.find("\ncycles,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nconfig.tess_factor,2,9,"), std::string::npos) << r.out;
}

// A statistics file of a newer schema may mean other things by the same keys: `report` refused
// it, `compare` compared it anyway.
TEST(CompareCli, RefusesANewerSchemaVersion) {
  testing::TempDir dir;
  const auto a = dir.path() / "a.json", b = dir.path() / "b.json";
  ASSERT_EQ(testing::run_tessim({"sim", kMesh, "-L", "2", "--stats", a.string()}, dir.path()).status, 0);
  json j = read_json(a);
  j["schema_version"] = sim::kStatsSchemaVersion + 96;
  std::ofstream(b) << j.dump();
  const auto r = testing::run_tessim({"compare", a.string(), b.string()}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("schema_version: " + std::to_string(sim::kStatsSchemaVersion + 96) + " is newer"),
            std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace
}  // namespace tessim
