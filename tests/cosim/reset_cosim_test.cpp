// Mid-stream resets at random cycles (docs/verification.md, cosim::RandomResets): the unit must
// come out of a reset in the same state as the cycle model wherever it lands — anywhere, inside
// the inner rings of a large D3D11 patch (the DPG's walk registers in use) and while the CPG is
// mid-triangle. The tallies prove that the resets did land there, so the test cannot quietly
// turn into one that resets an idle unit.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/host.hpp"

namespace tessim::cosim {
namespace {

// Uniform triangles with large D3D11 patches among them (up to 3169 points, several rings), in
// every partitioning; the first large patch comes second, so that it is reached after every
// restart of the stream.
std::vector<sim::TriangleFx> stream_with_large_patches(const sim::NumberFormat& fmt, std::uint64_t seed) {
  std::vector<sim::TriangleFx> s = random_triangles(10, seed, fmt, 5);
  struct Large {
    std::size_t at;
    Partitioning p;
    std::array<float, 3> outer;
    float inner;
  };
  for (const Large& l : {Large{1, Partitioning::integer, {33, 20, 64}, 41},
                         Large{4, Partitioning::fractional_odd, {12.3f, 5.01f, 40.9f}, 47.3f},
                         Large{7, Partitioning::fractional_even, {64, 64, 64}, 64},
                         Large{8, Partitioning::pow2, {3, 17, 9}, 30}}) {
    const D3D11Factors f = sim::d3d11_host_factors(l.outer, l.inner, l.p);
    sim::set_d3d11_pattern(s[l.at], f, l.p);
    EXPECT_GT(sim::patch_vertex_count(s[l.at]), 500) << "a large patch";
  }
  return s;
}

TEST(CosimRandomResets, LandInsideLargeD3D11PatchesAndMidTriangle) {
  for (const char* build : {"n2_verif", "n3_lat3", "n1_w20b18"}) {
    for (std::uint64_t seed : {1u, 2u}) {
      SCOPED_TRACE(std::string(build) + " seed " + std::to_string(seed));
      CosimOptions o;
      o.variant = build;
      static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(build)->config();
      o.seed = seed;
      o.unit.seed = seed;
      o.unit.gpe_cycles = 2;
      o.unit.gpe_stall_prob = 0.2;
      o.random_resets.count = 9;
      o.random_resets.span = 3000;
      const auto stream = stream_with_large_patches(o.unit.format, seed);
      const CosimReport r = run_cosim(stream, o);
      EXPECT_TRUE(r.passed) << format_report(r, o);
      std::uint64_t vertices = 0;
      for (const sim::TriangleFx& t : stream) vertices += static_cast<std::uint64_t>(sim::patch_vertex_count(t));
      EXPECT_EQ(r.vertices, vertices) << "a complete pass after the last reset";
      EXPECT_EQ(r.resets.total, 9u);
      EXPECT_GE(r.resets.dpg_inner_ring, 3u) << "resets inside the inner rings of a D3D11 patch";
      EXPECT_GE(r.resets.cpg_compute, 3u) << "resets with the CPG mid-triangle";
    }
  }
}

// Without D3D11 patches the aimed resets give way to any cycle after their span; the tally says so.
TEST(CosimRandomResets, UniformStreamTalliesNoD3D11Resets) {
  CosimOptions o;
  o.variant = "n2";
  o.random_resets.count = 4;
  o.random_resets.span = 300;
  const CosimReport r = run_cosim(random_triangles(40, 5, o.unit.format, 6), o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
  EXPECT_EQ(r.resets.total, 4u);
  EXPECT_EQ(r.resets.dpg_d3d11, 0u);
}

}  // namespace
}  // namespace tessim::cosim
