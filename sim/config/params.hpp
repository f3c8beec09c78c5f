// The parameters of the unit and its environment, described once: JSON key, command-line flag
// and its aliases, RTL parameter, kind, type, range, default, unit, description, and an
// accessor into sim::UnitConfig. apply_json, UnitConfig::validate, to_json, the flags of
// `tessim sim` / `tessim cosim` and `tessim schema` (sim/report/schema.hpp, which the scripts read)
// all loop over this table; README.md (Configuration files) lists it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "sim/config/config.hpp"

namespace tessim::sim {

// hardware: a property of the unit (a different RTL build or a different chip);
// environment: the geometry engine around the unit and its random stalls;
// workload: what a run asks the unit to do.
enum class ParamKind { Hardware, Environment, Workload };
enum class ParamType { Int, UInt64, Double, Enum };

const char* to_string(ParamKind k);
const char* to_string(ParamType t);

struct ParamSpec {
  const char* key;          // JSON key (config files, --stats "config", sweep specs)
  const char* flag;         // canonical flag: "--" + key with '-' for '_'
  const char* aliases;      // other spellings accepted on the command line, comma-separated, or ""
  const char* rtl;          // parameter of tess_unit (rtl/tess_pkg.sv), or nullptr
  const char* symbol;       // symbol in docs/microarchitecture.md, or ""
  ParamKind kind;
  ParamType type;
  double min, max;          // inclusive range (Int, Double); UInt64 takes its whole range
  std::span<const char* const> choices;  // Enum: the accepted names, in enum order
  const char* unit;         // "bits", "cycles", "blocks", ... or "" (dimensionless)
  const char* description;  // one line
  // The field in UnitConfig as JSON (an enum as its name), and back. set() receives a value
  // already checked against the type (and for an Enum, one of `choices`).
  nlohmann::json (*get)(const UnitConfig&);
  void (*set)(UnitConfig&, const nlohmann::json&);
};

// Every parameter, in the column order of the sweep results (workload, TE, GPE, CPG, widths,
// FIFOs).
std::span<const ParamSpec> unit_params();
const ParamSpec* find_param(std::string_view key);  // nullptr if unknown
const ParamSpec* find_rtl_param(std::string_view rtl_name);  // by tess_unit parameter name

// "1..32", "0..0.99", "quadratic, reflect, linear, derivative", "0..2^64-1".
std::string range_text(const ParamSpec& p);
// The aliases one by one: {"-L"}, {"--int"}, {}.
std::vector<std::string> alias_list(const ParamSpec& p);
// The CLI11 name string of the flag: "-L,--tess-factor", "--int-blocks,--int", ...
std::string cli_names(const ParamSpec& p);

}  // namespace tessim::sim
