// The 14 INT operations of one vertex, defined once (docs/microarchitecture.md §8): de Casteljau
// on the cubic geometry net (ops 0-5, 9-11, 13) and the quadratic normal net (ops 6-8, 12).
// One INT operation is w·A + u·B + v·C per component (sim/fixed.hpp, int_op). The cycle model's
// scheduler, the untimed datapath and `tessim schema` read this table.
#pragma once

#include <array>
#include <cstdint>

#include "model/normal_mode.hpp"

namespace tessim::sim {

constexpr int kIntOpsPerVertex = 14;

// Where an operand comes from: the control-point buffer's geometry net b0..b9 (Bernstein
// order of sim/cpg.hpp), its normal net n0..n5, or the context's temporaries T0..T13.
enum class OperandSpace : std::uint8_t { GeometryNet, NormalNet, Temp };

struct IntOperand {
  OperandSpace space;
  std::uint8_t index;
};

struct IntOpInfo {
  const char* level;                    // "geometry L1", ..., for tables and traces
  std::array<IntOperand, 3> operands;   // A (weight w), B (weight u), C (weight v)
  std::uint32_t depends_on;             // bit o: needs T[o]
};

namespace int_ops_detail {
constexpr IntOperand b(int i) { return {OperandSpace::GeometryNet, static_cast<std::uint8_t>(i)}; }
constexpr IntOperand n(int i) { return {OperandSpace::NormalNet, static_cast<std::uint8_t>(i)}; }
constexpr IntOperand t(int i) { return {OperandSpace::Temp, static_cast<std::uint8_t>(i)}; }
constexpr std::uint32_t bits(int a, int b, int c) { return (1u << a) | (1u << b) | (1u << c); }
}  // namespace int_ops_detail

// Quadratic and reflect normals. Linear mode replaces op 6 and drops ops 7, 8, 12 (below).
inline constexpr std::array<IntOpInfo, kIntOpsPerVertex> kIntOps = [] {
  using namespace int_ops_detail;
  return std::array<IntOpInfo, kIntOpsPerVertex>{{
      {"geometry L1", {b(0), b(1), b(4)}, 0},
      {"geometry L1", {b(1), b(2), b(5)}, 0},
      {"geometry L1", {b(2), b(3), b(6)}, 0},
      {"geometry L1", {b(4), b(5), b(7)}, 0},
      {"geometry L1", {b(5), b(6), b(8)}, 0},
      {"geometry L1", {b(7), b(8), b(9)}, 0},
      {"normal L1", {n(0), n(1), n(3)}, 0},
      {"normal L1", {n(1), n(2), n(4)}, 0},
      {"normal L1", {n(3), n(4), n(5)}, 0},
      {"geometry L2", {t(0), t(1), t(3)}, bits(0, 1, 3)},
      {"geometry L2", {t(1), t(2), t(4)}, bits(1, 2, 4)},
      {"geometry L2", {t(3), t(4), t(5)}, bits(3, 4, 5)},
      {"normal L2", {t(6), t(7), t(8)}, bits(6, 7, 8)},
      {"geometry L3", {t(9), t(10), t(11)}, bits(9, 10, 11)},
  }};
}();

// Linear normals: op 6 is w N1 + u N2 + v N3 and is the output normal.
inline constexpr IntOpInfo kLinearNormalOp = {"normal (linear)",
                                              {int_ops_detail::n(0), int_ops_detail::n(2), int_ops_detail::n(5)}, 0};
inline constexpr std::uint32_t kLinearAbsentOps = (1u << 7) | (1u << 8) | (1u << 12);
constexpr int kPositionOp = 13;

// The operation table of a normal mode: op 6 replaced for linear normals.
inline std::array<IntOpInfo, kIntOpsPerVertex> int_ops_for(NormalMode mode) {
  auto ops = kIntOps;
  if (mode == NormalMode::Linear) ops[6] = kLinearNormalOp;
  return ops;
}
// Ops that do not exist in the mode (allocated already issued and done).
constexpr std::uint32_t absent_ops(NormalMode mode) { return mode == NormalMode::Linear ? kLinearAbsentOps : 0; }
// The op whose result is the output normal.
constexpr int normal_op(NormalMode mode) { return mode == NormalMode::Linear ? 6 : 12; }

}  // namespace tessim::sim
