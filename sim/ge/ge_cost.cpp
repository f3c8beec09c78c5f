#include "sim/ge/ge_cost.hpp"

#include <algorithm>
#include <cmath>

namespace tessim::sim {

namespace {

// The Bernstein basis at (u, v), w = 1 - u - v: w (2 subtractions), u², v², w² (3), u³, v³, w³
// (3), u²v, u²w, v²u, v²w, w²u, w²v (6), uv and uvw (2).
constexpr int kBasisOps = 2 + 3 + 3 + 6 + 2;
// Position: ten control points times their basis value, three components each (a multiply, then
// multiply-adds).
constexpr int kPositionOps = 10 * 3;
// Normalizing a 3-vector: its dot with itself (3), one reciprocal square root, three multiplies.
constexpr GeOps kNormalize{3 + 3, 1, 0};

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
  ops.alu += kNormalize.alu;
  ops.sfu += kNormalize.sfu;
  return ops;
}

GeOps displacement_ops(DisplaceKind kind) {
  // Blinn's normal given g: g·N (3), t = g - (g·N) N (3 multiply-adds), N - t (3), normalize.
  constexpr GeOps kBlinn{3 + 3 + 3 + kNormalize.alu, kNormalize.sfu, 0};
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

GeOps vertex_work_ops() {
  // Position: a 4×4 matrix times (x, y, z, 1): 12 multiply-adds and 4 multiplies (16); the normal
  // by the 3×3 inverse transpose (9) and normalized (6 and an rsqrt); the light: N·L (3), its
  // clamp (1), the diffuse colour (3), N·H with H precomputed per light (3), its clamp (1), the
  // shininess power as exp2(s log2 x) (1 and two special functions), the specular colour added
  // (3); the perspective divide: 1/w (a special function) and x, y, z times it (3).
  constexpr int alu = 16 + 9 + kNormalize.alu + 3 + 1 + 3 + 3 + 1 + 1 + 3 + 3;
  constexpr int sfu = kNormalize.sfu + 2 + 1;
  return {alu, sfu, 0};
}

std::uint64_t ge_slots(const GeOps& ops, const EnvironmentConfig& env) {
  return static_cast<std::uint64_t>(ops.alu) + static_cast<std::uint64_t>(ops.sfu) * static_cast<std::uint64_t>(env.ge_sfu_cost) +
         static_cast<std::uint64_t>(ops.lookup) * static_cast<std::uint64_t>(env.ge_lookup_cost);
}

int ge_cycles(const GeOps& ops, const EnvironmentConfig& env) {
  const std::uint64_t lanes = static_cast<std::uint64_t>(env.ge_alu_lanes);
  return static_cast<int>((ge_slots(ops, env) + lanes - 1) / lanes);
}

std::uint64_t core_program_slots(const EnvironmentConfig& env) {
  return ge_slots(vertex_work_ops(), env) + env.ge_shader_slots;
}

std::uint64_t core_wave_cycles(const EnvironmentConfig& env) {
  const std::uint64_t issue = static_cast<std::uint64_t>(env.ge_core_issue);
  return std::max<std::uint64_t>(1, (core_program_slots(env) + issue - 1) / issue);
}

double core_cycles_per_vertex(const EnvironmentConfig& env) {
  return static_cast<double>(core_wave_cycles(env)) / env.ge_core_lanes * env.unit_mhz / env.ge_core_mhz;
}

int core_longest_wait(const EnvironmentConfig& env) {
  const double unit_per_core = env.unit_mhz / env.ge_core_mhz;
  const double wave = std::ceil(static_cast<double>(core_wave_cycles(env)) * unit_per_core);  // one wave, in unit cycles
  const double sync = 2 + std::ceil(2 * unit_per_core);                                      // both synchronizers
  return static_cast<int>(std::min(wave + sync + 1, 1e9));
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
