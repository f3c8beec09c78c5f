// `tessim sim --errors` (sim/run/reference_check.hpp): the end-to-end figures equal a direct
// comparison of the simulated mesh with `tessellate_mesh`'s output, vertex by vertex; the
// arithmetic check holds every vertex within its derived bound at the default widths and
// catches a vertex that is off by more than the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/error_bound.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const Mesh& sphere() {
  static const Mesh mesh = load_mesh("/usr/share/assimp/models/STL/sphereWithHole.stl");
  return mesh;
}

// The figures recomputed from the two output meshes, independently of MeshErrors.
ErrorStats direct_errors(const Mesh& mesh, const UnitConfig& cfg) {
  std::vector<glm::dvec3> sim_pos, sim_nrm, ref_pos, ref_nrm;
  SimHooks hooks;
  hooks.on_patch = [&](const PatchOut& p) {
    sim_pos.insert(sim_pos.end(), p.positions.begin(), p.positions.end());
    sim_nrm.insert(sim_nrm.end(), p.normals.begin(), p.normals.end());
  };
  simulate(mesh, cfg, hooks);
  tessellate_mesh(mesh, cfg.tess_factor, cfg.normals, [&](const PatchView& v) {
    ref_pos.insert(ref_pos.end(), v.positions.begin(), v.positions.end());
    ref_nrm.insert(ref_nrm.end(), v.normals.begin(), v.normals.end());
  });
  EXPECT_EQ(sim_pos.size(), ref_pos.size());
  const double diagonal = bounding_box(mesh).diagonal();
  ErrorStats e;
  double pos2 = 0, ang2 = 0;
  for (std::size_t i = 0; i < std::min(sim_pos.size(), ref_pos.size()); ++i) {
    const double d = glm::length(sim_pos[i] - ref_pos[i]) / diagonal;
    e.position_max = std::max(e.position_max, d);
    pos2 += d * d;
    ++e.vertices;
    if (glm::length(sim_nrm[i]) > 0) {
      const double a = std::atan2(glm::length(glm::cross(sim_nrm[i], ref_nrm[i])), glm::dot(sim_nrm[i], ref_nrm[i]));
      e.normal_angle_max = std::max(e.normal_angle_max, a);
      ang2 += a * a;
      ++e.normals_compared;
    }
  }
  e.position_rms = std::sqrt(pos2 / static_cast<double>(e.vertices));
  e.normal_angle_rms = std::sqrt(ang2 / static_cast<double>(e.normals_compared));
  return e;
}

class SimErrors : public ::testing::TestWithParam<NormalMode> {};

TEST_P(SimErrors, EqualTheDirectComparisonOfTheTwoMeshes) {
  UnitConfig cfg;
  cfg.normals = GetParam();
  cfg.tess_factor = 5;
  cfg.format.coord_frac_bits = 14;  // coarse enough that every error is well above zero
  SimHooks hooks;
  hooks.measure_errors = true;
  const SimResult r = simulate(sphere(), cfg, hooks);
  ASSERT_TRUE(r.errors.has_value());
  const ErrorStats want = direct_errors(sphere(), cfg);
  const ErrorStats& got = r.errors->mesh;
  EXPECT_EQ(got.vertices, want.vertices);
  EXPECT_EQ(got.normals_compared, want.normals_compared);
  EXPECT_GT(got.position_max, 0.0);
  EXPECT_NEAR(got.position_max, want.position_max, 1e-15);
  EXPECT_NEAR(got.position_rms, want.position_rms, 1e-15);
  EXPECT_NEAR(got.normal_angle_max, want.normal_angle_max, 1e-12);
  EXPECT_NEAR(got.normal_angle_rms, want.normal_angle_rms, 1e-12);

  // The arithmetic alone stays within its bound, and below the end-to-end figure (which adds
  // the input quantization and the barycentric rounding).
  const ArithmeticErrors& a = r.errors->arithmetic;
  EXPECT_EQ(a.stats.vertices, want.vertices);
  EXPECT_EQ(a.beyond_bound, 0u) << a.worst;
  EXPECT_LE(a.stats.position_max, got.position_max * 1.0001 + 1e-300);
}

INSTANTIATE_TEST_SUITE_P(Modes, SimErrors,
                         ::testing::Values(NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(ArithmeticCheck, CatchesAPositionOffByMoreThanTheBound) {
  UnitConfig cfg;
  cfg.tess_factor = 3;
  const Mesh& mesh = sphere();
  const HostScaling scaling = host_scaling(mesh);
  ArithmeticCheck check = ArithmeticCheck::for_mesh(mesh, scaling, cfg);
  std::vector<VertexFx> vertices;
  SimHooks hooks;
  hooks.on_vertex = [&](const VertexFx& v) {
    if (vertices.size() < 10) vertices.push_back(v);
  };
  simulate(mesh, cfg, hooks);
  ASSERT_EQ(vertices.size(), 10u);
  for (const VertexFx& v : vertices) EXPECT_TRUE(check.check(v));
  // A few LSBs more than the bound allows, on one coordinate of one vertex.
  VertexFx bad = vertices[4];
  const double lsb = std::ldexp(1.0, -cfg.format.coord_frac_bits);
  bad.pos[1] += static_cast<std::int64_t>(std::ceil(position_error_budget(cfg.format).position_units / lsb)) + 2;
  EXPECT_FALSE(check.check(bad));
  const ArithmeticErrors r = check.result();
  EXPECT_EQ(r.beyond_bound, 1u);
  EXPECT_NE(r.worst.find("position error"), std::string::npos) << r.worst;
}

}  // namespace
}  // namespace tessim::sim
