// Procedural displacement in the float reference (model/displace.hpp, docs/mathematics.md §12):
// the definition recomputed here from scratch, its special points (amplitude 0, the origin, the
// zeros of the cosine), the normal as the gradient of the displaced height field on a plane, and
// tessellate_mesh applying it to every evaluated point of every pattern.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "model/base/error.hpp"
#include "model/displace.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"

namespace tessim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

DisplaceSettings sine(double a, double f) { return {DisplaceKind::Sine, a, f}; }

TEST(Displace, FollowsItsDefinition) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 1000; ++i) {
    const double a = u(rng) * 0.1, f = std::abs(u(rng)) * 20.0;
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    const glm::dvec3 n = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) + glm::dvec3(0.0, 0.0, 2.5));
    const DisplacedPoint d = displace(sine(a, f), p, n);
    // P' = P + a sin(f r) N; N' = normalize(N - g + (g.N) N), g = a f cos(f r) P / r.
    const double r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    const double h = a * std::sin(f * r), k = a * f * std::cos(f * r) / r;
    const double gn = k * (p.x * n.x + p.y * n.y + p.z * n.z);
    const glm::dvec3 m(n.x - k * p.x + gn * n.x, n.y - k * p.y + gn * n.y, n.z - k * p.z + gn * n.z);
    const double len = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
    EXPECT_LT(glm::length(d.position - (p + h * n)), 1e-14);
    EXPECT_LT(glm::length(d.normal - m / len), 1e-14);
    EXPECT_NEAR(glm::length(d.normal), 1.0, 1e-15);
  }
}

TEST(Displace, SpecialPoints) {
  const glm::dvec3 n(0.0, 0.0, 1.0);
  const glm::dvec3 p(0.3, -0.4, 0.2);
  // Off, or amplitude 0: the point and its normal unchanged, bit for bit.
  EXPECT_EQ(displace(DisplaceSettings{}, p, n).position, p);
  EXPECT_EQ(displace(sine(0.0, 5.0), p, n).position, p);
  EXPECT_EQ(displace(sine(0.0, 5.0), p, n).normal, n);
  // The origin: no direction for the gradient; no displacement (sin 0) and the normal kept.
  const DisplacedPoint o = displace(sine(0.5, 3.0), glm::dvec3(0.0), n);
  EXPECT_EQ(o.position, glm::dvec3(0.0));
  EXPECT_EQ(o.normal, n);
  // Where cos(f r) = 0 the height is extreme and the normal unperturbed.
  const double f = 2.0, r = M_PI / (2.0 * f);
  const DisplacedPoint top = displace(sine(0.1, f), glm::dvec3(r, 0.0, 0.0), n);
  EXPECT_NEAR(top.position.z, 0.1, 1e-15);
  EXPECT_LT(glm::length(top.normal - n), 1e-15);
  // A huge slope still gives a unit normal (N minus a vector orthogonal to it).
  const DisplacedPoint steep = displace(sine(1e3, 1e3), p, n);
  EXPECT_TRUE(is_finite(steep.normal));
  EXPECT_NEAR(glm::length(steep.normal), 1.0, 1e-12);
}

// On the plane z = 0 with N = +z the displaced surface is the height field z = h(x, y), whose
// normal is normalize(-dh/dx, -dh/dy, 1): Blinn's perturbation is exact there (g.N = 0).
TEST(Displace, NormalIsTheHeightFieldsOnAPlane) {
  const DisplaceSettings d = sine(0.05, 7.0);
  const glm::dvec3 n(0.0, 0.0, 1.0);
  for (double x = -1.0; x <= 1.0; x += 0.173)
    for (double y = -1.0; y <= 1.0; y += 0.211) {
      const double e = 1e-6;
      auto h = [&](double px, double py) { return displace(d, glm::dvec3(px, py, 0.0), n).position.z; };
      const glm::dvec3 numeric = glm::normalize(
          glm::dvec3(-(h(x + e, y) - h(x - e, y)) / (2 * e), -(h(x, y + e) - h(x, y - e)) / (2 * e), 1.0));
      EXPECT_LT(glm::length(displace(d, glm::dvec3(x, y, 0.0), n).normal - numeric), 1e-8) << x << " " << y;
    }
}

// Gradient noise: zero at lattice points, its gradient the analytic one (finite differences),
// value and gradient continuous across cell faces, bounded, and the same everywhere in a run and
// across runs (a fixed permutation).
TEST(Displace, GradientNoise) {
  for (int i = -3; i <= 3; ++i) EXPECT_EQ(gradient_noise(glm::dvec3(i, 2 * i, -i)).value, 0.0);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  double largest = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 x(u(rng), u(rng), u(rng));
    const NoiseSample n = gradient_noise(x);
    largest = std::max(largest, std::abs(n.value));
    const double e = 1e-6;
    const glm::dvec3 numeric((gradient_noise(x + glm::dvec3(e, 0, 0)).value - gradient_noise(x - glm::dvec3(e, 0, 0)).value) / (2 * e),
                             (gradient_noise(x + glm::dvec3(0, e, 0)).value - gradient_noise(x - glm::dvec3(0, e, 0)).value) / (2 * e),
                             (gradient_noise(x + glm::dvec3(0, 0, e)).value - gradient_noise(x - glm::dvec3(0, 0, e)).value) / (2 * e));
    EXPECT_LT(glm::length(n.gradient - numeric), 1e-7) << x.x << " " << x.y << " " << x.z;
  }
  EXPECT_LT(largest, 1.1);
  EXPECT_GT(largest, 0.5);
  // Across a cell face (x = 3): the value and the gradient from both sides agree.
  for (double y = 0.05; y < 1.0; y += 0.1) {
    const NoiseSample a = gradient_noise(glm::dvec3(3.0 - 1e-12, y, 0.37)), b = gradient_noise(glm::dvec3(3.0, y, 0.37));
    EXPECT_NEAR(a.value, b.value, 1e-10);
    EXPECT_LT(glm::length(a.gradient - b.gradient), 1e-9);
  }
  EXPECT_EQ(gradient_noise(glm::dvec3(0.3, 0.4, 0.5)).value, gradient_noise(glm::dvec3(0.3, 0.4, 0.5)).value);
  // Far away or beyond the range: no NaN, no overflow in the lattice index.
  EXPECT_TRUE(std::isfinite(gradient_noise(glm::dvec3(1e300, -1e300, 3e18)).value));
  EXPECT_EQ(gradient_noise(glm::dvec3(INFINITY, 0, 0)).value, 0.0);
  // The displacement: h = a noise(f P), normal from a f grad noise(f P), as sine's.
  const DisplaceSettings d{DisplaceKind::Noise, 0.05, 3.0};
  const glm::dvec3 nz(0.0, 0.0, 1.0);
  for (double x = -1.0; x <= 1.0; x += 0.37)
    for (double y = -1.0; y <= 1.0; y += 0.41) {
      const DisplacedPoint q = displace(d, glm::dvec3(x, y, 0.0), nz);
      EXPECT_EQ(q.position.z, 0.05 * gradient_noise(glm::dvec3(3 * x, 3 * y, 0.0)).value);
      const double e = 1e-6;
      auto h = [&](double px, double py) { return displace(d, glm::dvec3(px, py, 0.0), nz).position.z; };
      const glm::dvec3 numeric = glm::normalize(
          glm::dvec3(-(h(x + e, y) - h(x - e, y)) / (2 * e), -(h(x, y + e) - h(x, y - e)) / (2 * e), 1.0));
      EXPECT_LT(glm::length(q.normal - numeric), 1e-7);
    }
}

TEST(Displace, BadSettingsAreInputErrors) {
  EXPECT_THROW(validate(sine(std::nan(""), 1.0), "x"), InputError);
  EXPECT_THROW(validate(sine(1.0, INFINITY), "x"), InputError);
  EXPECT_THROW(validate(sine(1.0, -1.0), "x"), InputError);
  EXPECT_THROW(validate(sine(1e300, 1e300), "x"), InputError);
  EXPECT_NO_THROW(validate(sine(-0.1, 0.0), "x"));  // a negative amplitude pushes inwards
  EXPECT_THROW(validate(DisplaceSettings{DisplaceKind::Noise, 1.0, -1.0}, "x"), InputError);
  // A phase beyond the double range displaces nothing rather than giving NaN.
  const DisplacedPoint far = displace(sine(1.0, 1e300), glm::dvec3(1e10, 0, 0), glm::dvec3(0, 0, 1));
  EXPECT_EQ(far.position, glm::dvec3(1e10, 0, 0));
}

// Every point of every pattern (the uniform one evaluated on every core, a D3D11 one patch by patch)
// is displaced from the point the plain tessellation evaluates.
TEST(Displace, TessellateDisplacesEveryEvaluatedPoint) {
  const Mesh mesh = load_mesh(kWuson);
  for (const bool d3d11 : {false, true}) {
    TessSettings plain;
    plain.L = 8;  // enough work for the uniform pattern's evaluation on every core
    if (d3d11) {
      plain.kind = PatternKind::D3D11;
      plain.partitioning = Partitioning::fractional_odd;
      plain.outer = {2.5f, 3.0f, 4.2f};
      plain.inner = 3.3f;
    }
    TessSettings displaced = plain;
    displaced.displace = sine(0.03, 25.0);
    std::vector<glm::dvec3> p0, n0, p1, n1;
    tessellate_mesh(mesh, plain, NormalMode::Quadratic, [&](const PatchView& v) {
      p0.insert(p0.end(), v.positions.begin(), v.positions.end());
      n0.insert(n0.end(), v.normals.begin(), v.normals.end());
    });
    const TessellationSummary s = tessellate_mesh(mesh, displaced, NormalMode::Quadratic, [&](const PatchView& v) {
      p1.insert(p1.end(), v.positions.begin(), v.positions.end());
      n1.insert(n1.end(), v.normals.begin(), v.normals.end());
    });
    ASSERT_EQ(p0.size(), p1.size());
    std::size_t moved = 0;
    for (std::size_t i = 0; i < p0.size(); ++i) {
      const DisplacedPoint want = displace(displaced.displace, p0[i], n0[i]);
      ASSERT_EQ(p1[i], want.position);
      ASSERT_EQ(n1[i], want.normal);
      moved += p1[i] != p0[i];
    }
    EXPECT_GT(moved, p0.size() / 2);
    EXPECT_EQ(s.vertices, p0.size());
  }
}

}  // namespace
}  // namespace tessim
