// The counter registry (sim/base/counter_registry.hpp) against the RTL's counters, and the
// outputs derived from it: tess_pkg::ctr_e (rtl/tess_pkg.sv) lists exactly the rows with an RTL
// counter, in the order of rtl_counter_index (the Verilated read-out's index into tess_unit's
// perf_ctr_o), and tess_unit sets each enumerator's increment once; every row reaches the
// statistics JSON, its units and the summary (the report's legend: tests/cli/report_cli_test.cpp).
// (tests/rtl/counter_readout_test.cpp checks that the Verilated read-out reads each counter.)
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/mesh_io.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/config/config.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {
namespace {

std::string read_source(const char* path) {
  std::ifstream in(std::string(TESSIM_SOURCE_DIR) + "/" + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return std::regex_replace(ss.str(), std::regex("//[^\n]*"), "");  // comments name counters too
}

// The enumerators of tess_pkg::ctr_e, in order.
std::vector<std::string> rtl_counter_enum() {
  const std::string pkg = read_source("rtl/tess_pkg.sv");
  std::smatch m;
  if (!std::regex_search(pkg, m, std::regex(R"(typedef\s+enum\s+int\s+unsigned\s*\{([^}]*)\}\s*ctr_e\s*;)"))) return {};
  const std::string body = m[1].str();
  std::vector<std::string> names;
  const std::regex name(R"(\b(Ctr\w+)\b)");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), name); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1].str());
  return names;
}

TEST(CounterRegistry, RtlCounterEnumIsTheRegistrysRowsInBusOrder) {
  const std::vector<std::string> names = rtl_counter_enum();
  // 4 per run, INT busy, 7 TE classes, 3 CPG classes today: a parse that finds few is broken.
  ASSERT_GE(names.size(), 15u) << "rtl/tess_pkg.sv: typedef enum ... ctr_e was not found";
  std::vector<std::string> expected(names.size());
  std::size_t rows = 0;
  for (std::size_t row = 0; row < kCounterRegistry.size(); ++row) {
    const CounterRow& r = kCounterRegistry[row];
    if (!r.has_rtl()) continue;
    ++rows;
    ASSERT_LT(rtl_counter_index(row), names.size()) << r.name << " (" << r.rtl << ")";
    expected[rtl_counter_index(row)] = std::string(r.rtl);
  }
  EXPECT_EQ(rows, names.size()) << "tess_pkg::ctr_e and the registry's rows with an RTL counter differ in number";
  EXPECT_EQ(names, expected) << "tess_pkg::ctr_e is not the registry's order (rtl_counter_index)";
  EXPECT_EQ(names.back(), "CtrIntBusy") << "the per-INT-block counters come last";
  EXPECT_EQ(kRtlScalarCounters + 1, names.size());
}

TEST(CounterRegistry, TessUnitIncrementsEveryCounterOnce) {
  const std::string unit = read_source("rtl/tess_unit.sv");
  for (const std::string& name : rtl_counter_enum()) {
    const std::regex inc("assign\\s+ctr_inc\\[tess_pkg::" + name + "\\b");
    const auto n = std::distance(std::sregex_iterator(unit.begin(), unit.end(), inc), std::sregex_iterator());
    EXPECT_EQ(n, 1) << "rtl/tess_unit.sv sets ctr_inc[tess_pkg::" << name << "] " << n << " times";
  }
}

TEST(CounterRegistry, RowsWithoutRtlCountersAreTheOnesTheRtlCannotCount) {
  for (const CounterRow& r : kCounterRegistry) {
    const bool expected_rtl = r.block != CounterBlock::Gpe &&  // the GPE is the testbench's
                              !(r.block == CounterBlock::Cpg && r.index == static_cast<int>(CpgClass::WaitGpe)) &&
                              !(r.block == CounterBlock::Int && r.index == static_cast<int>(IntClass::Idle));
    EXPECT_EQ(r.has_rtl(), expected_rtl) << r.name;
  }
}

TEST(CounterRegistry, DerivedNamesFollowTheRows) {
  EXPECT_STREQ(to_string(TeClass::ContextLimited), "context_limited");
  EXPECT_STREQ(to_string(CpgClass::WaitGpe), "wait_gpe");
  EXPECT_STREQ(to_string(GpeClass::Starved), "starved");
  EXPECT_EQ(kTeClasses.size(), row_count(CounterBlock::Te));
  EXPECT_EQ(kRunCounters.size(), row_count(CounterBlock::Run));
  EXPECT_STREQ(kClassCounters.front().name, "te_context_limited");
  EXPECT_STREQ(kClassCounters.back().name, "cpg_idle");
  EXPECT_EQ(row_of_rtl("CtrTriIn"), first_row(CounterBlock::Run) + 1);
  EXPECT_EQ(row_of_rtl("no_rtl"), kCounterRegistry.size());
  EXPECT_EQ(rtl_counter_index(row_of_rtl("CtrTriIn")), 1u);
  EXPECT_EQ(rtl_counter_index(row_of_rtl("CtrIntBusy")), kRtlScalarCounters);
}

// A run in which every class of every block occurs is not needed: the JSON has every key anyway.
SimResult short_run() {
  Mesh mesh = load_mesh("/usr/share/assimp/models/STL/sphereWithHole.stl");
  mesh.triangles.resize(6);
  UnitConfig cfg;
  cfg.int_blocks = 3;
  cfg.tess_factor = 5;
  cfg.gpe_cycles = 3;
  cfg.gpe_stall_prob = 0.2;
  cfg.validate("counter_registry_test");
  return simulate(mesh, cfg);
}

TEST(CounterRegistry, EveryRowReachesTheStatisticsAndSummary) {
  const SimResult r = short_run();
  const nlohmann::json j = stats_json(r);
  const nlohmann::json& units = j["units"];
  const std::string text = summary(r);
  std::uint64_t checked = 0;
  for (std::size_t row = 0; row < kCounterRegistry.size(); ++row) {
    const CounterRow& c = kCounterRegistry[row];
    const std::string key = c.key;
    SCOPED_TRACE(c.name);
    switch (c.block) {
      case CounterBlock::Run:
        EXPECT_EQ(j[key], counter_value(r.unit, row));
        EXPECT_EQ(units[key], c.unit);
        break;
      case CounterBlock::Int:
        ASSERT_EQ(j["int"]["blocks"].size(), 3u);
        for (int i = 0; i < 3; ++i) EXPECT_EQ(j["int"]["blocks"][i][key], counter_value(r.unit, row, i));
        EXPECT_EQ(units["int.blocks[]." + key], c.unit);
        break;
      default: {
        const std::string block = block_info(c.block).key;
        const std::uint64_t value = c.block == CounterBlock::Gpe ? r.gpe[static_cast<std::size_t>(c.index)]
                                                                  : counter_value(r.unit, row);
        EXPECT_EQ(j[block][key], value);
        EXPECT_EQ(units[block + "." + key], c.unit);
        // The summary's line of the block: "TE       ... busy 12.3%  ...".
        const std::size_t line = text.find("\n" + std::string(block_info(c.block).label) + " ");
        ASSERT_NE(line, std::string::npos) << text;
        EXPECT_NE(text.substr(line, text.find('\n', line + 1) - line).find(" " + key + " "), std::string::npos) << text;
        if (c.block == CounterBlock::Te || c.block == CounterBlock::Gpe) {
          EXPECT_EQ(j["timeline"][block][key].size(), j["timeline"]["buckets"].get<std::size_t>());
        }
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, kCounterRegistry.size());
}

}  // namespace
}  // namespace tessim::sim
