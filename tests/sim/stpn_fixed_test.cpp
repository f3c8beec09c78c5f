// The scalar-tagged control points in fixed point (sim/values/cpg.hpp, compute_control_points with
// tags): neutral tags give plain PN bit for bit, the result follows the float reference
// (model/pn.hpp make_stpn_patch) to within the format's precision, and shared edges of real
// ST-meshes come out bit-identical from both patches.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "model/base/error.hpp"
#include "model/mesh_io.hpp"
#include "model/pn.hpp"
#include "model/stpn_import.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const NumberFormat kFormat{};  // Q3.20
constexpr NormalMode kHardwareModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

TriangleFx sample_triangle(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  TriangleFx tri;
  for (int v = 0; v < 3; ++v) {
    tri.p[v] = quantize(glm::dvec3(u(rng), u(rng), u(rng)), kFormat);
    tri.n[v] = quantize(glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) + glm::dvec3(0, 0, 1.0)), kFormat);
  }
  tri.L = 4;
  return tri;
}

double largest_difference(const ControlPointsFx& cp, const PnPatch& ref, NormalMode mode) {
  double worst = 0.0;
  for (int i = 0; i < 10; ++i) worst = std::max(worst, glm::length(dequantize(cp.b[i], kFormat) - ref.b[i]));
  if (mode == NormalMode::Linear) return worst;
  // The unit stores the normal net at twice its Bernstein value.
  for (int i = 0; i < 6; ++i)
    worst = std::max(worst, glm::length(dequantize(cp.n[i], kFormat) - 2.0 * ref.n_bern[i]));
  return worst;
}

TEST(StpnFixed, NeutralTagsGivePlainPnBitForBit) {
  std::mt19937_64 rng(7);
  for (NormalMode mode : kHardwareModes)
    for (int trial = 0; trial < 200; ++trial) {
      const TriangleFx plain = sample_triangle(rng);
      TriangleFx tagged = plain;
      // σ and β act only with Δ != 0: a vertex with them but no Δ and no θ is neutral.
      tagged.tags[trial % 3].sigma = quantize(0.7, kFormat);
      tagged.tags[(trial + 1) % 3].beta = quantize(-0.4, kFormat);
      const ControlPointsFx a = compute_control_points(plain, mode, kFormat);
      const ControlPointsFx b = compute_control_points(tagged, mode, kFormat);
      ASSERT_EQ(a.b, b.b);
      ASSERT_EQ(a.n, b.n);
      ASSERT_EQ(a.flags, b.flags);
    }
}

TEST(StpnFixed, FollowsTheFloatReferenceForEveryKindOfTag) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  struct Case {
    const char* name;
    double sigma, theta, beta;
    bool delta0, delta1;  // which corners carry a crease vector
  };
  const Case cases[] = {
      {"sigma 0", 0.0, 0.0, 0.0, true, false},         {"sigma 1", 1.0, 0.0, 0.0, true, false},
      {"sigma 0.5", 0.5, 0.0, 0.0, true, false},       {"theta only", 0.0, 0.6, 0.0, false, false},
      {"theta and sigma", 1.0, -0.5, 0.0, true, false}, {"beta on a crease edge", 1.0, 0.0, 0.7, true, true},
      {"crease edge", 1.0, 0.3, -0.2, true, true},
  };
  for (NormalMode mode : kHardwareModes)
    for (const Case& c : cases)
      for (int trial = 0; trial < 100; ++trial) {
        TriangleFx tri = sample_triangle(rng);
        std::array<VertexTags, 3> tags{};
        for (int v = 0; v < 2; ++v) {
          const bool crease = v == 0 ? c.delta0 : c.delta1;
          VertexTags t;
          if (crease) {
            // A crease vector roughly across the normal, |Δ| up to 1.
            const glm::dvec3 n = dequantize(tri.n[v], kFormat);
            glm::dvec3 across = glm::cross(n, glm::dvec3(unit(rng), unit(rng), unit(rng)));
            t.delta = 0.8 * glm::normalize(across);
          }
          t.sigma = c.sigma;
          t.theta = c.theta;
          t.beta = c.beta;
          tri.tags[v] = {quantize(t.delta, kFormat), quantize(t.sigma, kFormat), quantize(t.theta, kFormat),
                         quantize(t.beta, kFormat)};
          // The reference takes the tags the unit received.
          tags[v] = {dequantize(tri.tags[v].delta, kFormat), t.sigma, t.theta, t.beta};
        }
        const ControlPointsFx cp = compute_control_points(tri, mode, kFormat);
        const PnPatch ref = make_stpn_patch(dequantized_input(tri, kFormat), tags, mode);
        ASSERT_EQ(cp.flags & kFlagSaturated, 0) << c.name;
        // A few LSB of 2^-20 per rounding; the normalizations of short vectors lose the most.
        EXPECT_LT(largest_difference(cp, ref, mode), 64.0 * std::ldexp(1.0, -20)) << c.name << " " << to_string(mode);
      }
}

// Real ST-meshes: every point on a shared edge is bit-identical in both patches, and the
// vertices follow the scalar-tagged float reference.
TEST(StpnFixed, RealStMeshesAreCrackFreeAndAccurate) {
  for (const char* file : {"/usr/share/assimp/models/Collada/Cinema4D.dae", "/usr/share/assimp/models/OBJ/spider.obj",
                           "/usr/share/assimp/models/X/BCN_Epileptic.X"}) {
    const Mesh mesh = import_st_mesh(file, StImportOptions{}).mesh;
    ASSERT_TRUE(mesh.has_tags()) << file;
    const HostScaling scaling = host_scaling(mesh);
    for (NormalMode mode : kHardwareModes) {
      const int L = 4;
      UnitConfig cfg;
      cfg.normals = mode;
      MeshErrors errors(mesh, scaling, cfg, true);
      MeshErrors plain_errors(mesh, scaling, cfg, false);  // the same mesh as plain PN
      std::map<std::tuple<unsigned, unsigned, int>, FxVec> seen;
      std::size_t shared = 0, cracks = 0, tagged_patches = 0;
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (const VertexFx& v : evaluate_patch(to_fixed(mesh, t, scaling, kFormat, L), mode, kFormat))
          plain_errors.add(v);
        const TriangleFx tri = to_fixed(mesh, t, scaling, kFormat, L, true);
        tagged_patches += !(tri.tags[0].neutral() && tri.tags[1].neutral() && tri.tags[2].neutral());
        const glm::uvec3 corners = mesh.triangles[t];
        for (const VertexFx& v : evaluate_patch(tri, mode, kFormat)) {
          errors.add(v);
          // Which edge the lattice point lies on, and how far along it from its first corner.
          int edge = -1, step = 0;
          if (v.k == 0) edge = 0, step = v.j;
          else if (v.j + v.k == L) edge = 1, step = v.k;
          else if (v.j == 0) edge = 2, step = L - v.k;
          if (edge < 0) continue;
          const unsigned a = corners[edge], b = corners[(edge + 1) % 3];
          if (a == b) continue;
          const auto key = a < b ? std::make_tuple(a, b, step) : std::make_tuple(b, a, L - step);
          const auto [it, inserted] = seen.emplace(key, v.pos);
          if (!inserted) {
            ++shared;
            cracks += it->second != v.pos;
          }
        }
      }
      EXPECT_GT(tagged_patches, 20u) << file;
      EXPECT_GT(shared, mesh.triangles.size()) << file;
      EXPECT_EQ(cracks, 0u) << file << " " << to_string(mode);
      // Positions within a few LSB (relative to the diagonal); normals as good as plain PN's on
      // the same mesh, whose worst vertices sit on short edges (docs/number-formats.md §5.2).
      const ErrorStats e = errors.result(), plain = plain_errors.result();
      EXPECT_LT(e.position_max, 1e-5) << file << " " << to_string(mode);
      EXPECT_LE(e.normal_angle_max, std::max(1.5 * plain.normal_angle_max, 1e-4)) << file << " " << to_string(mode);
      std::printf("%s %s: position max %.3g rms %.3g (plain %.3g), normal max %.3g rms %.3g rad (plain %.3g %.3g)\n",
                  file, std::string(to_string(mode)).c_str(), e.position_max, e.position_rms, plain.position_max,
                  e.normal_angle_max, e.normal_angle_rms, plain.normal_angle_max, plain.normal_angle_rms);
    }
  }
}

TEST(StpnFixed, SigmaBeyondTheFormatIsBadInput) {
  Mesh mesh = import_st_mesh("/usr/share/assimp/models/Collada/Cinema4D.dae", StImportOptions{}).mesh;
  std::size_t t = 0;
  while (mesh.tags[mesh.triangles[t][0]].delta == glm::dvec3(0.0)) ++t;
  mesh.tags[mesh.triangles[t][0]].sigma = 9.0;  // Q3.20 holds values below 8
  EXPECT_THROW(to_fixed(mesh, t, host_scaling(mesh), kFormat, 4, true), InputError);
  EXPECT_NO_THROW(to_fixed(mesh, t, host_scaling(mesh), kFormat, 4, false));  // tags not taken
}

}  // namespace
}  // namespace tessim::sim

// ---- the cycle model with a CPG that takes tags (cpg_tags) ----------------------------------

namespace tessim::sim {
namespace {

TEST(StpnCycleModel, TagCyclesFollowTheSchedule) {
  TriangleFx tri;
  const NumberFormat f{};  // W = 24: D = 24 at r = 1, 6 at r = 4
  EXPECT_EQ(cpg_tag_cycles(tri, f), 0);  // neutral: plain PN, no extra cycle
  tri.tags[0].delta = {1, 0, 0};
  // face normal 2 + side 1 + three normalizations of 2 + 2D + two tangent points of 4 cycles
  EXPECT_EQ(cpg_tag_cycles(tri, f, {1, 1}), 2 + 1 + 3 * (2 + 48) + 2 * 4);
  EXPECT_EQ(cpg_tag_cycles(tri, f, {1, 4}), 2 + 1 + 3 * (2 + 12) + 2 * 4);
  EXPECT_EQ(cpg_tag_cycles(tri, f, {3, 1}), 2 + 1 + 3 * (2 + 48) + 4);  // one corner, one tangent per lane
  tri.tags[1].delta = {0, 1, 0};
  tri.tags[2].theta = 5;  // θ only: X alone
  EXPECT_EQ(cpg_tag_cycles(tri, f, {1, 1}), 2 + 2 * (1 + 3 * 50) + 50 + 6 * 4);
  EXPECT_EQ(cpg_tag_cycles(tri, f, {3, 1}), 2 + (1 + 3 * 50) + 2 * 4);
}

struct TaggedRun {
  SimResult result;
  std::vector<VertexFx> vertices;
};

TaggedRun run(const Mesh& mesh, UnitConfig cfg, bool fast_forward = true) {
  TaggedRun r;
  SimHooks hooks;
  hooks.fast_forward = fast_forward;
  hooks.on_vertex = [&](const VertexFx& v) { r.vertices.push_back(v); };
  r.result = simulate(mesh, cfg, hooks);
  return r;
}

TEST(StpnCycleModel, TaggedRunsComputeTheFixedPointArithmeticAndTakeTheirCycles) {
  const Mesh mesh = import_st_mesh("/usr/share/assimp/models/Collada/Cinema4D.dae", StImportOptions{}).mesh;
  for (const CpgVariant variant : {CpgVariant{1, 1}, CpgVariant{3, 4}}) {
    UnitConfig cfg;
    cfg.tess_factor = 3;
    cfg.cpg = variant;
    cfg.validate();
    const TaggedRun plain = run(mesh, cfg);
    cfg.cpg_tags = 1;
    const TaggedRun tagged = run(mesh, cfg);
    const HostScaling scaling = host_scaling(mesh);
    std::vector<VertexFx> expected;
    std::uint64_t tag_cycles = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const TriangleFx tri = to_fixed(mesh, t, scaling, cfg.format, cfg.tess_factor, true);
      tag_cycles += static_cast<std::uint64_t>(cpg_tag_cycles(tri, cfg.format, variant));
      for (const VertexFx& v : evaluate_patch(tri, cfg.normals, cfg.format)) expected.push_back(v);
    }
    ASSERT_EQ(tagged.vertices.size(), expected.size());
    EXPECT_TRUE(tagged.vertices == expected) << "the cycle model's vertices are the datapath's";
    EXPECT_FALSE(plain.vertices == expected) << "the tags change the surface";
    EXPECT_GT(tag_cycles, 0u);
    EXPECT_EQ(tagged.result.cpg_tag_cycles, tag_cycles);
    EXPECT_EQ(plain.result.cpg_tag_cycles, 0u);
    // With the sequential CPG the workload is CPG-bound: the added cycles show in the run; the
    // fast CPG (three lanes, r = 4) hides them behind the geometry engine.
    if (variant == CpgVariant{1, 1}) EXPECT_GT(tagged.result.unit.cycles, plain.result.unit.cycles + tag_cycles / 2);
    else EXPECT_GE(tagged.result.unit.cycles, plain.result.unit.cycles);
    EXPECT_EQ(tagged.result.unit.cpg[CpgClass::Busy], plain.result.unit.cpg[CpgClass::Busy] + tag_cycles);

    // Fast-forward stays exact with tags.
    const TaggedRun slow = run(mesh, cfg, false);
    EXPECT_EQ(slow.result.unit, tagged.result.unit);
    EXPECT_EQ(slow.result.gpe, tagged.result.gpe);
    EXPECT_TRUE(slow.vertices == tagged.vertices);
  }
}

TEST(StpnCycleModel, AnUntaggedMeshRunsAlikeWithAndWithoutTheTaggedCpg) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  UnitConfig cfg;
  cfg.tess_factor = 2;
  const TaggedRun a = run(mesh, cfg);
  cfg.cpg_tags = 1;
  const TaggedRun b = run(mesh, cfg);
  EXPECT_EQ(a.result.unit, b.result.unit);
  EXPECT_TRUE(a.vertices == b.vertices);
  EXPECT_EQ(b.result.cpg_tag_cycles, 0u);
}

}  // namespace
}  // namespace tessim::sim
