// The tessim binary as a user runs it: `tessim info` and `tessim tessellate` (real meshes:
// docs/verification.md; bad input: docs/architecture.md, Bad input).
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "tests/support/temp_dir.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;

const fs::path kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

using tessim::testing::TempDir;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct RunResult {
  int status = -1;
  std::string out, err;
};

// Runs tessim with `args` (each quoted for the shell), capturing stdout and stderr.
RunResult tessim(const std::vector<std::string>& args, const fs::path& scratch) {
  std::string command = quote(TESSIM_BINARY);
  for (const std::string& a : args) {
    command += ' ';
    command += quote(a);
  }
  const fs::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  command += " >";
  command += quote(out.string());
  command += " 2>";
  command += quote(err.string());
  const int raw = std::system(command.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

// Streams of the captured output live beside the outputs: keep them in their own directory.
struct CliDirs {
  TempDir scratch;  // stdout/stderr captures
  TempDir work;     // where the command writes
};

TEST(CliInfo, PrintsCountsOfWuson) {
  if (!fs::exists(kWuson)) FAIL() << kWuson << " is missing: scripts/setup.sh installs assimp-testmodels";
  TempDir scratch;
  const RunResult r = tessim({"info", kWuson.string()}, scratch.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("triangles             3732"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vertices              2117"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("normals               file"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("diagonal              3.6973894"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliInfo, JsonOutput) {
  const fs::path off = "/usr/share/assimp/models/OFF/Wuson.off";
  if (!fs::exists(off)) FAIL() << off << " is missing: scripts/setup.sh installs assimp-testmodels";
  TempDir scratch;
  const RunResult r = tessim({"info", "--json", off.string()}, scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("file"), off.string());
  EXPECT_EQ(j.at("vertices"), 2117);
  EXPECT_EQ(j.at("triangles"), 3732);
  EXPECT_EQ(j.at("normals"), "computed");
  EXPECT_EQ(j.at("degenerate_triangles"), 0);
  EXPECT_EQ(j.at("zero_length_edges"), 0);
  EXPECT_EQ(j.at("normal_fallbacks"), 0);
  EXPECT_NEAR(j.at("diagonal").get<double>(), 3.697389, 1e-6);
  EXPECT_NEAR(j.at("bbox").at("min")[0].get<double>(), -0.459976, 1e-6);
  EXPECT_NEAR(j.at("bbox").at("max")[2].get<double>(), 1.622242, 1e-6);
}

TEST(CliInfo, BadInputExitsNonZeroWithMessage) {
  CliDirs d;
  const fs::path bad = d.work.path() / "bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
  const RunResult r = tessim({"info", bad.string()}, d.scratch.path());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("tessim: error: " + bad.string() + ": face at line 4: vertex index 4 out of range"),
            std::string::npos)
      << r.err;
}

// Each run must fail, say why on stderr, and leave the work directory as it was.
void expect_refused(const std::vector<std::string>& args, const std::vector<std::string>& message_parts,
                    const CliDirs& d) {
  const RunResult r = tessim(args, d.scratch.path());
  EXPECT_NE(r.status, 0);
  for (const std::string& part : message_parts) EXPECT_NE(r.err.find(part), std::string::npos) << "stderr: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(d.work.path())) left.push_back(e.path().filename().string());
  EXPECT_TRUE(left.empty()) << "files created: " << ::testing::PrintToString(left);
}

// -o - streams binary PLY to standard output, byte for byte what -o OUT.ply writes, with the
// summary on standard error; welded too, as `sim -o - --weld` does.
TEST(CliTessellate, StandardOutputCarriesTheSameBytesAsAFile) {
  CliDirs d;
  const fs::path file = d.work.path() / "out.ply";
  const RunResult to_file = tessim({"tessellate", kWuson.string(), "-L", "5", "-o", file.string()}, d.scratch.path());
  ASSERT_EQ(to_file.status, 0) << to_file.err;
  const RunResult piped = tessim({"tessellate", kWuson.string(), "-L", "5", "-o", "-"}, d.scratch.path());
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_TRUE(piped.out == slurp(file)) << piped.out.size() << " bytes on stdout";
  EXPECT_NE(piped.err.find("standard output: 3732 patches"), std::string::npos) << piped.err;
  const fs::path welded = d.work.path() / "welded.ply";
  ASSERT_EQ(tessim({"tessellate", kWuson.string(), "-o", welded.string(), "--weld"}, d.scratch.path()).status, 0);
  const RunResult weld = tessim({"tessellate", kWuson.string(), "-o", "-", "--weld"}, d.scratch.path());
  ASSERT_EQ(weld.status, 0) << weld.err;
  EXPECT_TRUE(weld.out == slurp(welded)) << weld.out.size() << " bytes on stdout";
  EXPECT_NE(weld.err.find("welded: "), std::string::npos) << weld.err;
}

TEST(CliTessellate, RefusesBadInputWithoutWritingAnything) {
  if (!fs::exists(kWuson)) FAIL() << kWuson << " is missing: scripts/setup.sh installs assimp-testmodels";
  CliDirs d;
  const std::string out_ply = (d.work.path() / "out.ply").string();

  expect_refused({"tessellate", (d.work.path() / "missing.ply").string(), "-o", out_ply},
                 {"missing.ply", "does not exist"}, d);

  TempDir inputs;
  const fs::path truncated = inputs.path() / "truncated.ply";
  {
    const std::string wuson = slurp(kWuson);
    std::ofstream(truncated, std::ios::binary) << wuson.substr(0, wuson.size() / 2);
  }
  expect_refused({"tessellate", truncated.string(), "-o", out_ply}, {"truncated.ply", "element 'vertex'", "truncated"}, d);

  expect_refused({"tessellate", kWuson.string(), "-L", "0", "-o", out_ply}, {"-L", "0 is outside 1..64"}, d);
  expect_refused({"tessellate", kWuson.string(), "-L", "65", "-o", out_ply}, {"-L", "65 is outside 1..64"}, d);
  expect_refused({"tessellate", kWuson.string(), "-L", "four", "-o", out_ply}, {"four"}, d);
  expect_refused({"tessellate", kWuson.string(), "-o", (d.work.path() / "out.stl").string()},
                 {"out.stl", "unsupported extension '.stl'"}, d);
  expect_refused({"tessellate", kWuson.string(), "--normals", "phong", "-o", out_ply}, {"--normals", "'phong'"}, d);
  expect_refused({"tessellate", kWuson.string(), "-o", (d.work.path() / "no_dir" / "out.ply").string()},
                 {"no_dir/out.ply", "cannot open for writing"}, d);
  expect_refused({"tessellate", kWuson.string()}, {"--output"}, d);
}

struct PlyFile {
  std::vector<glm::dvec3> positions, normals;
  std::vector<glm::uvec3> triangles;
};

// Reads the binary PLY that MeshWriter writes (double x y z nx ny nz, uchar/uint faces),
// checking that the header is exactly that.
PlyFile read_tessim_ply(const fs::path& path) {
  const std::string data = slurp(path);
  const std::size_t end = data.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(data.substr(0, end));
  std::vector<std::string> lines;
  for (std::string line; std::getline(header, line);)
    if (line.rfind("comment", 0) != 0) lines.push_back(line);
  std::size_t vertices = 0, faces = 0;
  EXPECT_EQ(lines.size(), 11u);
  if (lines.size() != 11u) return {};
  EXPECT_EQ(lines[0], "ply");
  EXPECT_EQ(lines[1], "format binary_little_endian 1.0");
  EXPECT_EQ(std::sscanf(lines[2].c_str(), "element vertex %zu", &vertices), 1);
  const char* props[] = {"x", "y", "z", "nx", "ny", "nz"};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(lines[3 + static_cast<std::size_t>(i)], std::string("property double ") + props[i]);
  EXPECT_EQ(std::sscanf(lines[9].c_str(), "element face %zu", &faces), 1);
  EXPECT_EQ(lines[10], "property list uchar uint vertex_indices");

  const std::size_t body = end + std::strlen("end_header\n");
  EXPECT_EQ(data.size(), body + vertices * 48 + faces * 13);
  if (data.size() != body + vertices * 48 + faces * 13) return {};
  PlyFile ply;
  const char* p = data.data() + body;
  for (std::size_t v = 0; v < vertices; ++v, p += 48) {
    double x[6];
    std::memcpy(x, p, sizeof x);
    ply.positions.emplace_back(x[0], x[1], x[2]);
    ply.normals.emplace_back(x[3], x[4], x[5]);
  }
  for (std::size_t f = 0; f < faces; ++f, p += 13) {
    EXPECT_EQ(static_cast<unsigned char>(*p), 3u);
    std::uint32_t idx[3];
    std::memcpy(idx, p + 1, sizeof idx);
    ply.triangles.emplace_back(idx[0], idx[1], idx[2]);
  }
  return ply;
}

PlyFile read_tessim_obj(const fs::path& path) {
  PlyFile obj;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    char* rest = nullptr;
    if (line.rfind("v ", 0) == 0 || line.rfind("vn ", 0) == 0) {
      const char* s = line.c_str() + (line[1] == ' ' ? 2 : 3);
      glm::dvec3 x;
      x.x = std::strtod(s, &rest);
      x.y = std::strtod(rest, &rest);
      x.z = std::strtod(rest, &rest);
      (line[1] == ' ' ? obj.positions : obj.normals).push_back(x);
    } else if (line.rfind("f ", 0) == 0) {
      unsigned a, a2, b, b2, c, c2;
      EXPECT_EQ(std::sscanf(line.c_str(), "f %u//%u %u//%u %u//%u", &a, &a2, &b, &b2, &c, &c2), 6) << line;
      EXPECT_TRUE(a == a2 && b == b2 && c == c2) << line;
      obj.triangles.emplace_back(a - 1, b - 1, c - 1);
    }
  }
  return obj;
}

// Every vertex of the file is the PN surface (and normal field) of its input triangle at its
// domain point, recomputed here by Bernstein sums from the original mesh.
void expect_pn_surface(const PlyFile& file, const Mesh& mesh, int L, NormalMode mode) {
  const std::size_t nv = static_cast<std::size_t>(pattern_vertex_count(L));
  const std::size_t nt = static_cast<std::size_t>(pattern_triangle_count(L));
  ASSERT_EQ(file.positions.size(), mesh.triangle_count() * nv);
  ASSERT_EQ(file.normals.size(), file.positions.size());
  ASSERT_EQ(file.triangles.size(), mesh.triangle_count() * nt);
  const double tol = 1e-9 * bounding_box(mesh).diagonal();
  const std::vector<DomainPoint> domain = pattern_points(L);
  const std::vector<glm::uvec3> topology = pattern_triangles(L);
  double worst_position = 0.0, worst_normal = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    PnInput in;
    for (int c = 0; c < 3; ++c) {
      in.p[static_cast<std::size_t>(c)] = mesh.positions[mesh.triangles[t][c]];
      in.n[static_cast<std::size_t>(c)] = mesh.normals[mesh.triangles[t][c]];
    }
    const PnPatch patch = make_patch(in, mode);
    for (std::size_t i = 0; i < nv; ++i) {
      const PnVertex expected = eval_bernstein(patch, static_cast<double>(domain[i].j) / L, static_cast<double>(domain[i].k) / L);
      worst_position = std::max(worst_position, glm::length(file.positions[t * nv + i] - expected.position));
      worst_normal = std::max(worst_normal, glm::length(file.normals[t * nv + i] - expected.normal));
    }
    for (std::size_t k = 0; k < nt; ++k)
      ASSERT_EQ(file.triangles[t * nt + k], topology[k] + glm::uvec3(static_cast<unsigned>(t * nv))) << t << " " << k;
  }
  EXPECT_LE(worst_position, tol);
  EXPECT_LE(worst_normal, 1e-9);
  char measured[128];
  std::snprintf(measured, sizeof measured, "position %.3g of the diagonal, normal %.3g",
                worst_position / bounding_box(mesh).diagonal(), worst_normal);
  ::testing::Test::RecordProperty("worst_deviation", measured);
}

TEST(CliTessellate, WusonPlyVerticesLieOnThePnSurface) {
  if (!fs::exists(kWuson)) FAIL() << kWuson << " is missing: scripts/setup.sh installs assimp-testmodels";
  CliDirs d;
  const fs::path out = d.work.path() / "w4.ply";
  const RunResult r = tessim({"tessellate", kWuson.string(), "-L", "4", "-o", out.string()}, d.scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, out.string() +
                       ": 3732 patches, 55980 vertices, 59712 triangles, 783720 INT ops, 0 degenerate events "
                       "(L=4, quadratic normals)\n");
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(d.work.path())) left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"w4.ply"}) << "no temporary left behind";
  expect_pn_surface(read_tessim_ply(out), load_mesh(kWuson), 4, NormalMode::Quadratic);
}

TEST(CliTessellate, ObjOutputIsExactToo) {
  const fs::path off = "/usr/share/assimp/models/OFF/Wuson.off";
  if (!fs::exists(off)) FAIL() << off << " is missing: scripts/setup.sh installs assimp-testmodels";
  CliDirs d;
  const fs::path out = d.work.path() / "w3.obj";
  const RunResult r = tessim({"tessellate", off.string(), "-L", "3", "--normals", "linear", "-o", out.string()}, d.scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  // 10 vertices per patch, 11 INT operations per vertex in linear mode.
  EXPECT_NE(r.out.find("3732 patches, 37320 vertices, 33588 triangles, 410520 INT ops"), std::string::npos) << r.out;
  expect_pn_surface(read_tessim_obj(out), load_mesh(off), 3, NormalMode::Linear);
}

TEST(CliTessellate, DefaultsAreL4Quadratic) {
  const fs::path stl = "/usr/share/assimp/models/STL/sphereWithHole.stl";
  if (!fs::exists(stl)) FAIL() << stl << " is missing: scripts/setup.sh installs assimp-testmodels";
  CliDirs d;
  const fs::path out = d.work.path() / "s.ply";
  const RunResult r = tessim({"tessellate", stl.string(), "--output", out.string()}, d.scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("285 patches, 4275 vertices, 4560 triangles, 59850 INT ops, 0 degenerate events (L=4, quadratic normals)"),
            std::string::npos)
      << r.out;
  expect_pn_surface(read_tessim_ply(out), load_mesh(stl), 4, NormalMode::Quadratic);
}

TEST(CliTessellate, WarnsAboutDegenerateInput) {
  CliDirs d;
  const fs::path in = d.work.path() / "degenerate.obj";
  // A good triangle and one with a repeated position (a zero-length edge, zero area).
  std::ofstream(in) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nf 1 2 3\nf 1 4 2\n";
  const fs::path out = d.work.path() / "d.obj";
  const RunResult r = tessim({"tessellate", in.string(), "-L", "2", "-o", out.string()}, d.scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("tessim: warning: " + in.string() + ": 1 zero-area input triangles, 1 mid-edge normal fallbacks"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("2 patches, 12 vertices, 8 triangles"), std::string::npos) << r.out;
  const PlyFile obj = read_tessim_obj(out);
  ASSERT_EQ(obj.positions.size(), 12u);
  for (const glm::dvec3& n : obj.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
}

}  // namespace
}  // namespace tessim
