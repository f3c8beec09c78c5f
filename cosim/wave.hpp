// Waveform files of the co-simulation (docs/verification.md, Waveforms): the RTL records FST, its
// native trace format; a `.vcd` file is that recording converted by gtkwave's fst2vcd. Next to
// every dump goes a gtkwave save file (`.gtkw`) that opens it with the unit's interfaces laid
// out: clock and reset, the triangle handshake, the CPG, the control-point buffers, the TE and
// the vertex handshake.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/base/output_file.hpp"
#include "sim/config/config.hpp"

namespace tessim::cosim {

enum class WaveFormat { Fst, Vcd };

// The format a path asks for, by its extension; InputError naming `option` for any other.
WaveFormat wave_format(const std::filesystem::path& path, const std::string& option = "--wave");

// What can be checked before a run: the extension, for VCD that fst2vcd is installed, and that
// the path names a file (or a new one): a waveform and its layout go side by side into a
// directory, so "-", a device or a pipe is refused.
void check_wave_path(const std::filesystem::path& path, const std::string& option = "--wave");

// The file the RTL records into: a temporary FST beside the dump (a symbolic link given as the
// dump resolved), `DUMP.tmp-PID.recording.fst`. finish_wave() moves it into place (FST) or
// converts and removes it (VCD); the FST writer keeps its hierarchy in `RECORDING.hier` until it
// closes the file.
std::filesystem::path wave_recording_path(const std::filesystem::path& path);

// The temporaries of a dump's recording (the recording, its .hier and .pak side files) entered in
// the table of files removed when the process is killed by SIGINT, SIGTERM or SIGHUP
// (model/base/output_file.hpp), and removed when this object goes, so that neither an interrupted nor
// a failed run leaves a partial recording behind. Hold one for as long as runs may record into
// `path`.
class WaveTemporaries {
 public:
  explicit WaveTemporaries(const std::filesystem::path& path);
  ~WaveTemporaries();
  WaveTemporaries(const WaveTemporaries&) = delete;
  WaveTemporaries& operator=(const WaveTemporaries&) = delete;

 private:
  std::vector<std::unique_ptr<PendingTemporary>> files_;
  BusErrorExit bus_error_;  // the FST writer's mapped files on a full file system: exit 2, nothing left
};

// Why an FST file is not complete, or nothing when it is: its blocks (a type byte and a
// big-endian length each) must tile the file exactly, starting with the header, and hold the
// value-change sections the header counts, the geometry and the hierarchy. The FST writer does
// not check its writes, so a full file system leaves a truncated file that it reports as written.
std::optional<std::string> fst_incomplete(const std::filesystem::path& fst);

// The gtkwave save file of a dump: the dump's path with the extension .gtkw.
std::filesystem::path gtkw_path(const std::filesystem::path& dump);

// Cycles [from, to] recorded during the run itself (both included; the time of cycle c is 2c
// and 2c + 1, microarchitecture.md §2).
struct WaveWindow {
  std::uint64_t from = 0;
  std::uint64_t to = std::numeric_limits<std::uint64_t>::max();
};

// After the RTL closed its recording: moves it into place as the FST, or converts it to the VCD
// (fst2vcd's standard output written through a temporary, renamed into place), and writes the
// .gtkw for `hw` (signal widths follow the configuration) opening at cycle `first_cycle`, with the
// marker on cycle `marker` (a divergence) when given. The .gtkw names the dump relative to itself,
// so the pair can move together. Throws InputError when the recording is incomplete or a write
// fails (a full file system: nothing is left in place), std::runtime_error if fst2vcd fails on a
// complete recording.
void finish_wave(const std::filesystem::path& path, const sim::HardwareConfig& hw, std::uint64_t first_cycle,
                 std::optional<std::uint64_t> marker = std::nullopt);

}  // namespace tessim::cosim
