// The unit's integer D3D11 walk (sim/values/d3d11_walk.hpp): the properties every implementation of
// the pattern has (tests/support/d3d11_pattern_checks.hpp), its fixed-point constants, its setup
// and point walk, and the walk against the float reference (model/d3d11_pattern.hpp), written
// independently from the same definition: the same factors, points and triangles, in the same
// order, over a dense grid of factors of every partitioning.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/d3d11_pattern.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/config/config.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/values/d3d11_walk.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"
#include "tests/support/d3d11_pattern_checks.hpp"

namespace tessim::sim {
namespace {

using d3d11_checks::D3D11PatternProperties;

INSTANTIATE_TEST_SUITE_P(IntegerWalk, D3D11PatternProperties,
                         ::testing::Values(d3d11_checks::D3D11Implementation{"integer_walk", d3d11_walk_pattern}),
                         d3d11_checks::implementation_name);

TEST(D3D11Walk, FixedPointConstants) {
  EXPECT_EQ(fixed16_reciprocal(3), 0x5555);
  EXPECT_EQ(fixed16_reciprocal(6), 0x2aab);  // rounded to nearest, not truncated
  EXPECT_EQ(fixed16_reciprocal(64), 0x400);
  EXPECT_EQ(float_to_fixed16(1.0f), 0x10000);
  EXPECT_EQ(float_to_fixed16(2.5f), 0x28000);
  EXPECT_EQ(float_to_fixed16(1.0f + 1.0f / 131072.0f), 0x10000);  // a tie rounds to even
  EXPECT_EQ(float_to_fixed16(1.0f + 3.0f / 131072.0f), 0x10002);
}

// What a tessellation unit derives from the processed factors (d3d11_factors_from_fixed) is what
// the host path derives, and the point walk's labels describe the points: ring 0 on the
// boundary, inner rings inside, the centre a ring of its own at (1/3, 1/3), indices in order.
TEST(D3D11Walk, UnitSideSetupAndWalkAgreeWithThePattern) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> f(0.5f, 70.0f);
  for (int i = 0; i < 4000; ++i) {
    const auto part = static_cast<Partitioning>(i % 4);
    const std::array<float, 3> outer{f(rng), f(rng), f(rng)};
    const float inner = i % 5 == 0 ? 1.0f : f(rng);
    const D3D11Factors a = d3d11_host_factors(outer, inner, part);
    const D3D11Factors b = d3d11_factors_from_fixed(a.outer_fixed, a.inner_fixed,
                                                    part == Partitioning::pow2 ? Partitioning::integer : part);
    ASSERT_EQ(a.single_triangle, b.single_triangle) << i;
    ASSERT_EQ(a.outer_odd, b.outer_odd) << i;
    ASSERT_EQ(a.inner_odd, b.inner_odd) << i;
    ASSERT_EQ(a.outer_points, b.outer_points) << i;
    ASSERT_EQ(a.inner_points, b.inner_points) << i;
    const D3D11Setup setup = d3d11_setup(b);
    const D3D11Pattern p = d3d11_walk_pattern(outer, inner, part);
    ASSERT_EQ(setup.point_count, static_cast<int>(p.points.size())) << i;
    int n = 0, last_ring = 0;
    for (D3D11PointWalker walk(setup);; walk.next(setup), ++n) {
      const FixedUV q = walk.point(setup);
      ASSERT_EQ(walk.index(), n);
      ASSERT_EQ(q.u, p.points[static_cast<std::size_t>(n)].u);
      ASSERT_EQ(q.v, p.points[static_cast<std::size_t>(n)].v);
      ASSERT_GE(walk.ring(), last_ring);
      last_ring = walk.ring();
      const Fixed16 w = kFixed16One - q.u - q.v;
      if (walk.ring() == 0) {
        ASSERT_TRUE(q.u == 0 || q.v == 0 || w == 0) << i << " point " << n;
      }
      if (walk.edge() == 3) {
        ASSERT_EQ(q.u, 0x5555);
        ASSERT_EQ(q.v, 0x5555);
        ASSERT_GT(walk.ring(), 0);
        ASSERT_TRUE(walk.last());
      }
      ASSERT_EQ(walk.last(), n + 1 == setup.point_count);
      if (walk.last()) break;
    }
  }
}

// Factors of one patch.
struct Case {
  std::array<float, 3> outer;
  float inner;
  Winding winding;
};

// The grid: (1) every factor from 0.5 to 65 in steps of 1/16, and around each integer 1..64 the
// values a grid step or half a step (a tie of the 16.16 rounding) away and 0.001 away, each
// value on all four factors at once, on one outer factor, on the inner factor, and on two outer
// factors beside an inner factor of 1 (fractional_odd's forced inner ring), the other factors
// drawn from the same values; (2) every combination of 11 coarse values on the four factors;
// (3) culling and out-of-range values. Every fifth patch also clockwise.
std::vector<Case> grid() {
  const float step = 1.0f / 65536.0f;
  std::vector<float> fine;
  for (int i = 8; i <= 65 * 16; ++i) fine.push_back(static_cast<float>(i) / 16.0f);
  for (int k = 1; k <= 64; ++k) {
    const auto f = static_cast<float>(k);
    for (float d : {-step, -step / 2, step / 2, step, 1.5f * step, -0.001f, 0.001f}) fine.push_back(f + d);
  }
  const std::size_t n = fine.size();
  std::vector<Case> cases;
  auto add = [&](float e0, float e1, float e2, float in) {
    cases.push_back({{e0, e1, e2}, in, Winding::ccw});
    if (cases.size() % 5 == 0) cases.push_back({{e0, e1, e2}, in, Winding::cw});
  };
  for (std::size_t i = 0; i < n; ++i) {
    const float x = fine[i], a = fine[(7 * i + 1) % n], b = fine[(13 * i + 5) % n], c = fine[(31 * i + 11) % n];
    add(x, x, x, x);
    add(x, a, b, c);
    add(a, b, c, x);
    add(b, x, x, 1.0f);
  }
  const float coarse[] = {1.0f, 1.0f + step, 1.4f, 2.0f, 2.7f, 3.0f, 4.5f, 7.0f, 12.3f, 31.9f, 64.0f};
  for (float e0 : coarse)
    for (float e1 : coarse)
      for (float e2 : coarse)
        for (float in : coarse) add(e0, e1, e2, in);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (float odd_one : {0.0f, -0.0f, -1.0f, nan, inf, 1e-30f, 0.3f, 100.0f, 1e30f})
    for (float in : {nan, 0.0f, -3.0f, inf, 0.5f, 5.0f}) {
      add(odd_one, 4.0f, 4.0f, in);
      add(3.0f, 7.5f, odd_one, in);
    }
  return cases;
}

std::string describe(const Case& c, Partitioning p) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s %s outer %.9g,%.9g,%.9g inner %.9g", partitioning_name(p), winding_name(c.winding),
                c.outer[0], c.outer[1], c.outer[2], c.inner);
  return buf;
}

// FNV-1a 64 of the triangles' corners in order, each corner's u then v as little-endian uint32:
// the hash tests/data/d3d11_reference.txt records.
std::uint64_t corner_hash(const D3D11Pattern& p) {
  std::uint64_t h = 0xcbf29ce484222325u;
  for (std::uint32_t i : p.indices)
    for (const Fixed16 x : {p.points[i].u, p.points[i].v})
      for (int byte = 0; byte < 4; ++byte) {
        h ^= (static_cast<std::uint32_t>(x) >> (8 * byte)) & 0xffu;
        h *= 0x100000001b3u;
      }
  return h;
}

float float_from_bits(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// Microsoft's reference tessellator (as Mesa ships and runs it; the file's header says how the
// data was made, scripts/d3d11_reference/): both implementations give its triangles, corner for
// corner, on 1 744 patches of every partitioning and both windings.
TEST(D3D11Reference, BothImplementationsGiveTheReferenceTessellatorsTriangles) {
  std::ifstream in(TESSIM_SOURCE_DIR "/tests/data/d3d11_reference.txt");
  ASSERT_TRUE(in) << "tests/data/d3d11_reference.txt";
  std::size_t patches = 0, triangles = 0, culled = 0, differing = 0;
  std::array<std::size_t, 4> per_partitioning{};
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string partitioning, winding;
    std::array<std::uint32_t, 4> bits{};
    std::size_t count = 0;
    std::uint64_t hash = 0;
    words >> partitioning >> winding >> std::hex >> bits[0] >> bits[1] >> bits[2] >> bits[3] >> std::dec >> count >>
        std::hex >> hash;
    ASSERT_TRUE(words && parse_partitioning(partitioning) && parse_winding(winding)) << line;
    const Partitioning p = *parse_partitioning(partitioning);
    const Winding w = *parse_winding(winding);
    const std::array<float, 3> outer{float_from_bits(bits[0]), float_from_bits(bits[1]), float_from_bits(bits[2])};
    const float inner = float_from_bits(bits[3]);
    for (const D3D11Pattern& mine : {d3d11_tri_pattern(outer, inner, p, w), d3d11_walk_pattern(outer, inner, p, w)}) {
      if (mine.triangle_count() != count || corner_hash(mine) != hash) {
        if (++differing <= 5)
          ADD_FAILURE() << line << ": " << mine.triangle_count() << " triangles, hash " << std::hex << corner_hash(mine);
      }
    }
    ++patches;
    ++per_partitioning[static_cast<std::size_t>(p)];
    triangles += count;
    culled += count == 0;
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(patches, 1744u);
  for (std::size_t n : per_partitioning) EXPECT_GT(n, 400u);
  EXPECT_GT(culled, 0u);
  EXPECT_GT(triangles, 1000000u);
}

// `tessim sim --errors` evaluates a D3D11 vertex at its index's point of the reference pattern,
// and refuses a vertex of the unit that is not that point.
TEST(D3D11Reference, MeshErrorsHoldsTheUnitsPointsToTheReferencePattern) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/cube.ply");
  TessSettings settings;
  settings.kind = PatternKind::D3D11;
  settings.partitioning = Partitioning::fractional_odd;
  settings.outer = {3.5f, 2.2f, 7.9f};
  settings.inner = 4.4f;
  const UnitConfig cfg;
  const HostScaling scaling = host_scaling(mesh);
  const std::optional<TriangleFx> tri = to_fixed(mesh, 0, scaling, cfg.format, settings);
  ASSERT_TRUE(tri);
  const std::vector<VertexFx> vertices = evaluate_patch(*tri, cfg.normals, cfg.format);
  ASSERT_EQ(vertices.size(), d3d11_tri_pattern(settings.outer, settings.inner, settings.partitioning).points.size());
  MeshErrors errors(mesh, scaling, cfg, false, &settings);
  for (const VertexFx& v : vertices) EXPECT_NO_THROW(errors.add(v));
  EXPECT_EQ(errors.result().vertices, vertices.size());
  EXPECT_LT(errors.result().position_max, 1e-3);
  // One point moved by one unit of its last bit, or two points swapped: refused.
  for (int change = 0; change < 2; ++change) {
    MeshErrors again(mesh, scaling, cfg, false, &settings);
    std::vector<VertexFx> changed = vertices;
    if (change == 0) changed[7].u += 1;
    else std::swap(changed[7].u, changed[8].u), std::swap(changed[7].v, changed[8].v);
    for (int i = 0; i < 7; ++i) again.add(changed[static_cast<std::size_t>(i)]);
    EXPECT_THROW(again.add(changed[7]), std::logic_error) << change;
  }
}

// The first difference between the two patterns, empty if none.
std::string difference(const D3D11Pattern& reference, const D3D11Pattern& walk) {
  if (!(reference.factors == walk.factors)) return "factors differ";
  if (reference.points.size() != walk.points.size())
    return std::to_string(reference.points.size()) + " points against " + std::to_string(walk.points.size());
  for (std::size_t i = 0; i < reference.points.size(); ++i)
    if (!(reference.points[i] == walk.points[i])) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "point %zu: (0x%x, 0x%x) against (0x%x, 0x%x)", i,
                    static_cast<unsigned>(reference.points[i].u), static_cast<unsigned>(reference.points[i].v),
                    static_cast<unsigned>(walk.points[i].u), static_cast<unsigned>(walk.points[i].v));
      return buf;
    }
  if (reference.indices.size() != walk.indices.size())
    return std::to_string(reference.triangle_count()) + " triangles against " + std::to_string(walk.triangle_count());
  for (std::size_t i = 0; i < reference.indices.size(); i += 3)
    for (std::size_t c = 0; c < 3; ++c)
      if (reference.indices[i + c] != walk.indices[i + c]) return "triangle " + std::to_string(i / 3);
  return {};
}

class D3D11Implementations : public ::testing::TestWithParam<Partitioning> {};

TEST_P(D3D11Implementations, FloatReferenceAndIntegerWalkAgreeOnADenseGrid) {
  const Partitioning p = GetParam();
  const std::vector<Case> cases = grid();
  std::size_t differing = 0, culled = 0, points = 0, triangles = 0;
  for (const Case& c : cases) {
    const D3D11Pattern reference = d3d11_tri_pattern(c.outer, c.inner, p, c.winding);
    const D3D11Pattern walk = d3d11_walk_pattern(c.outer, c.inner, p, c.winding);
    const std::string diff = difference(reference, walk);
    if (!diff.empty() && ++differing <= 5) ADD_FAILURE() << describe(c, p) << ": " << diff;
    culled += reference.factors.culled;
    points += reference.points.size();
    triangles += reference.triangle_count();
  }
  EXPECT_EQ(differing, 0u) << "of " << cases.size() << " patches";
  // The grid is what it says: tens of thousands of patches, a few culled, millions of points.
  EXPECT_GT(cases.size(), 20000u);
  EXPECT_GT(culled, 0u);
  EXPECT_LT(culled, cases.size() / 100);
  EXPECT_GT(points, 1000000u);
  EXPECT_GT(triangles, points);
}

INSTANTIATE_TEST_SUITE_P(Partitionings, D3D11Implementations,
                         ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                           Partitioning::fractional_even),
                         [](const ::testing::TestParamInfo<Partitioning>& info) {
                           return std::string(partitioning_name(info.param));
                         });

}  // namespace
}  // namespace tessim::sim
