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
#include "sim/base/fixed.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"
#include "model/pn.hpp"

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

// Triangles whose output depends on the rounding of alpha w (w_alpha = round(alpha w / 2^A), not
// floor): the +1/2 moves a tangent point by an LSB only when its numerator lies within about N/3
// of a rounding boundary, some 2^-F / 3 of the points, so random streams never show it. They are
// searched for: the tangent point recomputed with alpha w truncated differs, and so does a vertex
// of the patch at L = 3.
std::vector<sim::TriangleFx> rounding_ties(const sim::NumberFormat& f, std::size_t want, std::uint64_t seed) {
  using sim::i128;
  const int F = f.coord_frac_bits, A = f.alpha_bits;
  const std::int64_t alphas = (std::int64_t{1} << A) - 1;  // 1 .. 2^A - 1: alpha 0 and 1 round exactly
  static constexpr std::array<std::array<int, 2>, 3> kSlots{{{net_index(1, 0, 3), net_index(2, 0, 3)},
                                                             {net_index(2, 1, 3), net_index(1, 2, 3)},
                                                             {net_index(0, 2, 3), net_index(0, 1, 3)}}};
  sim::SplitMix64 rng(seed);
  auto uni = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
  std::vector<sim::TriangleFx> found;
  for (std::uint64_t tries = 0; found.size() < want && tries < 20'000'000; ++tries) {
    sim::TriangleFx tri;
    for (int v = 0; v < 3; ++v) {
      tri.p[v] = sim::quantize(glm::dvec3(uni(-0.9, 0.9), uni(-0.9, 0.9), uni(-0.9, 0.9)), f);
      tri.n[v] = sim::quantize(glm::normalize(glm::dvec3(uni(-1, 1), uni(-1, 1), uni(-1, 1)) + glm::dvec3(0, 0, 1.5)), f);
    }
    tri.L = 3;
    for (int end = 0; end < 6; ++end) {
      const int e = end / 2, a = e, b = (e + 1) % 3;
      const bool near_b = end % 2;
      const sim::FxVec d{tri.p[b][0] - tri.p[a][0], tri.p[b][1] - tri.p[a][1], tri.p[b][2] - tri.p[a][2]};
      const sim::FxVec& pn = tri.p[near_b ? b : a];
      const sim::FxVec& pf = tri.p[near_b ? a : b];
      const sim::FxVec& nn = tri.n[near_b ? b : a];
      const i128 w = sim::dot_exact(d, nn);
      // The tangent point from a given alpha w (the CPG's formula, sim/values/cpg.cpp).
      auto tangent = [&](i128 wa) {
        sim::FxVec t{};
        std::uint8_t flags = 0;
        for (int c = 0; c < 3; ++c) {
          const i128 chord = (i128{2} * pn[c] + pf[c]) << (2 * F);
          t[c] = sim::mul_const(near_b ? chord + wa * nn[c] : chord - wa * nn[c], 3 * F, sim::one_third(f), f, flags);
        }
        return t;
      };
      for (int k = 0; k < std::min<std::int64_t>(alphas, 64); ++k) {
        const std::int64_t alpha = alphas <= 64 ? 1 + k : 1 + static_cast<std::int64_t>(rng.next() % static_cast<std::uint64_t>(alphas));
        const i128 rounded = sim::round_shift(alpha * w, A), truncated = (alpha * w) >> A;
        if (rounded == truncated) continue;
        const sim::FxVec wrong = tangent(truncated);
        if (wrong == tangent(rounded)) continue;
        // Visible: a vertex of the patch at L = 3 differs when that tangent point does.
        sim::TriangleFx tie = tri;
        tie.alpha[static_cast<std::size_t>(e)] = static_cast<std::uint32_t>(alpha) << (sim::kAlphaFracBits - A);
        const sim::ControlPointsFx cp = sim::compute_control_points(tie, NormalMode::Quadratic, f);
        sim::ControlPointsFx mutated = cp;
        mutated.b[static_cast<std::size_t>(kSlots[static_cast<std::size_t>(e)][near_b ? 1 : 0])] = wrong;
        bool visible = false;
        for (int j = 0; j <= 3 && !visible; ++j)
          for (int i = 0; j + i <= 3 && !visible; ++i)
            visible = sim::evaluate_vertex(cp, j, i, 3, 0, NormalMode::Quadratic, f) !=
                      sim::evaluate_vertex(mutated, j, i, 3, 0, NormalMode::Quadratic, f);
        if (!visible) continue;
        tie.id = static_cast<std::uint32_t>(found.size());
        found.push_back(tie);
        break;
      }
      if (found.size() == want) break;
    }
  }
  return found;
}

TEST(CosimSilhouette, RoundingTiesOfAlphaWAgreeOnEveryBuild) {
  for (const std::string& name : alpha_builds()) {
    const CosimOptions o = build_options(name, NormalMode::Quadratic, 0.2, 5);
    const std::vector<sim::TriangleFx> stream = rounding_ties(o.unit.format, 2, 17);
    SCOPED_TRACE(name);
    ASSERT_EQ(stream.size(), 2u) << "the search finds triangles whose output the +1/2 changes";
    const CosimReport r = run_cosim(stream, o);
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
