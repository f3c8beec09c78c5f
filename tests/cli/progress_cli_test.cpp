// Progress of long runs as a person at a terminal sees it: `tessim sim` with standard error on a
// pseudo-terminal shows done/total, rate and time left, redrawn in place; with standard error on
// a pipe, or with --quiet, not a byte of it; and the output file is the same either way.
#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

const fs::path kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Runs `program` (default: tessim) with standard error on a pseudo-terminal (standard output to
// /dev/null) and returns what the terminal received; `status` the exit status.
std::string run_on_terminal(const std::vector<std::string>& args, int& status,
                            const std::string& program = TESSIM_BINARY) {
  int master = -1, slave = -1;
  if (::openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) {
    ADD_FAILURE() << "openpty failed";
    return {};
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(master);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(slave, 2);
    std::vector<char*> argv;
    std::string binary = program;
    argv.push_back(binary.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(slave);
  std::string received;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(master, buf, sizeof buf);
    if (n > 0) received.append(buf, static_cast<std::size_t>(n));
    else if (n < 0 && errno == EINTR) continue;
    else break;  // EIO: the child closed the terminal
  }
  ::close(master);
  int raw = 0;
  ::waitpid(pid, &raw, 0);
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return received;
}

// Long enough (a second or more) for the meter's first line, which comes after a quarter second.
std::vector<std::string> sim_args(const fs::path& out) {
  return {"sim", kWuson.string(), "-L", "32", "--stats", (out.parent_path() / (out.stem().string() + ".json")).string(),
          "-o", out.string()};
}

TEST(ProgressCli, SimOnATerminalShowsRateAndTimeLeft) {
  ASSERT_TRUE(fs::exists(kWuson)) << kWuson << " not installed (assimp-testmodels)";
  TempDir d;
  int status = -1;
  const std::string terminal = run_on_terminal(sim_args(d.path() / "tty.ply"), status);
  ASSERT_EQ(status, 0) << terminal;
  EXPECT_TRUE(contains(terminal, "\rsim  ")) << terminal;  // redrawn in place
  EXPECT_TRUE(contains(terminal, "vertices/s")) << terminal;
  EXPECT_TRUE(contains(terminal, "ETA ")) << terminal;
  EXPECT_TRUE(contains(terminal, "/2.09 M vertices")) << terminal;  // 3732 triangles x 561 vertices (L = 32)
  EXPECT_TRUE(contains(terminal, "100.0%")) << terminal;
  EXPECT_TRUE(contains(terminal, "done in")) << terminal;
  // A pipe sees none of it, and the output is the same bytes.
  const TessimRun piped = run_tessim(sim_args(d.path() / "pipe.ply"), d.path());
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_FALSE(contains(piped.err, "vertices/s")) << piped.err;
  EXPECT_FALSE(contains(piped.err, "\r")) << piped.err;
  EXPECT_EQ(slurp(d.path() / "tty.ply"), slurp(d.path() / "pipe.ply"));
  // The statistics too, but for the wall clock.
  nlohmann::json tty_stats = nlohmann::json::parse(slurp(d.path() / "tty.json"));
  nlohmann::json pipe_stats = nlohmann::json::parse(slurp(d.path() / "pipe.json"));
  tty_stats.erase("wall_seconds");
  pipe_stats.erase("wall_seconds");
  EXPECT_TRUE(tty_stats == pipe_stats) << "statistics differ with progress shown";
}

TEST(ProgressCli, QuietKeepsTheTerminalClean) {
  ASSERT_TRUE(fs::exists(kWuson)) << kWuson << " not installed (assimp-testmodels)";
  TempDir d;
  std::vector<std::string> args = sim_args(d.path() / "quiet.ply");
  args.push_back("--quiet");
  int status = -1;
  const std::string terminal = run_on_terminal(args, status);
  ASSERT_EQ(status, 0) << terminal;
  EXPECT_EQ(terminal, "");
}

TEST(ProgressCli, TessellateOnATerminalShowsProgress) {
  ASSERT_TRUE(fs::exists(kWuson)) << kWuson << " not installed (assimp-testmodels)";
  TempDir d;
  int status = -1;
  // --weld makes the job last long enough (about 20 s) for the meter to draw on a fast machine:
  // without it Wuson at L = 64 finishes in a third of a second and the test depended on load.
  const std::string terminal =
      run_on_terminal({"tessellate", kWuson.string(), "-L", "64", "--weld", "-o", (d.path() / "w.ply").string()}, status);
  ASSERT_EQ(status, 0) << terminal;
  EXPECT_TRUE(contains(terminal, "\rtessellate  ")) << terminal;
  EXPECT_TRUE(contains(terminal, "vertices/s")) << terminal;
}

TEST(ProgressCli, SweepOnATerminalShowsPointsRateAndTimeLeft) {
  TempDir d;
  const std::string sweep = std::string(TESSIM_SOURCE_DIR) + "/scripts/sweep.py";
  const std::string spec = std::string(TESSIM_SOURCE_DIR) + "/scripts/sweeps/smoke.json";
  int status = -1;
  const std::string terminal = run_on_terminal(
      {sweep, spec, "-o", (d.path() / "tty.csv").string(), "--tessim", TESSIM_BINARY}, status, "/usr/bin/python3");
  ASSERT_EQ(status, 0) << terminal;
  EXPECT_TRUE(contains(terminal, "\r[")) << terminal;
  EXPECT_TRUE(contains(terminal, "4/4 points (0 cached)")) << terminal;
  EXPECT_TRUE(contains(terminal, "points/s")) << terminal;
  EXPECT_TRUE(contains(terminal, "ETA ")) << terminal;
  // Quiet: the final summary line alone, not redrawn in place.
  const std::string quiet = run_on_terminal(
      {sweep, spec, "-o", (d.path() / "quiet.csv").string(), "--tessim", TESSIM_BINARY, "--quiet"}, status,
      "/usr/bin/python3");
  ASSERT_EQ(status, 0) << quiet;
  EXPECT_FALSE(contains(quiet, "\r[")) << quiet;
}

}  // namespace
}  // namespace tessim
