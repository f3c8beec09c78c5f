// The silhouette blend in fixed point (sim/values/cpg.hpp, alpha_bits > 0): alpha = 1 is plain PN
// bit for bit, alpha = 0 the flat triangle, any alpha follows the float blend
// (model/silhouette.hpp) within the tangent bound; the host's rounding of alpha; the extra CPG
// step; the unit's input contract; and a whole mesh through the cycle model against the float
// reference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "model/mesh_io.hpp"
#include "model/pn.hpp"
#include "model/silhouette.hpp"
#include "sim/run/simulate.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/error_bound.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

constexpr NormalMode kHardwareModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

NumberFormat with_alpha(int bits) {
  NumberFormat f;
  f.alpha_bits = bits;
  return f;
}

TriangleFx sample_triangle(std::mt19937_64& rng, const NumberFormat& f) {
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  TriangleFx tri;
  for (int v = 0; v < 3; ++v) {
    tri.p[v] = quantize(glm::dvec3(u(rng), u(rng), u(rng)), f);
    tri.n[v] = quantize(glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) + glm::dvec3(0, 0, 1.0)), f);
  }
  return tri;
}

// The float blend with the alpha the unit received.
PnPatch float_blend(const TriangleFx& tri, const NumberFormat& f, NormalMode mode) {
  const PnInput in = dequantized_input(tri, f);
  PatchSilhouette s;
  for (std::size_t e = 0; e < 3; ++e) {
    s.alpha[e] = std::ldexp(static_cast<double>(tri.alpha[e]), -kAlphaFracBits);
    s.normals[e] = in.n[e];
  }
  return make_silhouette_patch(in, s, mode);
}

TEST(SilhouetteFixed, AlphaOneIsPlainPnBitForBit) {
  std::mt19937_64 rng(5);
  for (int bits : {1, 5, 8, 16}) {
    const NumberFormat f = with_alpha(bits);
    for (int i = 0; i < 50; ++i) {
      const TriangleFx tri = sample_triangle(rng, f);  // alpha defaults to 1
      for (NormalMode mode : kHardwareModes) {
        const ControlPointsFx a = compute_control_points(tri, mode, f);
        const ControlPointsFx b = compute_control_points(tri, mode, NumberFormat{});
        EXPECT_EQ(a.b, b.b) << "alpha_bits " << bits;
        EXPECT_EQ(a.n, b.n);
      }
    }
  }
}

TEST(SilhouetteFixed, AlphaZeroIsTheFlatTriangleAndTheNormalsStay) {
  std::mt19937_64 rng(6);
  const NumberFormat f = with_alpha(8);
  const double lsb = f.coord_lsb();
  for (int i = 0; i < 50; ++i) {
    TriangleFx tri = sample_triangle(rng, f);
    tri.alpha = {0, 0, 0};
    for (NormalMode mode : kHardwareModes) {
      const ControlPointsFx cp = compute_control_points(tri, mode, f);
      const ControlPointsFx pn = compute_control_points(tri, mode, NumberFormat{});
      const PnInput in = dequantized_input(tri, f);
      // Every tangent point is (2 Pi + Pj) / 3, rounded once; b111 the centroid.
      for (int i3 = 0; i3 <= 3; ++i3)
        for (int j3 = 0; i3 + j3 <= 3; ++j3) {
          const int k3 = 3 - i3 - j3;
          const glm::dvec3 flat = (double(k3) * in.p[0] + double(i3) * in.p[1] + double(j3) * in.p[2]) / 3.0;
          EXPECT_LE(glm::length(dequantize(cp.b[net_index(i3, j3, 3)], f) - flat), 4 * lsb)
              << "b" << i3 << j3 << k3;
        }
      EXPECT_EQ(cp.n, pn.n) << "the normal field is the mode's, whatever alpha";
    }
  }
}

TEST(SilhouetteFixed, AnyAlphaFollowsTheFloatBlendWithinTheTangentBound) {
  std::mt19937_64 rng(7);
  for (int bits : {1, 4, 8, 16}) {
    const NumberFormat f = with_alpha(bits);
    const ErrorBudget budget = position_error_budget(f);
    const double tangent_bound = std::sqrt(3.0) * budget.tangent_lsb * f.coord_lsb();
    const double center_bound = std::sqrt(3.0) * budget.center_lsb * f.coord_lsb();
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::uint32_t step = std::uint32_t{1} << (kAlphaFracBits - bits);
    for (int i = 0; i < 80; ++i) {
      TriangleFx tri = sample_triangle(rng, f);
      for (std::uint32_t& a : tri.alpha) {
        const int pick = static_cast<int>(rng() % 5);
        a = pick == 0 ? step : pick == 1 ? kAlphaOne - step : pick == 2 ? 0 : quantize_alpha(u(rng), bits);
      }
      ASSERT_TRUE(alpha_in_contract(tri, f));
      for (NormalMode mode : kHardwareModes) {
        const ControlPointsFx cp = compute_control_points(tri, mode, f);
        const PnPatch ref = float_blend(tri, f, mode);
        for (int k = 0; k < 10; ++k) {
          const double err = glm::length(dequantize(cp.b[k], f) - ref.b[k]);
          EXPECT_LE(err, k == net_index(1, 1, 3) ? center_bound : tangent_bound)
              << "alpha_bits " << bits << " control point " << k;
        }
      }
    }
  }
}

TEST(SilhouetteFixed, HostRoundsAlphaToTheUnitsBits) {
  EXPECT_EQ(quantize_alpha(1.0, 8), kAlphaOne);
  EXPECT_EQ(quantize_alpha(0.0, 8), 0u);
  EXPECT_EQ(quantize_alpha(0.5, 1), kAlphaOne / 2);
  EXPECT_EQ(quantize_alpha(0.74, 1), kAlphaOne / 2);
  EXPECT_EQ(quantize_alpha(0.76, 1), kAlphaOne);
  EXPECT_EQ(quantize_alpha(std::ldexp(1.0, -9), 8), std::uint32_t{1} << 8) << "a tie rounds up";
  EXPECT_EQ(quantize_alpha(std::nan(""), 8), kAlphaOne) << "the reference's rule: no alpha, PN";
  EXPECT_EQ(quantize_alpha(7.0, 8), kAlphaOne);
  EXPECT_EQ(quantize_alpha(-1.0, 8), 0u);
  for (int bits = 1; bits <= kMaxAlphaBits; ++bits)
    for (double a : {0.0, 0.3, 0.5, 0.999, 1.0}) {
      const std::uint32_t q = quantize_alpha(a, bits);
      EXPECT_LE(std::abs(std::ldexp(double(q), -kAlphaFracBits) - a), std::ldexp(0.5, -bits));
      EXPECT_EQ(alpha_port_value(q, bits) << (kAlphaFracBits - bits), q) << "no bits below the unit's";
    }
}

TEST(SilhouetteFixed, TheBlendAddsAStepOnlyToTheLinearEdgeWithRegisteredProducts) {
  const NumberFormat plain{}, alpha = with_alpha(8);
  for (NormalMode mode : kHardwareModes)
    for (int lanes : {1, 3})
      for (int reg : {0, 1}) {
        const CpgVariant v{lanes, 4, 1, reg};
        const int extra = mode == NormalMode::Linear && reg ? (lanes == 1 ? 3 : 1) : 0;
        EXPECT_EQ(cpg_cycles(mode, alpha, v), cpg_cycles(mode, plain, v) + extra)
            << to_string(mode) << " lanes " << lanes << " product_reg " << reg;
      }
  EXPECT_EQ(cpg_edge_cycles(NormalMode::Linear, alpha, 1, true), 10);
}

TEST(SilhouetteFixed, TheUnitRefusesAlphaOutsideItsContract) {
  UnitConfig cfg;
  cfg.format = with_alpha(4);
  cfg.normals = NormalMode::Linear;
  Unit unit(cfg);
  UnitInputs in;
  in.tri_valid = true;
  in.tri.L = 2;
  in.tri.alpha = {kAlphaOne, kAlphaOne + 1, 0};
  try {
    unit.tick(in);
    FAIL() << "alpha above 1 must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("alpha of edge 1"), std::string::npos) << e.what();
  }
  in.tri.alpha = {kAlphaOne, 1u << 11, 0};  // below 2^-4: not rounded to 4 bits
  EXPECT_THROW(unit.tick(in), std::invalid_argument);
  in.tri.alpha = {kAlphaOne, 1u << 12, 0};
  EXPECT_NO_THROW(unit.tick(in));
  cfg.format = NumberFormat{};  // a unit without alpha ignores it
  Unit other(cfg);
  in.tri.alpha = {kAlphaOne + 5, 3, 0};
  EXPECT_NO_THROW(other.tick(in));
}

// A real mesh, an eye beside it: the cycle model's output against the float blend with the
// float alpha (mesh errors) and with the alpha it received (the derived bound, no vertex beyond);
// the blend changes the output where alpha < 1 and nothing where it is 1.
TEST(SilhouetteFixed, WholeMeshWithinTheBoundOfTheReference) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  const MeshSilhouette field(mesh, glm::dvec3(2.0, 1.5, -3.0), 0.25);
  ASSERT_GT(field.counts().flat, 0u);
  ASSERT_GT(field.counts().blended, 0u);
  UnitConfig cfg;
  cfg.format.alpha_bits = 8;
  cfg.tess_factor = 3;
  cfg.gpe_cycles = 1;
  for (NormalMode mode : kHardwareModes) {
    cfg.normals = mode;
    MeshPatterns patterns;
    patterns.silhouette = &field;
    SimHooks hooks;
    hooks.measure_errors = true;
    const SimResult blended = simulate(mesh, cfg, hooks, patterns);
    ASSERT_TRUE(blended.errors.has_value());
    EXPECT_EQ(blended.errors->arithmetic.beyond_bound, 0u) << to_string(mode) << ": " << blended.errors->arithmetic.worst;
    EXPECT_GT(blended.errors->arithmetic.stats.vertices, 0u);
    // Against the float alpha the host's rounding adds at most 2^-9 of a curve's offset.
    EXPECT_LT(blended.errors->mesh.position_max, 2e-3) << to_string(mode);
    const SimResult plain = simulate(mesh, cfg, hooks, MeshPatterns{});
    EXPECT_EQ(plain.unit.vertices_out, blended.unit.vertices_out);
    EXPECT_EQ(plain.unit.cycles, blended.unit.cycles) << "alpha costs no cycle in this CPG";
  }
}

}  // namespace
}  // namespace tessim::sim
