// Per-patch factors in the float reference (model/factors.hpp, model/tessellate.hpp): adaptive
// factors are symmetric in an edge's end points, and an adaptively tessellated real mesh is
// crack-free: welding its output within 1e-12 of the diagonal leaves exactly the vertices a
// watertight tessellation has (mesh vertices, the points inside each edge once, the points
// inside each patch).
#include <gtest/gtest.h>

#include "tests/support/distinct_points.hpp"

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <unordered_map>
#include <vector>

#include "model/d3d11_pattern.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"

namespace tessim {
namespace {

const Mesh& wuson() {
  static const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  return mesh;
}

TessSettings adaptive(Partitioning p) {
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.partitioning = p;
  s.camera.eye = {2.6, 1.3, -2.9};
  s.camera.target = {0.0, 0.6, -0.2};
  s.camera.width = 1024;
  s.camera.height = 768;
  s.pixels_per_segment = 10.0;
  return s;
}

TEST(AdaptiveFactors, DependOnTheEdgeOnlyNotOnItsOrder) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-3.0, 3.0);
  const ScreenCamera cam;
  for (int i = 0; i < 10000; ++i) {
    const glm::dvec3 a(x(rng), x(rng), x(rng)), b(x(rng), x(rng), x(rng));
    const float ab = adaptive_edge_factor(cam, 7.0, a, b), ba = adaptive_edge_factor(cam, 7.0, b, a);
    ASSERT_EQ(std::bit_cast<std::uint32_t>(ab), std::bit_cast<std::uint32_t>(ba)) << i;
    ASSERT_GE(ab, 1.0f);
    ASSERT_LE(ab, 64.0f);
  }
  // Nearer means finer: the same edge at twice the distance gets about half the factor.
  const glm::dvec3 a(-0.1, 0.0, 0.0), b(0.1, 0.0, 0.0);
  ScreenCamera near_cam, far_cam;
  near_cam.eye = {0.0, 0.0, 2.0};
  far_cam.eye = {0.0, 0.0, 4.0};
  const float near_f = adaptive_edge_factor(near_cam, 4.0, a, b), far_f = adaptive_edge_factor(far_cam, 4.0, a, b);
  EXPECT_NEAR(near_f / far_f, 2.0, 1e-6);
}

class AdaptiveMesh : public ::testing::TestWithParam<Partitioning> {};

TEST_P(AdaptiveMesh, IsCrackFree) {
  const Mesh& mesh = wuson();
  const TessSettings settings = adaptive(GetParam());
  std::vector<glm::dvec3> points;
  const TessellationSummary s = tessellate_mesh(mesh, settings, NormalMode::Quadratic, [&](const PatchView& p) {
    points.insert(points.end(), p.positions.begin(), p.positions.end());
  });
  ASSERT_EQ(s.culled, 0u);

  // The watertight count: every mesh vertex once, each edge's inner points once (both patches
  // of an edge must place the same ones), each patch's interior points. A fractional factor
  // just above an integer can put two points of one patch at the same (u, v): such points are
  // one vertex (a degenerate triangle of the tessellator), not a crack, so points are counted
  // as distinct 16.16 pairs.
  std::map<std::pair<unsigned, unsigned>, std::set<Fixed16>> edge_points;  // by the weight of the first end
  std::uint64_t interior = 0;
  std::set<float> factors_seen;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const PatchFactors f = patch_factors(settings, mesh, t);
    const D3D11Pattern pattern = d3d11_tri_pattern(f.outer, f.inner, settings.partitioning);
    const glm::uvec3& tri = mesh.triangles[t];
    for (float x : f.outer) factors_seen.insert(x);
    std::set<std::pair<Fixed16, Fixed16>> inside;
    // Edge e and the weight of each of its two ends: outer[0] (u = 0) joins vertices 0 (w) and
    // 2 (v); outer[1] (v = 0) joins 0 (w) and 1 (u); outer[2] (w = 0) joins 1 (u) and 2 (v).
    std::array<std::map<std::pair<unsigned, unsigned>, std::set<Fixed16>>, 3> mine;
    mine[0][std::minmax(tri[0], tri[2])];  // every edge, even one without inner points
    mine[1][std::minmax(tri[0], tri[1])];
    mine[2][std::minmax(tri[1], tri[2])];
    for (const FixedUV& q : pattern.points) {
      const Fixed16 w = kFixed16One - q.u - q.v;
      const int zeros = (q.u == 0) + (q.v == 0) + (w == 0);
      if (zeros >= 2) continue;  // a corner: a mesh vertex
      auto on_edge = [&](int e, unsigned a, Fixed16 wa, unsigned b, Fixed16 wb) {
        // Keyed by the smaller vertex index; the point by the weight of that vertex.
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
          // Both patches of the edge place the same points on it, bit for bit in 16.16.
          ASSERT_EQ(it->second, weights) << "edge " << key.first << "-" << key.second;
        }
      }
  }
  std::uint64_t expected = mesh.vertex_count() + interior;
  for (const auto& [edge, weights] : edge_points) expected += weights.size();

  const double diagonal = bounding_box(mesh).diagonal();
  EXPECT_EQ(testing::distinct_points(points, 1e-12 * diagonal), expected);
  // The camera makes the factors vary: a real test of stitching, not of one factor everywhere.
  EXPECT_GT(factors_seen.size(), 100u);
}

INSTANTIATE_TEST_SUITE_P(Partitionings, AdaptiveMesh,
                         ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                           Partitioning::fractional_even),
                         [](const auto& info) { return std::string(partitioning_name(info.param)); });

TEST(PatternCache, UniformSettingsGiveTheUniformPattern) {
  TessSettings s;
  s.L = 5;
  PatternCache cache(s);
  const DomainPattern& p = cache.pattern(wuson(), 0);
  EXPECT_EQ(p.uniform_L, 5);
  EXPECT_EQ(p.points.size(), 21u);
  EXPECT_EQ(p.triangle_count(), 25u);
  const TessellationCounts c = count_tessellation(wuson(), cache);
  EXPECT_EQ(c.vertices, 21u * wuson().triangle_count());
}

TEST(PatternCache, FixedFactorsCullEveryPatchWhenOneIsZero) {
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.outer = {0.0f, 3.0f, 3.0f};
  int calls = 0;
  const TessellationSummary r =
      tessellate_mesh(wuson(), s, NormalMode::Quadratic, [&](const PatchView&) { ++calls; });
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(r.culled, wuson().triangle_count());
  s.outer = {std::nanf(""), 3.0f, 3.0f};
  EXPECT_EQ(tessellate_mesh(wuson(), s, NormalMode::Quadratic, [&](const PatchView&) { ++calls; }).culled,
            wuson().triangle_count());
}

}  // namespace
}  // namespace tessim
