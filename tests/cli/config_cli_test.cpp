// The unit's configuration on the command line (app/config_flags.hpp): one flag per parameter of
// sim/config/params.hpp with its aliases, overriding a --config file, bad values naming the key;
// every RTL build's flags give its hardware; `tessim schema` prints the schema.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/config_flags.hpp"
#include "model/base/error.hpp"
#include "sim/config/config.hpp"
#include "sim/config/params.hpp"
#include "sim/config/rtl_builds.hpp"
#include "sim/report/schema.hpp"
#include "tests/support/param_values.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim::sim {
namespace {

using nlohmann::json;
using tessim::testing::context_for;
using tessim::testing::other_value;
using tessim::testing::TempDir;
using tessim::testing::with_context;


UnitConfig parse(std::vector<std::string> args) {
  CLI::App app;
  app::ConfigFlags flags(app);
  std::reverse(args.begin(), args.end());  // CLI11 takes a reversed vector
  app.parse(args);
  return flags.config();
}

TEST(ParamsCli, CanonicalFlagsAndAliasesGiveTheSameConfig) {
  const UnitConfig canonical = parse({"--tess-factor", "8", "--int-blocks", "3", "--te-contexts", "6",
                                      "--gpe-stall-prob", "0.25", "--cpg-mapping", "gpe", "--normals", "reflect"});
  const UnitConfig aliases = parse({"-L", "8", "--int", "3", "--contexts", "6", "--stall", "0.25", "--cpg", "gpe",
                                    "--normals", "reflect"});
  EXPECT_EQ(canonical, aliases);
  EXPECT_EQ(canonical.tess_factor, 8);
  EXPECT_EQ(canonical.int_blocks, 3);
  EXPECT_EQ(canonical.te_contexts, 6);
  EXPECT_EQ(canonical.gpe_stall_prob, 0.25);
  EXPECT_EQ(canonical.cpg_mapping, CpgMapping::Gpe);
  EXPECT_EQ(canonical.normals, NormalMode::Reflect);
  EXPECT_EQ(parse({}), UnitConfig{});
}

TEST(ParamsCli, EveryParameterHasAFlag) {
  for (const ParamSpec& p : unit_params()) {
    SCOPED_TRACE(p.key);
    const json v = other_value(p);
    const std::string text = v.is_string() ? v.get<std::string>() : v.dump();
    UnitConfig expected;
    apply_json(expected, with_context(p, json{{p.key, v}}), "test");
    std::vector<std::string> context;
    const json needs = context_for(p);
    for (const auto& [key, value] : needs.items()) {
      context.push_back(find_param(key)->flag);
      context.push_back(value.dump());
    }
    auto args = [&](const std::string& flag) {
      std::vector<std::string> a{flag, text};
      a.insert(a.end(), context.begin(), context.end());
      return a;
    };
    EXPECT_EQ(parse(args(p.flag)), expected);
    for (const std::string& alias : alias_list(p)) EXPECT_EQ(parse(args(alias)), expected);
  }
}

TEST(ParamsCli, FlagsOverrideTheFileOnlyWhenGiven) {
  TempDir dir;
  const auto file = dir.write("cfg.json", R"({"int_blocks": 1, "tess_factor": 3, "seed": 9})");
  const UnitConfig from_file = parse({"--config", file.string()});
  EXPECT_EQ(from_file.int_blocks, 1);
  EXPECT_EQ(from_file.tess_factor, 3);
  EXPECT_EQ(from_file.seed, 9u);
  const UnitConfig overridden = parse({"--config", file.string(), "--int", "4"});
  EXPECT_EQ(overridden.int_blocks, 4);
  EXPECT_EQ(overridden.tess_factor, 3);
}

TEST(ParamsCli, BadFlagValuesNameTheKey) {
  try {
    parse({"--int", "0"});
    FAIL() << "accepted --int 0";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "command line: int_blocks: value 0 out of range [1, 32]");
  }
  TempDir dir;
  const auto file = dir.write("cfg.json", R"({"int_blocks": 1})");
  try {
    parse({"--config", file.string(), "-L", "65"});
    FAIL() << "accepted -L 65";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file.string() + " with command-line overrides: tess_factor: value 65 out of range [1, 64]");
  }
}

// Each RTL build's flags (rtl/builds.json) through the parser of `tessim sim` / `tessim cosim`
// give the build's hardware.
TEST(RtlBuildsCli, FlagsGiveTheBuildsHardware) {
  ASSERT_FALSE(rtl_builds().empty());
  for (const RtlBuild& b : rtl_builds()) {
    CLI::App app;
    app::ConfigFlags flags(app);
    std::vector<std::string> args = b.flags();
    std::reverse(args.begin(), args.end());
    app.parse(args);
    EXPECT_EQ(flags.config().hardware(), b.hardware()) << b.name;
  }
}

// ---------------------------------------------------------------------------------------------
// tessim schema

TEST(Schema, BinaryPrintsValidJsonListingEveryParameter) {
  TempDir scratch;
  const auto r = tessim::testing::run_tessim({"schema"}, scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const json s = json::parse(r.out);
  EXPECT_EQ(s, schema_json());
  std::set<std::string> listed;
  for (const json& p : s["parameters"]) {
    listed.insert(p["key"].get<std::string>());
    for (const char* field : {"flag", "aliases", "rtl", "kind", "type", "default", "unit", "description"})
      EXPECT_TRUE(p.contains(field)) << p["key"] << " lacks " << field;
    EXPECT_TRUE(p.contains("choices") || (p.contains("minimum") && p.contains("maximum"))) << p["key"];
    EXPECT_EQ(p["default"], to_json(UnitConfig{})[p["key"].get<std::string>()]);
  }
  std::set<std::string> keys;
  const json config = to_json(UnitConfig{});
  for (const auto& [k, v] : config.items()) keys.insert(k);
  EXPECT_EQ(listed, keys);
  EXPECT_EQ(s["rtl_parameters"]["IntBlocks"], "int_blocks");
  EXPECT_EQ(s["rtl_parameters"]["Contexts"], "te_contexts");
  EXPECT_EQ(s["rtl_parameters"]["CpgDigitBits"], "cpg_digit_bits");
  EXPECT_EQ(s["rtl_parameters"]["CpgTags"], "cpg_tags");
  EXPECT_EQ(s["rtl_parameters"]["CpBuffers"], "cp_buffers");
  const auto with_rtl = std::count_if(unit_params().begin(), unit_params().end(), [](const ParamSpec& p) { return p.rtl; });
  EXPECT_EQ(s["rtl_parameters"].size(), static_cast<std::size_t>(with_rtl));
}

}  // namespace
}  // namespace tessim::sim
