#include "sim/ge/ge_cost.hpp"

namespace tessim::sim {

namespace {

// The Bernstein basis at (u, v), w = 1 - u - v: w (2 subtractions), u², v², w² (3), u³, v³, w³
// (3), u²v, u²w, v²u, v²w, w²u, w²v (6), uv and uvw (2).
constexpr int kBasisOps = 2 + 3 + 3 + 6 + 2;
// Position: ten control points times their basis value, three components each (a multiply, then
// multiply-adds).
constexpr int kPositionOps = 10 * 3;

}  // namespace

GeOps evaluation_ops(NormalMode normals) {
  GeOps ops{kBasisOps + kPositionOps, 0, 0};
  if (normals == NormalMode::Linear) {
    ops.alu += 3 * 3;  // w N1 + u N2 + v N3
  } else {
    // Quadratic and reflect: six control normals (they differ only in how the CPG computes the
    // mid-edge ones) on u², v², w², uv and the two products vw, wu not in the cubic basis.
    // Derivative: not offered by the unit or the GE model (validate()).
    ops.alu += 2 + 6 * 3;
  }
  ops.alu += kNormalizeOps.alu;
  ops.sfu += kNormalizeOps.sfu;
  return ops;
}

GeOps displacement_ops(DisplaceKind kind) {
  // Blinn's normal given g: g·N (3), t = g - (g·N) N (3 multiply-adds), N - t (3), normalize.
  constexpr GeOps kBlinn{3 + 3 + 3 + kNormalizeOps.alu, kNormalizeOps.sfu, 0};
  switch (kind) {
    case DisplaceKind::None: return {};
    case DisplaceKind::Sine: {
      // r² = P·P (3); s = rsqrt(r²); r = r² s (1); f r (1); sin, cos; h = a sin (1);
      // P + h N (3); a f cos s (2, a f a constant); g = (a f cos s) P (3).
      return {3 + 1 + 1 + 1 + 3 + 2 + 3 + kBlinn.alu, 1 + 2 + kBlinn.sfu, 0};
    }
    case DisplaceKind::Noise: {
      // model/displace.cpp gradient_noise at x = f P, as written:
      int alu = 3;                 // x = f P
      alu += 3 + 3 + 3 + 3;        // floor, t = x - floor, float-to-integer, & 255 per axis
      alu += 3 * 5 + 3 * 4;        // quintic fade and its derivative per axis
      alu += 3 + 3;                // 1 - s and -s' per axis
      alu += 2 + (1 + 4 + 8) + (2 + 4 + 8);  // j+1, k+1; the hash's additions and masks
      alu += 8 * 2;                // the gradient index: hash mod 12 (a multiply-high and a subtraction)
      alu += 3;                    // t - 1 per axis
      alu += 8 * 3;                // each corner's plane: grad · r
      alu += 4 + 8;                // the eight weights wx wy wz (wx wy shared by two corners)
      alu += 8;                    // value += w plane
      alu += 8 * 3 + 8 * (6 + 3);  // gradient += w grad + plane (dwx wy wz, wx dwy wz, wx wy dwz)
      const int lookups = (2 + 4 + 8) + 8;  // the permutation's three levels; the gradient table
      // h = a value (1); P + h N (3); g = (a f) gradient (3).
      alu += 1 + 3 + 3 + kBlinn.alu;
      return {alu, kBlinn.sfu, lookups};
    }
  }
  return {};
}

GeVertexCost ge_vertex_cost(const UnitConfig& cfg, DisplaceKind displace) {
  GeVertexCost c;
  c.base = cfg.gpe_cycles;
  // Evaluation and displacement are one shader program: their slots are rounded up to cycles once,
  // and the displacement's part is what it adds to the evaluation's.
  GeOps shader = displacement_ops(displace);
  if (cfg.evaluation == Evaluation::Gpe) {
    const GeOps evaluation = evaluation_ops(cfg.normals);
    c.evaluation = ge_cycles(evaluation, cfg);
    shader.alu += evaluation.alu;
    shader.sfu += evaluation.sfu;
    shader.lookup += evaluation.lookup;
  }
  c.displacement = ge_cycles(shader, cfg) - c.evaluation;
  c.shader_slots = ge_slots(shader, cfg);
  return c;
}

}  // namespace tessim::sim
