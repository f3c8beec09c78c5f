// The geometry engine's ALU model and its shader-core form, from the configuration alone
// (docs/microarchitecture.md §12): scalar operations by kind, their issue slots, the GE's own
// per-vertex work, and the K a shader core derives from its program. sim/ge/ge_cost.hpp counts
// the shader work (evaluation, displacement) on top; the analytic model and the GE's cycle model
// both read the core's K from here.
#pragma once

#include <cstdint>

#include "sim/config/config.hpp"

namespace tessim::sim {

// Scalar operations of one vertex by kind.
struct GeOps {
  int alu = 0;     // multiply, add, multiply-add, floor, conversion, integer: one slot each
  int sfu = 0;     // reciprocal square root, sine, cosine
  int lookup = 0;  // table reads
  bool operator==(const GeOps&) const = default;
};

// Normalizing a 3-vector: its dot with itself (3), one reciprocal square root, three multiplies.
inline constexpr GeOps kNormalizeOps{3 + 3, 1, 0};

// The GE's own work per vertex, which the fixed K stands for: transform to clip space, the
// normal to eye space, one directional light (diffuse and Blinn specular), the perspective divide.
GeOps vertex_work_ops();

// Issue slots and cycles of `ops` on the GE's ALU of `env`: a special function ge_sfu_cost slots,
// a table read ge_lookup_cost, ceil(slots / ge_alu_lanes) cycles.
std::uint64_t ge_slots(const GeOps& ops, const EnvironmentConfig& env);
int ge_cycles(const GeOps& ops, const EnvironmentConfig& env);

// The GE as a shader core (env.ge_core()): each lane runs one vertex's program — the GE's own
// work and the run's shader work, ge_shader_slots — and a wave of up to W vertices takes
// ceil(slots / I) core cycles of issue.
std::uint64_t core_program_slots(const EnvironmentConfig& env);
std::uint64_t core_wave_cycles(const EnvironmentConfig& env);
// K derived from the core: the unit's cycles per vertex at full waves,
// ceil(slots / I) / W × unit_mhz / ge_core_mhz (fractional).
double core_cycles_per_vertex(const EnvironmentConfig& env);
// The longest the unit can wait for the core to take one vertex from a full FIFO: one wave's
// issue in unit cycles, rounded up, and the pointers' two-register synchronizers both ways.
int core_longest_wait(const EnvironmentConfig& env);

}  // namespace tessim::sim
