// The unit's fixed-point arithmetic: the single definition shared by the cycle model, the
// co-simulation and (mirrored, operation for operation) the RTL. See docs/number-formats.md.
//
// Representation: a coordinate is a two's-complement integer x with F fraction bits, value
// x / 2^F, width W = 1 + I + F bits. Barycentric weights are unsigned with B fraction bits
// (1.0 = 2^B, width B + 1). Exact intermediate results (products and sums of products) are
// kept in 128-bit integers; every rounding and saturation below is named and happens once.
#pragma once

#include <array>
#include <cstdint>

namespace tessim::sim {

using i128 = __int128;
using u128 = unsigned __int128;

// One 3-component fixed-point vector (a position, a normal or a control point).
using FxVec = std::array<std::int64_t, 3>;

struct NumberFormat {
  int coord_int_bits = 3;    // I: integer bits of a coordinate (excluding sign)
  int coord_frac_bits = 20;  // F: fraction bits of a coordinate
  int bary_bits = 16;        // B: fraction bits of a barycentric weight
  // A: fraction bits of the silhouette weight alpha the CPG takes per edge (values 0..2^A, so
  // that 1 is exact); 0: the unit has no alpha input and computes plain PN (docs/number-formats.md).
  int alpha_bits = 0;

  int coord_width() const { return 1 + coord_int_bits + coord_frac_bits; }  // W
  std::int64_t coord_max() const { return (std::int64_t{1} << (coord_width() - 1)) - 1; }
  std::int64_t coord_min() const { return -(std::int64_t{1} << (coord_width() - 1)); }
  std::int64_t bary_one() const { return std::int64_t{1} << bary_bits; }
  double coord_lsb() const { return 1.0 / static_cast<double>(std::int64_t{1} << coord_frac_bits); }
  bool takes_alpha() const { return alpha_bits > 0; }
  bool operator==(const NumberFormat&) const = default;
};

// Sticky status bits raised by the arithmetic (carried per patch to the output).
enum FxFlag : std::uint8_t {
  kFlagSaturated = 1u << 0,    // a result did not fit in W bits and was clamped
  kFlagDivByZero = 1u << 1,    // a zero divisor (zero-length edge or vanishing normal)
};

// Clamp an exact value to the W-bit coordinate range, raising kFlagSaturated if it moved.
inline std::int64_t saturate(i128 x, const NumberFormat& f, std::uint8_t& flags) {
  if (x > f.coord_max()) { flags |= kFlagSaturated; return f.coord_max(); }
  if (x < f.coord_min()) { flags |= kFlagSaturated; return f.coord_min(); }
  return static_cast<std::int64_t>(x);
}

// Round half up (towards +inf) while dropping `shift` fraction bits: floor((x + 2^(s-1)) / 2^s).
// The arithmetic right shift of a negative value is a floor, in C++20 and in the RTL (>>>).
inline i128 round_shift(i128 x, int shift) {
  if (shift <= 0) return x;
  return (x + (i128{1} << (shift - 1))) >> shift;
}

// Exact dot product: the sum of three W x W products, 2F fraction bits, never rounded.
inline i128 dot_exact(const FxVec& a, const FxVec& b) {
  return i128{a[0]} * b[0] + i128{a[1]} * b[1] + i128{a[2]} * b[2];
}

// Division truncated towards zero, saturated to W bits. A zero divisor gives 0 and raises
// kFlagDivByZero. Truncation is odd-symmetric (q(-n, d) = -q(n, d)), which keeps edge
// quantities independent of the direction an edge is walked in.
inline std::int64_t div_trunc(i128 num, i128 den, const NumberFormat& f, std::uint8_t& flags) {
  if (den == 0) { flags |= kFlagDivByZero; return 0; }
  return saturate(num / den, f, flags);
}

// floor(sqrt(x)) of a non-negative integer, exact (digit-by-digit, as the RTL does it).
inline u128 isqrt(u128 x) {
  u128 root = 0;
  u128 bit = u128{1} << 126;
  while (bit > x) bit >>= 2;
  while (bit != 0) {
    if (x >= root + bit) {
      x -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

// Multiplication by a constant fraction c / 2^G applied to an exact value with `frac` fraction
// bits, rounded half up to F bits and saturated: the divisions by 3 and 12 of the control-point
// formulas (the hardware multiplies by a rounded reciprocal). G = F + 8 keeps the error of the
// rounded constant below 6 * 2^I / 256 LSB (docs/number-formats.md).
constexpr int kConstGuardBits = 8;
inline int const_frac_bits(const NumberFormat& f) { return f.coord_frac_bits + kConstGuardBits; }  // G
inline std::int64_t one_third(const NumberFormat& f) {  // round(2^G / 3)
  return ((std::int64_t{1} << const_frac_bits(f)) + 1) / 3;
}
inline std::int64_t one_twelfth(const NumberFormat& f) {  // round(2^G / 12)
  return ((std::int64_t{1} << const_frac_bits(f)) + 6) / 12;
}

inline std::int64_t mul_const(i128 x, int frac, std::int64_t c, const NumberFormat& f,
                              std::uint8_t& flags) {
  return saturate(round_shift(x * c, frac - f.coord_frac_bits + const_frac_bits(f)), f, flags);
}

// One INT operation (docs/mathematics.md §6), per component: r = round((w A + u B + v C) / 2^B)
// with w + u + v = 2^B. The sum is exact and rounded once, so it is symmetric in the operands
// and never overflows (the result is a convex combination of A, B, C). It needs no 128-bit
// arithmetic: |w A + u B + v C| <= 2^B * 2^(W-1), and the configuration limits W <= 32 and
// B <= 20 (sim/config/params.cpp, UnitConfig::validate) keep that below 2^51.
constexpr int kMaxCoordWidth = 32;
constexpr int kMaxBaryBits = 20;
static_assert(kMaxBaryBits + kMaxCoordWidth - 1 < 62, "int_op's exact sum must fit in 64 bits");
inline FxVec int_op(std::int64_t w, std::int64_t u, std::int64_t v, const FxVec& a, const FxVec& b,
                    const FxVec& c, int bary_bits) {
  const std::int64_t half = std::int64_t{1} << (bary_bits - 1);  // B >= 7: round half up
  FxVec r{};
  for (int i = 0; i < 3; ++i) r[i] = (w * a[i] + u * b[i] + v * c[i] + half) >> bary_bits;
  return r;
}

// Barycentric weight of lattice index j at factor L: round(j / L * 2^B), half up.
// For B >= 7 and L <= 64 no value is a tie, so weight(j) + weight(L - j) = 2^B exactly:
// an edge point gets the same weights from both patches that share the edge.
inline std::int64_t bary_weight(int j, int L, int bary_bits) {
  return ((std::int64_t{j} << (bary_bits + 1)) + L) / (2 * std::int64_t{L});
}

}  // namespace tessim::sim
