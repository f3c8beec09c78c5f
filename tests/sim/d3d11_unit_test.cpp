// The D3D11 pattern in the cycle model (docs/microarchitecture.md §7): the DPG hands out the
// pattern's points, in the tessellator's order, with every partitioning and per-patch factors;
// the values are the untimed datapath's at those points; and an adaptively tessellated real mesh
// is crack-free in fixed point: both patches of every edge put bit-identical positions and
// normals on it, and the distinct output vertices are exactly those of a watertight tessellation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "model/d3d11_pattern.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/config/config.hpp"
#include "sim/run/testbench.hpp"
#include "sim/unit/model_dut.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const Mesh& wuson() {
  static const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  return mesh;
}

UnitConfig config(int n, double stall) {
  UnitConfig c;
  c.int_blocks = n;
  c.gpe_cycles = 2;
  c.gpe_stall_prob = stall;
  c.seed = 5;
  c.validate("test");
  return c;
}

// Every vertex the geometry engine accepts, running the stream through the cycle model.
std::vector<VertexFx> run(const std::vector<TriangleFx>& stream, const UnitConfig& cfg) {
  ModelDut dut(cfg);
  Testbench tb(stream, cfg);
  std::vector<VertexFx> out;
  for (std::uint64_t cycle = 0; !tb.done(); ++cycle) {
    const UnitInputs& in = tb.inputs(dut);
    if (tb.gpe_cycle().accepted) out.push_back(dut.vtx());
    dut.tick(in);
    if (cycle > 50'000'000) {
      ADD_FAILURE() << "no progress";
      break;
    }
  }
  return out;
}

struct FactorSet {
  std::array<float, 3> outer;
  float inner;
  Partitioning partitioning;
};

// Factor sets the tessellator treats differently: all equal, each edge different, fractional
// values next to the rounding boundaries, the limits, clamping, single triangle.
std::vector<FactorSet> factor_sets() {
  std::vector<FactorSet> sets;
  for (Partitioning p : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                         Partitioning::fractional_even}) {
    for (float L : {1.0f, 2.0f, 3.0f, 8.0f, 64.0f}) sets.push_back({{L, L, L}, L, p});
    sets.push_back({{3.5f, 2.2f, 7.9f}, 4.4f, p});
    sets.push_back({{1.0f, 1.0f, 1.0f}, 5.0f, p});
    sets.push_back({{6.0f, 1.0f, 2.0f}, 1.0f, p});
    sets.push_back({{3.0001f, 4.9999f, 2.0002f}, 3.00001f, p});
    sets.push_back({{70.0f, 0.25f, 63.5f}, 100.0f, p});
  }
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> f(0.5f, 20.0f);
  for (int i = 0; i < 40; ++i)
    sets.push_back({{f(rng), f(rng), f(rng)}, f(rng), static_cast<Partitioning>(i % 4)});
  return sets;
}

TEST(D3D11Dpg, HandsOutThePatternsPointsInOrder) {
  const Mesh& mesh = wuson();
  const HostScaling scaling = host_scaling(mesh);
  const std::vector<FactorSet> sets = factor_sets();
  for (int n : {1, 2, 3}) {
    const UnitConfig cfg = config(n, n == 2 ? 0.4 : 0.0);
    std::vector<TriangleFx> stream;
    for (std::size_t i = 0; i < sets.size(); ++i) {
      TriangleFx tri = to_fixed(mesh, i, scaling, cfg.format, 1);
      tri.id = static_cast<std::uint32_t>(i);
      set_d3d11_pattern(tri, d3d11_host_factors(sets[i].outer, sets[i].inner, sets[i].partitioning), sets[i].partitioning);
      stream.push_back(tri);
    }
    const std::vector<VertexFx> got = run(stream, cfg);
    std::size_t at = 0;
    for (std::size_t i = 0; i < sets.size(); ++i) {
      const D3D11Pattern pattern = d3d11_tri_pattern(sets[i].outer, sets[i].inner, sets[i].partitioning);
      const std::vector<VertexFx> direct = evaluate_patch(stream[i], cfg.normals, cfg.format);
      ASSERT_EQ(direct.size(), pattern.points.size());
      ASSERT_EQ(patch_vertex_count(stream[i]), static_cast<int>(pattern.points.size()));
      for (std::size_t p = 0; p < pattern.points.size(); ++p, ++at) {
        ASSERT_LT(at, got.size());
        const VertexFx& v = got[at];
        const int shift = cfg.format.bary_bits - 16;
        ASSERT_EQ(v.id, i) << "N=" << n;
        ASSERT_EQ(v.index, static_cast<int>(p));
        ASSERT_EQ(v.u, std::int64_t{pattern.points[p].u} << shift) << "patch " << i << " point " << p;
        ASSERT_EQ(v.v, std::int64_t{pattern.points[p].v} << shift) << "patch " << i << " point " << p;
        ASSERT_EQ(v.L, 0);
        ASSERT_EQ(v.last, p + 1 == pattern.points.size());
        ASSERT_EQ(v, direct[p]) << "the untimed datapath, patch " << i << " point " << p;
      }
    }
    EXPECT_EQ(at, got.size());
  }
}

TEST(D3D11Dpg, UniformAndD3D11PatchesInterleave) {
  // A stream that switches pattern from patch to patch: the DPG's two walks share nothing.
  const Mesh& mesh = wuson();
  const HostScaling scaling = host_scaling(mesh);
  const UnitConfig cfg = config(2, 0.3);
  std::vector<TriangleFx> stream;
  for (std::uint32_t i = 0; i < 60; ++i) {
    TriangleFx tri = to_fixed(mesh, i, scaling, cfg.format, 1 + static_cast<int>(i % 7));
    if (i % 3 != 0) {
      const auto p = static_cast<Partitioning>(i % 4);
      const float x = 1.0f + 0.37f * static_cast<float>(i % 11);
      set_d3d11_pattern(tri, d3d11_host_factors({x, x + 1.3f, 2.0f}, x, p), p);
    }
    stream.push_back(tri);
  }
  const std::vector<VertexFx> got = run(stream, cfg);
  std::vector<VertexFx> want;
  for (const TriangleFx& tri : stream) {
    const std::vector<VertexFx> patch = evaluate_patch(tri, cfg.normals, cfg.format);
    want.insert(want.end(), patch.begin(), patch.end());
  }
  EXPECT_EQ(got, want);
}

// The unit's vertex as an exact key: position and normal bits.
using VertexKey = std::array<std::int64_t, 6>;
VertexKey key_of(const VertexFx& v) { return {v.pos[0], v.pos[1], v.pos[2], v.nrm[0], v.nrm[1], v.nrm[2]}; }

class D3D11CrackFree : public ::testing::TestWithParam<std::tuple<Partitioning, NormalMode>> {};

TEST_P(D3D11CrackFree, SharedEdgesAreBitIdentical) {
  const auto [partitioning, normals] = GetParam();
  const Mesh& mesh = wuson();
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.partitioning = partitioning;
  s.camera.eye = {2.6, 1.3, -2.9};
  s.camera.target = {0.0, 0.6, -0.2};
  s.camera.width = 1024;
  s.camera.height = 768;
  s.pixels_per_segment = 24.0;
  UnitConfig cfg = config(2, 0.0);
  cfg.normals = normals;
  const HostScaling scaling = host_scaling(mesh);
  std::vector<TriangleFx> stream;
  std::set<float> factors_seen;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const PatchFactors f = patch_factors(s, mesh, t);
    for (float x : f.outer) factors_seen.insert(x);
    TriangleFx tri = to_fixed(mesh, t, scaling, cfg.format, 1);
    set_d3d11_pattern(tri, d3d11_host_factors(f.outer, f.inner, partitioning), partitioning);
    stream.push_back(tri);
  }
  ASSERT_GT(factors_seen.size(), 50u) << "the camera should make the factors vary";
  const std::vector<VertexFx> got = run(stream, cfg);

  // Per mesh edge, the vertices each of its patches puts on it (corners included), as exact
  // keys. Edge e of a patch is where weight e is 0: u = 0 joins corners 0 and 2, v = 0 corners 0
  // and 1, w = 0 corners 1 and 2 (docs/patterns.md, Conventions).
  const std::int64_t one = cfg.format.bary_one();
  std::map<std::pair<unsigned, unsigned>, std::vector<std::multiset<VertexKey>>> on_edge;
  std::set<VertexKey> distinct;
  std::size_t at = 0;
  for (std::size_t t = 0; t < stream.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    std::array<std::multiset<VertexKey>, 3> edges;
    for (int p = 0; p < patch_vertex_count(stream[t]); ++p, ++at) {
      ASSERT_LT(at, got.size());
      const VertexFx& v = got[at];
      ASSERT_EQ(v.id, t);
      const std::int64_t w = one - v.u - v.v;
      const VertexKey k = key_of(v);
      distinct.insert(k);
      // The outer ring (j = ring 0) is the patch's boundary. An inner ring can touch it in the
      // fractional_odd "picture frame" with an inner factor just above 1, but its points are
      // the patch's own (the tessellator's degenerate slivers), not the edge's.
      if (v.j != 0) continue;
      if (v.u == 0) edges[0].insert(k);
      if (v.v == 0) edges[1].insert(k);
      if (w == 0) edges[2].insert(k);
    }
    on_edge[std::minmax(tri[0], tri[2])].push_back(edges[0]);
    on_edge[std::minmax(tri[0], tri[1])].push_back(edges[1]);
    on_edge[std::minmax(tri[1], tri[2])].push_back(edges[2]);
  }
  ASSERT_EQ(at, got.size());
  std::size_t shared = 0;
  for (const auto& [edge, patches] : on_edge) {
    for (std::size_t i = 1; i < patches.size(); ++i) {
      ASSERT_EQ(patches[i], patches[0]) << "edge " << edge.first << "-" << edge.second
                                        << ": its two patches put different vertices on it";
      ++shared;
    }
  }
  EXPECT_GT(shared, mesh.triangle_count() / 2) << "a mesh with shared edges";

  // The welded count of a watertight tessellation: mesh vertices, each edge's inner points once,
  // every patch's interior points (distinct (u, v): coincident points of a degenerate fractional
  // segment are one vertex, as is an inner ring's point that lands on the boundary). Distinct exact vertices must be exactly as many: no crack doubles a
  // vertex and no two places collapse.
  std::uint64_t expected = mesh.vertex_count();
  at = 0;
  for (std::size_t t = 0; t < stream.size(); ++t) {
    std::set<std::pair<std::int64_t, std::int64_t>> boundary, inside;
    for (int p = 0; p < patch_vertex_count(stream[t]); ++p, ++at) {
      const VertexFx& v = got[at];
      (v.j == 0 ? boundary : inside).emplace(v.u, v.v);
    }
    // An inner ring's point at a boundary point's (u, v) (fractional_odd picture frame) is that point.
    for (const auto& uv : boundary) inside.erase(uv);
    expected += inside.size();
  }
  for (const auto& [edge, patches] : on_edge) {
    std::set<VertexKey> points(patches[0].begin(), patches[0].end());
    expected += points.size() - 2;  // without the two corners
  }
  EXPECT_EQ(distinct.size(), expected);
}

INSTANTIATE_TEST_SUITE_P(
    PartitioningsAndModes, D3D11CrackFree,
    ::testing::Combine(::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                         Partitioning::fractional_even),
                       ::testing::Values(NormalMode::Quadratic, NormalMode::Linear)),
    [](const auto& info) {
      return std::string(partitioning_name(std::get<0>(info.param))) + "_" +
             (std::get<1>(info.param) == NormalMode::Linear ? "linear" : "quadratic");
    });

TEST(D3D11Dpg, RefusesFactorsOutsideTheRange) {
  const UnitConfig cfg = config(1, 0.0);
  TriangleFx tri;
  tri.pattern = TriPattern::integer;
  tri.factors = {3 << 16, 4 << 16, (5 << 16) + 1, 2 << 16};
  EXPECT_NE(tri_pattern_problem(tri).find("outer factor 2"), std::string::npos) << tri_pattern_problem(tri);
  tri.factors[2] = 65 << 16;
  EXPECT_NE(tri_pattern_problem(tri).find("range"), std::string::npos);
  tri.pattern = TriPattern::fractional_even;
  tri.factors = {3 << 16, 4 << 16, 5 << 16, 1 << 16};
  EXPECT_NE(tri_pattern_problem(tri).find("inner factor"), std::string::npos);
  Unit unit(cfg);
  UnitInputs in;
  in.tri_valid = true;
  in.tri = tri;
  EXPECT_THROW(unit.tick(in), std::invalid_argument);
}

}  // namespace
}  // namespace tessim::sim
