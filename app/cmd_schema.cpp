// tessim schema: the machine-readable description of the unit (sim/config/params.hpp) as JSON:
// every configuration parameter (key, flag, aliases, RTL name, kind, type, range, default,
// unit, description), the INT operation table, the statistics counters, the CPG cycles per
// normal mode and coordinate format, tess_unit's ports (widths as functions of the parameters,
// the codes they carry) and the Verilated builds of rtl/builds.json. Scripts read it instead of
// repeating the C++.
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "sim/config/params.hpp"
#include "sim/report/schema.hpp"

namespace tessim::app {

void register_schema(CLI::App& app) {
  auto indent = std::make_shared<int>(2);
  CLI::App* sub = app.add_subcommand(
      "schema", "Print the unit's parameters, INT operations, statistics, CPG cycles, ports and RTL builds as JSON");
  // Bounded: nlohmann's dump() writes past its buffer for indents in the thousands.
  sub->add_option("--indent", *indent, "JSON indentation in spaces, 0..16 (-1: one line)")
      ->transform(number_check<int>("command line", "--indent", "-1..16"))
      ->capture_default_str();
  sub->callback([indent] {
    if (*indent < -1 || *indent > 16)
      throw InputError("command line", "--indent", "'" + std::to_string(*indent) + "' is outside -1..16");
    std::cout << sim::schema_json().dump(*indent) << "\n";
  });
}

}  // namespace tessim::app
