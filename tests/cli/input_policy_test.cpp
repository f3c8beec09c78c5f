// The bad-input policy where input used to be accepted with a crash, an internal error, a
// silent loss or an ambiguity (docs/architecture.md, Bad input): exit status 2 with
// "tessim: error: FILE: ELEMENT: REASON", nothing on stdout and nothing written; or, for a loss
// tessim can only report, a warning with its count.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/commands.hpp"
#include "model/base/error.hpp"
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

// Statistics of a real run, for compare.
fs::path stats_of_cube(const Dirs& d, const std::string& name) {
  const fs::path stats = d.scratch.path() / name;
  const TessimRun r = run_tessim({"sim", kCube.string(), "-L", "2", "--stats", stats.string()}, d.scratch.path());
  EXPECT_EQ(r.status, 0) << r.err;
  return stats;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A tetrahedron as ASCII PLY with the scalar tags of docs/stpn.md; vertex 0 has the crease
// vector (0, 0, dz), the others none.
std::string tagged_tetrahedron(const std::string& dz) {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "property double dx\nproperty double dy\nproperty double dz\nproperty double sigma\n"
         "property double theta\nproperty double beta\nelement face 4\nproperty list uchar int vertex_indices\n"
         "end_header\n"
         "0 0 1 0 0 " + dz + " 0 0 0\n"
         "1 0 0 0 0 0 0 0 0\n"
         "0 1 0 0 0 0 0 0 0\n"
         "-1 -1 -1 0 0 0 0 0 0\n"
         "3 0 1 2\n3 0 2 3\n3 0 3 1\n3 1 3 2\n";
}

// ---------------------------------------------------------------------------------------------
// A crash: nlohmann's dump() overflows its buffer for an indent in the thousands.

// The image size options (render --size and --viewport, pattern --size) of app/options.cpp.
TEST(BadInputImageSize, WxHWithinTheImageLimit) {
  EXPECT_EQ(app::parse_image_size("1x1", "--size"), glm::ivec2(1, 1));
  EXPECT_EQ(app::parse_image_size("640X480", "--size"), glm::ivec2(640, 480));
  EXPECT_EQ(app::parse_image_size("8192x8192", "--size"), glm::ivec2(8192, 8192));
  for (const char* bad : {"", "x", "0x10", "10x0", "8193x10", "10x8193", "10", "axb", "10x10x10", "-5x5",
                          "10 x 10", "99999999999x1", "1.5x2"})
    EXPECT_THROW(app::parse_image_size(bad, "--size"), InputError) << "'" << bad << "'";
}

TEST(BadInputSchema, IndentIsBounded) {
  TempDir scratch;
  for (const char* indent : {"50000", "1100", "17", "-2"})
    expect_input_error(run_tessim({"schema", "--indent", indent}, scratch.path()),
                       {"command line: --indent: '", indent, "' is outside -1..16"});
  EXPECT_EQ(run_tessim({"schema", "--indent", "16"}, scratch.path()).status, 0);
  EXPECT_EQ(run_tessim({"schema", "--indent", "-1"}, scratch.path()).status, 0);
}

// ---------------------------------------------------------------------------------------------
// compare: fields of the wrong type are bad input, found before anything is printed.

TEST(BadInputCompare, WrongTypedSchemaVersionOrTool) {
  Dirs d;
  const fs::path good = stats_of_cube(d, "good.json");
  const std::string text = slurp(good);
  const struct {
    std::string from, to, element;
  } cases[] = {
      {"\"schema_version\": ", "\"schema_version\": \"2\", \"x_old_schema\": ", "schema_version"},
      {"\"tool\": {", "\"tool\": 5, \"x_old_tool\": {", "tool"},
      {"\"version\": \"", "\"version\": 3, \"x_old_version\": \"", "tool.version"},
  };
  for (const auto& c : cases) {
    std::string bad = text;
    const std::size_t at = bad.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    bad.replace(at, c.from.size(), c.to);
    const fs::path path = d.scratch.write("bad.json", bad);
    for (const auto& args : {std::vector<std::string>{"compare", good.string(), path.string()},
                             std::vector<std::string>{"compare", path.string(), good.string(), "--csv"}})
      expect_input_error(run_tessim(args, d.work.path()), {"bad.json: " + c.element + ": "});
  }
}

// ---------------------------------------------------------------------------------------------
// One behaviour for an empty run: fixed factors that cull every patch are refused everywhere.

TEST(BadInputEmptyRun, FactorsThatCullEveryPatch) {
  Dirs d;
  std::vector<std::vector<std::string>> runs = {
      {"sim", kCube.string(), "--outer", "0,0,0", "-o", d.at("out.ply").string(), "--stats", d.at("s.json").string()},
      {"sim", kCube.string(), "--outer", "1,nan,1", "--partitioning", "fractional_odd"},
      {"tessellate", kCube.string(), "--outer", "0,0,0", "-o", d.at("out.ply").string()},
      {"tessellate", kCube.string(), "--outer", "-1,2,2", "--inner", "2", "-o", d.at("out.obj").string()},
      {"render", kCube.string(), "--outer", "0,0,0", "-o", d.at("out.png").string()},
#ifdef TESSIM_HAVE_COSIM
      {"cosim", kCube.string(), "--outer", "0,0,0"},
#endif
  };
  for (const auto& args : runs) {
    SCOPED_TRACE(args.front() + " " + args[3]);
    expect_input_error(run_tessim(args, d.scratch.path()),
                       {"command line: --outer: '" + args[3] + "': every patch is culled", "nothing to tessellate"});
    EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
  }
  // A single patch's pattern may show the culling (tessim pattern prints it).
  EXPECT_EQ(run_tessim({"pattern", "--outer", "0,0,0", "--inner", "1", "--partitioning", "integer"}, d.scratch.path()).status,
            0);
}

// ---------------------------------------------------------------------------------------------
// Silent losses, now warned about with their count.

TEST(BadInputTags, TagsBelowTheFixedPointResolutionAreCounted) {
  Dirs d;
  const fs::path tiny = d.scratch.write("tiny.ply", tagged_tetrahedron("1e-7"));
  const TessimRun r = run_tessim({"sim", tiny.string(), "--cpg-tags", "1"}, d.work.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("tessim: warning: " + tiny.string() + ": tags: 1 vertices carry a crease vector or tension "
                       "below the fixed-point resolution"),
            std::string::npos)
      << r.err;
  // A crease the format resolves: no warning.
  const fs::path fine = d.scratch.write("fine.ply", tagged_tetrahedron("0.25"));
  const TessimRun ok = run_tessim({"sim", fine.string(), "--cpg-tags", "1"}, d.work.path());
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(ok.err.find("warning"), std::string::npos) << ok.err;
}

TEST(BadInputTags, StpnImportOfATaggedMeshSaysItReplacesTheTags) {
  Dirs d;
  const fs::path once = d.scratch.path() / "once.ply", twice = d.scratch.path() / "twice.ply";
  const TessimRun first = run_tessim({"stpn-import", kCube.string(), "-o", once.string()}, d.work.path());
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_EQ(first.err.find("already carry scalar tags"), std::string::npos) << first.err;
  const TessimRun again = run_tessim({"stpn-import", once.string(), "-o", twice.string()}, d.work.path());
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("tessim: warning: " + once.string() + ": tags: "), std::string::npos) << again.err;
  EXPECT_NE(again.err.find(" vertices already carry scalar tags; they are replaced"), std::string::npos) << again.err;
}

// The same tetrahedron with every corner written once per face (12 vertices): the apex, with
// tension 1, is 3 copies of one vertex.
TEST(BadInputTags, StpnImportCountsWeldedVerticesAsInfoDoes) {
  Dirs d;
  const char* corners[4] = {"0 0 1 0 0 0 0 1 0", "1 0 0 0 0 0 0 0 0", "0 1 0 0 0 0 0 0 0", "-1 -1 -1 0 0 0 0 0 0"};
  const int faces[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  std::string ply = "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\n"
                    "property double dx\nproperty double dy\nproperty double dz\nproperty double sigma\n"
                    "property double theta\nproperty double beta\nelement face 4\n"
                    "property list uchar int vertex_indices\nend_header\n";
  for (const auto& f : faces)
    for (int c : f) ply += std::string(corners[c]) + "\n";
  for (int f = 0; f < 4; ++f)
    ply += "3 " + std::to_string(3 * f) + " " + std::to_string(3 * f + 1) + " " + std::to_string(3 * f + 2) + "\n";
  const fs::path split = d.scratch.write("split.ply", ply);
  const TessimRun info = run_tessim({"info", split.string()}, d.work.path());
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("vertices with tags    1 "), std::string::npos) << info.out;
  const TessimRun r = run_tessim({"stpn-import", split.string(), "-o", d.at("out.ply").string()}, d.work.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find(": tags: 1 vertices already carry scalar tags"), std::string::npos) << r.err;
}

// ---------------------------------------------------------------------------------------------
// Accepted but ambiguous: now input errors.

TEST(BadInputAmbiguous, DuplicatePlyProperty) {
  Dirs d;
  const fs::path ply = d.scratch.write(
      "dup.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float x\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 5\n1 0 0 6\n0 1 0 7\n3 0 1 2\n");
  expect_input_error(run_tessim({"tessellate", ply.string(), "-o", d.at("out.ply").string()}, d.scratch.path()),
                     {"dup.ply: PLY header line 7: property 'x' declared twice in element 'vertex'"});
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

TEST(BadInputAmbiguous, DuplicateJsonKeysAndTrailingBytes) {
  Dirs d;
  const struct {
    std::string name, text, expected;
  } files[] = {
      {"dup.json", "{\"tess_factor\": 4, \"tess_factor\": 8}\n", "dup.json: tess_factor: the key appears twice"},
      {"nul.json", std::string("{\"tess_factor\": 4}\n\0\0garbage", 27), "nul.json: JSON: byte 20 is a NUL byte"},
      {"two.json", "{\"tess_factor\": 4}\n{}\n", "two.json: JSON: line 2, column 1: syntax error"},
  };
  for (const auto& f : files) {
    const fs::path config = d.scratch.write(f.name, f.text);
    expect_input_error(run_tessim({"sim", kCube.string(), "--config", config.string(), "-o", d.at("out.ply").string()},
                                  d.scratch.path()),
                       {f.expected});
    EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
  }
  // The statistics read by compare and report go through the same parser.
  const fs::path good = stats_of_cube(d, "good.json");
  std::string text = slurp(good);
  text.insert(text.find('{') + 1, "\"cycles\": 1, ");
  const fs::path dup = d.scratch.write("dupstats.json", text);
  expect_input_error(run_tessim({"compare", good.string(), dup.string()}, d.scratch.path()),
                     {"dupstats.json: cycles: the key appears twice"});
  expect_input_error(run_tessim({"report", dup.string(), "-o", d.at("r.html").string()}, d.scratch.path()),
                     {"dupstats.json: cycles: the key appears twice"});
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
}

TEST(BadInputAmbiguous, OptionsThatMeantNothingDefinite) {
  Dirs d;
  const std::string out = d.at("out.ply").string();
  const struct {
    std::vector<std::string> args;
    std::string expected;
  } cases[] = {
      {{"tessellate", kCube.string(), "-o", out, "--adaptive", "screen", "--camera", "eye=0,0,5,eye=0,0,9"},
       "command line: --camera: 'eye' is given twice"},
      {{"tessellate", kCube.string(), "-o", out, "--viewport", "640x480"}, "command line: --viewport: needs --adaptive"},
      {{"tessellate", kCube.string(), "-o", out, "--pixels-per-segment", "8"},
       "command line: --pixels-per-segment: needs --adaptive"},
      {{"sim", kCube.string(), "-o", out, "--viewport", "640x480"}, "command line: --viewport: needs --adaptive"},
#ifdef TESSIM_HAVE_COSIM
      {{"cosim", "--random", "0"}, "command line: --random: '0' is outside 1.."},
      {{"cosim", "--random", "5", "--reset-at", "-1"}, "command line: --reset-at: '-1' is outside 0.."},
      {{"cosim", "--random", "5", "--reset-at", "1,,2"}, "command line: --reset-at: '' is not an integer"},
#endif
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.expected);
    expect_input_error(run_tessim(c.args, d.scratch.path()), {c.expected});
    EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
  }
}

// ---------------------------------------------------------------------------------------------
// Messages: printable, bounded, in the documented form.

TEST(BadInputMessages, ControlBytesAreEscaped) {
  Dirs d;
  // A 0x10 byte in a face line: the message shows it as \x10 and the line stays one line.
  const fs::path off = d.scratch.write("ctl.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 \x10\n");
  const TessimRun r = run_tessim({"tessellate", off.string(), "-o", d.at("out.ply").string()}, d.scratch.path());
  expect_input_error(r, {"ctl.off: ", "\\x10"});
  EXPECT_EQ(r.err.find('\x10'), std::string::npos) << r.err;
  EXPECT_TRUE(d.work.empty()) << entries_text(d.work);
  // Warnings too: a file name with a control byte in it.
  const fs::path named = d.scratch.write("line\x01.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n");
  const TessimRun w = run_tessim({"tessellate", named.string(), "-o", d.at("lines.ply").string()}, d.scratch.path());
  EXPECT_EQ(w.status, 0) << w.err;
  EXPECT_NE(w.err.find("tessim: warning: " + d.scratch.path().string() + "/line\\x01.obj: "), std::string::npos)
      << w.err;
  EXPECT_EQ(w.err.find('\x01'), std::string::npos) << w.err;
  fs::remove(d.at("lines.ply"));
  // A newline in an option value cannot start a second, forged line.
  expect_input_error(run_tessim({"tessellate", kCube.string(), "-o", d.at("out.ply").string(), "--outer",
                                 "1,2\ntessim: error: forged,3"},
                                d.scratch.path()),
                     {"command line: --outer: '2\\ntessim: error: forged' is not a number"});
}

TEST(BadInputMessages, HugeValuesAreTruncated) {
  Dirs d;
  const std::string key(900'000, 'k');  // within the size limit of a configuration file
  const fs::path config = d.scratch.write("huge.json", "{\"" + key + "\": 1}\n");
  const TessimRun r = run_tessim({"sim", kCube.string(), "--config", config.string()}, d.scratch.path());
  expect_input_error(r, {"huge.json: kkkk", " bytes ...] ", "unknown configuration key"});
  EXPECT_LT(r.err.size(), 2000u);
  const TessimRun opt = run_tessim(
      {"tessellate", kCube.string(), "-o", d.at("out.ply").string(), "--normals", std::string(100'000, 'n')},
      d.scratch.path());
  expect_input_error(opt, {"command line: --normals: 'nnn", "is not one of"});
  EXPECT_LT(opt.err.size(), 2000u);
}

TEST(BadInputMessages, OptionErrorsNameTheCommandLine) {
  Dirs d;
  const std::string out = d.at("out.ply").string();
  const struct {
    std::vector<std::string> args;
    std::string expected;
  } cases[] = {
      {{"sim", kCube.string(), "--outer", "x,1,1"}, "tessim: error: command line: --outer: 'x' is not a number"},
      {{"render", kCube.string(), "-o", d.at("o.png").string(), "--up", "w"}, "tessim: error: command line: --up: "},
      {{"render", kCube.string(), "-o", d.at("o.png").string(), "--normals", "x"},
       "tessim: error: command line: --normals: "},
      {{"tessellate", kCube.string(), "-o", out, "--adaptive", "screen", "--camera", "eye=0,0,5", "--viewport", "0x0"},
       "tessim: error: command line: --viewport: "},
      {{"tessellate", kCube.string(), "-o", out, "--normals", "x"}, "tessim: error: command line: --normals: "},
      {{"stpn-import", kCube.string(), "-o", out, "--sigma", "-1"}, "tessim: error: command line: --sigma: "},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.expected);
    expect_input_error(run_tessim(c.args, d.scratch.path()), {c.expected});
  }
}

TEST(BadInputMessages, JsonErrorsWithoutTheLibraryPrefix) {
  Dirs d;
  const fs::path config = d.scratch.write("broken.json", "{\"tess_factor\": }");
  expect_input_error(run_tessim({"sim", kCube.string(), "--config", config.string()}, d.scratch.path()),
                     {"broken.json: JSON: line 1, column 17: syntax error while parsing value"});
  const fs::path stats = d.scratch.write("broken_stats.json", "[1, 2");
  expect_input_error(run_tessim({"compare", stats.string(), stats.string()}, d.scratch.path()),
                     {"broken_stats.json: JSON: line 1, column 6: syntax error"});
}

// ---------------------------------------------------------------------------------------------
// Help that is true.

TEST(HelpText, RenderDoesNotClaimAFixedViewAsDefault) {
  TempDir scratch;
  const TessimRun r = run_tessim({"render", "--help"}, scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("FLOAT=35"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("FLOAT=25"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("automatic best view"), std::string::npos) << r.out;
}

TEST(HelpText, CosimShowsItsDefaults) {
#ifndef TESSIM_HAVE_COSIM
  GTEST_SKIP() << "built without the RTL co-simulation";
#endif
  TempDir scratch;
  const TessimRun r = run_tessim({"cosim", "--help"}, scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("--seeds INT=1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--random-max-L INT=8 "), std::string::npos) << r.out;
}

// "Needs:" and "Excludes:" belong to the description, not to the option's syntax.
TEST(HelpText, NotesAreNotOnTheOptionNameLine) {
  TempDir scratch;
  for (const char* command : {"sim", "tessellate", "render", "compare", "schema", "pattern", "stpn-import"}) {
    const TessimRun r = run_tessim({command, "--help"}, scratch.path());
    ASSERT_EQ(r.status, 0) << command << ": " << r.err;
    EXPECT_EQ(r.out.find("Needs:"), std::string::npos) << command << ":\n" << r.out;
    EXPECT_EQ(r.out.find("Excludes:"), std::string::npos) << command << ":\n" << r.out;
  }
  const TessimRun sim = run_tessim({"sim", "--help"}, scratch.path());
  EXPECT_TRUE(sim.out.find("(needs ") != std::string::npos || sim.out.find("(excludes ") != std::string::npos)
      << sim.out;
}

}  // namespace
}  // namespace tessim
