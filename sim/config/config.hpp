// Every parameter of the unit, its environment and the workload, in three parts joined in one
// type. JSON config files and the command line both land here; validate() is the single place
// where ranges are checked.
// sim/config/params.hpp describes every field (key, flag, range, default, ...); README.md
// (Configuration files) lists them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "model/normal_mode.hpp"
#include "sim/base/fixed.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

enum class CpgMapping {
  Dedicated,  // CPG is its own sequential datapath (the RTL's choice)
  Gpe,        // CPG runs on the geometry engine's spare cycles (Chung & Kim)
  Host,       // the host computes the control points and sends them (Boubekeur & Schlick; evaluation gpe only)
};

// Where the patch is evaluated at each domain point: the unit's TE with its INT blocks, or the
// geometry engine as a shader (Boubekeur & Schlick), fed by the DPG, with no TE and no INT block
// (sim/ge/ge_evaluation.hpp).
enum class Evaluation {
  Unit,
  Gpe,
};

// How a system of several units shares one triangle stream (sim/system/system.hpp).
enum class Distribution {
  RoundRobin,     // triangle (or batch) i to unit i mod M, waiting for it when its TRI FIFO is full
  LeastLoaded,    // to the unit with the fewest vertices dispatched and not yet out (from the factors)
  EarliestFinish, // to the unit whose predicted drain time, max(CPG backlog, vertex backlog), is least
};

// Whether the system's reassembly buffer gives the ports the vertices in stream order (the
// hardware's contract) or in any order (a study's bound: what keeping the order costs).
enum class Reassembly {
  Ordered,    // the oldest patch's vertices first; one slot kept for them
  Unordered,  // any unit's vertex, the units served in turn; every slot for anyone
};

// What a chip is: a different value is a different RTL build (rtl/tess_pkg.sv parameters) or a
// different unit. Blocks of the unit are built from this part only.
struct HardwareConfig {
  NumberFormat format;
  int int_blocks = 2;        // N: INT blocks in the TE
  int int_latency = 1;       // cycles from issue to result visible to a dependent operation
  int te_contexts = 4;       // vertices the TE keeps in flight (temporary-register sets)
  int tri_fifo_depth = 2;    // input triangle FIFO in front of the CPG
  int vtx_fifo_depth = 2;    // output vertex FIFO between the TE and the geometry engine
  int cp_buffers = 2;        // control-point buffers: patches between the CPG's write and their last retirement
  CpgMapping cpg_mapping = CpgMapping::Dedicated;
  Evaluation evaluation = Evaluation::Unit;
  CpgVariant cpg;            // datapath shape of the dedicated CPG (lanes, digit bits)
  // The CPG takes scalar tags (docs/stpn.md): the input stream carries them and tagged
  // triangles get scalar-tagged control points, for extra CPG cycles (cpg_tag_cycles).
  int cpg_tags = 0;  // 0 or 1 (an int so that the parameter table's range check sees the value given)
  // Several units behind a distributor, their output put back in stream order
  // (sim/system/system.hpp).
  int units = 1;              // M
  int reorder_slots = 256;    // R: vertex slots of the reassembly buffer, shared by the units
  Distribution distribution = Distribution::RoundRobin;
  Reassembly reassembly = Reassembly::Ordered;
  int dispatch_batch = 1;     // consecutive triangles the distributor sends to the same unit
  bool operator==(const HardwareConfig&) const = default;
};

// The geometry engine around the unit (sim/ge/gpe.hpp) and its random stalls.
struct EnvironmentConfig {
  int gpe_cycles = 8;        // K: the geometry engine accepts at most one vertex every K cycles
  double gpe_stall_prob = 0.0;  // chance that a ready geometry engine stalls a cycle anyway
  std::uint64_t seed = 1;    // seeds the geometry engine's random stalls
  int cpg_gpe_cycles = 64;   // geometry-engine cycles CPG needs per triangle when mapped there
  // The GE's ALU for work it runs as a shader (evaluation gpe, displacement; sim/ge/ge_cost.hpp).
  int ge_alu_lanes = 4;      // scalar issue slots per cycle
  int ge_sfu_cost = 4;       // slots of a special function (reciprocal square root, sine, cosine)
  int ge_lookup_cost = 1;    // slots of a table read
  int ge_ports = 1;          // P: geometry-engine ports behind a system of units, each one vertex every K cycles
  // The GE as a shader core on a clock of its own (sim/ge/gpe.hpp, docs/microarchitecture.md §12):
  // 0 lanes keeps the fixed K above; W > 0 derives K from the core and its per-vertex program.
  int ge_core_lanes = 0;     // W: SIMD lanes, one vertex each
  int ge_core_issue = 1;     // I: wave instructions issued per core cycle
  double ge_core_mhz = 200;  // the core's clock (kept to 1 kHz)
  double unit_mhz = 200;     // the unit's clock, the cross-clock FIFO's write side (kept to 1 kHz)
  int ge_core_fifo = 64;     // D: entries of the cross-clock vertex FIFO between the unit and the core
  // Derived, not a parameter: issue slots per vertex of the shader work the run adds to the core's
  // own program (evaluation gpe, displacement); set by with_ge_cost (sim/ge/ge_cost.hpp).
  std::uint64_t ge_shader_slots = 0;
  bool ge_core() const { return ge_core_lanes > 0; }
  bool operator==(const EnvironmentConfig&) const = default;
};

// What a run asks of the unit: the normal mode (the unit's static mode_i input) and the factor
// the host attaches to every triangle (the unit itself takes L per triangle).
struct WorkloadConfig {
  NormalMode normals = NormalMode::Quadratic;
  int tess_factor = 4;       // L, uniform for every triangle of a run
  bool operator==(const WorkloadConfig&) const = default;
};

// The three parts together: what a config file, the command line and a stats file hold (one
// flat JSON object; sim/config/params.hpp gives each key its part).
struct UnitConfig : HardwareConfig, EnvironmentConfig, WorkloadConfig {
  const HardwareConfig& hardware() const { return *this; }
  const EnvironmentConfig& environment() const { return *this; }
  const WorkloadConfig& workload() const { return *this; }

  // Throws InputError(source, key, reason) on the first value out of range.
  void validate(const std::string& source = "configuration") const;
  bool operator==(const UnitConfig&) const = default;
};

// `rest` with its hardware part replaced by `hw` (an RTL build's hardware, the run's rest).
inline UnitConfig with_hardware(const HardwareConfig& hw, UnitConfig rest = {}) {
  static_cast<HardwareConfig&>(rest) = hw;
  return rest;
}

// JSON: an object whose keys are the parameters of sim/config/params.hpp (format fields flattened:
// coord_int_bits, coord_frac_bits, bary_bits; enums as strings). Unknown keys, wrong types
// and out-of-range values are InputErrors naming the file and the key.
void apply_json(UnitConfig& cfg, const nlohmann::json& j, const std::string& source);
// The JSON text of a configuration file; every failure (syntax, a number beyond double's range
// such as 1e400) is an InputError naming `source` and, where known, the key.
nlohmann::json parse_config_text(const std::string& text, const std::string& source);
nlohmann::json to_json(const UnitConfig& cfg);

std::string to_string(CpgMapping m);
std::string to_string(Evaluation e);
std::string to_string(Distribution d);
std::string to_string(Reassembly r);

}  // namespace tessim::sim
