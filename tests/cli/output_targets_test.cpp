// Output targets and whole-file inputs as they meet tessim in daily use (docs/architecture.md,
// Bad input): a device or a named pipe given as an output is written, never replaced; a
// symbolic link is written through; "-" is standard output for every output option; inputs read
// whole are bounded and refused at once when they are devices, pipes or too large; an
// interrupted waveform leaves nothing behind.
//
// TESSIM_UNDER_TEST, when set, runs these tests against another tessim binary (an older build,
// to see them fail).
#include <fcntl.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const fs::path kCube = "/usr/share/assimp/models/OFF/Cube.off";

const char* binary_under_test() {
  const char* other = std::getenv("TESSIM_UNDER_TEST");
  return other && *other ? other : TESSIM_BINARY;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct TessimRun {
  int status = -1;  // exit status; 137 when the time limit killed it
  std::string out, err;
  double seconds = 0;
};

// Runs tessim in `cwd` with a time limit (a run that blocks fails instead of hanging the test).
TessimRun tessim(const std::vector<std::string>& args, const fs::path& cwd, int limit_seconds = 120) {
  const TempDir scratch;
  std::string command = "cd " + quote(cwd.string()) + " && exec timeout -s KILL " + std::to_string(limit_seconds) +
                        " " + quote(binary_under_test());
  for (const std::string& a : args) {
    command += ' ';
    command += quote(a);
  }
  const fs::path out = scratch.path() / "stdout", err = scratch.path() / "stderr";
  command += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
  const auto start = std::chrono::steady_clock::now();
  const int raw = std::system(command.c_str());
  TessimRun r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The names in `dir`, sorted, each after a space; " (empty)" for none.
std::string listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string text;
  for (const std::string& n : names) text += " " + n;
  return text.empty() ? " (empty)" : text;
}

// A null device to write to. As root, a private one (same device numbers as /dev/null) in `dir`:
// a tessim that replaced its outputs would replace that node, not the system's /dev/null. As
// another user /dev/null itself, which only root could replace.
fs::path null_device(const fs::path& dir) {
  if (::geteuid() == 0) {
    const fs::path node = dir / "null";
    if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) return node;
  }
  return "/dev/null";
}

bool is_character_device(const fs::path& p) {
  struct stat st = {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// Statistics of a small run, for tessim report.
fs::path write_stats(const TempDir& dir) {
  const fs::path stats = dir.path() / "stats.json";
  const TessimRun r = tessim({"sim", kCube.string(), "-L", "2", "--stats", stats.string()}, dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  return stats;
}

const std::vector<std::string> kPattern = {"pattern", "--outer", "3,2,2", "--inner", "2", "--partitioning", "integer"};

// Every command's output options, each given `target`.
std::vector<std::vector<std::string>> every_output(const fs::path& target, const fs::path& stats) {
  auto with = [](std::vector<std::string> args, std::initializer_list<std::string> more) {
    args.insert(args.end(), more);
    return args;
  };
  const std::string t = target.string(), mesh = kCube.string();
  return {
      {"sim", mesh, "-L", "2", "--stats", t},
      {"sim", mesh, "-L", "2", "--trace", t},
      {"sim", mesh, "-L", "2", "-o", t},
      {"tessellate", mesh, "-L", "2", "-o", t},
      {"report", stats.string(), "-o", t},
      {"render", mesh, "-L", "2", "--size", "64x48", "-o", t},
      with(kPattern, {"-o", t}),
  };
}

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += " " + a;
  return s;
}

// ---------------------------------------------------------------------------------------------
// Outputs that are not regular files.

TEST(BadOutputDevice, NullDeviceStaysADevice) {
  const TempDir dir;
  const fs::path stats = write_stats(dir);
  const fs::path null = null_device(dir.path());
  for (const auto& args : every_output(null, stats)) {
    const TessimRun r = tessim(args, dir.path());
    EXPECT_EQ(r.status, 0) << joined(args) << "\n" << r.err;
    EXPECT_TRUE(is_character_device(null)) << joined(args) << ": " << null << " is no longer a character device";
    EXPECT_FALSE(contains(listing(dir.path()), ".tmp-")) << joined(args) << ":" << listing(dir.path());
    if (!is_character_device(null)) {  // put it back for the next command
      fs::remove(null);
      ASSERT_EQ(null_device(dir.path()), null);
    }
  }
}

// Reads a FIFO to its end in a thread while tessim writes it.
class FifoReader {
 public:
  explicit FifoReader(fs::path fifo) : fifo_(std::move(fifo)) {
    thread_ = std::thread([this] { text_ = slurp(fifo_); });
  }
  // What was read. If tessim never opened the FIFO, the reader is released by opening it once.
  std::string finish() {
    const int fd = ::open(fifo_.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    thread_.join();
    return text_;
  }

 private:
  fs::path fifo_;
  std::string text_;
  std::thread thread_;
};

TEST(BadOutputFifo, NamedPipeIsWrittenDirectly) {
  const TempDir dir;
  const fs::path stats = write_stats(dir);
  const fs::path fifo = dir.path() / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  struct Case {
    std::vector<std::string> args;
    std::string starts;  // what the data read from the pipe begins with
  };
  const std::vector<Case> cases = {
      {{"sim", kCube.string(), "-L", "2", "--stats", fifo.string()}, "{"},
      {{"sim", kCube.string(), "-L", "2", "--trace", fifo.string()}, "{\"otherData\""},
      {{"tessellate", kCube.string(), "-L", "2", "-o", fifo.string()}, "ply\n"},
      {{"report", stats.string(), "-o", fifo.string()}, "<!DOCTYPE html>"},
      {{"render", kCube.string(), "-L", "2", "--size", "64x48", "-o", fifo.string()}, "\x89PNG"},
  };
  for (const Case& c : cases) {
    FifoReader reader(fifo);
    const TessimRun r = tessim(c.args, dir.path(), 60);
    const std::string data = reader.finish();
    EXPECT_EQ(r.status, 0) << joined(c.args) << "\n" << r.err;
    EXPECT_EQ(data.substr(0, c.starts.size()), c.starts) << joined(c.args) << ": read " << data.size() << " bytes";
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo))) << joined(c.args) << ": the pipe was replaced";
    EXPECT_FALSE(contains(listing(dir.path()), ".tmp-")) << joined(c.args) << ":" << listing(dir.path());
  }
  // The statistics arrive whole.
  FifoReader reader(fifo);
  const TessimRun r = tessim({"sim", kCube.string(), "-L", "2", "--stats", fifo.string()}, dir.path(), 60);
  const std::string data = reader.finish();
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(data, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << data.substr(0, 200);
  EXPECT_TRUE(j.contains("cycles"));
}

TEST(OutputTargets, SymbolicLinkIsWrittenThrough) {
  const TempDir dir;
  fs::create_directory(dir.path() / "real");
  // A relative link into another directory, and a dangling one (its target is created).
  fs::create_symlink("real/stats.json", dir.path() / "link.json");
  fs::create_symlink("real/mesh.ply", dir.path() / "mesh-link.ply");
  {
    std::ofstream(dir.path() / "real" / "stats.json") << "old\n";
  }
  const TessimRun r = tessim({"sim", kCube.string(), "-L", "2", "--stats", "link.json", "-o", "mesh-link.ply"}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir.path() / "link.json")) << "the link was replaced by a file";
  EXPECT_TRUE(fs::is_symlink(dir.path() / "mesh-link.ply")) << "the link was replaced by a file";
  const std::string stats = slurp(dir.path() / "real" / "stats.json");
  EXPECT_TRUE(contains(stats, "\"cycles\"")) << stats.substr(0, 100);
  EXPECT_EQ(slurp(dir.path() / "real" / "mesh.ply").substr(0, 4), "ply\n");
  EXPECT_FALSE(contains(listing(dir.path()) + listing(dir.path() / "real"), ".tmp-"));
}

// ---------------------------------------------------------------------------------------------
// "-": standard output, for every output option; the summary then goes to stderr.

TEST(OutputTargets, DashIsStandardOutputEverywhere) {
  const TempDir dir;
  const fs::path stats = write_stats(dir);
  struct Case {
    std::vector<std::string> args;
    std::string starts;  // what standard output begins with
    std::string summary;  // a part of the summary, now on stderr
  };
  const std::string mesh = kCube.string();
  std::vector<std::string> pattern = kPattern;
  pattern.insert(pattern.end(), {"-o", "-"});
  const std::vector<Case> cases = {
      {{"sim", mesh, "-L", "2", "--stats", "-"}, "{", "cycles"},
      {{"sim", mesh, "-L", "2", "--trace", "-"}, "{\"otherData\"", "cycles"},
      {{"sim", mesh, "-L", "2", "-o", "-"}, "ply\n", "cycles"},
      {{"tessellate", mesh, "-L", "2", "-o", "-"}, "ply\n", "patches"},
      // Welded, as `sim -o - --weld` does (tessellate refused it).
      {{"tessellate", mesh, "-L", "2", "--weld", "-o", "-"}, "ply\n", "welded"},
      {{"sim", mesh, "-L", "2", "--weld", "-o", "-"}, "ply\n", "welded"},
      {{"report", stats.string(), "-o", "-"}, "<!DOCTYPE html>", "wrote"},
      {{"render", mesh, "-L", "2", "--size", "64x48", "-o", "-"}, "\x89PNG", "wrote"},
      {pattern, "<svg", "triangles"},
  };
  for (const Case& c : cases) {
    const TessimRun r = tessim(c.args, dir.path());
    EXPECT_EQ(r.status, 0) << joined(c.args) << "\n" << r.err;
    EXPECT_EQ(r.out.substr(0, c.starts.size()), c.starts) << joined(c.args) << ": stdout " << r.out.substr(0, 80);
    EXPECT_TRUE(contains(r.err, c.summary)) << joined(c.args) << ": stderr " << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "-")) << joined(c.args) << ": wrote a file named '-'";
    fs::remove(dir.path() / "-");
  }
  // The statistics on standard output are the whole JSON and nothing else.
  const TessimRun r = tessim({"sim", mesh, "-L", "2", "--stats", "-"}, dir.path());
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << r.out.substr(0, 200);
  EXPECT_TRUE(j.contains("cycles"));
}

TEST(BadOutputDash, TwoOutputsOnStandardOutputAreRefused) {
  const TempDir dir;
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"sim", kCube.string(), "-L", "2", "--stats", "-", "--trace", "-"},
           {"sim", kCube.string(), "-L", "2", "--stats", "-", "-o", "/dev/stdout"},
       }) {
    const TessimRun r = tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << joined(args) << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "tessim: error: ") && contains(r.err, "standard output")) << r.err;
    EXPECT_TRUE(r.out.empty()) << joined(args) << ": " << r.out.substr(0, 80);
    EXPECT_EQ(listing(dir.path()), " (empty)");
  }
}

// ---------------------------------------------------------------------------------------------
// Inputs read whole: bounded, and refused at once when not a regular file.

// A sparse file of `bytes` zero bytes (no disk space used).
fs::path sparse_file(const TempDir& dir, const std::string& name, std::uintmax_t bytes) {
  const fs::path p = dir.path() / name;
  { std::ofstream(p) << ""; }
  fs::resize_file(p, bytes);
  return p;
}

TEST(BadInputSize, OversizedInputsAreRefusedNamingTheLimit) {
  const TempDir dir;
  const fs::path stats = write_stats(dir);
  const fs::path config = sparse_file(dir, "config.json", (1u << 20) + 1);
  const fs::path big_stats = sparse_file(dir, "big-stats.json", (64u << 20) + 1);
  const fs::path image = sparse_file(dir, "image.png", (256u << 20) + 1);
  struct Case {
    std::vector<std::string> args;
    fs::path file;
    std::string limit;
  };
  const std::vector<Case> cases = {
      {{"sim", kCube.string(), "--config", config.string()}, config, "larger than 1 MiB"},
      {{"render", kCube.string(), "--color", "error-position", "--config", config.string(), "-o", "out.png"},
       config,
       "larger than 1 MiB"},
      {{"report", big_stats.string(), "-o", "out.html"}, big_stats, "larger than 64 MiB"},
      {{"compare", big_stats.string(), stats.string()}, big_stats, "larger than 64 MiB"},
      {{"report", stats.string(), "--image", image.string(), "-o", "out.html"}, image, "larger than 256 MiB"},
  };
  for (const Case& c : cases) {
    const TessimRun r = tessim(c.args, dir.path(), 30);
    EXPECT_EQ(r.status, 2) << joined(c.args) << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "tessim: error: " + c.file.string() + ": ") && contains(r.err, c.limit))
        << joined(c.args) << "\n" << r.err;
    EXPECT_LT(r.seconds, 5.0) << joined(c.args);
    EXPECT_FALSE(fs::exists(dir.path() / "out.html") || fs::exists(dir.path() / "out.png"));
  }
}

TEST(BadInputDevice, DevicesAndPipesAreRefusedAtOnce) {
  const TempDir dir;
  const fs::path stats = write_stats(dir);
  const fs::path fifo = dir.path() / "image.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);  // no writer: reading it would block forever
  struct Case {
    std::vector<std::string> args;
    std::string file;
  };
  const std::vector<Case> cases = {
      {{"sim", kCube.string(), "--config", "/dev/zero"}, "/dev/zero"},
      {{"report", "/dev/zero", "-o", "out.html"}, "/dev/zero"},
      {{"report", stats.string(), "--image", "/dev/zero", "-o", "out.html"}, "/dev/zero"},
      {{"report", stats.string(), "--image", fifo.string(), "-o", "out.html"}, fifo.string()},
      {{"sim", kCube.string(), "--config", fifo.string()}, fifo.string()},
  };
  for (const Case& c : cases) {
    const TessimRun r = tessim(c.args, dir.path(), 20);
    EXPECT_EQ(r.status, 2) << joined(c.args) << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "tessim: error: " + c.file + ": ") && contains(r.err, "not a regular file"))
        << joined(c.args) << "\n" << r.err;
    EXPECT_LT(r.seconds, 5.0) << joined(c.args);
    EXPECT_FALSE(fs::exists(dir.path() / "out.html"));
  }
}

// ---------------------------------------------------------------------------------------------
// Waveforms: an interrupted recording leaves nothing; the layout names its dump relatively.

void expect_interrupted_wave_leaves_nothing(int sig, const std::string& name) {
  const TempDir dir;
  const std::string wave = (dir.path() / name).string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(sig, SIG_DFL);
    if (FILE* f = std::freopen("/dev/null", "w", stdout)) (void)f;
    if (FILE* f = std::freopen("/dev/null", "w", stderr)) (void)f;
    const char* tessim = binary_under_test();
    // A long run recording every cycle: killed while the recording grows.
    ::execl(tessim, tessim, "cosim", "--random", "200000", "--random-max-L", "8", "--wave", wave.c_str(),
            "--wave-window", "0:100000000", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Should an assertion end the test early, the run does not outlive it.
  struct Reaper {
    pid_t pid;
    bool reaped = false;
    ~Reaper() {
      if (reaped) return;
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  } reaper{pid};
  // Wait until the recording has grown a little, then interrupt.
  auto recorded = [&] {
    std::uintmax_t bytes = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir.path(), ec))
      if (e.is_regular_file(ec)) bytes += e.file_size(ec);
    return bytes;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (recorded() < 100000 && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      reaper.reaped = true;
      FAIL() << "cosim ended before it was interrupted: status " << status;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_GE(recorded(), 100000u) << "no recording grew:" << listing(dir.path());
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  reaper.reaped = true;
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
  EXPECT_EQ(listing(dir.path()), " (empty)");
}

TEST(BadOutputInterruptedWave, SigintLeavesNoFst) { expect_interrupted_wave_leaves_nothing(SIGINT, "w.fst"); }
TEST(BadOutputInterruptedWave, SigtermLeavesNoFst) { expect_interrupted_wave_leaves_nothing(SIGTERM, "w.fst"); }
TEST(BadOutputInterruptedWave, SigtermLeavesNoVcdRecording) {
  expect_interrupted_wave_leaves_nothing(SIGTERM, "w.vcd");
}

TEST(OutputTargets, GtkwaveLayoutNamesItsDumpRelatively) {
  const TempDir dir;
  fs::create_directory(dir.path() / "waves");
  const TessimRun r = tessim({"cosim", "--random", "4", "--random-max-L", "3", "--wave", "waves/w.fst",
                        "--wave-window", "0:40"},
                       dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(listing(dir.path() / "waves"), " w.fst w.gtkw");
  const std::string layout = slurp(dir.path() / "waves" / "w.gtkw");
  // gtkwave opens a relative dump file beside the save file: the pair can move together.
  EXPECT_TRUE(contains(layout, "[dumpfile] \"w.fst\"\n")) << layout.substr(0, 300);
  EXPECT_TRUE(contains(layout, "[savefile] \"w.gtkw\"\n")) << layout.substr(0, 300);
  EXPECT_FALSE(contains(layout, dir.path().string())) << "an absolute path in the layout";
}

// ---------------------------------------------------------------------------------------------
// Empty values, outputs that are inputs, link loops, a full standard output, no command at all.

TEST(BadInputEmptyValue, AnEmptyValueIsRefusedNotIgnored) {
  const TempDir dir;
  const std::string mesh = kCube.string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"sim", mesh, "-L", "2", "--stats", ""},
           {"sim", mesh, "-L", "2", "-o", ""},
           {"sim", mesh, "-L", "2", "--trace", ""},
           {"sim", mesh, "-L", "2", "--config", ""},
           {"tessellate", mesh, "-L", "2", "-o", ""},
           {"render", mesh, "-L", "2", "-o", ""},
       }) {
    const TessimRun r = tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << joined(args) << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "has an empty value")) << joined(args) << ": " << r.err;
    EXPECT_EQ(listing(dir.path()), " (empty)") << joined(args);
  }
}

TEST(BadOutputIsInput, AnOutputMayNotOverwriteTheInputMesh) {
  const TempDir dir;
  fs::copy_file("/usr/share/assimp/models/PLY/cube.ply", dir.path() / "m.ply");
  fs::create_symlink("m.ply", dir.path() / "alias.ply");
  const std::string before = slurp(dir.path() / "m.ply");
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"tessellate", "m.ply", "-L", "2", "-o", "m.ply"},
           {"sim", "m.ply", "-L", "2", "-o", "m.ply"},
           {"sim", "m.ply", "-L", "2", "-o", "alias.ply"},
           {"sim", "m.ply", "-L", "2", "--stats", "./m.ply"},
           {"sim", "m.ply", "-L", "2", "--trace", "alias.ply"},
       }) {
    const TessimRun r = tessim(args, dir.path());
    EXPECT_EQ(r.status, 2) << joined(args) << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "is the same file as the input MESH")) << joined(args) << ": " << r.err;
    EXPECT_EQ(slurp(dir.path() / "m.ply"), before) << joined(args) << ": the input changed";
  }
  EXPECT_TRUE(fs::is_symlink(dir.path() / "alias.ply"));
  EXPECT_EQ(listing(dir.path()), " alias.ply m.ply");
}

TEST(BadOutputIsInput, AnOutputMayNotOverwriteTheConfiguration) {
  const TempDir dir;
  { std::ofstream(dir.path() / "c.json") << "{\"int_blocks\": 2}\n"; }
  const TessimRun r = tessim({"sim", kCube.string(), "-L", "2", "--config", "c.json", "--stats", "c.json"}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "is the same file as the input --config")) << r.err;
  EXPECT_EQ(slurp(dir.path() / "c.json"), "{\"int_blocks\": 2}\n");
}

TEST(BadOutputLinkLoop, ALoopOfSymbolicLinksIsRefused) {
  const TempDir dir;
  fs::create_symlink("b", dir.path() / "a");
  fs::create_symlink("a", dir.path() / "b");
  const TessimRun r = tessim({"sim", kCube.string(), "-L", "2", "--stats", "a"}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "loop of symbolic links")) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir.path() / "a") && fs::is_symlink(dir.path() / "b")) << "a link was replaced";
  EXPECT_EQ(listing(dir.path()), " a b");
}

// Runs `tessim ARGS > /dev/full`: every byte written to standard output fails with ENOSPC.
int status_with_full_stdout(const std::vector<std::string>& args, std::string* err) {
  const TempDir scratch;
  // Appended piece by piece: GCC 12 warns (-Wrestrict) about "literal" + std::string here.
  std::string command = "exec ";
  command += quote(binary_under_test());
  for (const std::string& a : args) {
    command += ' ';
    command += quote(a);
  }
  command += " >/dev/full 2>";
  command += quote((scratch.path() / "err").string());
  command += " </dev/null";
  const int raw = std::system(command.c_str());
  *err = slurp(scratch.path() / "err");
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(BadOutputFullStdout, WhatIsPrintedMustReachStandardOutput) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this machine";
  const TempDir dir;
  const fs::path stats = write_stats(dir);
  const std::string mesh = kCube.string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"schema"},
           {"info", mesh, "--json"},
           {"compare", stats.string(), stats.string()},
           {"sim", mesh, "-L", "2"},
           {"pattern", "--outer", "3,2,2", "--inner", "2", "--partitioning", "integer", "--json"},
       }) {
    std::string err;
    EXPECT_EQ(status_with_full_stdout(args, &err), 2) << joined(args) << "\n" << err;
    EXPECT_TRUE(contains(err, "standard output")) << joined(args) << ": " << err;
  }
}

// A small tmpfs mounted on a directory for as long as it lives (root only); `mounted()` false
// when it could not be mounted.
class SmallFileSystem {
 public:
  SmallFileSystem(const fs::path& dir, const std::string& size) : dir_(dir) {
    fs::create_directories(dir_);
    mounted_ = ::geteuid() == 0 && ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
  }
  ~SmallFileSystem() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }
  // Leaves `free_kib` KiB free: a file "fill" takes the rest.
  void leave_free(std::uintmax_t free_kib) const {
    fs::remove(dir_ / "fill");
    const std::uintmax_t space = fs::space(dir_).available;
    const std::uintmax_t fill = space > free_kib * 1024 ? space - free_kib * 1024 : 0;
    std::ofstream(dir_ / "fill", std::ios::binary) << std::string(fill, '\0');
  }

 private:
  fs::path dir_;
  bool mounted_ = false;
};

// A waveform on a full file system: the FST writer neither checks its writes nor survives a
// mapped file it cannot grow (SIGBUS); every run must end in exit 2 with one message naming the
// dump, and leave nothing but the file that filled the disk. From no space at all to space for
// part of the recording (a truncated FST), and a VCD whose recording fits but whose conversion
// does not.
TEST(BadOutputFullDisk, AWaveformThatDoesNotFitLeavesNothing) {
  const TempDir dir;
  const fs::path small = dir.path() / "small";
  const SmallFileSystem fs_small(small, "128k");
  if (!fs_small.mounted()) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const std::vector<std::string> cosim{"cosim", kCube.string(), "-L", "8", "--wave-window", "0:4500", "--quiet"};
  for (const char* dump : {"w.fst", "w.vcd"})
    for (const std::uintmax_t free_kib : {0u, 8u, 24u, 48u, 96u}) {
      fs_small.leave_free(free_kib);
      std::vector<std::string> args = cosim;
      args.insert(args.end(), {"--wave", dump});
      const TessimRun r = tessim(args, small);
      const std::string what = std::string(dump) + " with " + std::to_string(free_kib) + " KiB free";
      EXPECT_EQ(r.status, 2) << what << ": " << r.err;
      EXPECT_EQ(r.err.rfind(std::string("tessim: error: ") + dump + ": output: ", 0), 0u) << what << ": " << r.err;
      EXPECT_EQ(listing(small), " fill") << what;
    }
  // The recording fits (about 1.1 MB), its 48 MB VCD does not.
  const fs::path mid = dir.path() / "mid";
  const SmallFileSystem fs_mid(mid, "4m");
  ASSERT_TRUE(fs_mid.mounted());
  std::vector<std::string> args = cosim;
  args.insert(args.end(), {"--wave", "w.vcd"});
  const TessimRun r = tessim(args, mid);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "tessim: error: w.vcd: output: write failed")) << r.err;
  EXPECT_EQ(listing(mid), " (empty)");
  // The same run with room writes both files: the checks do not refuse a complete waveform.
  const TessimRun ok = tessim(args, dir.path());
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_GT(fs::file_size(dir.path() / "w.vcd"), 40'000'000u);
  EXPECT_TRUE(fs::exists(dir.path() / "w.gtkw"));
}

TEST(BadInputNumbers, OnlyDecimalNumbersInSubOptions) {
  const TempDir dir;
  for (const char* bad : {"eye=0x10,0,0", "eye=1,2,3,beta=0x10", "eye=1,2,3,beta=inf", "eye=1,nan,3"}) {
    const TessimRun r = tessim({"info", kCube.string(), "--silhouette", bad}, dir.path());
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "--silhouette")) << bad << ": " << r.err;
  }
  EXPECT_EQ(tessim({"info", kCube.string(), "--silhouette", "eye=1e3,-2.5,+3,beta=0.5"}, dir.path()).status, 0);
  // A key given twice is named as such (it used to read "'beta=2' ... is not a number").
  const TessimRun twice = tessim({"info", kCube.string(), "--silhouette", "eye=1,2,3,beta=1,beta=2"}, dir.path());
  EXPECT_EQ(twice.status, 2) << twice.err;
  EXPECT_TRUE(contains(twice.err, "'beta' is given twice")) << twice.err;
}

TEST(BadInputIgnored, ColorMaxWithoutAHeatMapIsRefused) {
  const TempDir dir;
  const TessimRun r =
      tessim({"render", kCube.string(), "-L", "2", "--size", "64x48", "--color-max", "2", "-o", "o.png"}, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "--color-max: scales a heat map")) << r.err;
  EXPECT_EQ(listing(dir.path()), " (empty)");
}

TEST(BadInputIgnored, ABadPictureSizeIsRefusedForAnSvgToo) {
  const TempDir dir;
  std::vector<std::string> args = kPattern;
  args.insert(args.end(), {"-o", "x.svg", "--size", "0x0"});
  const TessimRun r = tessim(args, dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "--size")) << r.err;
  EXPECT_EQ(listing(dir.path()), " (empty)");
}

// A file name with an escape sequence or a newline is shown as error messages show it: a name
// cannot recolour the terminal or forge a summary line.
TEST(Summaries, FileNamesArePrintedEscaped) {
  const TempDir dir;
  const std::string name = "a\x1b[31m\nlimit fake.ply";
  fs::copy_file("/usr/share/assimp/models/PLY/cube.ply", dir.path() / name);
  for (const auto& args : std::vector<std::vector<std::string>>{{"info", name}, {"sim", name, "-L", "2"}}) {
    const TessimRun r = tessim(args, dir.path());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(contains(r.out, "\x1b")) << args[0] << ": a raw ESC in the summary";
    EXPECT_FALSE(contains(r.out, "\nlimit fake")) << args[0] << ": a raw newline in the summary";
    EXPECT_TRUE(contains(r.out, "a\\x1b[31m\\nlimit fake.ply")) << r.out;
  }
  const TessimRun info = tessim({"info", name}, dir.path());
  EXPECT_TRUE(contains(info.out, "edges                 18")) << info.out;
  EXPECT_TRUE(contains(info.out, "half-extent")) << info.out;
}

TEST(NoCommand, TessimAloneShowsTheHelp) {
  const TempDir dir;
  const TessimRun r = tessim({}, dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "sim") && contains(r.out, "cosim") && contains(r.out, "--help")) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

}  // namespace
}  // namespace tessim
