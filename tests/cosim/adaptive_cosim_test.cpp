// An adaptive workload (docs/patterns.md §7) through the RTL and the cycle model in lock-step:
// every triangle of a real mesh with its own D3D11 factors from the camera, which the unit
// takes per patch, for every partitioning, N = 1..4, every normal mode the unit implements,
// with random backpressure.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>

#include "cosim/cosim.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/values/host.hpp"

namespace tessim::cosim {
namespace {

std::vector<sim::TriangleFx> adaptive_stream(const sim::NumberFormat& fmt, Partitioning p, std::set<int>* sizes) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/STL/sphereWithHole.stl");
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.partitioning = p;
  // Close to one side of the sphere: near triangles get large factors, far ones small.
  const BoundingBox box = bounding_box(mesh);
  s.camera.eye = box.center() + glm::dvec3(0.0, 0.0, 0.9 * box.diagonal());
  s.camera.target = box.center();
  s.pixels_per_segment = 12.0;
  const sim::HostScaling scaling = sim::host_scaling(mesh);
  std::vector<sim::TriangleFx> stream;
  for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
    const std::optional<sim::TriangleFx> tri = sim::to_fixed(mesh, i, scaling, fmt, s);
    EXPECT_TRUE(tri.has_value()) << "adaptive factors never cull";
    if (!tri) continue;
    stream.push_back(*tri);
    sizes->insert(sim::patch_vertex_count(*tri));
  }
  return stream;
}

constexpr NormalMode kModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

class AdaptiveCosim : public ::testing::TestWithParam<std::tuple<int, Partitioning>> {};

TEST_P(AdaptiveCosim, AgreesOnEveryCycle) {
  const auto [n, partitioning] = GetParam();
  CosimOptions o;
  o.unit.int_blocks = n;
  o.unit.normals = kModes[(n + static_cast<int>(partitioning)) % 3];
  o.unit.gpe_cycles = 2;
  o.unit.gpe_stall_prob = 0.25;
  o.unit.seed = 11;
  o.seed = 11;
  o.variant = std::string(1, 'n').append(std::to_string(n));
  std::set<int> sizes;
  const std::vector<sim::TriangleFx> stream = adaptive_stream(o.unit.format, partitioning, &sizes);
  // pow2 rounds the factors to 1, 2, 4, ..., 64: fewer sizes than the other partitionings.
  ASSERT_GE(sizes.size(), 4u) << "the camera should give patches of many sizes";
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
  EXPECT_EQ(r.triangles, stream.size());
}

INSTANTIATE_TEST_SUITE_P(
    NAndPartitionings, AdaptiveCosim,
    ::testing::Combine(::testing::Values(1, 2, 3, 4),
                       ::testing::Values(Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                         Partitioning::fractional_even)),
    [](const auto& info) {
      std::string name = "N";
      name += std::to_string(std::get<0>(info.param));
      name += '_';
      name += partitioning_name(std::get<1>(info.param));
      return name;
    });

}  // namespace
}  // namespace tessim::cosim
