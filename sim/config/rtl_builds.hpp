// The Verilated builds of the unit, declared once in rtl/builds.json: rtl/CMakeLists.txt
// verilates them, and the file is embedded here at build time so that `tessim schema` lists
// each build with its parameters, its hardware configuration and the flags that select it,
// whether or not this tessim was built with the RTL.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "sim/config/config.hpp"

namespace tessim::sim {

struct RtlBuild {
  std::string name;     // the model is Vtess_<name>
  bool verif = false;   // random X values and assertions (otherwise X resolved fast, no assertions)
  std::vector<std::pair<std::string, int>> parameters;  // tess_unit parameters, in -G order
  std::string comment;
  int inject_bug() const;  // InjectBug (a test fault, not hardware): 0 when not given
  // UnitConfig's defaults (tess_pkg's) with the parameters, dedicated CPG.
  HardwareConfig hardware() const;
  // The command-line flags of the parameters (InjectBug excluded), in their order:
  // {"--int-blocks", "3", "--int-latency", "3", ...}.
  std::vector<std::string> flags() const;
};

// Every build of rtl/builds.json, in its order. The file is checked when first read (unique
// names, known parameters, values in range): a mistake there is a std::logic_error.
const std::vector<RtlBuild>& rtl_builds();
const RtlBuild* find_rtl_build(std::string_view name);  // nullptr if unknown

// `tessim schema`, "rtl_builds": per build its name, verif, inject_bug, parameters, comment,
// hardware configuration (every hardware key), flags and triangle / vertex bits
// (sim/config/ports.hpp).
nlohmann::json rtl_builds_json();

}  // namespace tessim::sim
