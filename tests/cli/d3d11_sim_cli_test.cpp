// `tessim sim` with the D3D11 pattern in the unit (docs/patterns.md §8): fixed and adaptive
// factors give the model's pattern, vertex for vertex and triangle for triangle, within the
// arithmetic's error of the float reference; the welded output is watertight; chunked runs
// write the same file; bad combinations are input errors.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <utility>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "model/d3d11_pattern.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;

const char* const kSphere = "/usr/share/assimp/models/STL/sphereWithHole.stl";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(D3D11SimCli, FixedFactorsGiveTheReferencePattern) {
  TempDir dir;
  const fs::path sim_out = dir.path() / "sim.obj", ref_out = dir.path() / "ref.obj", stats = dir.path() / "s.json";
  const std::vector<std::string> pattern = {"--outer", "2,3.5,5", "--inner", "4", "--partitioning", "fractional_odd"};
  std::vector<std::string> sim_args = {"sim", kSphere, "-o", sim_out.string(), "--stats", stats.string()};
  std::vector<std::string> ref_args = {"tessellate", kSphere, "-o", ref_out.string()};
  sim_args.insert(sim_args.end(), pattern.begin(), pattern.end());
  ref_args.insert(ref_args.end(), pattern.begin(), pattern.end());
  auto r = run_tessim(sim_args, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("D3D11 pattern fractional_odd outer 2,3.5,5 inner 4"), std::string::npos) << r.out;
  r = run_tessim(ref_args, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const Mesh sim = load_mesh(sim_out), ref = load_mesh(ref_out);
  ASSERT_EQ(sim.triangles, ref.triangles);  // the same points in the same order, the same triangles
  ASSERT_EQ(sim.positions.size(), ref.positions.size());
  const double diagonal = bounding_box(ref).diagonal();
  double worst = 0;
  for (std::size_t i = 0; i < sim.positions.size(); ++i)
    worst = std::max(worst, glm::length(sim.positions[i] - ref.positions[i]) / diagonal);
  EXPECT_LT(worst, 1e-5) << "the unit's fixed point against the float reference";
  const nlohmann::json j = nlohmann::json::parse(slurp(stats));
  EXPECT_EQ(j["workload"]["pattern"], "fractional_odd outer 2,3.5,5 inner 4");
  const D3D11Pattern p = d3d11_tri_pattern({2.0f, 3.5f, 5.0f}, 4.0f, Partitioning::fractional_odd);
  EXPECT_EQ(j["vertices_out"].get<std::uint64_t>(), load_mesh(kSphere).triangle_count() * p.points.size());
}

TEST(D3D11SimCli, AdaptiveWeldedOutputIsWatertightAndChunksAgree) {
  TempDir dir;
  const fs::path one = dir.path() / "one.ply", two = dir.path() / "two.ply";
  const std::vector<std::string> base = {"sim", kSphere, "--adaptive", "screen", "--camera", "eye=0,0,40,fov=30",
                                         "--pixels-per-segment", "6", "--partitioning", "fractional_even", "--weld"};
  auto args = base;
  args.insert(args.end(), {"-o", one.string()});
  auto r = run_tessim(args, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  // Welding the unit's bit-identical shared vertices leaves the model's watertight count.
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.partitioning = Partitioning::fractional_even;
  s.camera.eye = {0, 0, 40};
  s.camera.fov_deg = 30;
  s.pixels_per_segment = 6;
  const Mesh mesh = load_mesh(kSphere);
  PatternCache cache(s);
  const TessellationCounts c = count_tessellation(mesh, cache);
  const Mesh welded = load_mesh(one);
  EXPECT_EQ(welded.triangle_count(), c.triangles);
  EXPECT_LT(welded.positions.size(), c.vertices) << "shared vertices are written once";
  // No crack: every edge of the welded output is shared by two triangles except those on the
  // input's own boundary (the sphere's hole), which are exactly its boundary edges' segments.
  auto edge_uses = [](const Mesh& m) {
    std::map<std::pair<unsigned, unsigned>, int> uses;
    for (const glm::uvec3& t : m.triangles)
      for (int e = 0; e < 3; ++e)
        if (t[e] != t[(e + 1) % 3]) ++uses[std::minmax(t[e], t[(e + 1) % 3])];
    return uses;
  };
  const auto input_uses = edge_uses(mesh);
  std::uint64_t boundary_segments = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const PatchFactors f = patch_factors(s, mesh, t);
    const D3D11Factors d = d3d11_tri_factors(f.outer, f.inner, s.partitioning);
    const glm::uvec3& tri = mesh.triangles[t];
    // outer[0]: corners 0 and 2, outer[1]: 0 and 1, outer[2]: 1 and 2.
    const std::pair<unsigned, unsigned> edges[3] = {std::minmax(tri[0], tri[2]), std::minmax(tri[0], tri[1]),
                                                    std::minmax(tri[1], tri[2])};
    for (int e = 0; e < 3; ++e)
      if (input_uses.at(edges[e]) == 1) boundary_segments += static_cast<std::uint64_t>(d.outer_points[e] - 1);
  }
  ASSERT_GT(boundary_segments, 0u) << "sphereWithHole has a hole";
  std::uint64_t once = 0;
  for (const auto& [edge, n] : edge_uses(welded)) once += n == 1;
  EXPECT_EQ(once, boundary_segments);
  args = base;
  args.insert(args.end(), {"-o", two.string(), "--chunks", "2"});
  r = run_tessim(args, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(one), slurp(two)) << "a chunked run writes the same file";
}

TEST(D3D11SimCli, BadCombinationsAreInputErrors) {
  TempDir dir;
  auto r = run_tessim({"sim", kSphere, "--partitioning", "fractional_odd", "--bary-bits", "12"}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bary_bits"), std::string::npos) << r.err;
  r = run_tessim({"sim", kSphere, "--inner", "3"}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--inner"), std::string::npos) << r.err;
  r = run_tessim({"cosim", kSphere, "--outer", "0,2,2"}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("every patch is culled"), std::string::npos) << r.err;
  r = run_tessim({"cosim", kSphere, "--partitioning", "mixed"}, dir.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("needs --random"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tessim
