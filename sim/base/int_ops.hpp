// The 14 INT operations of one vertex (docs/microarchitecture.md §8): operand sources, level
// and dependences, defined once for the cycle model, `tessim schema` and the scripts that read
// it. One INT op is w·A + u·B + v·C per component (int_op, sim/base/fixed.hpp).
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "model/normal_mode.hpp"

namespace tessim::sim::int_ops {

// Where an operand comes from: the geometry net b, the normal net n (of the context's
// control-point buffer) or the context's temporaries T (results of earlier ops).
enum class Net : std::uint8_t { B, N, T };

struct Operand {
  Net net;
  std::uint8_t index;
};

constexpr Operand b(int i) { return {Net::B, static_cast<std::uint8_t>(i)}; }
constexpr Operand n(int i) { return {Net::N, static_cast<std::uint8_t>(i)}; }
constexpr Operand t(int i) { return {Net::T, static_cast<std::uint8_t>(i)}; }
constexpr std::uint32_t bit(int op) { return std::uint32_t{1} << op; }

struct IntOp {
  int op;                        // index 0..13; the result is temporary T[op]
  int level;                     // de Casteljau level 1..3
  const char* what;              // "geometry" or "normal", as in the doc's table
  std::array<Operand, 3> operands;  // A, B, C (quadratic and reflect normals)
  std::uint32_t depends;         // bit o: needs the result of op o
};

inline constexpr int kOpCount = 14;

inline constexpr std::array<IntOp, kOpCount> kIntOps{{
    {0, 1, "geometry", {b(0), b(1), b(4)}, 0},
    {1, 1, "geometry", {b(1), b(2), b(5)}, 0},
    {2, 1, "geometry", {b(2), b(3), b(6)}, 0},
    {3, 1, "geometry", {b(4), b(5), b(7)}, 0},
    {4, 1, "geometry", {b(5), b(6), b(8)}, 0},
    {5, 1, "geometry", {b(7), b(8), b(9)}, 0},
    {6, 1, "normal", {n(0), n(1), n(3)}, 0},
    {7, 1, "normal", {n(1), n(2), n(4)}, 0},
    {8, 1, "normal", {n(3), n(4), n(5)}, 0},
    {9, 2, "geometry", {t(0), t(1), t(3)}, bit(0) | bit(1) | bit(3)},
    {10, 2, "geometry", {t(1), t(2), t(4)}, bit(1) | bit(2) | bit(4)},
    {11, 2, "geometry", {t(3), t(4), t(5)}, bit(3) | bit(4) | bit(5)},
    {12, 2, "normal", {t(6), t(7), t(8)}, bit(6) | bit(7) | bit(8)},
    {13, 3, "geometry", {t(9), t(10), t(11)}, bit(9) | bit(10) | bit(11)},
}};

// Linear normals: op kLinearNormalOp reads N1, N2, N3 instead, and the ops of kLinearAbsent do
// not exist (allocated already issued and done).
inline constexpr int kLinearNormalOp = 6;
inline constexpr std::array<Operand, 3> kLinearNormalOperands{n(0), n(2), n(5)};
inline constexpr std::uint32_t kLinearAbsent = bit(7) | bit(8) | bit(12);

inline constexpr int kPositionOp = 13;  // T13 is the output position
constexpr int normal_op(NormalMode m) { return m == NormalMode::Linear ? kLinearNormalOp : 12; }
constexpr std::uint32_t absent_ops(NormalMode m) { return m == NormalMode::Linear ? kLinearAbsent : 0; }
constexpr std::array<Operand, 3> operands(int op, NormalMode m) {
  return m == NormalMode::Linear && op == kLinearNormalOp ? kLinearNormalOperands
                                                          : kIntOps[static_cast<std::size_t>(op)].operands;
}
// INT ops issued per vertex: 14 (quadratic, reflect), 11 (linear).
constexpr int ops_per_vertex(NormalMode m) { return kOpCount - std::popcount(absent_ops(m)); }

constexpr const char* to_string(Net net) { return net == Net::B ? "b" : net == Net::N ? "n" : "T"; }

}  // namespace tessim::sim::int_ops
