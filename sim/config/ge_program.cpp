#include "sim/config/ge_program.hpp"

#include <algorithm>
#include <cmath>

namespace tessim::sim {

GeOps vertex_work_ops() {
  // Position: a 4×4 matrix times (x, y, z, 1): 12 multiply-adds and 4 multiplies (16); the normal
  // by the 3×3 inverse transpose (9) and normalized (6 and an rsqrt); the light: N·L (3), its
  // clamp (1), the diffuse colour (3), N·H with H precomputed per light (3), its clamp (1), the
  // shininess power as exp2(s log2 x) (1 and two special functions), the specular colour added
  // (3); the perspective divide: 1/w (a special function) and x, y, z times it (3).
  constexpr int alu = 16 + 9 + kNormalizeOps.alu + 3 + 1 + 3 + 3 + 1 + 1 + 3 + 3;
  constexpr int sfu = kNormalizeOps.sfu + 2 + 1;
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

}  // namespace tessim::sim
