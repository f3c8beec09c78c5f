// An adaptive workload (docs/patterns.md §7) through the RTL and the cycle model in lock-step:
// every triangle of a real mesh with its own factor from the camera, for every normal mode the
// unit implements, N = 1..4, with random backpressure.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>

#include "cosim/cosim.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/host.hpp"

namespace tessim::cosim {
namespace {

std::vector<sim::TriangleFx> adaptive_stream(const sim::NumberFormat& fmt, std::set<int>* factors) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/STL/sphereWithHole.stl");
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  // Close to one side of the sphere: near triangles get factors up to the maximum.
  const BoundingBox box = bounding_box(mesh);
  s.camera.eye = box.center() + glm::dvec3(0.0, 0.0, 0.9 * box.diagonal());
  s.camera.target = box.center();
  s.pixels_per_segment = 6.0;
  const std::vector<std::uint8_t> L = uniform_factors_covering(s, mesh);
  const sim::HostScaling scaling = sim::host_scaling(mesh);
  std::vector<sim::TriangleFx> stream;
  for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
    stream.push_back(sim::to_fixed(mesh, i, scaling, fmt, L[i]));
    factors->insert(L[i]);
  }
  return stream;
}

class AdaptiveCosim : public ::testing::TestWithParam<std::tuple<int, NormalMode>> {};

TEST_P(AdaptiveCosim, AgreesOnEveryCycle) {
  const auto [n, mode] = GetParam();
  CosimOptions o;
  o.unit.int_blocks = n;
  o.unit.normals = mode;
  o.unit.gpe_cycles = 2;
  o.unit.gpe_stall_prob = 0.25;
  o.unit.seed = 11;
  o.seed = 11;
  o.variant = std::string(1, 'n').append(std::to_string(n));
  std::set<int> factors;
  const std::vector<sim::TriangleFx> stream = adaptive_stream(o.unit.format, &factors);
  ASSERT_GT(factors.size(), 5u) << "the camera should give many different factors";
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
  EXPECT_EQ(r.triangles, stream.size());
}

INSTANTIATE_TEST_SUITE_P(
    NAndModes, AdaptiveCosim,
    ::testing::Combine(::testing::Values(1, 2, 3, 4),
                       ::testing::Values(NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear)),
    [](const auto& info) {
      std::string name(1, 'N');
      name.append(std::to_string(std::get<0>(info.param))).append(1, '_').append(to_string(std::get<1>(info.param)));
      return name;
    });

}  // namespace
}  // namespace tessim::cosim
