// Values of the unit's parameters (sim/config/params.hpp) for the tests of the table: JSON
// (tests/sim/params_test.cpp) and command-line flags (tests/cli/config_cli_test.cpp).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sim/config/config.hpp"
#include "sim/config/params.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::testing {

using nlohmann::json;
using sim::ParamSpec;
using sim::ParamType;
using sim::UnitConfig;

// A valid value of `p` other than its default.
inline json other_value(const ParamSpec& p) {
  const json d = p.get(UnitConfig{});
  switch (p.type) {
    case ParamType::Int: return d.get<long long>() == static_cast<long long>(p.max) ? json(static_cast<long long>(p.min))
                                                                                   : json(static_cast<long long>(p.max));
    case ParamType::Double: return d.get<double>() == p.max ? p.min : p.max;
    case ParamType::UInt64: return std::numeric_limits<std::uint64_t>::max();
    case ParamType::Enum:
      for (const char* c : p.choices) {
        UnitConfig cfg;
        p.set(cfg, std::string(c));
        if (c != d.get<std::string>() && sim::hardware_supports(cfg.normals)) return c;
      }
  }
  return nullptr;
}

// The other parameters a value needs to be valid: cpg_digit_bits may not exceed the coordinate
// width, so its upper bound (32) is tried with W = 32.
inline json context_for(const ParamSpec& p) {
  if (std::string_view(p.key) == "cpg_digit_bits") return {{"coord_int_bits", 6}, {"coord_frac_bits", 25}};
  return json::object();
}

inline json with_context(const ParamSpec& p, json j) {
  j.update(context_for(p));
  return j;
}

}  // namespace tessim::testing
