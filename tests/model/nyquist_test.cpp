// The Nyquist rule of adaptive factors (model/factors.hpp nyquist_edge_factor, docs/patterns.md
// §9): the factor depends on the edge, not on the order of its ends; ceil(F) equal segments of the
// chord sample the sine's phase f‖P‖ at least S times per 2π (measured by dense sampling, not by
// the formula), and no fewer segments would do on a radial edge; the noise kind is S·f·ℓ
// anywhere; the clamps; the two patches of every edge of a real mesh get the same factor, and its
// displaced tessellation is watertight; screen+nyquist is the larger of both per edge; validate()
// refuses the rule without a displacement and an S below 1 or not finite.
#include <gtest/gtest.h>

#include "tests/support/distinct_points.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "model/base/error.hpp"
#include "model/d3d11_pattern.hpp"
#include "model/displace.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"

namespace tessim {
namespace {

const Mesh& wuson() {
  static const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  return mesh;
}

DisplaceSettings sine(double a, double f) { return {DisplaceKind::Sine, a, f}; }
DisplaceSettings noise(double a, double f) { return {DisplaceKind::Noise, a, f}; }

std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x); }

glm::dvec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  for (;;) {
    const glm::dvec3 v(n(rng), n(rng), n(rng));
    const double l = glm::length(v);
    if (l > 1e-3) return v / l;
  }
}

// The largest change of the phase f‖P‖ along one of `segments` equal parts of the chord a-b,
// measured on `samples` + 1 points of each part (both ends included).
double largest_phase_step(double f, const glm::dvec3& a, const glm::dvec3& b, int segments, int samples) {
  double largest = 0.0;
  for (int k = 0; k < segments; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i <= samples; ++i) {
      const double t = (k + static_cast<double>(i) / samples) / segments;
      const double phase = f * glm::length(a + t * (b - a));
      lo = std::min(lo, phase);
      hi = std::max(hi, phase);
    }
    largest = std::max(largest, hi - lo);
  }
  return largest;
}

TEST(NyquistFactor, DependsOnTheEdgeNotOnTheOrderOfItsEnds) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> x(-3.0, 3.0), freq(0.1, 80.0), spw(1.0, 16.0);
  std::uniform_int_distribution<int> pick(0, 5);
  std::set<std::uint32_t> seen;
  for (const DisplaceKind kind : {DisplaceKind::Sine, DisplaceKind::Noise}) {
    for (int i = 0; i < 20000; ++i) {
      const DisplaceSettings d{kind, 0.05, freq(rng)};
      const double S = spw(rng);
      glm::dvec3 a(x(rng), x(rng), x(rng)), b(x(rng), x(rng), x(rng));
      switch (pick(rng)) {
        case 0: a = glm::dvec3(0.0); break;                       // one end at the origin
        case 1: b = glm::dvec3(0.0); break;
        case 2: b = glm::dvec3(a.x, a.y, -a.z); break;              // ends that differ in z only
        case 3: b = glm::dvec3(-a.x, a.y, b.z); break;              // mixed signs, a tie-break on y
        case 4: b = -a; break;                                      // through the origin
        default: break;
      }
      const float ab = nyquist_edge_factor(d, S, a, b), ba = nyquist_edge_factor(d, S, b, a);
      ASSERT_EQ(bits(ab), bits(ba)) << to_string(kind) << " " << i;
      ASSERT_GE(ab, 1.0f);
      ASSERT_LE(ab, 64.0f);
      seen.insert(bits(ab));
    }
  }
  EXPECT_GT(seen.size(), 5000u);  // not one clamped value everywhere
}

// Sine: along ceil(F) equal segments of the chord, the phase f‖P‖ changes by at most 2π/S in
// every segment: each wavelength along the edge gets at least S points. Edges of every kind:
// random, tangent to the sphere ‖P‖ = r at one end (the rate is 0 there), through or near the
// origin, with an end at the origin.
TEST(NyquistFactor, SineSegmentsSampleEveryWavelengthSTimes) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> x(-2.0, 2.0), len(0.01, 1.0), freq(1.0, 150.0), spw(1.0, 12.0);
  std::uniform_int_distribution<int> pick(0, 4);
  int checked = 0, fine = 0;
  for (int i = 0; i < 3000; ++i) {
    const double f = freq(rng), S = spw(rng);
    const glm::dvec3 a(x(rng), x(rng), x(rng));
    glm::dvec3 b;
    const glm::dvec3 e = random_unit(rng);
    const double l = len(rng);
    switch (pick(rng)) {
      case 0: b = a + l * e; break;
      case 1: {  // tangent at a: the chord at right angles to a
        const glm::dvec3 t = glm::normalize(glm::cross(a, e));
        b = a + l * t;
        break;
      }
      case 2: b = -a * (l / glm::length(a)); break;  // through the origin
      case 3: b = l * e; break;  // near the origin
      default: b = a + l * e + glm::dvec3(1e-3); break;
    }
    glm::dvec3 p = a, q = b;
    if (pick(rng) == 3) p = glm::dvec3(0.0);  // one fifth of the edges from the origin
    const float F = nyquist_edge_factor(sine(0.02, f), S, p, q);
    if (F >= 64.0f) continue;  // clamped: the bound is not promised
    ++checked;
    fine += F > 2.0f;
    const int segments = static_cast<int>(std::ceil(F));
    const double step = largest_phase_step(f, p, q, segments, 400);
    ASSERT_LE(step, 2.0 * M_PI / S * (1.0 + 1e-6) + 1e-12)
        << "F " << F << " S " << S << " f " << f << " a (" << p.x << ", " << p.y << ", " << p.z << ") b (" << q.x
        << ", " << q.y << ", " << q.z << ")";
  }
  EXPECT_GT(checked, 1500);
  EXPECT_GT(fine, 1000);  // most edges need several segments: a real test of the bound
}

// On a radial edge ‖P‖ changes at rate 1 along the whole chord: the rule is tight there. F is
// S·f·ℓ/2π (to the float it returns), and ceil(F) − 1 equal segments leave some segment with a
// phase change above 2π/S.
TEST(NyquistFactor, IsTightOnRadialEdges) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> r(0.0, 2.0), freq(1.0, 100.0), spw(1.0, 12.0);
  int tight = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 u = random_unit(rng);
    double r0 = r(rng), r1 = r(rng);
    if (i % 7 == 0) r0 = 0.0;  // from the origin
    const double f = freq(rng), S = spw(rng);
    const glm::dvec3 a = r0 * u, b = r1 * u;
    const float F = nyquist_edge_factor(sine(0.02, f), S, a, b);
    const double exact = S * f * std::abs(r1 - r0) / (2.0 * M_PI);
    if (exact >= 64.0 || exact <= 1.0) {
      EXPECT_EQ(F, exact >= 64.0 ? 64.0f : 1.0f);
      continue;
    }
    // A float: within one unit in the last place of the exact value's nearest float.
    const float want = static_cast<float>(exact);
    ASSERT_TRUE(F == want || F == std::nextafter(want, 0.0f) || F == std::nextafter(want, 100.0f))
        << F << " vs " << exact << " (r0 " << r0 << ", r1 " << r1 << ")";
    EXPECT_NEAR(F, exact, 2e-7 * exact);
    const int segments = static_cast<int>(std::ceil(F));
    EXPECT_LE(largest_phase_step(f, a, b, segments, 64), 2.0 * M_PI / S * (1.0 + 1e-6));
    if (segments >= 2 && static_cast<double>(F) > segments - 1 + 1e-5) {
      ++tight;
      EXPECT_GT(largest_phase_step(f, a, b, segments - 1, 64), 2.0 * M_PI / S)
          << "ceil(F) - 1 segments suffice: F " << F << " S " << S << " f " << f;
    }
  }
  EXPECT_GT(tight, 1000);
}

// Noise: S·f·ℓ in every direction and at every place. Dyadic coordinates and integer shifts keep
// the translated chord exactly the same vector.
TEST(NyquistFactor, NoiseIsSFLAnywhere) {
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<int> k(-2048, 2048), shift(-50, 50);
  std::uniform_real_distribution<double> freq(0.1, 40.0), spw(1.0, 10.0);
  int unclamped = 0;
  for (int i = 0; i < 5000; ++i) {
    const glm::dvec3 a(k(rng) / 1024.0, k(rng) / 1024.0, k(rng) / 1024.0);
    const glm::dvec3 b = a + glm::dvec3(k(rng), k(rng), k(rng)) / 8192.0;
    const double f = freq(rng), S = spw(rng);
    const float F = nyquist_edge_factor(noise(0.1, f), S, a, b);
    const double exact = std::clamp(S * (f * glm::length(b - a)), 1.0, 64.0);
    ASSERT_EQ(F, static_cast<float>(exact)) << i;
    unclamped += exact > 1.0 && exact < 64.0;
    const glm::dvec3 t(shift(rng), shift(rng), shift(rng));
    ASSERT_EQ(bits(nyquist_edge_factor(noise(0.1, f), S, a + t, b + t)), bits(F)) << i;
    // The sine's factor does depend on where the edge is (its rate is radial).
  }
  EXPECT_GT(unclamped, 2500);
  const glm::dvec3 a(0.5, 0.0, 0.0), b(1.0, 0.0, 0.0), t(0.0, 3.0, 0.0);
  EXPECT_NE(nyquist_edge_factor(sine(0.1, 30.0), 4.0, a, b), nyquist_edge_factor(sine(0.1, 30.0), 4.0, a + t, b + t));
}

TEST(NyquistFactor, Clamps) {
  const glm::dvec3 a(0.3, -0.2, 0.7), b(-0.4, 0.5, 0.1);
  for (const DisplaceKind kind : {DisplaceKind::Sine, DisplaceKind::Noise}) {
    const DisplaceSettings d{kind, 0.01, 1e6};
    EXPECT_EQ(nyquist_edge_factor(d, 4.0, a, b), 64.0f);
    EXPECT_EQ(nyquist_edge_factor({kind, 1e-300, 1e308}, 64.0, a, b), 64.0f);  // near the double range
    EXPECT_EQ(nyquist_edge_factor({kind, 0.01, 0.0}, 4.0, a, b), 1.0f);        // f = 0
    EXPECT_EQ(nyquist_edge_factor(d, 4.0, a, a), 1.0f);                         // zero length
    EXPECT_EQ(nyquist_edge_factor(d, 4.0, glm::dvec3(0.0), glm::dvec3(0.0)), 1.0f);
    EXPECT_EQ(nyquist_edge_factor({kind, 0.01, 1e-3}, 4.0, a, b), 1.0f);        // fewer than one segment
  }
  // Displacement off: one segment, whatever the frequency.
  EXPECT_EQ(nyquist_edge_factor({DisplaceKind::None, 0.5, 1e6}, 16.0, a, b), 1.0f);
}

// ---- a real mesh ----

TessSettings nyquist(Partitioning p, const DisplaceSettings& d) {
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.partitioning = p;
  s.rule = AdaptiveRule::Nyquist;
  s.displace = d;
  return s;
}

TessSettings screen_and_nyquist(Partitioning p, const DisplaceSettings& d) {
  TessSettings s = nyquist(p, d);
  s.rule = AdaptiveRule::Screen;
  s.with_nyquist = true;
  s.camera.eye = {0.0, 0.0, 3.0};
  return s;
}

// Every edge shared by two patches gets one factor from both, bit for bit. Returns how many
// distinct factors the mesh's edges have.
std::size_t expect_shared_edges_agree(const TessSettings& settings) {
  const Mesh& mesh = wuson();
  std::map<std::pair<unsigned, unsigned>, float> factor;
  std::size_t shared = 0;
  std::set<std::uint32_t> distinct;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const PatchFactors f = patch_factors(settings, mesh, t);
    const glm::uvec3& tri = mesh.triangles[t];
    EXPECT_EQ(f.inner, std::max({f.outer[0], f.outer[1], f.outer[2]}));
    const std::array<std::pair<unsigned, unsigned>, 3> edges{std::minmax(tri[0], tri[2]), std::minmax(tri[0], tri[1]),
                                                             std::minmax(tri[1], tri[2])};
    for (std::size_t i = 0; i < 3; ++i) {
      distinct.insert(bits(f.outer[i]));
      auto [it, fresh] = factor.emplace(edges[i], f.outer[i]);
      if (!fresh) {
        ++shared;
        EXPECT_EQ(bits(it->second), bits(f.outer[i])) << "edge " << edges[i].first << "-" << edges[i].second
                                                      << " of triangle " << t << ": " << it->second << " vs "
                                                      << f.outer[i];
      }
    }
  }
  EXPECT_GT(shared, mesh.triangle_count());  // a closed-ish mesh: most edges have two patches
  return distinct.size();
}

TEST(NyquistMesh, BothPatchesOfAnEdgeGetTheSameFactor) {
  const DisplaceSettings d = sine(0.02, 60.0);
  EXPECT_GT(expect_shared_edges_agree(nyquist(Partitioning::integer, d)), 100u);
  EXPECT_GT(expect_shared_edges_agree(screen_and_nyquist(Partitioning::integer, d)), 100u);
  EXPECT_GT(expect_shared_edges_agree(nyquist(Partitioning::integer, noise(0.02, 20.0))), 100u);
}

// The watertight count of factors_test (AdaptiveMesh.IsCrackFree): the mesh vertices, each
// edge's inner points once (both patches place the same ones, checked in 16.16), each patch's
// interior points; the displaced output welded within 1e-12 of the diagonal has exactly that many.
void expect_watertight(const TessSettings& settings) {
  const Mesh& mesh = wuson();
  std::vector<glm::dvec3> points;
  const TessellationSummary s = tessellate_mesh(mesh, settings, NormalMode::Quadratic, [&](const PatchView& p) {
    points.insert(points.end(), p.positions.begin(), p.positions.end());
  });
  ASSERT_EQ(s.culled, 0u);
  std::map<std::pair<unsigned, unsigned>, std::set<Fixed16>> edge_points;  // by the weight of the lower vertex
  std::uint64_t interior = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const PatchFactors f = patch_factors(settings, mesh, t);
    const D3D11Pattern pattern = d3d11_tri_pattern(f.outer, f.inner, settings.partitioning);
    const glm::uvec3& tri = mesh.triangles[t];
    std::set<std::pair<Fixed16, Fixed16>> inside;
    std::array<std::map<std::pair<unsigned, unsigned>, std::set<Fixed16>>, 3> mine;
    mine[0][std::minmax(tri[0], tri[2])];
    mine[1][std::minmax(tri[0], tri[1])];
    mine[2][std::minmax(tri[1], tri[2])];
    for (const FixedUV& q : pattern.points) {
      const Fixed16 w = kFixed16One - q.u - q.v;
      if ((q.u == 0) + (q.v == 0) + (w == 0) >= 2) continue;  // a corner: a mesh vertex
      auto on_edge = [&](int e, unsigned a, Fixed16 wa, unsigned b, Fixed16 wb) {
        mine[static_cast<std::size_t>(e)][std::minmax(a, b)].insert(a < b ? wa : wb);
      };
      if (q.u == 0) on_edge(0, tri[0], w, tri[2], q.v);
      else if (q.v == 0) on_edge(1, tri[0], w, tri[1], q.u);
      else if (w == 0) on_edge(2, tri[1], q.u, tri[2], q.v);
      else inside.emplace(q.u, q.v);
    }
    interior += inside.size();
    for (const auto& edge : mine)
      for (const auto& [key, weights] : edge) {
        auto [it, fresh] = edge_points.emplace(key, weights);
        if (!fresh) {
          ASSERT_EQ(it->second, weights) << "edge " << key.first << "-" << key.second;
        }
      }
  }
  std::uint64_t expected = mesh.vertex_count() + interior;
  for (const auto& [edge, weights] : edge_points) expected += weights.size();
  EXPECT_EQ(testing::distinct_points(points, 1e-12 * bounding_box(mesh).diagonal()), expected);
}

class NyquistWatertight : public ::testing::TestWithParam<Partitioning> {};

TEST_P(NyquistWatertight, DisplacedTessellationIsCrackFree) {
  expect_watertight(nyquist(GetParam(), sine(0.02, 60.0)));
  expect_watertight(screen_and_nyquist(GetParam(), sine(0.02, 60.0)));
}

INSTANTIATE_TEST_SUITE_P(Partitionings, NyquistWatertight,
                         ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                           Partitioning::fractional_even),
                         [](const auto& info) { return std::string(partitioning_name(info.param)); });

// screen+nyquist (and silhouette+nyquist) is the per-edge maximum of the two rules alone, and
// both rules win somewhere on this mesh and camera.
TEST(NyquistMesh, CombinedRuleIsThePerEdgeMaximum) {
  const Mesh& mesh = wuson();
  const DisplaceSettings d = sine(0.02, 60.0);
  for (const AdaptiveRule rule : {AdaptiveRule::Screen, AdaptiveRule::Silhouette}) {
    TessSettings both = screen_and_nyquist(Partitioning::fractional_odd, d);
    both.rule = rule;
    both.outline_tolerance = 0.1;
    TessSettings alone = both;
    alone.with_nyquist = false;
    const TessSettings by_nyquist = nyquist(Partitioning::fractional_odd, d);
    bind_silhouette(both, mesh);
    bind_silhouette(alone, mesh);
    int camera_wins = 0, nyquist_wins = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const PatchFactors fb = patch_factors(both, mesh, t), fa = patch_factors(alone, mesh, t),
                         fn = patch_factors(by_nyquist, mesh, t);
      for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_EQ(bits(fb.outer[i]), bits(std::max(fa.outer[i], fn.outer[i]))) << "triangle " << t << " edge " << i;
        camera_wins += fa.outer[i] > fn.outer[i];
        nyquist_wins += fn.outer[i] > fa.outer[i];
      }
      ASSERT_EQ(fb.inner, std::max({fb.outer[0], fb.outer[1], fb.outer[2]}));
    }
    EXPECT_GT(camera_wins, 100) << static_cast<int>(rule);
    EXPECT_GT(nyquist_wins, 100) << static_cast<int>(rule);
  }
}

// The edges whose rule asks for more than 64 segments (they still alias; the CLI warns): for the
// noise kind F = S·f·ℓ, so they are the edges longer than 64 / (S·f), each counted once.
TEST(NyquistMesh, ShortfallCountsEachEdgeClampedAt64Once) {
  const Mesh& mesh = wuson();
  const double S = 4.0, f = 250.0;
  std::set<std::pair<unsigned, unsigned>> edges;
  for (const glm::uvec3& tri : mesh.triangles)
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(tri[i], tri[(i + 1) % 3]));
  std::size_t longer = 0;
  double longest = 0.0;
  for (const auto& [a, b] : edges) {
    const double length = glm::length(mesh.positions[b] - mesh.positions[a]);
    if (S * f * length > 64.0) ++longer;
    longest = std::max(longest, length);
  }
  TessSettings s = nyquist(Partitioning::integer, noise(0.01, f));
  s.samples_per_wavelength = S;
  const NyquistShortfall shortfall = nyquist_shortfall(s, mesh);
  EXPECT_EQ(shortfall.edges, longer);
  EXPECT_GT(shortfall.edges, 0u);
  EXPECT_LT(shortfall.edges, edges.size());
  EXPECT_NEAR(shortfall.most_segments, S * f * longest, 1e-9 * S * f * longest);
  // The combined rule counts the Nyquist part; without a Nyquist rule nothing is counted.
  EXPECT_EQ(nyquist_shortfall(screen_and_nyquist(Partitioning::integer, noise(0.01, f)), mesh).edges, longer);
  TessSettings screen = screen_and_nyquist(Partitioning::integer, noise(0.01, f));
  screen.with_nyquist = false;
  EXPECT_EQ(nyquist_shortfall(screen, mesh).edges, 0u);
  // A low frequency asks for fewer than 64 segments everywhere.
  EXPECT_EQ(nyquist_shortfall(nyquist(Partitioning::integer, noise(0.01, 1.0)), mesh).edges, 0u);
}

TEST(NyquistValidate, RefusesBadSettings) {
  TessSettings s = nyquist(Partitioning::integer, sine(0.02, 60.0));
  EXPECT_NO_THROW(validate(s, "x"));
  EXPECT_NO_THROW(validate(screen_and_nyquist(Partitioning::integer, sine(0.02, 60.0)), "x"));
  TessSettings off = s;
  off.displace = {};
  EXPECT_THROW(validate(off, "x"), InputError);
  TessSettings combined_off = screen_and_nyquist(Partitioning::integer, {});
  EXPECT_THROW(validate(combined_off, "x"), InputError);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const double S : {0.5, 0.0, -4.0, std::nan(""), inf, -inf}) {
    s.samples_per_wavelength = S;
    EXPECT_THROW(validate(s, "x"), InputError) << S;
    TessSettings c = screen_and_nyquist(Partitioning::integer, sine(0.02, 60.0));
    c.samples_per_wavelength = S;
    EXPECT_THROW(validate(c, "x"), InputError) << S;
  }
  s.samples_per_wavelength = 1.0;  // the least S
  EXPECT_NO_THROW(validate(s, "x"));
  // Without the Nyquist rule, S and the displacement's presence are not the rule's business.
  TessSettings screen = screen_and_nyquist(Partitioning::integer, {});
  screen.with_nyquist = false;
  screen.samples_per_wavelength = 0.5;
  EXPECT_NO_THROW(validate(screen, "x"));
}

}  // namespace
}  // namespace tessim
