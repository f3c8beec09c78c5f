// What the geometry engine (GE) pays per vertex for work it runs as a shader: the evaluation of
// a PN patch at a domain point (evaluation gpe) and procedural displacement (model/displace.hpp).
// docs/microarchitecture.md §12 derives every count below. The GE's ALU model: ge_alu_lanes
// scalar issue slots per cycle; a multiply, add, multiply-add, compare, floor, conversion or
// integer operation takes one slot, a special function (reciprocal square root, sine, cosine)
// ge_sfu_cost slots and a table read (the noise's permutation and gradients) ge_lookup_cost slots.
// The shader's slots cost ceil(slots / lanes) cycles per vertex, added to K (gpe_cycles), the GE's
// own work per vertex (transform and lighting).
#pragma once

#include <cstdint>

#include "model/displace.hpp"
#include "model/normal_mode.hpp"
#include "sim/config/config.hpp"

namespace tessim::sim {

// Scalar operations of one vertex by kind.
struct GeOps {
  int alu = 0;     // multiply, add, multiply-add, floor, conversion, integer: one slot each
  int sfu = 0;     // reciprocal square root, sine, cosine
  int lookup = 0;  // table reads
  bool operator==(const GeOps&) const = default;
};

// The PN patch at one domain point in Bernstein form (position from the ten control points, the
// normal from the six quadratic control normals, or the three vertex normals in linear mode),
// the normal normalized. The producer of the control points folds the multinomial 3 and 6 into
// them once per patch.
GeOps evaluation_ops(NormalMode normals);
// Displacement of one point and Blinn's normal (mathematics.md §12); none for DisplaceKind::None.
GeOps displacement_ops(DisplaceKind kind);

// The GE's own work per vertex, which the fixed K stands for: transform to clip space, the
// normal to eye space, one directional light (diffuse and Blinn specular), the perspective divide.
GeOps vertex_work_ops();

// Issue slots and cycles of `ops` on the GE's ALU of `env`.
std::uint64_t ge_slots(const GeOps& ops, const EnvironmentConfig& env);
int ge_cycles(const GeOps& ops, const EnvironmentConfig& env);

// GE cycles per vertex of a run, by part: K, the evaluation (evaluation gpe), the displacement.
// Evaluation and displacement run as one program: total = K + ceil((evaluation's + displacement's
// slots) / lanes); `displacement` is what the displacement adds to ceil(evaluation's slots / lanes).
struct GeVertexCost {
  int base = 0;
  int evaluation = 0;
  int displacement = 0;
  std::uint64_t shader_slots = 0;  // issue slots per vertex of evaluation and displacement together
  int total() const { return base + evaluation + displacement; }
  bool operator==(const GeVertexCost&) const = default;
};
GeVertexCost ge_vertex_cost(const UnitConfig& cfg, DisplaceKind displace);
// The GE as a shader core (env.ge_core(); docs/microarchitecture.md §12): each lane runs one
// vertex's program — the GE's own work and the run's shader work, ge_shader_slots — and a wave of
// up to W vertices takes ceil(slots / I) core cycles of issue.
std::uint64_t core_program_slots(const EnvironmentConfig& env);
std::uint64_t core_wave_cycles(const EnvironmentConfig& env);
// K derived from the core: the unit's cycles per vertex at full waves,
// ceil(slots / I) / W × unit_mhz / ge_core_mhz (fractional).
double core_cycles_per_vertex(const EnvironmentConfig& env);
// The longest the unit can wait for the core to take one vertex from a full FIFO: one wave's
// issue in unit cycles, rounded up, and the pointers' two-register synchronizers both ways.
int core_longest_wait(const EnvironmentConfig& env);

// `cfg` as the run's geometry engine behaves (what the testbench, the watchdog, the analytic model
// and the chunk bounds take as K): a fixed K of cost.total() cycles per vertex; or, for a shader
// core, its program grown by the shader work's slots, K the longest wait for one vertex.
inline UnitConfig with_ge_cost(UnitConfig cfg, const GeVertexCost& cost) {
  if (cfg.ge_core()) {
    cfg.ge_shader_slots = cost.shader_slots;
    cfg.gpe_cycles = core_longest_wait(cfg);
  } else {
    cfg.gpe_cycles = cost.total();
  }
  return cfg;
}

}  // namespace tessim::sim
