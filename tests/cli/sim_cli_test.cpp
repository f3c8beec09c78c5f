// `tessim sim` end to end: configuration errors naming the key, flags over a --config file, the
// statistics file, the tessellated mesh, the issue schedule and the trace.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/mesh.hpp"
#include "model/mesh_io.hpp"

namespace tessim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

struct CommandResult {
  int status;
  std::string output;
};

CommandResult run_tessim(const std::string& args) {
  const std::string cmd = std::string(TESSIM_BINARY) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("tessim_" + std::to_string(::getpid()) + "_" + name);
}

TEST(SimCli, RejectsBadConfigurationsNamingTheKey) {
  const auto cfg = temp_file("bad.json");
  const auto stats = temp_file("stats.json");
  struct Case {
    std::string json, flags, key;
  };
  for (const Case& c : {Case{R"({"te_contextz": 4})", "", "te_contextz"},
                        Case{R"({"int_blocks": 40})", "", "int_blocks"},
                        Case{R"({"gpe_cycles": "slow"})", "", "gpe_cycles"},
                        Case{R"({"normals": "derivative"})", "", "normals"},
                        Case{"{}", "--int 0", "int_blocks"},
                        Case{"{}", "--normals derivative", "normals"},
                        Case{"{}", "--cpg magic", "cpg_mapping"},
                        Case{"{}", "--stall 2", "gpe_stall_prob"},
                        // The shader-core geometry engine: its ranges, and what it cannot be combined with.
                        Case{R"({"ge_core_lanes": 4, "units": 2})", "", "ge_core_lanes"},
                        Case{"{}", "--ge-core-lanes 8 --ge-core-mhz 0", "ge_core_mhz"},
                        Case{"{}", "--ge-core-lanes 8 --ge-core-fifo 0", "ge_core_fifo"},
                        Case{"{}", "--ge-core-lanes 8 --chunks 2", "--chunks"}}) {
    std::ofstream(cfg) << c.json;
    const CommandResult r =
        run_tessim("sim --config " + cfg.string() + " " + c.flags + " --stats " + stats.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("tessim: error:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.key), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(stats)) << "nothing written on error";
  }
  std::filesystem::remove(cfg);
}

TEST(SimCli, FlagsOverrideConfigAndStatsFileHasEverything) {
  const auto cfg = temp_file("cfg.json");
  const auto stats = temp_file("stats2.json");
  std::ofstream(cfg) << R"({"int_blocks": 1, "tess_factor": 2, "gpe_cycles": 3})";
  const CommandResult r = run_tessim(std::string("sim ") + kWuson + " --config " + cfg.string() +
                                     " --int 3 --contexts 2 --stats " + stats.string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(stats);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["config"]["int_blocks"], 3);    // flag wins
  EXPECT_EQ(j["config"]["te_contexts"], 2);   // flag
  EXPECT_EQ(j["config"]["tess_factor"], 2);   // file
  EXPECT_EQ(j["config"]["gpe_cycles"], 3);    // file
  EXPECT_EQ(j["config"]["int_latency"], 1);   // default
  for (const char* key : {"cycles", "triangles_in", "vertices_out", "throughput", "cycles_per_vertex", "int",
                          "te", "cpg", "gpe", "stalls", "bottleneck"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["int"]["blocks"].size(), 3u);
  EXPECT_NE(r.output.find("cycles/vertex"), std::string::npos);
  std::filesystem::remove(cfg);
  std::filesystem::remove(stats);
}

TEST(SimCli, WritesTheTessellatedMeshAndNothingOnError) {
  const auto out = temp_file("out.ply");
  const CommandResult r = run_tessim(std::string("sim ") + kWuson + " -L 3 --gpe-cycles 1 -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Mesh in = load_mesh(kWuson);
  const Mesh result = load_mesh(out);
  EXPECT_EQ(result.triangle_count(), in.triangle_count() * 9);
  // In the mesh's own coordinates: the same bounding box up to the PN bulge and the rounding.
  const BoundingBox a = bounding_box(in), b = bounding_box(result);
  EXPECT_LT(glm::length(a.lo - b.lo) + glm::length(a.hi - b.hi), 0.05 * a.diagonal());
  std::filesystem::remove(out);

  // Widths that cannot hold the mesh: an error naming the mesh, and no file.
  const auto cfg = temp_file("narrow.json");
  std::ofstream(cfg) << R"({"coord_int_bits": 1})";
  const CommandResult bad = run_tessim(std::string("sim ") + kWuson + " --config " + cfg.string() + " -o " + out.string());
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("Wuson.ply"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("cannot hold"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  std::filesystem::remove(cfg);
}

// A small grid of 18 triangles, so that the trace covers the whole run.
std::filesystem::path write_grid(const std::string& name) {
  const auto path = temp_file(name);
  std::ofstream f(path);
  for (int y = 0; y <= 3; ++y)
    for (int x = 0; x <= 3; ++x) f << "v " << x << ' ' << y << ' ' << 0.1 * ((x * y) % 3) << '\n';
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      const int a = y * 4 + x + 1, b = a + 1, c = a + 4, d = c + 1;
      f << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
    }
  return path;
}

// One cell of the issue schedule, or one INT op of the trace: cycle, block, vertex, op.
using IssueCell = std::tuple<std::uint64_t, int, std::uint64_t, int>;

// `--schedule` and `--trace` of one run describe the same issue: the schedule's rows are
// consecutive cycles from the first issue, block i holding the i-th op of the cycle; every op
// of the schedule is the trace's op on that INT track in that cycle and the trace has no other
// op in those cycles; the trace has each (vertex, op) once, in cycle order on each track, after
// the ops it depends on; its ops per block are the statistics' busy cycles, vertices x 14 in all;
// retirements in the schedule come in vertex order.
TEST(SimCli, ScheduleAndTrace) {
  const auto grid = write_grid("grid.obj");
  const auto trace = temp_file("trace.json");
  const auto stats = temp_file("schedule_stats.json");
  const CommandResult r = run_tessim("sim " + grid.string() + " -L 2 --gpe-cycles 1 --int 3 --schedule --trace " +
                                     trace.string() + " --trace-cycles 100000 --stats " + stats.string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream sin(stats);
  const nlohmann::json s = nlohmann::json::parse(sin);
  const std::uint64_t vertices = s["vertices_out"].get<std::uint64_t>();
  ASSERT_EQ(vertices, 18u * 6u);

  // The schedule: the header, then rows "cycle INT0 INT1 INT2 class [alloc vA] [retire vR]".
  const std::size_t head = r.output.find("\ncycle ");
  ASSERT_NE(head, std::string::npos) << r.output;
  std::istringstream text(r.output.substr(head + 1));
  std::string line;
  std::getline(text, line);
  EXPECT_NE(line.find("INT2"), std::string::npos) << line;
  EXPECT_EQ(line.find("INT3"), std::string::npos) << line;
  std::set<IssueCell> schedule;
  std::vector<std::uint64_t> cycles, retired;
  while (std::getline(text, line) && !line.empty() && std::isdigit(static_cast<unsigned char>(line[line.find_first_not_of(' ')]))) {
    std::istringstream row(line);
    std::uint64_t cycle = 0;
    row >> cycle;
    cycles.push_back(cycle);
    bool empty_seen = false;
    for (int b = 0; b < 3; ++b) {
      std::string cell;
      row >> cell;
      if (cell == ".") {
        empty_seen = true;
        continue;
      }
      EXPECT_FALSE(empty_seen) << "block " << b << " issues only after blocks 0.." << b - 1 << ": " << line;
      unsigned long long v = 0;
      int op = -1;
      ASSERT_EQ(std::sscanf(cell.c_str(), "v%llu.%d", &v, &op), 2) << line;
      EXPECT_TRUE(op >= 0 && op < 14) << line;
      EXPECT_TRUE(schedule.insert({cycle, b, v, op}).second) << line;
    }
    for (std::string word; row >> word;) {
      if (word == "retire") {
        std::string v;
        row >> v;
        retired.push_back(std::stoull(v.substr(1)));
      }
    }
  }
  ASSERT_EQ(cycles.size(), 48u) << r.output;  // ScheduleRecorder's table_cycles
  for (std::size_t i = 1; i < cycles.size(); ++i) EXPECT_EQ(cycles[i], cycles[i - 1] + 1) << "row " << i;
  ASSERT_FALSE(schedule.empty());
  EXPECT_EQ(std::get<0>(*schedule.begin()), cycles.front()) << "the table starts at the first issue";
  ASSERT_FALSE(retired.empty());
  for (std::size_t i = 0; i < retired.size(); ++i) EXPECT_EQ(retired[i], i) << "in-order retirement";

  // The trace's INT ops: complete events on the INT tracks (tid 1..N) with vertex and op.
  std::ifstream tin(trace);
  const nlohmann::json t = nlohmann::json::parse(tin);
  std::map<int, std::vector<IssueCell>> by_track;
  std::map<std::pair<std::uint64_t, int>, std::uint64_t> issue_cycle;  // (vertex, op) -> cycle
  for (const nlohmann::json& e : t["traceEvents"]) {
    if (e.value("ph", "") != "X" || !e.contains("args") || !e["args"].contains("op")) continue;
    const int tid = e["tid"].get<int>();
    ASSERT_TRUE(tid >= 1 && tid <= 3) << e;
    const IssueCell c{e["ts"].get<std::uint64_t>(), tid - 1, e["args"]["vertex"].get<std::uint64_t>(),
                      e["args"]["op"].get<int>()};
    by_track[tid - 1].push_back(c);
    EXPECT_TRUE(issue_cycle.insert({{std::get<2>(c), std::get<3>(c)}, std::get<0>(c)}).second) << "issued twice: " << e;
  }
  std::set<IssueCell> traced_in_window;
  std::uint64_t traced = 0;
  for (int b = 0; b < 3; ++b) {
    const std::vector<IssueCell>& track = by_track[b];
    for (std::size_t i = 1; i < track.size(); ++i)
      EXPECT_LT(std::get<0>(track[i - 1]), std::get<0>(track[i])) << "INT" << b << ": one op a cycle, in cycle order";
    for (const IssueCell& c : track)
      if (std::get<0>(c) >= cycles.front() && std::get<0>(c) <= cycles.back()) traced_in_window.insert(c);
    EXPECT_EQ(track.size(), s["int"]["blocks"][static_cast<std::size_t>(b)]["busy"].get<std::uint64_t>()) << "INT" << b;
    traced += track.size();
  }
  EXPECT_EQ(traced_in_window, schedule);
  EXPECT_EQ(traced, vertices * 14);
  EXPECT_EQ(issue_cycle.size(), vertices * 14);
  // Dependences (sim/base/int_ops.hpp, latency 1): an op issues after the ops it reads.
  for (std::uint64_t v = 0; v < vertices; ++v)
    for (const auto& [op, deps] : std::vector<std::pair<int, std::vector<int>>>{
             {9, {0, 1, 3}}, {10, {1, 2, 4}}, {11, {3, 4, 5}}, {12, {6, 7, 8}}, {13, {9, 10, 11}}})
      for (int d : deps) {
        const std::uint64_t at = issue_cycle[std::make_pair(v, op)], dep = issue_cycle[std::make_pair(v, d)];
        EXPECT_GT(at, dep) << "v" << v << "." << op << " after op " << d;
      }
  std::filesystem::remove(grid);
  std::filesystem::remove(trace);
  std::filesystem::remove(stats);
}

}  // namespace
}  // namespace tessim
