// Welded output (model/weld.hpp): the keys merge exactly the points the patches share, never
// two different ones, for the uniform pattern and adaptive D3D11 patterns of every
// partitioning. The CLI's --weld: tests/cli/weld_cli_test.cpp.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "model/weld.hpp"
#include "tests/support/distinct_points.hpp"

namespace tessim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kWuson);
  return mesh;
}

struct Welded {
  std::size_t vertices_in = 0, keys = 0, distinct_positions = 0;
  double worst = 0;  // largest distance of a copy from its key's first position, of the diagonal
};

Welded weld(const Mesh& mesh, const TessSettings& settings) {
  struct KeyHash {
    std::size_t operator()(const WeldKey& k) const {
      std::size_t h = 0;
      for (std::uint64_t w : k) h = h * 1000003u ^ static_cast<std::size_t>(w);
      return h;
    }
  };
  std::unordered_map<WeldKey, glm::dvec3, KeyHash> first;
  std::vector<glm::dvec3> points;
  std::vector<WeldKey> keys;
  Welded w;
  const double diagonal = bounding_box(mesh).diagonal();
  tessellate_mesh(mesh, settings, NormalMode::Quadratic, [&](const PatchView& p) {
    patch_weld_keys(mesh, p, keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const auto [it, fresh] = first.try_emplace(keys[i], p.positions[i]);
      if (!fresh) w.worst = std::max(w.worst, glm::length(p.positions[i] - it->second) / diagonal);
      points.push_back(p.positions[i]);
    }
  });
  w.vertices_in = points.size();
  w.keys = first.size();
  w.distinct_positions = testing::distinct_points(points, 1e-12 * diagonal);
  return w;
}

TEST(Weld, UniformPatternGivesTheWatertightCount) {
  const Mesh& mesh = wuson();
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const glm::uvec3& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[std::minmax(t[e], t[(e + 1) % 3])];
  for (int L : {1, 3, 4, 7}) {
    TessSettings s;
    s.L = L;
    const Welded w = weld(mesh, s);
    // Every mesh vertex once, each edge's L - 1 inner points once, each patch's interior.
    const std::size_t expected = mesh.vertex_count() + edges.size() * static_cast<std::size_t>(L - 1) +
                                 mesh.triangle_count() * static_cast<std::size_t>((L - 1) * (L - 2) / 2);
    EXPECT_EQ(w.keys, expected) << "L = " << L;
    EXPECT_EQ(w.keys, w.distinct_positions) << "L = " << L;
    EXPECT_LE(w.worst, 1e-12) << "L = " << L;
  }
}

class WeldAdaptive : public ::testing::TestWithParam<Partitioning> {};

TEST_P(WeldAdaptive, KeysAreExactlyTheDistinctPoints) {
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.partitioning = GetParam();
  s.camera.eye = {2.6, 1.3, -2.9};
  s.camera.target = {0.0, 0.6, -0.2};
  s.pixels_per_segment = 10.0;
  const Welded w = weld(wuson(), s);
  EXPECT_LT(w.keys, w.vertices_in);
  EXPECT_EQ(w.keys, w.distinct_positions);  // no two keys for one point, no key for two points
  EXPECT_LE(w.worst, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Partitionings, WeldAdaptive,
                         ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                           Partitioning::fractional_even));

}  // namespace
}  // namespace tessim
