// Waveform files of the co-simulation (docs/verification.md, Waveforms): the RTL records FST, its
// native trace format; a `.vcd` file is that recording converted by gtkwave's fst2vcd. Next to
// every dump goes a gtkwave save file (`.gtkw`) that opens it with the unit's interfaces laid
// out: clock and reset, the triangle handshake, the CPG, the control-point buffers, the TE and
// the vertex handshake.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "sim/config.hpp"

namespace tessim::cosim {

enum class WaveFormat { Fst, Vcd };

// The format a path asks for, by its extension; InputError naming `option` for any other.
WaveFormat wave_format(const std::filesystem::path& path, const std::string& option = "--wave");

// What can be checked before a run: the extension, and for VCD that fst2vcd is installed.
void check_wave_path(const std::filesystem::path& path, const std::string& option = "--wave");

// The file the RTL records into: the FST itself, or a temporary FST beside a VCD.
std::filesystem::path wave_recording_path(const std::filesystem::path& path);

// The gtkwave save file of a dump: the dump's path with the extension .gtkw.
std::filesystem::path gtkw_path(const std::filesystem::path& dump);

// Cycles [from, to] recorded during the run itself (both included; the time of cycle c is 2c
// and 2c + 1, microarchitecture.md §2).
struct WaveWindow {
  std::uint64_t from = 0;
  std::uint64_t to = std::numeric_limits<std::uint64_t>::max();
};

// After the RTL closed its recording: converts it to VCD where the path asks for it, and writes
// the .gtkw for `hw` (signal widths follow the configuration) opening at cycle `first_cycle`, with
// the marker on cycle `marker` (a divergence) when given. Throws std::runtime_error if fst2vcd
// fails.
void finish_wave(const std::filesystem::path& path, const sim::HardwareConfig& hw, std::uint64_t first_cycle,
                 std::optional<std::uint64_t> marker = std::nullopt);

}  // namespace tessim::cosim
