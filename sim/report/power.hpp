// Silicon figures of a run: area, clock, power and energy per vertex on the OSU 0.18 um cells,
// per block, from a configuration's energy characterization (docs/silicon.md, Energy).
//
// scripts/energy.py characterizes a configuration once: each block's area and leakage, the
// energy its clock costs every cycle, and its data energy per action (an INT operation, a CPG
// cycle, a triangle, a vertex; per pattern class, uniform or Direct3D 11), measured from the
// RTL's toggles on real workloads propagated through the mapped cells and priced by OpenSTA.
// The characterizations in
// docs/results/silicon/energy/ are embedded at build time; a run's energy is then
//   per block: leakage x time + clock energy x clocked cycles + energy per action x actions
// with the actions taken from the run's statistics.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/config/config.hpp"

namespace tessim::sim {

struct PowerBlock {
  std::string name;         // cpg, fsu, cp_buffers, te, dpg, int0, int1, ..., fifos, top
  std::string action;       // what counts one action (energy.py's ACTIONS)
  double area_um2 = 0;
  double leakage_nw = 0;
  double clock_pj_per_cycle = 0;  // every flip-flop clocked, nothing else switching
  double pj_per_action_uniform = 0;  // data energy per action, uniform pattern
  double pj_per_action_d3d11 = 0;    // ... Direct3D 11 pattern (the DPG walks rings, the FSU works)
  int flops = 0;
};

struct ClockGate {             // a latch-based gate built from the library's cells
  double area_um2 = 0, leakage_nw = 0, pj_per_cycle = 0;
  int flops_per_gate = 32;
};

struct EnergyCharacterization {
  std::string name;               // e.g. n2
  std::vector<std::pair<std::string, int>> parameters;  // tess_unit parameters off tess_pkg's defaults
  HardwareConfig hardware;        // what they make of the defaults
  double clock_ns = 0;            // the configuration's clock (the composed worst register path)
  std::vector<PowerBlock> blocks;
  ClockGate gate;
  nlohmann::json source;          // the characterization as written by scripts/energy.py
};

// The characterizations embedded at build time (docs/results/silicon/energy/*.json).
const std::vector<EnergyCharacterization>& energy_characterizations();
// Reads one characterization (scripts/energy.py's JSON); a malformed one is an InputError
// naming `origin`.
EnergyCharacterization read_energy_characterization(const nlohmann::json& j, const std::string& origin);
// The characterization of a hardware configuration, or nullptr.
const EnergyCharacterization* find_energy_characterization(const std::vector<EnergyCharacterization>& all,
                                                           const HardwareConfig& hw);

struct PowerOptions {
  bool clock_gating = false;  // idle INT blocks and CPG gated, the whole unit gated when idle
  double clock_mhz = 0;       // 0: the configuration's own clock
};

// The power report of a run from its statistics (sim::stats_json): the keys of docs/silicon.md
// (area_mm2, clock_mhz, power_mw, energy_nj_per_vertex, idle_power_mw, int_blocks, blocks, ...).
nlohmann::json power_report(const nlohmann::json& stats, const EnergyCharacterization& c, const PowerOptions& o);
// One screen of it for a person.
std::string power_summary(const nlohmann::json& report);

}  // namespace tessim::sim
