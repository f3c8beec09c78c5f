#include "sim/values/error_bound.hpp"

#include <algorithm>
#include <cmath>

namespace tessim::sim {

namespace {

constexpr double kSqrt3 = 1.7320508075688772;

double lsb(const NumberFormat& f) { return std::ldexp(1.0, -f.coord_frac_bits); }

}  // namespace

ErrorBudget position_error_budget(const NumberFormat& f) {
  // R bounds the magnitude of any representable value: 2^I.
  const double R = std::ldexp(1.0, f.coord_int_bits);
  const double const_err = std::ldexp(1.0, f.coord_frac_bits - const_frac_bits(f));  // 2^(F-G)
  ErrorBudget b;
  // Tangent point: exact numerator (relative to the quantized input), a constant round(2^G/3)
  // off by at most 1/2 on a value |num| <= 3R (error 3R/2 2^-G), then one rounding (1/2 LSB).
  b.tangent_lsb = 0.5 + 1.5 * R * const_err;
  // The silhouette blend rounds alpha w to w's 2F fraction bits: off by 2^-(2F+1), times a
  // normal component (|Nc| <= 1) over 3, i.e. 2^-(F+1)/3 of an LSB.
  if (f.takes_alpha()) b.tangent_lsb += std::ldexp(1.0, -(f.coord_frac_bits + 1)) / 3.0;
  // b111 = (3 sum T - 2 sum C) / 12: six tangents weighted 3/12 carry 1.5 tangent errors; the
  // constant round(2^G/12) is off by at most 1/2 on |x| <= 12R (error 6R 2^-G); one rounding.
  b.center_lsb = 1.5 * b.tangent_lsb + 0.5 + 6.0 * R * const_err;
  // Each de Casteljau level is a convex combination (errors do not grow) plus one rounding.
  b.position_lsb = std::max(b.tangent_lsb, b.center_lsb) + 3 * 0.5;
  b.position_units = kSqrt3 * b.position_lsb * lsb(f);
  return b;
}

double normal_error_bound(const TriangleFx& tri, NormalMode mode, const NumberFormat& f) {
  const double q = lsb(f);
  if (mode == NormalMode::Linear) return 0.5 * q;  // exact corners, one INT level
  double mid_lsb = 0;
  if (mode == NormalMode::Reflect) {
    // t = trunc(...) is off by < 1 LSB; m = s - 4 t multiplies that by 4.
    mid_lsb = 4.0;
  } else {
    // m = s - 2t is off by < 2 LSB per component (|dm| < 2 sqrt3 LSB); normalizing divides by
    // |m| (Lipschitz constant 2/|m| for the direction), the floor of the square root adds
    // < 1 LSB relative, and the final truncation < 1 LSB.
    for (int e = 0; e < 3; ++e) {
      const int a = e, bidx = (e + 1) % 3;
      double d[3], s[3], dd = 0, ds = 0;
      for (int c = 0; c < 3; ++c) {
        d[c] = static_cast<double>(tri.p[bidx][c] - tri.p[a][c]) * q;
        s[c] = static_cast<double>(tri.n[a][c] + tri.n[bidx][c]) * q;
        dd += d[c] * d[c];
        ds += d[c] * s[c];
      }
      double mm = 0;
      for (int c = 0; c < 3; ++c) {
        const double m = s[c] - (dd > 0 ? 2.0 * d[c] * ds / dd : 0.0);
        mm += m * m;
      }
      const double norm = std::sqrt(mm);
      const double dm = 2.0 * kSqrt3 * q;
      if (norm <= 4.0 * dm) return -1.0;  // direction of m not determined by the arithmetic
      const double rel = 2.0 * (dm + q) / (norm - dm);
      mid_lsb = std::max(mid_lsb, 1.0 + rel / q);
    }
  }
  // Corners (2 Ni) are exact; two INT levels add 1/2 LSB each.
  return (mid_lsb + 2 * 0.5) * q;
}

double normal_angle_bound(double component_bound, double output_length) {
  const double e = kSqrt3 * component_bound;
  if (component_bound < 0 || output_length <= 2.0 * e) return -1.0;
  return std::asin(std::min(1.0, e / (output_length - e)));
}

}  // namespace tessim::sim
