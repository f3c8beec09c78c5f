// Silhouette enhancement in the float reference (model/silhouette.hpp, docs/mathematics.md §11):
// the silhouetteness α of an edge by its definition, the blend's two ends (α = 1 is plain PN bit
// for bit, α = 0 the flat triangle), a whole-mesh tessellation against an implementation of the
// definitions written here from scratch, crack-free output with the silhouette rule, and feature
// ends on meshes with hard edges.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "model/base/error.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/pn.hpp"
#include "model/silhouette.hpp"
#include "model/stpn_import.hpp"
#include "model/tessellate.hpp"
#include "model/weld.hpp"

namespace tessim {
namespace {

const std::filesystem::path kModels = "/usr/share/assimp/models";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kModels / "PLY/Wuson.ply");
  return mesh;
}

bool same_bits(const glm::dvec3& a, const glm::dvec3& b) {
  for (int i = 0; i < 3; ++i)
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  return true;
}

TEST(Silhouetteness, FollowsTheDefinition) {
  const double beta = 0.25;
  const glm::dvec3 a(-1, 0, 0), b(1, 0, 0);  // midpoint at the origin
  const glm::dvec3 eye(0, 0, 5);             // d = (0, 0, -1)
  const glm::dvec3 up(0, 0, 1), down(0, 0, -1);
  // Both faces towards the eye: f = 1 > β, flat.
  EXPECT_EQ(silhouetteness(eye, beta, a, b, up, up), 0.0);
  // One towards, one away: f = -1 <= 0, an outline edge.
  EXPECT_EQ(silhouetteness(eye, beta, a, b, up, down), 1.0);
  // f = cos²: a face normal at angle t from the view gives f = cos(t)² for two such faces.
  for (double f : {0.01, 0.1, 0.2, 0.25, 0.3}) {
    const double c = std::sqrt(f);
    const glm::dvec3 n(std::sqrt(1 - f), 0.0, c);
    const double expected = f <= beta ? 1.0 - f / beta : 0.0;
    EXPECT_NEAR(silhouetteness(eye, beta, a, b, n, n), expected, 1e-12) << f;
  }
  // A face seen exactly edge-on: f = 0, α = 1.
  EXPECT_EQ(silhouetteness(eye, beta, a, b, glm::dvec3(0, 1, 0), up), 1.0);
  // The eye on the midpoint: no direction of view, α = 1 and never a NaN.
  EXPECT_EQ(silhouetteness(glm::dvec3(0.0), beta, a, b, up, up), 1.0);
  // A degenerate face (zero normal): α = 1.
  EXPECT_EQ(silhouetteness(eye, beta, a, b, glm::dvec3(0.0), up), 1.0);
}

TEST(Silhouetteness, IsSymmetricInTheEdgeEndsAndFaces) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-2.0, 2.0);
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 a(x(rng), x(rng), x(rng)), b(x(rng), x(rng), x(rng)), eye(x(rng), x(rng), x(rng));
    const glm::dvec3 ns = glm::normalize(glm::dvec3(x(rng), x(rng), x(rng)));
    const glm::dvec3 nt = glm::normalize(glm::dvec3(x(rng), x(rng), x(rng)));
    const double r = silhouetteness(eye, 0.25, a, b, ns, nt);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(r), std::bit_cast<std::uint64_t>(silhouetteness(eye, 0.25, b, a, ns, nt)));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(r), std::bit_cast<std::uint64_t>(silhouetteness(eye, 0.25, a, b, nt, ns)));
    ASSERT_GE(r, 0.0);
    ASSERT_LE(r, 1.0);
  }
}

PnInput random_input(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(-1.0, 1.0);
  PnInput in;
  for (int c = 0; c < 3; ++c) {
    in.p[c] = glm::dvec3(x(rng), x(rng), x(rng));
    in.n[c] = glm::normalize(glm::dvec3(x(rng), x(rng), x(rng)));
  }
  return in;
}

TEST(SilhouettePatch, AlphaOneIsPlainPnBitForBit) {
  std::mt19937_64 rng(3);
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear, NormalMode::Derivative}) {
    for (int i = 0; i < 2000; ++i) {
      const PnInput in = random_input(rng);
      PatchSilhouette s;
      s.normals = in.n;
      const PnPatch blended = make_silhouette_patch(in, s, mode);
      const PnPatch plain = make_patch(in, mode);
      for (std::size_t k = 0; k < 10; ++k) ASSERT_TRUE(same_bits(blended.b[k], plain.b[k])) << i << " b" << k;
      for (std::size_t k = 0; k < 6; ++k) ASSERT_TRUE(same_bits(blended.n_bern[k], plain.n_bern[k])) << i;
    }
  }
}

TEST(SilhouettePatch, AlphaZeroIsTheFlatTriangle) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 2000; ++i) {
    const PnInput in = random_input(rng);
    PatchSilhouette s;
    s.normals = in.n;
    s.alpha = {0.0, 0.0, 0.0};
    const PnPatch patch = make_silhouette_patch(in, s, NormalMode::Quadratic);
    for (double u = 0.0; u <= 1.0; u += 0.125) {
      for (double v = 0.0; u + v <= 1.0; v += 0.125) {
        const glm::dvec3 flat = (1.0 - u - v) * in.p[0] + u * in.p[1] + v * in.p[2];
        ASSERT_LT(glm::length(eval_de_casteljau(patch, u, v).position - flat), 1e-14) << i;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// An implementation of the definitions written apart from model/: adjacency by a map of vertex
// pairs, α, the six blended edge points, b111 = (1/4) Σ six − (1/6) Σ corners, and the cubic
// Bernstein sum at each point of the uniform pattern.

struct Independent {
  const Mesh& mesh;
  glm::dvec3 eye;
  double beta;
  std::map<std::pair<unsigned, unsigned>, std::vector<unsigned>> faces;

  Independent(const Mesh& m, glm::dvec3 e, double b) : mesh(m), eye(e), beta(b) {
    for (unsigned t = 0; t < m.triangles.size(); ++t)
      for (int e = 0; e < 3; ++e) {
        unsigned a = m.triangles[t][e], c = m.triangles[t][(e + 1) % 3];
        faces[{std::min(a, c), std::max(a, c)}].push_back(t);
      }
  }

  glm::dvec3 unit_normal(unsigned t) const {
    const glm::uvec3 v = mesh.triangles[t];
    const glm::dvec3 n = glm::cross(mesh.positions[v[1]] - mesh.positions[v[0]], mesh.positions[v[2]] - mesh.positions[v[0]]);
    return n / glm::length(n);
  }

  double alpha(unsigned i, unsigned j) const {
    const auto& f = faces.at({std::min(i, j), std::max(i, j)});
    if (f.size() != 2) return 1.0;
    const glm::dvec3 mid = (mesh.positions[i] + mesh.positions[j]) / 2.0;
    const glm::dvec3 d = glm::normalize(mid - eye);
    const double fv = glm::dot(d, unit_normal(f[0])) * glm::dot(d, unit_normal(f[1]));
    if (fv <= 0.0) return 1.0;
    if (fv <= beta) return 1.0 - fv / beta;
    return 0.0;
  }

  // b_ij nearest vertex i on edge (i, j).
  glm::dvec3 edge_point(unsigned i, unsigned j) const {
    const glm::dvec3 pi = mesh.positions[i], pj = mesh.positions[j], ni = mesh.normals[i];
    const glm::dvec3 l = (2.0 * pi + pj) / 3.0;
    const glm::dvec3 c = l - glm::dot(pj - pi, ni) / 3.0 * ni;
    const double a = alpha(i, j);
    return a * c + (1.0 - a) * l;
  }

  glm::dvec3 point(unsigned t, double u, double v) const {
    const glm::uvec3 x = mesh.triangles[t];
    const glm::dvec3 p1 = mesh.positions[x[0]], p2 = mesh.positions[x[1]], p3 = mesh.positions[x[2]];
    const glm::dvec3 b210 = edge_point(x[0], x[1]), b120 = edge_point(x[1], x[0]);
    const glm::dvec3 b021 = edge_point(x[1], x[2]), b012 = edge_point(x[2], x[1]);
    const glm::dvec3 b102 = edge_point(x[2], x[0]), b201 = edge_point(x[0], x[2]);
    const glm::dvec3 b111 = (b210 + b120 + b021 + b012 + b102 + b201) / 4.0 - (p1 + p2 + p3) / 6.0;
    const double w = 1.0 - u - v;
    return w * w * w * p1 + u * u * u * p2 + v * v * v * p3 + 3 * w * w * u * b210 + 3 * w * u * u * b120 +
           3 * u * u * v * b021 + 3 * u * v * v * b012 + 3 * w * v * v * b102 + 3 * w * w * v * b201 +
           6 * w * u * v * b111;
  }
};

void expect_matches_independent(const Mesh& mesh, const glm::dvec3& eye, double beta, int L) {
  TessSettings settings;
  settings.L = L;
  settings.silhouette.enabled = true;
  settings.silhouette.eye = eye;
  settings.silhouette.beta = beta;
  const Independent ref(mesh, eye, beta);
  const double tolerance = 1e-7 * bounding_box(mesh).diagonal();
  double worst = 0.0;
  std::size_t blended_patches = 0;
  tessellate_mesh(mesh, settings, NormalMode::Quadratic, [&](const PatchView& view) {
    const glm::uvec3 x = mesh.triangles[view.triangle];
    const double a = ref.alpha(x[0], x[1]) + ref.alpha(x[1], x[2]) + ref.alpha(x[2], x[0]);
    if (a > 0.0 && a < 3.0) ++blended_patches;
    for (std::size_t i = 0; i < view.positions.size(); ++i) {
      const glm::dvec3 expected = ref.point(view.triangle, view.domain[i].x, view.domain[i].y);
      worst = std::max(worst, glm::length(view.positions[i] - expected));
    }
  });
  EXPECT_LT(worst, tolerance) << "worst distance " << worst;
  EXPECT_LT(worst, 1e-13 * bounding_box(mesh).diagonal());  // the same formulas: rounding only
  EXPECT_GT(blended_patches, mesh.triangle_count() / 10);    // the eye makes α vary: a real test
}

TEST(SilhouetteMesh, MatchesAnIndependentImplementationOfTheDefinitions) {
  expect_matches_independent(wuson(), glm::dvec3(3.0, 1.0, -3.0), 0.25, 4);
  expect_matches_independent(wuson(), glm::dvec3(-0.5, 4.0, 1.0), 0.6, 3);
  const std::filesystem::path sphere = kModels / "STL/sphereWithHole.stl";
  if (!std::filesystem::exists(sphere)) FAIL() << sphere << " is missing: scripts/setup.sh installs assimp-testmodels";
  expect_matches_independent(load_mesh(sphere), glm::dvec3(0.0, 0.0, 60.0), 0.25, 5);
}

TEST(SilhouetteMesh, CountsEveryEdgeOnceAndBoundariesCurved) {
  const MeshSilhouette s(wuson(), glm::dvec3(3.0, 1.0, -3.0), 0.25);
  const SilhouetteCounts& c = s.counts();
  EXPECT_EQ(c.flat + c.blended + c.curved, c.edges);
  // Euler: E = (3T + B) / 2 for a mesh whose edges have one or two faces.
  EXPECT_EQ(c.non_manifold, 0u);
  EXPECT_EQ(2 * c.edges, 3 * wuson().triangle_count() + c.boundary);
  EXPECT_GE(c.curved, c.boundary);
  EXPECT_GT(c.flat, 0u);
  EXPECT_GT(c.blended, 0u);
  EXPECT_EQ(c.feature_ends, 0u);  // one normal per position: every end is smooth
  // Each triangle reads its edges' α: a boundary edge's is 1.
  for (std::size_t t = 0; t < wuson().triangle_count(); ++t)
    for (double a : s.alpha(t)) ASSERT_TRUE(a >= 0.0 && a <= 1.0);
}

TEST(SilhouetteMesh, BadSettingsAreRefusedBeforeAnything) {
  TessSettings s;
  s.silhouette.enabled = true;
  s.silhouette.eye = glm::dvec3(0.0, std::nan(""), 0.0);
  int calls = 0;
  EXPECT_THROW(tessellate_mesh(wuson(), s, NormalMode::Quadratic, [&](const PatchView&) { ++calls; }), InputError);
  s.silhouette.eye = glm::dvec3(1.0);
  for (const double beta : std::array<double, 4>{0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    s.silhouette.beta = beta;
    EXPECT_THROW(tessellate_mesh(wuson(), s, NormalMode::Quadratic, [&](const PatchView&) { ++calls; }), InputError);
  }
  // An eye so far away that the test's products overflow (every edge came out curved at 1e155).
  s.silhouette.beta = 1.0;
  s.silhouette.eye = glm::dvec3(1e155, 1e155, 1e155);
  EXPECT_THROW(tessellate_mesh(wuson(), s, NormalMode::Quadratic, [&](const PatchView&) { ++calls; }), InputError);
  EXPECT_EQ(calls, 0);
  // Far but representable: the same edges as a distant eye in that direction.
  s.silhouette.eye = glm::dvec3(1e100, 1e100, 1e100);
  const MeshSilhouette far(wuson(), s.silhouette.eye, 1.0);
  const MeshSilhouette distant(wuson(), glm::dvec3(1e12, 1e12, 1e12), 1.0);
  EXPECT_EQ(far.counts().curved, distant.counts().curved);
  EXPECT_EQ(far.counts().flat, distant.counts().flat);
}

// ---------------------------------------------------------------------------------------------
// The silhouette rule: crack-free in every partitioning. Both patches of an edge must put the
// same points on it, bit for bit: vertices named alike by their place on the input mesh
// (model/weld.hpp) must have the same position.

// Tessellates and checks that every vertex two patches name alike by its place on the input mesh
// (model/weld.hpp) has the same position bit for bit in both; `each` sees every patch. Returns how
// many vertices were met again (shared).
template <class Each>
std::uint64_t expect_closed(const Mesh& mesh, const TessSettings& s, Each each) {
  std::map<WeldKey, glm::dvec3> seen;
  std::vector<WeldKey> keys;
  std::uint64_t shared = 0;
  tessellate_mesh(mesh, s, NormalMode::Quadratic, [&](const PatchView& view) {
    patch_weld_keys(mesh, view, keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      auto [it, fresh] = seen.emplace(keys[i], view.positions[i]);
      if (!fresh) {
        ++shared;
        ASSERT_TRUE(same_bits(it->second, view.positions[i])) << "triangle " << view.triangle;
      }
    }
    each(view);
  });
  return shared;
}

class SilhouetteRule : public ::testing::TestWithParam<Partitioning> {};

TEST_P(SilhouetteRule, IsCrackFreeAndRefinesOnlyNearTheOutline) {
  const Mesh& mesh = wuson();
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.rule = AdaptiveRule::Silhouette;
  s.partitioning = GetParam();
  s.camera.eye = {2.6, 1.3, -2.9};
  s.camera.target = {0.0, 0.6, -0.2};
  s.outline_tolerance = 0.1;
  s.silhouette.enabled = true;  // the blend too: both patches must also agree on the blended curve
  s.silhouette.eye_from_camera = true;
  bind_silhouette(s, mesh);
  ASSERT_EQ(s.silhouette_field->eye(), s.camera.eye);

  std::uint64_t one_segment = 0, refined = 0;
  const std::uint64_t shared = expect_closed(mesh, s, [&](const PatchView& view) {
    const float inner = patch_factors(s, mesh, view.triangle).inner;
    if (inner == 1.0f) ++one_segment;
    if (inner > 4.0f) ++refined;
  });
  EXPECT_GT(shared, mesh.triangle_count());
  // Face-on patches get factor 1 on every edge, those near the outline more.
  EXPECT_GT(one_segment, mesh.triangle_count() / 10);
  EXPECT_GT(refined, mesh.triangle_count() / 10);
}

INSTANTIATE_TEST_SUITE_P(Partitionings, SilhouetteRule,
                         ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                           Partitioning::fractional_even),
                         [](const auto& info) { return std::string(partitioning_name(info.param)); });

// ---------------------------------------------------------------------------------------------
// The contour rule: the per-patch test and the factors it raises.

// g = (P - eye) . (P_u x P_v) at (u, v), from eval_bernstein and central differences: an
// independent evaluation of what contour_can_cross bounds.
double contour_function(const PnPatch& patch, const glm::dvec3& eye, double u, double v) {
  constexpr double h = 1e-6;
  auto at = [&](double a, double b) { return eval_bernstein(patch, a, b).position; };
  const glm::dvec3 pu = (at(u + h, v) - at(u - h, v)) / (2 * h);
  const glm::dvec3 pv = (at(u, v + h) - at(u, v - h)) / (2 * h);
  return glm::dot(at(u, v) - eye, glm::cross(pu, pv));
}

PnPatch sphere_octant() {
  PnInput in;
  in.p = {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)};
  in.n = in.p;  // a sphere's normals
  return make_patch(in, NormalMode::Quadratic);
}

TEST(ContourCanCross, FollowsTheContourOfASphereOctant) {
  const PnPatch octant = sphere_octant();
  // From far up the z axis the sphere's contour is the circle z = 1/10 (r^2 / d): it crosses the
  // octant, whose points run from z = 0 to 1.
  EXPECT_TRUE(contour_can_cross(octant, {0, 0, 10}));
  EXPECT_TRUE(contour_can_cross(octant, {10, 0, 0}));
  // Seen head-on or from behind the sphere, the octant faces one way all over.
  EXPECT_FALSE(contour_can_cross(octant, {5, 5, 5}));
  EXPECT_FALSE(contour_can_cross(octant, {-5, -5, -5}));
  // A flat triangle has no contour unless the eye is in its plane.
  PnInput flat;
  flat.p = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
  flat.n = {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)};
  const PnPatch plane = make_patch(flat, NormalMode::Quadratic);
  EXPECT_FALSE(contour_can_cross(plane, {0.3, 0.3, 2}));
  EXPECT_FALSE(contour_can_cross(plane, {0.3, 0.3, -2}));
  EXPECT_TRUE(contour_can_cross(plane, {3, 3, 0}));  // g = 0 everywhere: counted as crossed
}

// Conservative: wherever dense sampling finds both signs of g, the test says the contour can
// cross; where it says it cannot, every sample has one sign. Random curved patches and eyes.
TEST(ContourCanCross, IsConservativeAgainstDenseSampling) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> x(-1.0, 1.0);
  int crossed = 0, clear = 0, loose = 0;
  for (int trial = 0; trial < 400; ++trial) {
    PnInput in;
    for (int c = 0; c < 3; ++c) {
      in.p[c] = glm::dvec3(x(rng), x(rng), 0.3 * x(rng));
      in.n[c] = glm::normalize(glm::dvec3(0.6 * x(rng), 0.6 * x(rng), 1.0));
    }
    const PnPatch patch = make_patch(in, NormalMode::Quadratic);
    const glm::dvec3 eye(3 * x(rng), 3 * x(rng), 3 * x(rng));
    int positive = 0, negative = 0;
    constexpr int kSteps = 40;
    for (int j = 0; j <= kSteps; ++j)
      for (int k = 0; j + k <= kSteps; ++k) {
        const double g = contour_function(patch, eye, double(j) / kSteps, double(k) / kSteps);
        positive += g > 1e-9;
        negative += g < -1e-9;
      }
    const bool sampled_both = positive > 0 && negative > 0;
    const bool can_cross = contour_can_cross(patch, eye);
    if (sampled_both) {
      EXPECT_TRUE(can_cross) << "trial " << trial;
    }
    crossed += sampled_both;
    clear += !can_cross;
    loose += can_cross && !sampled_both;
  }
  EXPECT_GT(crossed, 40);  // the draw has both kinds
  EXPECT_GT(clear, 40);
  RecordProperty("crossed", crossed);
  RecordProperty("marked_without_a_sampled_crossing", loose);
}

class ContourRule : public ::testing::TestWithParam<Partitioning> {};

// Crack-free in every partitioning (both patches of an edge put the same points on it), one
// factor per edge whichever face asks, and never below the silhouette rule.
TEST_P(ContourRule, IsCrackFreeAndRefinesAtLeastAsMuchAsThePerEdgeRule) {
  const Mesh& mesh = wuson();
  TessSettings per_edge;
  per_edge.kind = PatternKind::D3D11;
  per_edge.source = FactorSource::Adaptive;
  per_edge.rule = AdaptiveRule::Silhouette;
  per_edge.partitioning = GetParam();
  per_edge.camera.eye = {2.6, 1.3, -2.9};
  per_edge.camera.target = {0.0, 0.6, -0.2};
  per_edge.outline_tolerance = 0.1;
  per_edge.silhouette.enabled = true;  // the blend too: the test runs on the blended patches
  per_edge.silhouette.eye_from_camera = true;
  TessSettings contour = per_edge;
  contour.rule = AdaptiveRule::Contour;
  bind_silhouette(per_edge, mesh);
  bind_silhouette(contour, mesh);
  const MeshSilhouette& field = *contour.silhouette_field;
  ASSERT_GT(field.contour_patches(), 0u);
  ASSERT_LT(field.contour_patches(), mesh.triangle_count());
  EXPECT_EQ(per_edge.silhouette_field->contour_patches(), 0u);  // only the contour rule marks

  std::uint64_t marked = 0, raised = 0;
  std::map<std::pair<std::uint32_t, std::uint32_t>, float> edge_factor;
  const std::uint64_t shared = expect_closed(mesh, contour, [&](const PatchView& view) {
    const std::size_t t = view.triangle;
    const PatchFactors c = patch_factors(contour, mesh, t), e = patch_factors(per_edge, mesh, t);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_GE(c.outer[i], e.outer[i]) << "triangle " << t;
    EXPECT_GE(c.inner, e.inner);
    raised += c.inner > e.inner;
    if (field.contour_patch(t)) {
      ++marked;
      // Every edge of a marked patch as a silhouette edge (alpha 1).
      const glm::uvec3& tri = mesh.triangles[t];
      const std::array<int, 3> edge_of_outer{2, 0, 1};  // outer[i]'s edge (01 = 0, 12 = 1, 20 = 2)
      for (std::size_t i = 0; i < 3; ++i) {
        const int e = edge_of_outer[i];
        const glm::dvec3& a = mesh.positions[tri[static_cast<std::size_t>(e)]];
        const glm::dvec3& b = mesh.positions[tri[static_cast<std::size_t>((e + 1) % 3)]];
        EXPECT_EQ(c.outer[i], silhouette_edge_factor(contour.camera, contour.outline_tolerance, 1.0,
                                                     field.deviation(t)[static_cast<std::size_t>(e)], a, b));
      }
    }
    // One factor per edge of welded positions, whichever face asks.
    const glm::uvec3& tri = mesh.triangles[t];
    const std::array<std::pair<int, int>, 3> ends{{{0, 2}, {0, 1}, {1, 2}}};  // outer[0..2]
    for (std::size_t i = 0; i < 3; ++i) {
      std::uint32_t a = tri[static_cast<std::size_t>(ends[i].first)], b = tri[static_cast<std::size_t>(ends[i].second)];
      if (a > b) std::swap(a, b);
      const auto [it, fresh] = edge_factor.emplace(std::make_pair(a, b), c.outer[i]);
      if (!fresh) {
        EXPECT_EQ(it->second, c.outer[i]) << "edge " << a << "-" << b;
      }
    }
  });
  EXPECT_GT(shared, mesh.triangle_count());
  EXPECT_EQ(marked, field.contour_patches());
  EXPECT_GT(raised, 0u) << "the contour rule refines some patch beyond the per-edge rule";
  RecordProperty("contour_patches", static_cast<int>(marked));
  RecordProperty("raised_inner_factors", static_cast<int>(raised));
}

INSTANTIATE_TEST_SUITE_P(Partitionings, ContourRule,
                         ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                           Partitioning::fractional_even),
                         [](const auto& info) { return std::string(partitioning_name(info.param)); });

TEST(SilhouetteRuleFactor, KeepsTheBlendedCurveWithinTheTolerance) {
  ScreenCamera cam;  // eye (0, 0, 5), 45 degrees, 720 pixels high
  const glm::dvec3 a(-0.5, 0, 0), b(0.5, 0, 0);
  const double pixels_per_unit = 0.5 * 720 / std::tan(22.5 * M_PI / 180.0) / 5.0;
  const double deviation = 0.01;  // mesh units
  const double f = silhouette_edge_factor(cam, 0.5, 1.0, deviation, a, b);
  EXPECT_NEAR(f, 1.5 * std::sqrt(deviation * pixels_per_unit / 0.5), 1e-5);
  EXPECT_EQ(silhouette_edge_factor(cam, 0.5, 0.0, deviation, a, b), 1.0f);  // face-on: one segment
  EXPECT_EQ(silhouette_edge_factor(cam, 0.5, 1.0, 0.0, a, b), 1.0f);        // a straight edge
  EXPECT_NEAR(silhouette_edge_factor(cam, 0.5, 0.25, deviation, a, b), 0.5 * f, 1e-5);  // sqrt(α)
  EXPECT_NEAR(silhouette_edge_factor(cam, 2.0, 1.0, deviation, a, b), 0.5 * f, 1e-5);
  EXPECT_EQ(silhouette_edge_factor(cam, 1e-9, 1.0, 1.0, a, b), 64.0f);
  // The bound behind the rule: a cubic whose inner control points are at most h off the chord's
  // third points is within 2.25 h / F² of the chords of F equal segments.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> x(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 p0(x(rng), x(rng), x(rng)), p3(x(rng), x(rng), x(rng));
    glm::dvec3 d1(x(rng), x(rng), x(rng)), d2(x(rng), x(rng), x(rng));
    const double h = std::max(glm::length(d1), glm::length(d2));
    const glm::dvec3 c1 = p0 + (p3 - p0) / 3.0 + d1, c2 = p0 + 2.0 * (p3 - p0) / 3.0 + d2;
    auto curve = [&](double t) {
      const double s = 1 - t;
      return s * s * s * p0 + 3 * s * s * t * c1 + 3 * s * t * t * c2 + t * t * t * p3;
    };
    const int segments = 1 + i % 9;
    double worst = 0.0;
    for (int k = 0; k < segments; ++k) {
      const double t0 = double(k) / segments, t1 = double(k + 1) / segments;
      for (int j = 1; j < 16; ++j) {
        const double t = t0 + (t1 - t0) * j / 16.0;
        const glm::dvec3 chord = glm::mix(curve(t0), curve(t1), (t - t0) / (t1 - t0));
        worst = std::max(worst, glm::length(curve(t) - chord));
      }
    }
    ASSERT_LE(worst, 2.25 * h / (segments * segments) * (1 + 1e-12)) << i;
  }
}

// ---------------------------------------------------------------------------------------------
// Feature ends: a mesh with hard edges imported as a tagged mesh (docs/stpn.md) has, across
// each crease, faces that shade an end with different normals. The surface stays closed.

TEST(SilhouetteFeatureEnds, HardEdgedMeshHasThemAndStaysClosed) {
  const std::filesystem::path file = kModels / "Collada/Cinema4D.dae";
  if (!std::filesystem::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
  const Mesh mesh = import_st_mesh(file, {}).mesh;
  TessSettings s;
  s.L = 4;
  s.silhouette.enabled = true;
  s.silhouette.eye = {300.0, 200.0, -400.0};
  bind_silhouette(s, mesh);
  EXPECT_GT(s.silhouette_field->counts().feature_ends, 20u);

  EXPECT_GT(expect_closed(mesh, s, [](const PatchView&) {}), mesh.triangle_count());
}

TEST(SilhouetteFeatureEnds, AFeatureEndFollowsTheCreaseDirection) {
  // Two faces of a hinge meeting at the x axis, shading its ends with their own face normals:
  // m is along the crease, so with α = 1 the edge's tangent points lie on it at 1/3 and 2/3.
  PnInput in;
  in.p = {glm::dvec3(0, 0, 0), glm::dvec3(3, 0, 0), glm::dvec3(1, 2, 0)};
  in.n = {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)};
  PatchSilhouette s;
  s.normals = in.n;
  for (int corner : {0, 1}) {
    PatchSilhouette::End& end = s.end[corner][corner == 0 ? 0 : 1];
    end.feature = true;
    end.m = glm::normalize(glm::cross(glm::dvec3(0, 1, 1), glm::dvec3(0, 0, 1)));  // ±x
  }
  const PnPatch patch = make_silhouette_patch(in, s, NormalMode::Quadratic);
  EXPECT_LT(glm::length(patch.b[net_index(1, 0, 3)] - glm::dvec3(1, 0, 0)), 1e-15);
  EXPECT_LT(glm::length(patch.b[net_index(2, 0, 3)] - glm::dvec3(2, 0, 0)), 1e-15);
  // A direction off the edge moves the point: c follows m, not the smooth end's normal.
  s.end[0][0].m = glm::normalize(glm::dvec3(1, 0, 1));
  const PnPatch tilted = make_silhouette_patch(in, s, NormalMode::Quadratic);
  // c = p0 + ((p1 - p0)·m)/3 m = (3/√2)/3 · (1, 0, 1)/√2 = (0.5, 0, 0.5).
  EXPECT_LT(glm::length(tilted.b[net_index(1, 0, 3)] - glm::dvec3(0.5, 0, 0.5)), 1e-15);
  s.alpha[0] = 0.5;  // halfway to l = (1, 0, 0)
  const PnPatch half = make_silhouette_patch(in, s, NormalMode::Quadratic);
  EXPECT_LT(glm::length(half.b[net_index(1, 0, 3)] - glm::dvec3(0.75, 0, 0.25)), 1e-15);
}

}  // namespace
}  // namespace tessim
