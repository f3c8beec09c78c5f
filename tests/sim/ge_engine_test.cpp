// The geometry engine as a shader machine (sim/ge/ge_cost.hpp, sim/ge/ge_evaluation.hpp): its
// cycles per vertex from the operation counts; --displace applied to the unit's output in float and
// charged on top of K; evaluation gpe (the DPG feeding the GE, no TE) against the float reference
// and the unit, its buffers and its statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "model/base/error.hpp"
#include "model/displace.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "sim/config/analytic.hpp"
#include "sim/ge/ge_cost.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
constexpr NormalMode kHardwareModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kWuson);
  return mesh;
}

// The first `n` triangles of Wuson (a short run).
Mesh wuson_part(std::size_t n) {
  Mesh m = wuson();
  m.triangles.resize(n);
  return m;
}

struct Output {
  std::vector<glm::dvec3> positions, normals;
  SimResult result;
};

Output run(const Mesh& mesh, const UnitConfig& cfg, const MeshPatterns& patterns = {}) {
  Output o;
  SimHooks hooks;
  hooks.on_patch = [&](const PatchOut& p) {
    o.positions.insert(o.positions.end(), p.positions.begin(), p.positions.end());
    o.normals.insert(o.normals.end(), p.normals.begin(), p.normals.end());
  };
  o.result = simulate(mesh, cfg, hooks, patterns);
  return o;
}

// Every point of the float reference (tessellate_mesh) for the same pattern and displacement.
Output reference(const Mesh& mesh, const TessSettings& s, NormalMode mode) {
  Output o;
  tessellate_mesh(mesh, s, mode, [&](const PatchView& v) {
    o.positions.insert(o.positions.end(), v.positions.begin(), v.positions.end());
    o.normals.insert(o.normals.end(), v.normals.begin(), v.normals.end());
  });
  return o;
}

double angle(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

struct Deviation {
  double position = 0.0, normal = 0.0;  // largest, relative to the diagonal / radians
};
Deviation deviation(const Output& a, const Output& b, double diagonal) {
  EXPECT_EQ(a.positions.size(), b.positions.size());
  Deviation d;
  for (std::size_t i = 0; i < std::min(a.positions.size(), b.positions.size()); ++i) {
    d.position = std::max(d.position, glm::length(a.positions[i] - b.positions[i]) / diagonal);
    d.normal = std::max(d.normal, angle(a.normals[i], b.normals[i]));
  }
  return d;
}

TEST(GeCost, CyclesAreTheIssueSlotsOverTheLanesRoundedUp) {
  UnitConfig cfg;
  for (const DisplaceKind kind : {DisplaceKind::Sine, DisplaceKind::Noise}) {
    const GeOps ops = displacement_ops(kind);
    for (int lanes : {1, 2, 3, 4, 7, 16, 256}) {
      for (int sfu : {1, 4, 9}) {
        cfg.ge_alu_lanes = lanes;
        cfg.ge_sfu_cost = sfu;
        cfg.ge_lookup_cost = 2;
        const std::uint64_t slots = static_cast<std::uint64_t>(ops.alu + ops.sfu * sfu + ops.lookup * 2);
        EXPECT_EQ(ge_slots(ops, cfg), slots);
        const int cycles = ge_cycles(ops, cfg);
        // The fewest whole cycles that hold the slots.
        EXPECT_GE(static_cast<std::uint64_t>(cycles) * static_cast<std::uint64_t>(lanes), slots);
        EXPECT_LT(static_cast<std::uint64_t>(cycles - 1) * static_cast<std::uint64_t>(lanes), slots);
      }
    }
  }
  EXPECT_EQ(displacement_ops(DisplaceKind::None), GeOps{});
  // Noise does the sine's Blinn normal and more: it can never be cheaper.
  EXPECT_GT(displacement_ops(DisplaceKind::Noise).alu, displacement_ops(DisplaceKind::Sine).alu);
  // Linear mode evaluates three corner normals instead of six control normals.
  EXPECT_LT(evaluation_ops(NormalMode::Linear).alu, evaluation_ops(NormalMode::Quadratic).alu);
  EXPECT_EQ(evaluation_ops(NormalMode::Reflect), evaluation_ops(NormalMode::Quadratic));
}

TEST(GeCost, VertexCostSplitsIntoKEvaluationAndDisplacement) {
  UnitConfig cfg;
  cfg.gpe_cycles = 5;
  GeVertexCost c = ge_vertex_cost(cfg, DisplaceKind::None);
  EXPECT_EQ(c, (GeVertexCost{5, 0, 0}));
  c = ge_vertex_cost(cfg, DisplaceKind::Sine);
  EXPECT_EQ(c.base, 5);
  EXPECT_EQ(c.evaluation, 0);
  EXPECT_EQ(c.displacement, ge_cycles(displacement_ops(DisplaceKind::Sine), cfg));
  cfg.evaluation = Evaluation::Gpe;
  c = ge_vertex_cost(cfg, DisplaceKind::Noise);
  EXPECT_EQ(c.evaluation, ge_cycles(evaluation_ops(cfg.normals), cfg));
  // One program: the slots of both rounded up once.
  const GeOps e = evaluation_ops(cfg.normals), d = displacement_ops(DisplaceKind::Noise);
  EXPECT_EQ(c.total(), 5 + ge_cycles(GeOps{e.alu + d.alu, e.sfu + d.sfu, e.lookup + d.lookup}, cfg));
  EXPECT_LE(c.displacement, ge_cycles(d, cfg));
  EXPECT_EQ(with_ge_cost(cfg, c).gpe_cycles, c.total());
}

TEST(SimDisplace, OutputIsTheUnitsOutputDisplacedInFloat) {
  const Mesh mesh = wuson_part(300);
  UnitConfig cfg;
  cfg.tess_factor = 5;
  const Output plain = run(mesh, cfg);
  for (const DisplaceSettings d : {DisplaceSettings{DisplaceKind::Sine, 0.03, 45.0},
                                   DisplaceSettings{DisplaceKind::Noise, 0.02, 12.0}}) {
    MeshPatterns patterns;
    patterns.displace = d;
    const Output displaced = run(mesh, cfg, patterns);
    ASSERT_EQ(displaced.positions.size(), plain.positions.size());
    for (std::size_t i = 0; i < plain.positions.size(); ++i) {
      const DisplacedPoint want = displace(d, plain.positions[i], plain.normals[i]);
      ASSERT_EQ(displaced.positions[i], want.position) << i;
      ASSERT_EQ(displaced.normals[i], want.normal) << i;
    }
    // The GE is the limit at K = 8: every vertex takes K plus the displacement's cycles.
    const GeVertexCost cost = displaced.result.ge;
    EXPECT_EQ(cost.base, cfg.gpe_cycles);
    EXPECT_EQ(cost.displacement, ge_cycles(displacement_ops(d.kind), cfg));
    const std::uint64_t v = displaced.result.unit.vertices_out;
    EXPECT_EQ(displaced.result.gpe[GpeClass::Busy], (v - 1) * static_cast<std::uint64_t>(cost.total()) + 1);
    EXPECT_GT(displaced.result.unit.cycles, plain.result.unit.cycles);
    EXPECT_EQ(displaced.result.unit.vertices_out, plain.result.unit.vertices_out);
  }
}

TEST(SimDisplace, StaysWithinOneHundredThousandthOfTheDiagonalOfTheReference) {
  const Mesh& mesh = wuson();
  const double diagonal = bounding_box(mesh).diagonal();
  for (const NormalMode mode : kHardwareModes) {
    for (const DisplaceSettings d : {DisplaceSettings{DisplaceKind::Sine, 0.05, 40.0},
                                     DisplaceSettings{DisplaceKind::Noise, 0.02, 10.0}}) {
      UnitConfig cfg;
      cfg.tess_factor = 4;
      cfg.normals = mode;
      MeshPatterns patterns;
      patterns.displace = d;
      TessSettings s;
      s.L = 4;
      s.displace = d;
      const Deviation dev = deviation(run(mesh, cfg, patterns), reference(mesh, s, mode), diagonal);
      EXPECT_LE(dev.position, 1e-5) << to_string(mode) << " " << to_string(d.kind);
      // The unit's own normal error (about 0.013 degrees at these widths) perturbed by Blinn's term.
      EXPECT_LE(dev.normal, 0.1 * M_PI / 180.0) << to_string(mode) << " " << to_string(d.kind);
    }
  }
}

TEST(SimDisplace, PointsPushedFarOutsideTheUnitsRangeStayFiniteAndExact) {
  // The GE computes in float after the unit: an amplitude ten times the mesh moves points far
  // outside the unit's [-1, 1] coordinates, and nothing saturates or becomes NaN.
  const Mesh mesh = wuson_part(50);
  UnitConfig cfg;
  cfg.tess_factor = 3;
  const Output plain = run(mesh, cfg);
  const double diagonal = bounding_box(wuson()).diagonal();
  MeshPatterns patterns;
  patterns.displace = {DisplaceKind::Sine, 10.0 * diagonal, 7.0};
  const Output far = run(mesh, cfg, patterns);
  double farthest = 0.0;
  for (std::size_t i = 0; i < far.positions.size(); ++i) {
    ASSERT_TRUE(std::isfinite(far.positions[i].x) && std::isfinite(far.positions[i].y) && std::isfinite(far.positions[i].z));
    ASSERT_NEAR(glm::length(far.normals[i]), 1.0, 1e-12);
    farthest = std::max(farthest, glm::length(far.positions[i] - plain.positions[i]));
  }
  EXPECT_GT(farthest, 2.0 * diagonal);
}

TEST(SimDisplace, AVanishedNormalKeepsItsPoint) {
  const std::vector<glm::dvec3> positions{{1.0, 2.0, 3.0}, {0.5, 0.0, 0.0}};
  const std::vector<glm::dvec3> normals{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  std::vector<glm::dvec3> got_p, got_n;
  const auto sink = displaced(
      [&](const PatchOut& p) {
        got_p.assign(p.positions.begin(), p.positions.end());
        got_n.assign(p.normals.begin(), p.normals.end());
      },
      DisplaceSettings{DisplaceKind::Sine, 0.1, 3.0});
  sink(PatchOut{0, 1, positions, normals, {}});
  ASSERT_EQ(got_p.size(), 2u);
  EXPECT_EQ(got_p[0], positions[0]);
  EXPECT_EQ(got_n[0], normals[0]);
  EXPECT_EQ(got_p[1], displace({DisplaceKind::Sine, 0.1, 3.0}, positions[1], normals[1]).position);
}

UnitConfig ge_evaluation(int L, CpgMapping mapping = CpgMapping::Dedicated) {
  UnitConfig cfg;
  cfg.tess_factor = L;
  cfg.evaluation = Evaluation::Gpe;
  cfg.cpg_mapping = mapping;
  cfg.validate("test");
  return cfg;
}

TEST(GeEvaluation, HostControlPointsGiveTheFloatReferenceBitForBit) {
  const Mesh mesh = wuson_part(400);
  for (const NormalMode mode : kHardwareModes) {
    UnitConfig cfg = ge_evaluation(6, CpgMapping::Host);
    cfg.normals = mode;
    TessSettings s;
    s.L = 6;
    const Output got = run(mesh, cfg), want = reference(mesh, s, mode);
    ASSERT_EQ(got.positions.size(), want.positions.size());
    // The DPG's weights i/L in B = 16 bits are the reference's i/L rounded: the same points to
    // the rounding of the weight (2^-17 of an edge), not bit for bit at every L.
    const Deviation d = deviation(got, want, bounding_box(mesh).diagonal());
    EXPECT_LE(d.position, 1e-5) << to_string(mode);
    EXPECT_LE(d.normal, 1e-4) << to_string(mode);
  }
  // L = 4: every weight is exact in binary, so the GE evaluates exactly the reference's points.
  TessSettings s;
  s.L = 4;
  const Output got = run(mesh, ge_evaluation(4, CpgMapping::Host)), want = reference(mesh, s, NormalMode::Quadratic);
  EXPECT_EQ(got.positions, want.positions);
  EXPECT_EQ(got.normals, want.normals);
}

TEST(GeEvaluation, CpgControlPointsStayWithinTheUnitsErrorOfTheReference) {
  const Mesh& mesh = wuson();
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.partitioning = Partitioning::fractional_odd;
  s.outer = {3.5f, 5.25f, 2.0f};
  s.inner = 4.5f;
  const Output got = run(mesh, ge_evaluation(4), MeshPatterns(&s)), want = reference(mesh, s, NormalMode::Quadratic);
  const Deviation d = deviation(got, want, bounding_box(mesh).diagonal());
  EXPECT_LE(d.position, 1e-5);
  EXPECT_LE(d.normal, 0.05 * M_PI / 180.0);
  // The GE-mapped CPG computes the same fixed-point control points, on the GE's spare cycles.
  const Output gpe_cpg = run(mesh, ge_evaluation(4, CpgMapping::Gpe), MeshPatterns(&s));
  EXPECT_EQ(gpe_cpg.positions, got.positions);
  EXPECT_GT(gpe_cpg.result.unit.cycles, got.result.unit.cycles);
}

TEST(GeEvaluation, TheGeEvaluatingEveryPointIsTheLimitAtLargeFactors) {
  const Mesh mesh = wuson_part(40);
  const UnitConfig cfg = ge_evaluation(16);
  const Output o = run(mesh, cfg);
  const SimResult& r = o.result;
  const int per_vertex = cfg.gpe_cycles + ge_cycles(evaluation_ops(cfg.normals), cfg);
  EXPECT_EQ(r.ge.total(), per_vertex);
  const std::uint64_t v = r.unit.vertices_out;
  EXPECT_EQ(v, 40u * 153u);
  // The GE never waits once it started: one vertex every K + E cycles, after the first patch's CPG.
  EXPECT_EQ(r.gpe[GpeClass::Busy], (v - 1) * static_cast<std::uint64_t>(per_vertex) + 1);
  EXPECT_LE(r.unit.cycles, (v - 1) * static_cast<std::uint64_t>(per_vertex) + 1 + static_cast<std::uint64_t>(r.cpg_cycles) + 8);
  // The analytic model knows there is no TE: the GE's K + E bounds the run, and its run length
  // is the measured one within a patch's CPG.
  const AnalyticPrediction p = predict(with_ge_cost(cfg, r.ge), r.cpg_cycles);
  EXPECT_EQ(p.bottleneck, std::string("gpe"));
  EXPECT_EQ(p.int_issue, 0.0);
  EXPECT_NEAR(p.run_cycles(40), static_cast<double>(r.unit.cycles), static_cast<double>(r.cpg_cycles));
  // No INT blocks; the DPG hands out each point in exactly one cycle.
  EXPECT_EQ(r.unit.int_blocks, 0);
  EXPECT_EQ(r.unit.te[TeClass::Busy], v);
}

TEST(GeEvaluation, ABufferHoldsItsPatchUntilTheGeAcceptedItsLastPointAndStallsLoseNothing) {
  // A fast CPG (three lanes, a whole quotient per cycle) writes a patch long before the GE has
  // evaluated the one before, and the VTX FIFO holds several patches' points: a buffer freed when
  // the DPG hands out the last point (not when the GE accepts it) would be overwritten under the
  // points still waiting, and they would come out of the next patch.
  const Mesh mesh = wuson_part(60);
  UnitConfig two = ge_evaluation(1);
  two.cpg = CpgVariant{3, 24};
  two.vtx_fifo_depth = 8;
  UnitConfig one = two;
  one.cp_buffers = 1;
  const Output a = run(mesh, two), b = run(mesh, one);
  ASSERT_LT(a.result.cpg_cycles, 3 * a.result.ge.total());
  TessSettings s;
  s.L = 1;
  const Output want = reference(mesh, s, NormalMode::Quadratic);
  const double diagonal = bounding_box(wuson()).diagonal();
  EXPECT_LE(deviation(a, want, diagonal).position, 1e-5);
  EXPECT_LE(deviation(b, want, diagonal).position, 1e-5);
  EXPECT_EQ(b.positions, a.positions);
  EXPECT_EQ(b.normals, a.normals);
  EXPECT_GE(b.result.unit.cycles, a.result.unit.cycles);
  UnitConfig stalls = two;
  stalls.gpe_stall_prob = 0.4;
  stalls.seed = 7;
  const Output c = run(mesh, stalls);
  EXPECT_EQ(c.positions, a.positions);
  EXPECT_GT(c.result.gpe[GpeClass::Stalled], 0u);
}

TEST(GeEvaluation, HostMappingNeedsGpeEvaluation) {
  UnitConfig cfg;
  cfg.cpg_mapping = CpgMapping::Host;
  EXPECT_THROW(cfg.validate("test"), InputError);
  cfg.evaluation = Evaluation::Gpe;
  EXPECT_NO_THROW(cfg.validate("test"));
  cfg.cpg.copies = 2;
  EXPECT_THROW(cfg.validate("test"), InputError);
}

}  // namespace
}  // namespace tessim::sim
