#include "cosim/wave.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/config/ports.hpp"
#include "sim/values/cpg.hpp"

extern char** environ;

namespace tessim::cosim {

namespace {

constexpr const char* kFst2Vcd = "fst2vcd";  // Debian package gtkwave

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((std::filesystem::path(dir) / program).c_str(), X_OK) == 0) return true;
  }
  return false;
}

// Verilog's $clog2: the bits that count 0 .. x - 1.
int clog2(std::uint64_t x) {
  int bits = 0;
  while ((std::uint64_t{1} << bits) < x) ++bits;
  return bits;
}

std::string range(int width) {
  std::string r;
  if (width == 1) return r;
  r += '[';
  r += std::to_string(width - 1);
  r += ":0]";
  return r;
}

// Runs fst2vcd on `recording` and copies its standard output into `out`.
void convert_to_vcd(const std::filesystem::path& recording, std::ostream& out, const std::filesystem::path& path) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error("cannot create a pipe for fst2vcd");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[1]);
  std::vector<std::string> args{kFst2Vcd, "-f", recording.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, kFst2Vcd, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (spawned != 0) {
    ::close(pipe_fds[0]);
    throw std::runtime_error("cannot run fst2vcd to write " + path.string());
  }
  std::vector<char> buffer(1 << 16);
  bool write_failed = false;
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    if (!write_failed) {
      out.write(buffer.data(), n);
      write_failed = !out;  // keep draining, so that fst2vcd is not left blocked on the pipe
    }
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (write_failed) throw InputError(path.string(), "output", "write failed (no space left on the file system?)");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("fst2vcd failed to convert the waveform into " + path.string());
}

}  // namespace

WaveFormat wave_format(const std::filesystem::path& path, const std::string& option) {
  const std::string ext = path.extension().string();
  if (ext == ".fst") return WaveFormat::Fst;
  if (ext == ".vcd") return WaveFormat::Vcd;
  throw InputError("command line", option,
                   "'" + path.string() + "': the waveform format is chosen by the extension, .fst or .vcd");
}

void check_wave_path(const std::filesystem::path& path, const std::string& option) {
  if (output_kind(path) != OutputKind::File)
    throw InputError("command line", option,
                     "'" + path.string() +
                         "': a waveform is written as a file, with its .gtkw layout beside it; give a file name, "
                         "not standard output, a device or a pipe");
  if (wave_format(path, option) == WaveFormat::Vcd && !on_path(kFst2Vcd))
    throw InputError("command line", option,
                     "'" + path.string() + "': VCD output needs fst2vcd (Debian package gtkwave, scripts/setup.sh)");
}

std::filesystem::path wave_recording_path(const std::filesystem::path& path) {
  std::filesystem::path tmp = resolve_output_path(path);
  tmp += ".tmp-" + std::to_string(::getpid()) + ".recording.fst";
  return tmp;
}

WaveTemporaries::WaveTemporaries(const std::filesystem::path& path)
    : bus_error_(path.string(),
                 "the waveform could not be written: a file the FST writer maps could not grow (no space left on "
                 "the file system?)") {
  const std::filesystem::path recording = wave_recording_path(path);
  for (const char* suffix : {"", ".hier", ".pak"}) {  // the FST writer's side files (fstapi.c)
    std::filesystem::path file = recording;
    file += suffix;
    files_.push_back(std::make_unique<PendingTemporary>(file));
  }
}

WaveTemporaries::~WaveTemporaries() = default;

std::optional<std::string> fst_incomplete(const std::filesystem::path& fst) {
  // Block types of the FST format (gtkwave's fstapi.h): header, value changes (three kinds),
  // blackout, geometry, hierarchy (gzip, LZ4, LZ4 twice). 255 marks a block still being written.
  enum : int { kHeader = 0, kValues = 1, kBlackout = 2, kGeometry = 3, kHierarchy = 4, kValuesAlias = 5,
               kHierarchyLz4 = 6, kHierarchyLz4Duo = 7, kValuesAlias2 = 8 };
  std::ifstream in(fst, std::ios::binary);
  if (!in) return "cannot be read back";
  in.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  auto u64 = [&](std::uint64_t at) -> std::optional<std::uint64_t> {
    unsigned char b[8];
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(b), 8)) return std::nullopt;
    std::uint64_t v = 0;
    for (unsigned char c : b) v = v << 8 | c;
    return v;
  };
  std::uint64_t at = 0, values = 0, expected_values = 0;
  bool geometry = false, hierarchy = false;
  for (int block = 0; at < size; ++block) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(at));
    const int type = in.get();
    const std::optional<std::uint64_t> length = u64(at + 1);  // counts itself, not the type byte
    if (type == EOF || !length || *length < 8 || *length > size - at - 1)
      return "its block at byte " + std::to_string(at) + " runs past the end of the file (" + std::to_string(size) +
             " bytes)";
    if (block == 0) {
      if (type != kHeader) return "it does not begin with an FST header";
      const std::optional<std::uint64_t> count = u64(at + 65);  // the value-change sections written
      if (!count) return "its header is cut short";
      expected_values = *count;
    } else if (type == kValues || type == kValuesAlias || type == kValuesAlias2) {
      ++values;
    } else if (type == kGeometry) {
      geometry = true;
    } else if (type == kHierarchy || type == kHierarchyLz4 || type == kHierarchyLz4Duo) {
      hierarchy = true;
    } else if (type != kBlackout) {
      return "its block at byte " + std::to_string(at) + " has type " + std::to_string(type) +
             " (unfinished or unknown)";
    }
    at += 1 + *length;
  }
  if (at == 0) return "it is empty";
  if (values != expected_values)
    return "it holds " + std::to_string(values) + " value-change sections where its header counts " +
           std::to_string(expected_values);
  if (!geometry || !hierarchy) return std::string("it has no ") + (geometry ? "hierarchy" : "geometry");
  return std::nullopt;
}

std::filesystem::path gtkw_path(const std::filesystem::path& dump) {
  std::filesystem::path p = dump;
  p.replace_extension(".gtkw");
  return p;
}

// The .gtkw layout of a dump (see wave.hpp).
static std::string gtkw_text(const std::filesystem::path& dump, const sim::HardwareConfig& hw, std::uint64_t first_cycle,
                      std::optional<std::uint64_t> marker) {
  const int V = hw.te_contexts;
  // Widths of the RTL's internal registers for this configuration (rtl/tess_cpg.sv, tess_te.sv, tess_fifo.sv).
  // The CPG's counter holds C plus, with scalar tags, the longest tag pass (three tagged corners).
  sim::TriangleFx all_tagged;
  for (sim::TagsFx& t : all_tagged.tags) t.delta[0] = 1;
  const int tag_max = hw.cpg_tags ? sim::cpg_tag_cycles(all_tagged, hw.format, hw.cpg) : 0;
  const int cpg_counter =
      clog2(static_cast<std::uint64_t>(sim::cpg_cycles(NormalMode::Quadratic, hw.format, hw.cpg) + tag_max));
  const int cpg_step = clog2(static_cast<std::uint64_t>(sim::cpg_edge_cycles(NormalMode::Quadratic, hw.format, hw.cpg.digit_bits,
                                                                           hw.cpg.product_reg != 0)));
  const int te_count = clog2(static_cast<std::uint64_t>(V) + 1);
  const int te_index = V > 1 ? clog2(static_cast<std::uint64_t>(V)) : 1;
  const int buf_index = hw.cp_buffers > 1 ? clog2(static_cast<std::uint64_t>(hw.cp_buffers)) : 1;

  std::ostringstream o;
  // Relative names: gtkwave finds a relative dump file beside the save file it opens, so the
  // pair can move together (and the page of tessim report links to both relatively).
  o << "[*] tessim cosim: the interfaces of tess_unit (docs/verification.md, Waveforms)\n";
  o << "[dumpfile] \"" << dump.filename().string() << "\"\n";
  o << "[savefile] \"" << gtkw_path(dump).filename().string() << "\"\n";
  // Zoom (about 40 cycles across a 1600-pixel window), the marker on the divergence, and the view
  // opening 34 cycles before it.
  o << "*-4.000000 " << (marker ? static_cast<long long>(2 * *marker) : -1LL) << "\n";
  const std::uint64_t start = marker && *marker > first_cycle + 34 ? *marker - 34 : first_cycle;
  o << "[timestart] " << 2 * start << "\n";
  o << "[size] 1600 1150\n[signals_width] 320\n[sst_width] 240\n[sst_expanded] 1\n";
  o << "[treeopen] tess.\n[treeopen] tess.tess_unit.\n";
  const std::string top = "tess.", unit = "tess.tess_unit.";
  auto group = [&](const char* title) { o << "@200\n-" << title << "\n"; };
  auto bit = [&](const std::string& name) { o << "@28\n" << name << "\n"; };
  auto hex = [&](const std::string& name, int width) { o << "@22\n" << name << range(width) << "\n"; };
  auto dec = [&](const std::string& name, int width) { o << "@24\n" << name << range(width) << "\n"; };

  // Ports: their widths for this configuration (sim/config/ports.hpp).
  auto port = [&](const char* name, bool as_hex = false) {
    const sim::Port* p = sim::find_port(name);
    if (!p) throw std::logic_error(std::string("wave layout: no port ") + name);
    const int width = sim::width_bits(p->width, hw);
    if (width == 1) return bit(top + name);
    as_hex ? hex(top + name, width) : dec(top + name, width);
  };

  group("clock, reset, mode");
  port("clk_i");
  port("rst_ni");
  port("mode_i");
  // The cycle counter, one of perf_ctr_o's (tess_pkg::CtrCycles).
  dec(unit + "g_ctr[" + std::to_string(sim::rtl_counter_index(sim::row_of_rtl("CtrCycles"))) + "].ctr_q",
      sim::pkg::kCounterBits);
  group("triangles in");
  port("tri_valid_i");
  port("tri_ready_o");
  port("tri_id_i");
  port("tri_l_i");
  port("tri_pattern_i");
  port("tri_factors_i", true);
  dec(unit + "u_tri_fifo.count_q", clog2(static_cast<std::uint64_t>(hw.tri_fifo_depth) + 1));
  group("CPG");
  // Each copy of the CPG (rtl/tess_cpg_array.sv); the turn pointers exist with two or more.
  const int copies = hw.cpg.copies;
  if (copies > 1) {
    const std::string turn = "[" + std::to_string(clog2(static_cast<std::uint64_t>(copies)) - 1) + ":0]";
    o << "@24\n" << unit << "u_cpgs.accept_q" << turn << "\n";
    o << "@24\n" << unit << "u_cpgs.write_q" << turn << "\n";
  }
  for (int c = 0; c < copies; ++c) {
    const std::string cpg = unit + "u_cpgs.g_copy[" + std::to_string(c) + "].u_cpg.";
    bit(cpg + "accept");
    bit(cpg + "busy_q");
    dec(cpg + "counter_q", cpg_counter);
    dec(cpg + "edge_q", 2);
    dec(cpg + "step_q", cpg_step);
    bit(cpg + "write");
  }
  group("control-point buffers (0 EMPTY, 1 FULL, 2 DRAINING)");
  for (int b = 0; b < hw.cp_buffers; ++b) dec(unit + "u_cpbuf.state_q[" + std::to_string(b) + "]", 2);
  // The pointers are vectors even when one bit wide: the dump names them with their range.
  const std::string ptr_range = "[" + std::to_string(buf_index - 1) + ":0]";
  o << "@24\n" << unit << "u_cpbuf.wr_ptr_q" << ptr_range << "\n";
  o << "@24\n" << unit << "u_cpbuf.rd_ptr_q" << ptr_range << "\n";
  group("DPG (D3D11 walk: ring, edge, position)");
  dec(unit + "u_te.u_dpg.index_q", sim::pkg::kIndexBits);
  dec(unit + "u_te.u_dpg.ring_q", 6);
  dec(unit + "u_te.u_dpg.edge_q", 2);
  dec(unit + "u_te.u_dpg.p_q", 7);
  group("TE");
  dec(unit + "u_te.count_q", te_count);
  dec(unit + "u_te.head_q", te_index);
  hex(unit + "u_te.int_busy_o", hw.int_blocks);
  bit(unit + "u_te.te_busy_o");
  bit(unit + "u_te.te_starved_o");
  bit(unit + "u_te.te_blocked_o");
  group("vertices out");
  dec(unit + "u_vtx_fifo.count_q", clog2(static_cast<std::uint64_t>(hw.vtx_fifo_depth) + 1));
  port("vtx_valid_o");
  port("vtx_ready_i");
  port("vtx_id_o");
  port("vtx_j_o");
  port("vtx_k_o");
  port("vtx_l_o");
  port("vtx_index_o");
  port("vtx_last_o");
  port("vtx_u_o", true);
  port("vtx_v_o", true);
  port("vtx_pos_o", true);
  port("vtx_nrm_o", true);
  port("vtx_flags_o");
  return o.str();
}

void finish_wave(const std::filesystem::path& path, const sim::HardwareConfig& hw, std::uint64_t first_cycle,
                 std::optional<std::uint64_t> marker) {
  const std::filesystem::path recording = wave_recording_path(path);
  // Whatever happens below, the recording does not stay (moved into place, or converted).
  struct RemoveRecording {
    const std::filesystem::path& path;
    ~RemoveRecording() {
      std::error_code ec;
      std::filesystem::remove(path, ec);
    }
  } remove_recording{recording};
  if (const std::optional<std::string> why = fst_incomplete(recording))
    throw InputError(path.string(), "output",
                     "the waveform could not be written: the recording " + recording.filename().string() +
                         " is incomplete, " + *why + " (no space left on the file system?)");
  AtomicOutput dump(path, true);
  if (wave_format(path) == WaveFormat::Fst) {
    std::error_code ec;
    std::filesystem::rename(recording, dump.temp_path(), ec);
    if (ec) throw std::runtime_error("cannot move the recording into " + path.string() + ": " + ec.message());
  } else {
    // fst2vcd writes to a pipe and the dump's stream checks every write: fst2vcd does not check
    // its own (a full file system would leave a truncated VCD and exit 0).
    convert_to_vcd(recording, dump.stream(), path);
    dump.stream().flush();
    if (!dump.stream()) throw InputError(path.string(), "output", "write failed (no space left on the file system?)");
  }
  AtomicOutput gtkw(gtkw_path(path));
  gtkw.stream() << gtkw_text(path, hw, first_cycle, marker);
  // The layout is complete before the dump moves into place: a failure leaves neither.
  gtkw.stream().flush();
  if (!gtkw.stream()) throw std::runtime_error("cannot write " + gtkw_path(path).string());
  if (wave_format(path) == WaveFormat::Fst) dump.commit_external();
  else dump.commit();
  gtkw.commit();
}

}  // namespace tessim::cosim
