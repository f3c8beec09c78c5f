// Lock-step co-simulation of the silhouette blend (docs/verification.md): every RTL build that
// takes alpha (N = 1..4, one and three CPG lanes, with and without registered products, alpha
// widths 1, 5, 8 and 16) against the cycle model, in every hardware normal mode, on random
// alpha that includes 0, 1, the smallest step and 1 minus it, under random stalls; and a real
// mesh's silhouette from an eye in every partitioning with the silhouette rule's factors.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "model/base/error.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/silhouette.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/host.hpp"

namespace tessim::cosim {
namespace {

std::vector<std::string> alpha_builds() {
  std::vector<std::string> names;
  for (const std::string& name : rtl::rtl_variants())
    if (rtl::make_rtl_unit(name)->config().format.takes_alpha()) names.push_back(name);
  return names;
}

CosimOptions build_options(const std::string& name, NormalMode mode, double stall, std::uint64_t seed) {
  CosimOptions o;
  o.variant = name;
  static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(name)->config();
  o.unit.normals = mode;
  o.unit.gpe_stall_prob = stall;
  o.unit.gpe_cycles = 2;
  o.seed = o.unit.seed = seed;
  return o;
}

TEST(CosimSilhouette, TheBuildsCoverNOneToFourAndTheCpgShapes) {
  std::vector<int> ns;
  bool one_lane_plain = false, one_lane_reg = false, three_lanes = false;
  for (const std::string& name : alpha_builds()) {
    const sim::HardwareConfig hw = rtl::make_rtl_unit(name)->config();
    ns.push_back(hw.int_blocks);
    one_lane_plain |= hw.cpg.lanes == 1 && !hw.cpg.product_reg;
    one_lane_reg |= hw.cpg.lanes == 1 && hw.cpg.product_reg;
    three_lanes |= hw.cpg.lanes == 3;
  }
  for (int n = 1; n <= 4; ++n) EXPECT_NE(std::find(ns.begin(), ns.end(), n), ns.end()) << "N = " << n;
  EXPECT_TRUE(one_lane_plain && one_lane_reg && three_lanes);
}

TEST(CosimSilhouette, RandomAlphaAgreesForEveryBuildAndMode) {
  for (const std::string& name : alpha_builds()) {
    for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
      const CosimOptions o = build_options(name, mode, 0.3, 90 + static_cast<std::uint64_t>(sim::mode_code(mode)));
      std::vector<sim::TriangleFx> stream = random_triangles(24, o.seed, o.unit.format, 5);
      const std::array<std::size_t, 4> seen = assign_random_alpha(stream, o.seed, o.unit.format.alpha_bits);
      for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_GT(seen[i], 0u) << "alpha 0, 1, step, 1 - step: " << i;
      const CosimReport r = run_cosim(stream, o);
      SCOPED_TRACE(name + " " + std::string(to_string(mode)));
      EXPECT_TRUE(r.passed) << format_report(r, o);
      EXPECT_TRUE(r.counters_match);
      EXPECT_EQ(r.reference.beyond_bound, 0u) << r.reference.worst;
      if (!r.passed) return;
    }
  }
}

// Wuson from an eye behind its back, the silhouette rule's factors (crack-free per edge) in every
// partitioning, the blend on: the stream tessim cosim --silhouette sends.
TEST(CosimSilhouette, RealMeshInEveryPartitioning) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  const sim::HostScaling scaling = sim::host_scaling(mesh);
  for (const Partitioning p : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                               Partitioning::fractional_even}) {
    const CosimOptions o = build_options("n3_lat3", NormalMode::Quadratic, 0.1, 7);
    TessSettings s;
    s.kind = PatternKind::D3D11;
    s.source = FactorSource::Adaptive;
    s.rule = AdaptiveRule::Silhouette;
    s.partitioning = p;
    s.camera.eye = {1.9, 1.9, -2.7};
    s.camera.target = {0, 1.0, -0.9};
    s.camera.fov_deg = 30;
    s.outline_tolerance = 2.0;  // a short stream: fewer segments than the pictures' 0.5 px
    s.silhouette.enabled = true;
    s.silhouette.eye_from_camera = true;
    bind_silhouette(s, mesh);
    ASSERT_TRUE(s.silhouette_field);
    std::vector<sim::TriangleFx> stream;
    std::size_t blended = 0;
    for (std::size_t i = 0; i < mesh.triangle_count() && stream.size() < 400; i += 7) {
      std::optional<sim::TriangleFx> tri = sim::to_fixed(mesh, i, scaling, o.unit.format, s);
      if (!tri) continue;
      sim::set_silhouette_alpha(*tri, *s.silhouette_field, i, o.unit.format);
      for (std::uint32_t a : tri->alpha) blended += a != sim::kAlphaOne;
      tri->id = static_cast<std::uint32_t>(stream.size());
      stream.push_back(*tri);
    }
    ASSERT_GT(blended, 0u) << "the eye makes some edges flat or blended";
    const CosimReport r = run_cosim(stream, o);
    SCOPED_TRACE(partitioning_name(p));
    EXPECT_TRUE(r.passed) << format_report(r, o);
    EXPECT_EQ(r.reference.beyond_bound, 0u) << r.reference.worst;
  }
}

// Alpha the unit's contract excludes (not rounded to the build's bits) is refused before the run.
TEST(CosimSilhouette, AlphaNotRoundedToTheBuildsBitsIsRefused) {
  const CosimOptions o = build_options("n1_r4", NormalMode::Linear, 0.0, 1);  // alpha_bits 1
  std::vector<sim::TriangleFx> stream = random_triangles(2, 1, o.unit.format, 2);
  stream[1].alpha[2] = sim::kAlphaOne / 4;
  try {
    run_cosim(stream, o);
    FAIL() << "alpha 1/4 on a 1-bit build must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("alpha of edge 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessim::cosim
