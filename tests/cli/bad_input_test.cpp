// Bad input as a user meets it (docs/architecture.md, Bad input): every case ends with
// "tessim: error: FILE-OR-FLAG: ELEMENT: REASON" on stderr, exit status 2 and no file written;
// a killed run leaves no temporary behind.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "sim/version.hpp"

#include "tests/support/input_error.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using testing::run_tessim;
using testing::TempDir;
using testing::TessimRun;
using testing::Dirs;
using testing::entries_text;
using testing::expect_input_error;

const fs::path kCube = "/usr/share/assimp/models/OFF/Cube.off";
const fs::path kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

// ---------------------------------------------------------------------------------------------
// Outputs: every path is checked and opened before anything is computed or moved into place.

TEST(BadOutput, UnwritableStatsLeavesNoMeshAndNoTrace) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const TessimRun r = run_tessim({"sim", kCube.string(), "-o", d.at("out.ply").string(), "--trace",
                                  d.at("trace.json").string(), "--stats", d.at("missing/stats.json").string()},
                                 d.scratch.path());
  expect_input_error(r, {"stats.json", "--stats", "does not exist"});
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

TEST(BadOutput, StatsPathThatIsADirectory) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  fs::create_directory(d.at("stats.json"));
  const TessimRun r = run_tessim({"sim", kCube.string(), "-o", d.at("out.ply").string(), "--stats",
                                  d.at("stats.json").string()},
                                 d.scratch.path());
  expect_input_error(r, {"stats.json", "is a directory"});
  EXPECT_EQ(d.work.entries(), std::vector<std::string>{"stats.json"});
}

TEST(BadOutput, TheSamePathForTwoOutputs) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const TessimRun r = run_tessim({"sim", kCube.string(), "--trace", d.at("a.json").string(), "--stats",
                                  d.work.path().string() + "/./a.json"},
                                 d.scratch.path());
  expect_input_error(r, {"a.json", "--stats", "another output"});
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

TEST(BadOutput, TessellateAndRenderIntoADirectory) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  fs::create_directory(d.at("out.ply"));
  fs::create_directory(d.at("out.png"));
  expect_input_error(run_tessim({"tessellate", kCube.string(), "-o", d.at("out.ply").string()}, d.scratch.path()),
                     {"out.ply", "is a directory"});
  expect_input_error(run_tessim({"render", kCube.string(), "--size", "64x64", "-o", d.at("out.png").string()},
                                d.scratch.path()),
                     {"out.png", "is a directory"});
  expect_input_error(run_tessim({"render", kCube.string(), "--size", "64x64", "-o", d.at("no/out.png").string()},
                                d.scratch.path()),
                     {"out.png", "-o", "does not exist"});
  EXPECT_EQ(d.work.entries().size(), 2u) << entries_text(d.work);
  EXPECT_TRUE(fs::is_empty(d.at("out.ply")));
  EXPECT_TRUE(fs::is_empty(d.at("out.png")));
}

// ---------------------------------------------------------------------------------------------
// Configuration files.

TEST(BadConfig, NumberBeyondJsonNamesFileAndKey) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const fs::path config = d.scratch.write("big.json", "{\"tess_factor\": 4, \"int_blocks\": 1e400}\n");
  const TessimRun r = run_tessim({"sim", kCube.string(), "--config", config.string(), "--stats",
                                  d.at("stats.json").string()},
                                 d.scratch.path());
  expect_input_error(r, {"big.json: int_blocks: ", "1e400"});
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

TEST(BadConfig, DirectoryAndMissingFile) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  expect_input_error(run_tessim({"sim", kCube.string(), "--config", d.work.path().string()}, d.scratch.path()),
                     {d.work.path().string() + ": file: is a directory"});
  expect_input_error(run_tessim({"sim", kCube.string(), "--config", d.at("none.json").string()}, d.scratch.path()),
                     {"none.json: file: does not exist"});
  const fs::path bad = d.scratch.write("bad.json", "{\"int_blocks\": }\n");
  expect_input_error(run_tessim({"sim", kCube.string(), "--config", bad.string()}, d.scratch.path()),
                     {"bad.json: JSON: "});
}

// ---------------------------------------------------------------------------------------------
// Command-line syntax: the same form and status as every other bad input.

TEST(BadCommandLine, ValuesThatAreNotNumbersOrDoNotFit) {
  Dirs d;
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"sim", "-L", "abc"}, {"command line: --tess-factor: 'abc' is not an integer"}},
      {{"sim", "-L", "99999999999999"}, {"command line: --tess-factor: '99999999999999' is outside 1..64"}},
      {{"sim", "--stall", "abc"}, {"command line: --gpe-stall-prob: 'abc' is not a number"}},
      {{"sim", "--stall", "nan"}, {"'nan' is not a finite number"}},
      {{"sim", "--stall", "1e999"}, {"'1e999' is outside"}},
      {{"sim", "--seed", "-1"}, {"--seed: '-1' is outside"}},
      {{"sim", "--trace-cycles", "x"}, {"--trace-cycles: 'x' is not an integer"}},
      {{"tessellate", "in.obj", "-o", "out.ply", "-L", "4.5"}, {"command line: -L: '4.5' is not an integer"}},
      {{"render", "in.obj", "-o", "out.png", "--azimuth", "inf"}, {"command line: --azimuth: 'inf' is not a finite number"}},
      {{"bench", "--int", "1", "x"}, {"--int: 'x' is not an integer"}},
      {{"bench", "--repeat", "99999999999"}, {"--repeat: '99999999999' is outside"}},
      {{"sim", "--no-such-option"}, {"command line: arguments: ", "--no-such-option"}},
      {{"tessellate", "in.obj"}, {"command line: arguments: ", "--output is required"}},
      {{"frobnicate"}, {"command line: frobnicate: not a tessim command"}},
  };
  for (const auto& [args, expected] : cases) {
    std::string line;
    for (const std::string& a : args) line += " " + a;
    SCOPED_TRACE(line);
    expect_input_error(run_tessim(args, d.scratch.path()), expected);
  }
}

#ifdef TESSIM_HAVE_COSIM
TEST(BadCommandLine, CosimRanges) {
  Dirs d;
  expect_input_error(run_tessim({"cosim", "--random", "4", "--int", "0"}, d.scratch.path()), {"int_blocks", "0"});
  expect_input_error(run_tessim({"cosim", "--random", "4", "--int", "33"}, d.scratch.path()), {"int_blocks", "33"});
  expect_input_error(run_tessim({"cosim", "--random", "4", "--seeds", "0"}, d.scratch.path()),
                     {"command line: --seeds: 0 is outside 1..1000000"});
  expect_input_error(run_tessim({"cosim", "--random", "-4"}, d.scratch.path()), {"--random: '-4' is outside"});
  expect_input_error(run_tessim({"cosim", "--random", "4", "--wave", d.at("no/w.fst").string()}, d.scratch.path()),
                     {"w.fst", "--wave", "does not exist"});
}
#endif

TEST(BadCommandLine, IntegersAreDecimal) {
  if (!fs::exists(kCube)) FAIL() << kCube << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const TessimRun r = run_tessim({"tessellate", kCube.string(), "-L", "010", "-o", d.at("c.obj").string()},
                                 d.scratch.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("L=10,"), std::string::npos) << r.out;  // not octal 8
}

TEST(BadCommandLine, HelpAndVersionStillExitZero) {
  Dirs d;
  TessimRun r = run_tessim({"--version"}, d.scratch.path());
  EXPECT_EQ(r.status, 0);
  // The release and the source tree's git describe (sim/version.hpp).
  EXPECT_EQ(r.out, std::string("tessim 0.1.0 (") + tool_version() + ")\n");
  r = run_tessim({"--help"}, d.scratch.path());
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("Usage"), std::string::npos) << r.out;
  r = run_tessim({"sim", "--help"}, d.scratch.path());
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--tess-factor"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

// ---------------------------------------------------------------------------------------------
// Meshes: what is left out is a warning, what is broken an error.

TEST(BadMesh, PointAndLineFacesAreAWarning) {
  Dirs d;
  const fs::path mesh = d.scratch.write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\nf 1 2\n");
  const TessimRun r = run_tessim({"tessellate", mesh.string(), "-o", d.at("out.obj").string()}, d.scratch.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("tessim: warning: " + mesh.string() + ": face 2: 1 face of 1 or 2 vertices (points or lines) ignored"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(d.at("out.obj")));
}

TEST(BadMesh, TruncatedStlBadObjNormalAndFarAwayMeshWriteNothing) {
  Dirs d;
  const std::string facet =
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  const fs::path stl = d.scratch.write("cut.stl", "solid cut\n" + facet + facet);
  const fs::path obj = d.scratch.write("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n");
  const fs::path far = d.scratch.write("far.obj", "v 10000000 0 0\nv 10000001 0 0\nv 10000000 1 0\nv 10000000 0 1\n"
                                                  "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  expect_input_error(run_tessim({"tessellate", stl.string(), "-o", d.at("a.ply").string()}, d.scratch.path()),
                     {"cut.stl: endsolid: missing", "truncated after 2 facets"});
  expect_input_error(run_tessim({"sim", obj.string(), "-o", d.at("b.ply").string()}, d.scratch.path()),
                     {"normal.obj: face at line 5: normal index 2 out of range (1 in the file)"});
  expect_input_error(run_tessim({"render", far.string(), "--size", "64x64", "-o", d.at("c.png").string()},
                                d.scratch.path()),
                     {"far.obj: vertex coordinates: x reaches 1e+07", "single precision"});
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

// A closed fan (centre 0, ring 1-6) as ASCII PLY with scalar tags (docs/stpn.md): Δ = (1, 0, 0)
// and σ = 1 on the vertices listed, the `sigma` text of vertex 0 replaced by `sigma0` if given.
std::string tagged_fan_ply(const std::vector<int>& tagged, const std::string& sigma0 = "") {
  std::string s =
      "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty double dx\nproperty double dy\n"
      "property double dz\nproperty double sigma\nproperty double theta\nproperty double beta\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  const char* ring[7] = {"0 0 0", "1 0 0", "0.5 0.866 0", "-0.5 0.866 0", "-1 0 0", "-0.5 -0.866 0", "0.5 -0.866 0"};
  for (int v = 0; v < 7; ++v) {
    const bool t = std::find(tagged.begin(), tagged.end(), v) != tagged.end();
    const std::string sigma = v == 0 && !sigma0.empty() ? sigma0 : (t ? "1" : "0");
    s += std::string(ring[v]) + " 0 0 1 " + (t ? "1" : "0") + " 0 0 " + sigma + " 0 0\n";
  }
  s += "3 0 1 2\n3 0 2 3\n3 0 3 4\n3 0 4 5\n3 0 5 6\n3 0 6 1\n";
  return s;
}

TEST(BadMesh, TagRuleViolationsAndBadTagsWriteNothing) {
  Dirs d;
  const fs::path neighbours = d.scratch.write("neighbours.ply", tagged_fan_ply({0, 1, 3, 5}));
  const fs::path triangle = d.scratch.write("triangle.ply", tagged_fan_ply({0, 3, 4}));
  const fs::path nan = d.scratch.write("nan.ply", tagged_fan_ply({0}, "nan"));
  const fs::path fine = d.scratch.write("fine.ply", tagged_fan_ply({0, 1, 4}));
  const std::vector<std::pair<fs::path, std::vector<std::string>>> cases = {
      {neighbours, {"neighbours.ply: vertex 0: tagged, with 3 tagged neighbours (vertex 1, vertex 3, vertex 5)"}},
      {triangle, {"triangle.ply: triangle 2: all three of its vertices (vertex 0, vertex 3, vertex 4) are tagged"}},
      {nan, {"nan.ply: vertex 0: tag sigma is nan (tags must be finite)"}},
  };
  for (const auto& [mesh, expected] : cases) {
    SCOPED_TRACE(mesh.filename().string());
    expect_input_error(run_tessim({"info", mesh.string()}, d.scratch.path()), expected);
    expect_input_error(run_tessim({"tessellate", mesh.string(), "-o", d.at("t.ply").string()}, d.scratch.path()), expected);
    expect_input_error(run_tessim({"render", mesh.string(), "--size", "32x32", "-o", d.at("r.png").string()},
                                  d.scratch.path()),
                       expected);
    expect_input_error(run_tessim({"sim", mesh.string(), "-o", d.at("s.ply").string()}, d.scratch.path()), expected);
  }
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
  // Two tagged neighbours and two tagged vertices per triangle at most: accepted.
  const TessimRun ok = run_tessim({"tessellate", fine.string(), "-o", d.at("t.ply").string()}, d.scratch.path());
  EXPECT_EQ(ok.status, 0) << ok.err;
}

// ---------------------------------------------------------------------------------------------
// A run killed by SIGINT or SIGTERM removes its pending temporaries and dies of the signal.

void expect_killed_render_leaves_nothing(int sig) {
  if (!fs::exists(kWuson)) FAIL() << kWuson << " is missing: scripts/setup.sh installs assimp-testmodels";
  Dirs d;
  const std::string output = d.at("out.png").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // The child: quiet, with the signals at their defaults (as from a shell).
    ::signal(sig, SIG_DFL);
    const std::string null = "/dev/null";
    if (FILE* f = std::freopen(null.c_str(), "w", stdout)) (void)f;
    if (FILE* f = std::freopen(null.c_str(), "w", stderr)) (void)f;
    ::execl(TESSIM_BINARY, TESSIM_BINARY, "render", kWuson.c_str(), "-L", "16", "--size", "6000x6000", "--compare",
            "flat", "-o", output.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until the image is being written (its temporary exists), then kill.
  bool pending = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!pending && std::chrono::steady_clock::now() < deadline) {
    for (const std::string& e : d.work.entries()) pending = pending || e.find(".tmp-") != std::string::npos;
    if (!pending) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    int status = 0;
    if (!pending && ::waitpid(pid, &status, WNOHANG) == pid) FAIL() << "render ended before it was killed";
  }
  ASSERT_TRUE(pending) << "no temporary appeared";
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

TEST(KilledRun, SigtermRemovesTheTemporary) { expect_killed_render_leaves_nothing(SIGTERM); }
TEST(KilledRun, SigintRemovesTheTemporary) { expect_killed_render_leaves_nothing(SIGINT); }

}  // namespace
}  // namespace tessim
