// The boundary of tess_unit as the RTL declares it (rtl/tess_unit.sv, rtl/tess_pkg.sv), defined
// once: tess_pkg's fixed field widths, every port with its width as a function of the
// parameters, the bits of one triangle in and one vertex out, and the codes the ports carry.
// `tessim schema` lists it (scripts read the widths there), cosim/wave.cpp lays out its
// waveforms with it; tests/sim/rtl_package_test.cpp checks it against tess_pkg.sv and
// tests/rtl/rtl_ports_test.cpp against the ports of every Verilated build.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "sim/config/config.hpp"

namespace tessim::sim {

// Fixed field widths of the interfaces (tess_pkg, docs/microarchitecture.md §3).
namespace pkg {
inline constexpr int kFactorBits = 7;    // L in 1..64, lattice indices j, k in 0..64
inline constexpr int kIdBits = 32;       // patch id
inline constexpr int kFlagBits = 2;      // FxFlag bits
inline constexpr int kModeBits = 2;      // mode_i
inline constexpr int kPatternBits = 2;   // TriPattern
inline constexpr int kFixBits = 23;      // a D3D11 factor: unsigned 16.16, at most 64
inline constexpr int kIndexBits = 12;    // a point's index in its patch
inline constexpr int kCounterBits = 64;  // one counter of perf_ctr_o
// The triangle's pattern descriptor {inner factor, outer factors 2..0, pattern, L}.
inline constexpr int kDescBits = kFactorBits + kPatternBits + 4 * kFixBits;

// The localparams above by their tess_pkg names.
struct Constant {
  const char* name;
  int value;
};
inline constexpr std::array<Constant, 9> kWidths{{
    {"FactorBits", kFactorBits},
    {"IdBits", kIdBits},
    {"FlagBits", kFlagBits},
    {"ModeBits", kModeBits},
    {"PatternBits", kPatternBits},
    {"FixBits", kFixBits},
    {"IndexBits", kIndexBits},
    {"CounterBits", kCounterBits},
    {"DescBits", kDescBits},
}};
}  // namespace pkg

// A width is a sum of terms coef * (product of the variables in `vars`); no variable: a
// constant. Variables: W = 1 + coord_int_bits + coord_frac_bits, the configuration keys
// bary_bits, int_blocks, cpg_tags, alpha_bits, and takes_alpha (1 when alpha_bits > 0).
enum WidthVar : std::uint8_t {
  kVarW = 1, kVarBaryBits = 2, kVarIntBlocks = 4, kVarCpgTags = 8, kVarAlphaBits = 16, kVarTakesAlpha = 32
};
struct WidthTerm {
  int coef = 0;  // 0: unused slot
  std::uint8_t vars = 0;
};
using Width = std::array<WidthTerm, 3>;

enum class PortDir : std::uint8_t { In, Out };
// Which data item a port is part of: one triangle accepted (tri_valid_i && tri_ready_o), one
// vertex delivered (vtx_valid_o && vtx_ready_i), or neither (clock, reset, handshake, mode,
// counters).
enum class PortItem : std::uint8_t { None, Triangle, Vertex };

struct Port {
  const char* name;
  PortDir dir;
  Width width;
  PortItem item;
  // 0, or the variable (kVarCpgTags, kVarTakesAlpha) without which the port is not part of the
  // item (it exists in every build, unread).
  std::uint8_t only_with;
  const char* what;
};

// The ports of tess_unit in declaration order.
std::span<const Port> unit_ports();
const Port* find_port(const std::string& name);  // nullptr if unknown

// Width evaluated for a configuration.
int width_bits(const Width& w, const HardwareConfig& hw);
// "9*W", "bary_bits + 1", "18*W*cpg_tags + 3*alpha_bits + 3*takes_alpha + 18*W + 133".
std::string width_text(const Width& w);

// Bits of one item: the ports that carry it (the TRI FIFO's and the VTX FIFO's entry width,
// tess_unit's TriW and VtxW), as terms and evaluated.
std::vector<WidthTerm> item_terms(PortItem item);
int item_bits(PortItem item, const HardwareConfig& hw);

// A code a port carries, with its tess_pkg name (nullptr where tess_pkg has none).
struct PortCode {
  const char* port;
  std::string name;
  int value;
  const char* pkg;
};
// mode_i (normal modes), tri_pattern_i (patterns), vtx_flags_o (flag bits).
std::vector<PortCode> port_codes();

// The ports, item widths, tess_pkg widths and codes as JSON (`tessim schema`, "interface"), with
// every width also evaluated at the default configuration.
nlohmann::json interface_json();

}  // namespace tessim::sim
