// What is reported of a run (sim/run/simulate.hpp's SimResult): the figures derived from its
// statistics and the block that limits it (figures.cpp), the statistics JSON with the unit of
// every number (stats_json.cpp) and one screen for a person (summary.cpp).
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "sim/run/simulate.hpp"

namespace tessim::sim {

// Figures derived from the statistics (docs/microarchitecture.md §10).
double throughput(const SimResult& r);         // vertices per cycle
double cycles_per_vertex(const SimResult& r);
double int_utilisation(const SimResult& r);    // sum of INT busy / (N cycles)

// Which block limits the run, as one line with the figure that shows it.
std::string bottleneck(const SimResult& r);

nlohmann::json stats_json(const SimResult& r);

// The statistics JSON's format: its version (raised when a key changes meaning or goes away),
// and the unit of every number in it by path, array elements as "[]" ("int.blocks[].busy").
// stats_json() carries both, and `tessim schema` lists the units (docs/statistics.md).
inline constexpr int kStatsSchemaVersion = 3;
nlohmann::json stats_units();
std::string summary(const SimResult& r);       // one screen for a hardware architect

}  // namespace tessim::sim
