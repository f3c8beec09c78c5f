// The D3D11 pattern through the RTL and the cycle model in lock-step (docs/patterns.md,
// docs/verification.md): per-patch factors with every partitioning, random factors (near the
// rounding boundaries, beyond the range, single triangles) and adaptive ones from a camera, on
// N = 1..4, every normal mode, random geometry-engine stalls; plain and tag-taking builds.
#include <gtest/gtest.h>

#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "cosim/cosim.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/host.hpp"
#include "tests/support/rtl_build_config.hpp"

namespace tessim::cosim {
namespace {

CosimOptions options(const char* variant, int n, NormalMode mode, double stall, std::uint64_t seed) {
  CosimOptions o;
  o.variant = variant;
  o.unit.int_blocks = n;
  o.unit.normals = mode;
  o.unit.gpe_cycles = 2;
  o.unit.gpe_stall_prob = stall;
  o.unit.seed = seed;
  o.seed = seed;
  return o;
}

constexpr NormalMode kModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

class RandomD3D11Cosim : public ::testing::TestWithParam<std::tuple<int, int>> {};

// Random triangles, each with random D3D11 factors: one partitioning for the whole stream, or
// (index 4) one drawn per triangle.
TEST_P(RandomD3D11Cosim, AgreesOnEveryCycle) {
  const auto [n, which] = GetParam();
  const std::optional<Partitioning> partitioning =
      which < 4 ? std::optional<Partitioning>(static_cast<Partitioning>(which)) : std::nullopt;
  const std::string variant = std::string(1, 'n').append(std::to_string(n));
  const std::uint64_t seed = 100 + static_cast<std::uint64_t>(4 * n + which);
  CosimOptions o = options(variant.c_str(), n, kModes[(n + which) % 3], 0.25, seed);
  std::vector<sim::TriangleFx> stream = random_triangles(60, seed, o.unit.format, 8);
  assign_random_patterns(stream, seed, 12, partitioning);
  std::set<int> counts;
  for (const sim::TriangleFx& t : stream) {
    ASSERT_NE(t.pattern, sim::TriPattern::uniform);
    counts.insert(sim::patch_vertex_count(t));
  }
  ASSERT_GT(counts.size(), 10u) << "patches of many sizes";
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
  EXPECT_EQ(r.triangles, stream.size());
}

INSTANTIATE_TEST_SUITE_P(NAndPartitionings, RandomD3D11Cosim,
                         ::testing::Combine(::testing::Values(1, 2, 3, 4), ::testing::Values(0, 1, 2, 3, 4)),
                         [](const auto& info) {
                           const int p = std::get<1>(info.param);
                           std::string name = "N";
                           name += std::to_string(std::get<0>(info.param));
                           name += '_';
                           name += p < 4 ? partitioning_name(static_cast<Partitioning>(p)) : "mixed";
                           return name;
                         });

TEST(RandomD3D11Cosim, UniformAndD3D11PatchesInterleave) {
  // Every other patch keeps the uniform pattern: the DPG switches walks between patches.
  CosimOptions o = options("n2", 2, NormalMode::Quadratic, 0.3, 7);
  std::vector<sim::TriangleFx> stream = random_triangles(80, 7, o.unit.format, 6);
  std::vector<sim::TriangleFx> d3d11 = stream;
  assign_random_patterns(d3d11, 7, 10);
  for (std::size_t i = 0; i < stream.size(); i += 2) stream[i] = d3d11[i];
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
}

TEST(RandomD3D11Cosim, TagTakingBuildsWithD3D11Patterns) {
  // Builds with other CPG variants and latency 3 (tags on): the pattern rides on the CPG's
  // latch for as long as the CPG takes, tag pass included.
  for (const char* name : {"n1_r4", "n3_lat3"}) {
    CosimOptions o = options(name, 2, NormalMode::Quadratic, 0.2, 21);
    o.unit = tessim::testing::with_rtl_build(o.unit, name);
    std::vector<sim::TriangleFx> stream = random_triangles(40, 21, o.unit.format, 6, 0.1, 1.0, true);
    assign_random_patterns(stream, 21, 16);
    const CosimReport r = run_cosim(stream, o);
    EXPECT_TRUE(r.passed) << format_report(r, o);
  }
}

TEST(RandomD3D11Cosim, LargestPatternsAndTheirLimits) {
  // Factors at the top of each range (up to 3169 points a patch) and at the bottom (one
  // triangle, the picture frame of fractional_odd with an inner factor of 1).
  CosimOptions o = options("n4", 4, NormalMode::Quadratic, 0.0, 3);
  o.unit.gpe_cycles = 1;
  std::vector<sim::TriangleFx> stream = random_triangles(8, 3, o.unit.format, 4);
  const std::vector<std::tuple<std::array<float, 3>, float, Partitioning>> sets = {
      {{64, 64, 64}, 64, Partitioning::integer},       {{63, 63, 63}, 63, Partitioning::fractional_odd},
      {{64, 64, 64}, 64, Partitioning::fractional_even}, {{1, 1, 1}, 1, Partitioning::integer},
      {{1, 1, 1}, 1, Partitioning::fractional_odd},     {{2.5f, 1, 1}, 1, Partitioning::fractional_odd},
      {{64, 1, 33}, 17, Partitioning::pow2},            {{2, 2, 2}, 2, Partitioning::fractional_even}};
  for (std::size_t i = 0; i < stream.size(); ++i) {
    const auto& [outer, inner, p] = sets[i];
    sim::set_d3d11_pattern(stream[i], sim::d3d11_host_factors(outer, inner, p), p);
  }
  EXPECT_EQ(sim::patch_vertex_count(stream[0]), 3169);
  EXPECT_EQ(sim::patch_vertex_count(stream[3]), 3);
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
}

TEST(FixedD3D11Cosim, TheSameFactorsForEveryPatchOfAMesh) {
  // tessim cosim MESH --outer A,B,C --inner F --partitioning P: every partitioning, N = 2 and 3.
  const Mesh mesh = load_mesh("/usr/share/assimp/models/STL/sphereWithHole.stl");
  for (Partitioning p : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                         Partitioning::fractional_even}) {
    for (int n : {2, 3}) {
      const std::string variant = std::string(1, 'n').append(std::to_string(n));
      CosimOptions o = options(variant.c_str(), n, NormalMode::Reflect, 0.2, 5);
      TessSettings s;
      s.kind = PatternKind::D3D11;
      s.partitioning = p;
      s.outer = {3.5f, 2.2f, 7.9f};
      s.inner = 4.4f;
      const sim::HostScaling scaling = sim::host_scaling(mesh);
      std::vector<sim::TriangleFx> stream;
      for (std::size_t i = 0; i < mesh.triangle_count(); ++i) stream.push_back(*sim::to_fixed(mesh, i, scaling, o.unit.format, s));
      const CosimReport r = run_cosim(stream, o);
      EXPECT_TRUE(r.passed) << partitioning_name(p) << "\n" << format_report(r, o);
    }
  }
}

}  // namespace
}  // namespace tessim::cosim
