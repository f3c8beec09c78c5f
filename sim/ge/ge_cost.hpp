// What the geometry engine (GE) pays per vertex for work it runs as a shader: the evaluation of
// a PN patch at a domain point (evaluation gpe) and procedural displacement (model/displace.hpp).
// docs/microarchitecture.md §12 derives every count below. The GE's ALU model (ge_slots, ge_cycles)
// and its shader-core form are in sim/config/ge_program.hpp. The shader's slots cost
// ceil(slots / lanes) cycles per vertex, added to K (gpe_cycles), the GE's own work per vertex
// (transform and lighting); on a shader core they join its program.
#pragma once

#include <cstdint>

#include "model/displace.hpp"
#include "model/normal_mode.hpp"
#include "sim/config/config.hpp"
#include "sim/config/ge_program.hpp"

namespace tessim::sim {

// The PN patch at one domain point in Bernstein form (position from the ten control points, the
// normal from the six quadratic control normals, or the three vertex normals in linear mode),
// the normal normalized. The producer of the control points folds the multinomial 3 and 6 into
// them once per patch.
GeOps evaluation_ops(NormalMode normals);
// Displacement of one point and Blinn's normal (mathematics.md §12); none for DisplaceKind::None.
GeOps displacement_ops(DisplaceKind kind);

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
