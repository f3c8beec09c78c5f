// `tessim info` and `tessim sim` count the same vertices as carrying tags: info names the count
// sim warns of (vertices whose tags change the surface: tagged or corner-like) beside the tagged
// vertices (crease vector non-zero) alone, and gives no σ/β/|Δ| range over no tagged vertex.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using testing::run_tessim;
using testing::TempDir;
using testing::TessimRun;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A tetrahedron whose vertex 0 is tagged (a crease vector) and vertex 1 corner-like (θ > 0).
fs::path tagged_tetrahedron(const fs::path& dir, bool with_tagged) {
  const fs::path path = dir / (with_tagged ? "mixed.ply" : "corners.ply");
  std::ofstream out(path);
  out << "ply\nformat ascii 1.0\nelement vertex 4\n";
  for (const char* p : {"x", "y", "z", "dx", "dy", "dz", "sigma", "theta", "beta"}) out << "property double " << p << "\n";
  out << "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  out << (with_tagged ? "0 0 0 1 0 0 0.5 0 0.25\n" : "0 0 0 0 0 0 0 0 0\n");
  out << "1 0 0 0 0 0 0 1 0\n0 1 0 0 0 0 0 0 0\n0 0 1 0 0 0 0 0 0\n";
  out << "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  return path;
}

std::string sim_warning(const fs::path& mesh, const TempDir& d) {
  const TessimRun s = run_tessim({"sim", mesh.string(), "-L", "1"}, d.path());
  EXPECT_EQ(s.status, 0) << s.err;
  return s.err;
}

TEST(InfoTags, CountsWhatSimWarnsOfBesideTheTaggedVertices) {
  TempDir d;
  const fs::path mesh = tagged_tetrahedron(d.path(), true);
  const TessimRun text = run_tessim({"info", mesh.string()}, d.path());
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_TRUE(contains(text.out, "vertices with tags    2 (")) << text.out;
  EXPECT_TRUE(contains(text.out, "tagged vertices       1 (")) << text.out;
  EXPECT_TRUE(contains(text.out, "corner-like vertices  1 (")) << text.out;
  EXPECT_TRUE(contains(text.out, "sigma                 0.5 .. 0.5 (tagged vertices)")) << text.out;
  EXPECT_TRUE(contains(sim_warning(mesh, d), ": tags: 2 vertices carry scalar tags")) << "the same count as info";
  const TessimRun json = run_tessim({"info", "--json", mesh.string()}, d.path());
  const nlohmann::json tags = nlohmann::json::parse(json.out)["tags"];
  EXPECT_EQ(tags["acting"], 2);
  EXPECT_EQ(tags["tagged"], 1);
  EXPECT_EQ(tags["corner_like"], 1);
}

TEST(InfoTags, NoRangesOverNoTaggedVertex) {
  TempDir d;
  const fs::path mesh = tagged_tetrahedron(d.path(), false);
  const TessimRun text = run_tessim({"info", mesh.string()}, d.path());
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_TRUE(contains(text.out, "vertices with tags    1 (")) << text.out;
  EXPECT_TRUE(contains(text.out, "tagged vertices       0 (")) << text.out;
  EXPECT_FALSE(contains(text.out, "sigma                 0 .. 0")) << text.out;
  EXPECT_TRUE(contains(text.out, "sigma, beta, |crease vector|  none: no tagged vertex")) << text.out;
  EXPECT_TRUE(contains(sim_warning(mesh, d), ": tags: 1 vertices carry scalar tags"));
  const TessimRun json = run_tessim({"info", "--json", mesh.string()}, d.path());
  const nlohmann::json tags = nlohmann::json::parse(json.out)["tags"];
  EXPECT_TRUE(tags["sigma"].is_null()) << tags;
  EXPECT_TRUE(tags["beta"].is_null()) << tags;
  EXPECT_TRUE(tags["delta_length"].is_null()) << tags;
  EXPECT_EQ(tags["theta"], nlohmann::json({0.0, 1.0}));
}

}  // namespace
}  // namespace tessim
