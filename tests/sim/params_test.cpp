// The description of the unit's parameters (sim/config/params.hpp) and everything driven by it:
// JSON round trip, ranges, the schema, the README table. The command-line flags and aliases and
// the `tessim schema` binary: tests/cli/config_cli_test.cpp.
#include <gtest/gtest.h>

#include <iterator>
#include <regex>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/mesh_io.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/config/config.hpp"
#include "sim/config/params.hpp"
#include "sim/report/report.hpp"
#include "sim/report/schema.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/error_bound.hpp"
#include "tests/support/param_values.hpp"

namespace tessim::sim {
namespace {

using nlohmann::json;
using tessim::testing::other_value;
using tessim::testing::with_context;

// The InputError of applying and validating `j`, or "" when it is accepted.
std::string error_of(const json& j) {
  UnitConfig cfg;
  try {
    apply_json(cfg, j, "cfg.json");
    cfg.validate("cfg.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Params, TableMatchesToJson) {
  const json j = to_json(UnitConfig{});
  std::set<std::string> keys;
  for (const ParamSpec& p : unit_params()) {
    keys.insert(p.key);
    EXPECT_EQ(find_param(p.key), &p);
    // The canonical flag is the key spelled as a flag.
    std::string flag = std::string("--") + p.key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    EXPECT_EQ(flag, p.flag);
    EXPECT_TRUE(*p.description);
  }
  std::set<std::string> json_keys;
  for (const auto& [k, v] : j.items()) json_keys.insert(k);
  EXPECT_EQ(keys, json_keys);
  EXPECT_EQ(find_param("int_blockz"), nullptr);
}

TEST(Params, EveryParameterRoundTripsJson) {
  for (const ParamSpec& p : unit_params()) {
    SCOPED_TRACE(p.key);
    UnitConfig cfg;
    apply_json(cfg, with_context(p, json{{p.key, other_value(p)}}), "test");
    EXPECT_NO_THROW(cfg.validate("test"));
    EXPECT_FALSE(cfg == UnitConfig{});
    EXPECT_EQ(to_json(cfg)[p.key], other_value(p));
    UnitConfig back;
    apply_json(back, to_json(cfg), "test");
    EXPECT_EQ(back, cfg);
  }
}

TEST(Params, RangeBoundsAcceptedAndValuesOutsideRejectedNamingTheKey) {
  for (const ParamSpec& p : unit_params()) {
    SCOPED_TRACE(p.key);
    if (p.type == ParamType::Int) {
      const auto lo = static_cast<long long>(p.min), hi = static_cast<long long>(p.max);
      EXPECT_EQ(error_of(with_context(p, {{p.key, lo}})), "");
      EXPECT_EQ(error_of(with_context(p, {{p.key, hi}})), "");
      for (long long bad : {lo - 1, hi + 1}) {
        const std::string e = error_of({{p.key, bad}});
        EXPECT_EQ(e, "cfg.json: " + std::string(p.key) + ": value " + std::to_string(bad) + " out of range [" +
                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
      }
      EXPECT_NE(error_of({{p.key, "four"}}).find(std::string(p.key) + ": expected an integer"), std::string::npos);
      EXPECT_NE(error_of({{p.key, 1.5}}).find(p.key), std::string::npos);
    } else if (p.type == ParamType::Double) {
      EXPECT_EQ(error_of({{p.key, p.min}}), "");
      EXPECT_EQ(error_of({{p.key, p.max}}), "");
      for (double bad : {p.min - 0.01, p.max + 0.01, std::nan("")}) {
        const std::string e = error_of({{p.key, bad}});
        EXPECT_NE(e.find("cfg.json: " + std::string(p.key) + ": value"), std::string::npos) << e;
        EXPECT_NE(e.find("out of range"), std::string::npos) << e;
      }
      // NaN is named as NaN (JSON's dump() printed it as null).
      EXPECT_NE(error_of({{p.key, std::nan("")}}).find(": value NaN out of range"), std::string::npos);
      EXPECT_NE(error_of({{p.key, "x"}}).find(std::string(p.key) + ": expected a number"), std::string::npos);
    } else if (p.type == ParamType::UInt64) {
      EXPECT_EQ(error_of({{p.key, 0}}), "");
      EXPECT_EQ(error_of({{p.key, std::numeric_limits<std::uint64_t>::max()}}), "");
      EXPECT_EQ(error_of({{p.key, -1}}), "cfg.json: " + std::string(p.key) + ": expected a non-negative integer");
    } else {
      for (const char* c : p.choices) {
        const std::string e = error_of({{p.key, c}});
        // Alone, derivative is the float reference's and host needs evaluation gpe.
        const bool needs_more = std::string(c) == "derivative" || std::string(c) == "host";
        EXPECT_TRUE(e.empty() || needs_more) << e;
      }
      EXPECT_EQ(error_of({{p.key, "nonsense"}}),
                "cfg.json: " + std::string(p.key) + ": 'nonsense' is not one of " + range_text(p));
      EXPECT_EQ(error_of({{p.key, 3}}), "cfg.json: " + std::string(p.key) + ": expected a string");
    }
  }
  // Checks across parameters stay.
  EXPECT_EQ(error_of({{"coord_int_bits", 8}, {"coord_frac_bits", 26}}),
            "cfg.json: coord_int_bits + coord_frac_bits: coordinate width 35 exceeds 32 bits");
  EXPECT_NE(error_of({{"normals", "derivative"}}).find("cfg.json: normals: 'derivative' is available in the float reference only"),
            std::string::npos);
  EXPECT_EQ(error_of({{"int_blockz", 2}}), "cfg.json: int_blockz: unknown configuration key");
}

// ---------------------------------------------------------------------------------------------
// tessim schema

// A Verilated variant gives only the parameters that differ from tess_pkg's defaults
// (rtl/CMakeLists.txt), so those defaults must be UnitConfig's.
TEST(Schema, RtlPackageDefaultsAreTheConfigDefaults) {
  std::ifstream sv(std::string(TESSIM_SOURCE_DIR) + "/rtl/tess_pkg.sv");
  ASSERT_TRUE(sv) << "rtl/tess_pkg.sv";
  const std::string pkg((std::istreambuf_iterator<char>(sv)), std::istreambuf_iterator<char>());
  int checked = 0;
  for (const ParamSpec& p : unit_params()) {
    if (!p.rtl) continue;
    const std::regex line(std::string("localparam int unsigned ") + p.rtl + R"(\s*=\s*(\d+);)");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(pkg, m, line)) << p.rtl << " not in tess_pkg.sv";
    EXPECT_EQ(json(std::stoi(m[1].str())), p.get(UnitConfig{})) << p.rtl;
    ++checked;
  }
  // And every configuration default of the package has its row (InjectBug, a test fault, has none).
  const auto begin = pkg.find("configuration defaults"), end = pkg.find("lint_on UNUSEDPARAM");
  ASSERT_LT(begin, end);
  const std::string defaults = pkg.substr(begin, end - begin);
  const std::regex any(R"(localparam int unsigned \w+\s*=)");
  const auto in_package = std::distance(std::sregex_iterator(defaults.begin(), defaults.end(), any), std::sregex_iterator());
  EXPECT_EQ(checked, in_package - 1);
}

TEST(Schema, IntOpsAndStatistics) {
  const json s = schema_json();
  ASSERT_EQ(s["int_ops"].size(), 14u);
  for (int op = 0; op < 14; ++op) {
    const json& e = s["int_ops"][static_cast<std::size_t>(op)];
    EXPECT_EQ(e["op"], op);
    // An op depends only on ops of the level below (the doc's table).
    for (const json& d : e["depends_on"])
      EXPECT_EQ(s["int_ops"][d.get<std::size_t>()]["level"].get<int>() + 1, e["level"].get<int>());
  }
  EXPECT_EQ(s["int_ops"][13]["operands"], json({"T9", "T10", "T11"}));
  EXPECT_EQ(s["int_ops"][6]["operands_linear"], json({"n0", "n2", "n5"}));
  EXPECT_EQ(s["int_ops_per_mode"]["quadratic"]["ops_per_vertex"], 14);
  EXPECT_EQ(s["int_ops_per_mode"]["linear"]["ops_per_vertex"], 11);
  EXPECT_EQ(s["statistics"]["classes"]["te"], json({"context_limited", "int_limited", "busy", "blocked_by_gpe",
                                                     "starved_by_cpg", "idle", "pipeline"}));
  // The counters the co-simulation compares are the RTL's perf ports, the vertex fields its
  // vtx ports (rtl/tess_unit.sv).
  std::ifstream sv(std::string(TESSIM_SOURCE_DIR) + "/rtl/tess_unit.sv");
  const std::string rtl((std::istreambuf_iterator<char>(sv)), std::istreambuf_iterator<char>());
  for (const json& o : s["statistics"]["vertex_outputs"])
    EXPECT_NE(rtl.find(" " + o["port"].get<std::string>() + ","), std::string::npos) << o;
  // The run counters (cycles, triangles_in, vertices_out, tri_stalls, vtx_stalls), INT busy, the TE and CPG classes.
  EXPECT_EQ(s["statistics"]["counters"].size(), 5u + 1u + 11u);
  EXPECT_EQ(s["statistics"]["classes"]["gpe"], json({"busy", "stalled", "cpg", "starved"}));
}

// The cycle model issues exactly the ops of the table (sim/base/int_ops.hpp) for every normal mode:
// over a whole run, the INT blocks' busy cycles add up to vertices x ops per vertex (1710
// vertices of sphereWithHole at L = 2: 23940 ops quadratic and reflect, 18810 linear), and the
// statistics report that ratio and the CPG's cycles per triangle.
TEST(Schema, CycleModelIssuesTheOpsOfTheTable) {
  const std::filesystem::path path = "/usr/share/assimp/models/STL/sphereWithHole.stl";
  if (!std::filesystem::exists(path)) FAIL() << path << " is missing: scripts/setup.sh installs assimp-testmodels";
  const Mesh mesh = load_mesh(path.string());
  for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    SCOPED_TRACE(to_string(m));
    UnitConfig cfg;
    cfg.normals = m;
    cfg.tess_factor = 2;
    cfg.int_blocks = 3;
    cfg.validate("test");
    const SimResult r = simulate(mesh, cfg);
    EXPECT_EQ(r.unit.vertices_out, 1710u);
    std::uint64_t busy = 0;
    for (std::uint64_t b : r.unit.int_busy_used()) busy += b;
    EXPECT_EQ(busy, r.unit.vertices_out * static_cast<std::uint64_t>(int_ops::ops_per_vertex(m)));
    EXPECT_EQ(busy, m == NormalMode::Linear ? 18810u : 23940u);
    const json j = stats_json(r);
    EXPECT_EQ(j["int"]["ops_per_vertex"].get<double>(), int_ops::ops_per_vertex(m));
    EXPECT_EQ(j["cpg_cycles_per_triangle"].get<int>(), cpg_cycles(m, NumberFormat{}));
  }
}

TEST(Schema, CpgCyclesAreSimCpgCyclesAndIgnoreBaryBits) {
  const json s = schema_json();
  for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    const json& rows = s["cpg_cycles"][std::string(to_string(m))];
    EXPECT_GT(rows.size(), 100u);
    for (const json& r : rows) {
      NumberFormat f;
      f.coord_int_bits = r["coord_int_bits"];
      f.coord_frac_bits = r["coord_frac_bits"];
      ASSERT_LE(f.coord_width(), 32);
      for (int b = 7; b <= 20; ++b) {
        f.bary_bits = b;
        EXPECT_EQ(r["cycles"].get<int>(), cpg_cycles(m, f));
      }
    }
  }
}

TEST(Schema, CpgCyclesByVariantAreSimCpgCycles) {
  const json rows = schema_json()["cpg_cycles_by_variant"];
  ASSERT_EQ(rows.size(), 4u * static_cast<std::size_t>(NumberFormat{}.coord_width()));
  for (const json& r : rows) {
    const CpgVariant v{r["cpg_lanes"].get<int>(), r["cpg_digit_bits"].get<int>(), 1, r["cpg_product_reg"].get<int>()};
    for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear})
      EXPECT_EQ(r[std::string(to_string(m))].get<int>(), cpg_cycles(m, NumberFormat{}, v));
  }
  EXPECT_EQ(rows[0]["quadratic"], 245);            // one lane, one bit a cycle
  EXPECT_EQ(rows[2 * 24 - 1]["quadratic"], 12 + 2);  // three lanes, a whole quotient a cycle
  // Registered products: 4 more steps per edge and one more b111 cycle (rtl/tess_cpg_edge.sv).
  EXPECT_EQ(rows[2 * 24]["quadratic"], 3 * (3 * 24 + 13) + 3);
  EXPECT_EQ(rows.back()["linear"], 9 + 3);
}

// The arithmetic position bound per coordinate format, which scripts/plots.py draws: the C++
// derivation, for every valid format, independent of bary_bits.
TEST(Schema, PositionBoundsArePositionErrorBudget) {
  const json s = schema_json();
  const json& rows = s["position_bound"];
  EXPECT_GT(rows.size(), 100u);
  for (const json& r : rows) {
    NumberFormat f;
    f.coord_int_bits = r["coord_int_bits"];
    f.coord_frac_bits = r["coord_frac_bits"];
    ASSERT_LE(f.coord_width(), 32);
    EXPECT_GT(r["units"].get<double>(), 0.0);
    for (int b : {7, 16, 20}) {
      f.bary_bits = b;
      EXPECT_EQ(r["units"].get<double>(), position_error_budget(f).position_units);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Documentation: README's "Configuration files" table lists every parameter with its flags.

TEST(ParamsDocs, ReadmeListsEveryParameter) {
  std::ifstream in(std::string(TESSIM_SOURCE_DIR) + "/README.md");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto start = text.find("### Configuration files");
  ASSERT_NE(start, std::string::npos);
  const std::string section = text.substr(start, text.find("\n## ", start) - start);
  const UnitConfig defaults{};
  for (const ParamSpec& p : unit_params()) {
    SCOPED_TRACE(p.key);
    auto cell = [](const std::string& left, const std::string& text, const std::string& right) {
      std::string c = left;
      c += text;
      c += right;
      return c;
    };
    const auto row = section.find(cell("| `", p.key, "` |"));
    ASSERT_NE(row, std::string::npos);
    const std::string line = section.substr(row, section.find('\n', row) - row);
    EXPECT_NE(line.find(cell("`", p.flag, "`")), std::string::npos) << line;
    for (const std::string& alias : alias_list(p)) EXPECT_NE(line.find(cell("`", alias, "`")), std::string::npos) << line;
    const json d = p.get(defaults);
    EXPECT_NE(line.find(cell("| ", d.is_string() ? d.get<std::string>() : d.dump(), " |")), std::string::npos) << line;
    EXPECT_NE(line.find(range_text(p)), std::string::npos) << line;
  }
}

}  // namespace
}  // namespace tessim::sim
