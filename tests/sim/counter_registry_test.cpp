// The counter registry (sim/base/counter_registry.hpp) against the RTL's counter ports, and
// the outputs derived from it: every perf_*_o output of rtl/tess_unit.sv has exactly one row and
// every row's port exists; every row reaches the statistics JSON, its units and the summary (the
// report's legend: tests/cli/report_cli_test.cpp). (tests/rtl/counter_readout_test.cpp checks
// that the Verilated read-out reads each port.)
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "model/mesh_io.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/config/config.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {
namespace {

// The perf_*_o outputs of tess_unit: every such name in its port list (module header to ");").
std::map<std::string, int> rtl_counter_ports() {
  std::ifstream in(std::string(TESSIM_SOURCE_DIR) + "/rtl/tess_unit.sv");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string sv = ss.str();
  const std::size_t begin = sv.find("module tess_unit");
  const std::size_t end = sv.find(");", begin);
  if (begin == std::string::npos || end == std::string::npos) return {};
  std::string header = sv.substr(begin, end - begin);
  header = std::regex_replace(header, std::regex("//[^\n]*"), "");  // comments name ports too
  std::map<std::string, int> ports;
  const std::regex port(R"(\b(perf_\w+_o)\b)");
  for (auto it = std::sregex_iterator(header.begin(), header.end(), port); it != std::sregex_iterator(); ++it)
    ++ports[(*it)[1].str()];
  return ports;
}

TEST(CounterRegistry, EveryRtlCounterPortHasExactlyOneRow) {
  const std::map<std::string, int> ports = rtl_counter_ports();
  // 3 per run, INT busy, 7 TE classes, 3 CPG classes today: a parse that finds few is broken.
  ASSERT_GE(ports.size(), 14u) << "rtl/tess_unit.sv: the perf_*_o ports were not found";
  for (const auto& [port, declared] : ports) {
    EXPECT_EQ(declared, 1) << port << " declared " << declared << " times";
    int rows = 0;
    for (const CounterRow& r : kCounterRegistry) rows += r.port == port;
    EXPECT_EQ(rows, 1) << port << ": " << rows << " rows of sim/base/counter_registry.hpp name it";
  }
  for (const CounterRow& r : kCounterRegistry) {
    if (r.has_port()) {
      EXPECT_TRUE(ports.count(std::string(r.port))) << r.name << ": no output " << r.port;
    }
  }
}

TEST(CounterRegistry, RowsWithoutPortsAreTheOnesTheRtlCannotCount) {
  for (const CounterRow& r : kCounterRegistry) {
    const bool expected_port = r.block != CounterBlock::Gpe &&  // the GPE is the testbench's
                               !(r.block == CounterBlock::Cpg && r.index == static_cast<int>(CpgClass::WaitGpe)) &&
                               !(r.block == CounterBlock::Int && r.index == static_cast<int>(IntClass::Idle));
    EXPECT_EQ(r.has_port(), expected_port) << r.name;
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
  EXPECT_EQ(row_of_port("perf_tri_in_o"), first_row(CounterBlock::Run) + 1);
  EXPECT_EQ(row_of_port("no_port"), kCounterRegistry.size());
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
