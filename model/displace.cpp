#include "model/displace.hpp"

#include <array>
#include <cmath>
#include <cstdint>

#include "model/base/error.hpp"

namespace tessim {

namespace {

// A fixed permutation of 0..255: a Fisher-Yates shuffle driven by SplitMix64 from seed 0 (any
// fixed permutation will do; this one is written down by its construction, not as a table).
constexpr std::array<std::uint8_t, 256> make_permutation() {
  std::array<std::uint8_t, 256> p{};
  for (int i = 0; i < 256; ++i) p[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
  std::uint64_t state = 0;
  for (int i = 255; i > 0; --i) {
    state += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    const auto j = static_cast<std::size_t>(z % static_cast<std::uint64_t>(i + 1));
    const std::uint8_t t = p[static_cast<std::size_t>(i)];
    p[static_cast<std::size_t>(i)] = p[j];
    p[j] = t;
  }
  return p;
}
constexpr std::array<std::uint8_t, 256> kPermutation = make_permutation();

// The 12 edge directions of a cube.
constexpr std::array<std::array<double, 3>, 12> kGradients{{{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                                            {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                                            {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}}};

int hash(long long i, long long j, long long k) {
  auto p = [](long long v) { return static_cast<int>(kPermutation[static_cast<std::size_t>(v & 255)]); };
  return p(p(p(i) + j) + k);
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
double fade_derivative(double t) { return 30.0 * t * t * (t * (t - 2.0) + 1.0); }

}  // namespace

NoiseSample gradient_noise(const glm::dvec3& x) {
  if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return {};  // beyond the range: 0
  const glm::dvec3 cell = glm::floor(x);
  const glm::dvec3 t = x - cell;
  // The lattice repeats every 256 cells (the permutation's period): the cell index modulo 256
  // keeps the integer conversion in range for any finite x.
  const auto i0 = static_cast<long long>(std::fmod(cell.x, 256.0));
  const auto j0 = static_cast<long long>(std::fmod(cell.y, 256.0));
  const auto k0 = static_cast<long long>(std::fmod(cell.z, 256.0));
  const glm::dvec3 s(fade(t.x), fade(t.y), fade(t.z));
  const glm::dvec3 ds(fade_derivative(t.x), fade_derivative(t.y), fade_derivative(t.z));
  NoiseSample out;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const auto& g = kGradients[static_cast<std::size_t>(hash(i0 + di, j0 + dj, k0 + dk) % 12)];
    const glm::dvec3 grad(g[0], g[1], g[2]);
    const glm::dvec3 r(t.x - di, t.y - dj, t.z - dk);
    const double plane = glm::dot(grad, r);
    // The corner's weight and its derivative along each axis.
    const double wx = di ? s.x : 1.0 - s.x, wy = dj ? s.y : 1.0 - s.y, wz = dk ? s.z : 1.0 - s.z;
    const double dwx = di ? ds.x : -ds.x, dwy = dj ? ds.y : -ds.y, dwz = dk ? ds.z : -ds.z;
    const double w = wx * wy * wz;
    out.value += w * plane;
    out.gradient += w * grad + plane * glm::dvec3(dwx * wy * wz, wx * dwy * wz, wx * wy * dwz);
  }
  return out;
}

DisplacedPoint displace(const DisplaceSettings& d, const glm::dvec3& p, const glm::dvec3& n) {
  if (!d.enabled()) return {p, n};
  double h = 0.0;
  glm::dvec3 g(0.0);
  if (d.kind == DisplaceKind::Noise) {
    const NoiseSample s = gradient_noise(d.frequency * p);
    h = d.amplitude * s.value;
    g = (d.amplitude * d.frequency) * s.gradient;
  } else {
    const double r = glm::length(p), phase = d.frequency * r;
    if (std::isfinite(phase)) {  // a phase beyond the double range displaces nothing
      h = d.amplitude * std::sin(phase);
      if (r > 0.0) g = (d.amplitude * d.frequency * std::cos(phase) / r) * p;
    }
  }
  const glm::dvec3 tangential = g - glm::dot(g, n) * n;
  return {p + h * n, glm::normalize(n - tangential)};
}

void validate(const DisplaceSettings& d, const std::string& source) {
  if (!d.enabled()) return;
  if (!std::isfinite(d.amplitude))
    throw InputError(source, "--amplitude", std::to_string(d.amplitude) + " is not a finite number");
  if (!std::isfinite(d.frequency))
    throw InputError(source, "--frequency", std::to_string(d.frequency) + " is not a finite number");
  if (d.frequency < 0.0)
    throw InputError(source, "--frequency", std::to_string(d.frequency) + " is negative (radians per unit of |P|)");
  if (!std::isfinite(d.amplitude * d.frequency))
    throw InputError(source, "--amplitude", "amplitude x frequency is beyond the double range");
}

}  // namespace tessim
