// What `tessim schema` prints (and the Python module's schema()): the parameter table, the INT
// operations, the statistics' counters and units, the CPG cycles, the position bound, the unit's
// ports and the RTL builds, as one JSON document that the scripts read.
#pragma once

#include <nlohmann/json_fwd.hpp>

namespace tessim::sim {

// "parameters" (sim/config/params.hpp), "int_ops", "statistics", "cpg_cycles",
// "cpg_cycles_by_variant", "rtl_parameters", "position_bound", "interface" (tess_unit's ports,
// item widths and codes, sim/config/ports.hpp) and "rtl_builds" (rtl/builds.json,
// sim/config/rtl_builds.hpp).
nlohmann::json schema_json();

}  // namespace tessim::sim
