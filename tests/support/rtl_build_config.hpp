// The hardware configuration of a Verilated build as rtl/builds.json gives it
// (sim::find_rtl_build): tests that co-simulate a named build take its parameters from there
// instead of restating them.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "sim/config/config.hpp"
#include "sim/config/rtl_builds.hpp"

namespace tessim::testing {

// `unit` with every hardware parameter of build `name` (its workload and environment kept).
inline sim::UnitConfig with_rtl_build(sim::UnitConfig unit, std::string_view name) {
  const sim::RtlBuild* build = sim::find_rtl_build(name);
  if (build == nullptr) throw std::invalid_argument("no RTL build '" + std::string(name) + "' in rtl/builds.json");
  static_cast<sim::HardwareConfig&>(unit) = build->hardware();
  return unit;
}

}  // namespace tessim::testing
