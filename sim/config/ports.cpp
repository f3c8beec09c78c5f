#include "sim/config/ports.hpp"

#include <nlohmann/json.hpp>

#include "sim/base/counter_registry.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/d3d11_walk.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {

namespace {

using nlohmann::json;

constexpr Width bits(int k) { return {{{k, 0}}}; }
constexpr Width per_w(int k) { return {{{k, kVarW}}}; }
constexpr Width weight{{{1, kVarBaryBits}, {1, 0}}};  // B + 1: a barycentric weight, 1.0 = 2^B
constexpr Width counter = bits(pkg::kCounterBits);

constexpr auto In = PortDir::In;
constexpr auto Out = PortDir::Out;
constexpr auto Tri = PortItem::Triangle;
constexpr auto Vtx = PortItem::Vertex;
constexpr auto None = PortItem::None;

// The data and control ports, in declaration order; the counter bus perf_ctr_o follows them.
constexpr std::array<Port, 26> kIoPorts{{
    {"clk_i", In, bits(1), None, 0, "clock"},
    {"rst_ni", In, bits(1), None, 0, "asynchronous reset, active low"},
    {"mode_i", In, bits(pkg::kModeBits), None, 0, "normal mode (codes), static during a run"},
    {"tri_valid_i", In, bits(1), None, 0, "a triangle is offered"},
    {"tri_ready_o", Out, bits(1), None, 0, "the TRI FIFO takes it"},
    {"tri_p_i", In, per_w(9), Tri, 0, "positions P1..P3: vertex v component c at [(3v+c)W +: W]"},
    {"tri_n_i", In, per_w(9), Tri, 0, "normals N1..N3, laid out as tri_p_i"},
    {"tri_l_i", In, bits(pkg::kFactorBits), Tri, 0, "uniform pattern: L in 1..64"},
    {"tri_pattern_i", In, bits(pkg::kPatternBits), Tri, 0, "pattern (codes)"},
    {"tri_factors_i", In, bits(4 * pkg::kFixBits), Tri, 0,
     "D3D11: factor e at [e*FixBits +: FixBits] (3 = inner), unsigned 16.16"},
    {"tri_id_i", In, bits(pkg::kIdBits), Tri, 0, "patch id, passed to every vertex"},
    {"tri_tags_i", In, per_w(18), Tri, kVarCpgTags,
     "scalar tags, read only with cpg_tags 1: vertex v's crease vector (3W), sigma, theta, beta at [6vW +: 6W]"},
    {"tri_alpha_i", In, {{{3, kVarAlphaBits}, {3, 0}}}, Tri, kVarTakesAlpha,
     "silhouette weights, read only with alpha_bits > 0: edge e's (corners e -> e+1) alpha at "
     "[e(alpha_bits+1) +: alpha_bits+1], alpha_bits fraction bits, 0..2^alpha_bits"},
    {"vtx_valid_o", Out, bits(1), None, 0, "a vertex is offered"},
    {"vtx_ready_i", In, bits(1), None, 0, "the geometry engine takes it"},
    {"vtx_pos_o", Out, per_w(3), Vtx, 0, "position: component c at [cW +: W]"},
    {"vtx_nrm_o", Out, per_w(3), Vtx, 0, "unnormalized normal, laid out as vtx_pos_o"},
    {"vtx_u_o", Out, weight, Vtx, 0, "barycentric weight u, B fraction bits"},
    {"vtx_v_o", Out, weight, Vtx, 0, "barycentric weight v"},
    {"vtx_j_o", Out, bits(pkg::kFactorBits), Vtx, 0, "uniform: lattice index j; D3D11: ring"},
    {"vtx_k_o", Out, bits(pkg::kFactorBits), Vtx, 0, "uniform: lattice index k; D3D11: edge"},
    {"vtx_l_o", Out, bits(pkg::kFactorBits), Vtx, 0, "uniform: L; D3D11: 0"},
    {"vtx_index_o", Out, bits(pkg::kIndexBits), Vtx, 0, "position in the patch's pattern order"},
    {"vtx_id_o", Out, bits(pkg::kIdBits), Vtx, 0, "patch id"},
    {"vtx_last_o", Out, bits(1), Vtx, 0, "last vertex of its patch"},
    {"vtx_flags_o", Out, bits(pkg::kFlagBits), Vtx, 0, "flag bits of the patch's control points (codes)"},
}};

// The counters: one bus, the registry's rows with an RTL counter at rtl_counter_index (the
// order of tess_pkg::ctr_e), an INT block row N counters side by side, last.
static_assert(pkg::kCounterBits == 64, "perf_ctr_o's text assumes 64-bit counters");
constexpr std::array<Port, kIoPorts.size() + 1> kPorts = [] {
  std::array<Port, kIoPorts.size() + 1> a{};
  std::size_t i = 0;
  for (const Port& p : kIoPorts) a[i++] = p;
  a[i] = {"perf_ctr_o", Out,
          {{{pkg::kCounterBits, kVarIntBlocks}, {static_cast<int>(pkg::kCounterBits * kRtlScalarCounters), 0}}},
          None, 0,
          "counters (docs/statistics.md): counter k of tess_pkg::ctr_e at [64k +: 64], INT block i's busy cycles "
          "at k = CtrIntBusy + i"};
  return a;
}();

constexpr std::array<std::pair<WidthVar, const char*>, 6> kVarNames{{{kVarW, "W"},
                                                                     {kVarBaryBits, "bary_bits"},
                                                                     {kVarIntBlocks, "int_blocks"},
                                                                     {kVarCpgTags, "cpg_tags"},
                                                                     {kVarAlphaBits, "alpha_bits"},
                                                                     {kVarTakesAlpha, "takes_alpha"}}};

int var_value(WidthVar v, const HardwareConfig& hw) {
  switch (v) {
    case kVarW: return hw.format.coord_width();
    case kVarBaryBits: return hw.format.bary_bits;
    case kVarIntBlocks: return hw.int_blocks;
    case kVarCpgTags: return hw.cpg_tags;
    case kVarAlphaBits: return hw.format.alpha_bits;
    case kVarTakesAlpha: return hw.format.takes_alpha() ? 1 : 0;
  }
  return 0;
}

int term_bits(const WidthTerm& t, const HardwareConfig& hw) {
  int x = t.coef;
  for (const auto& [v, name] : kVarNames)
    if (t.vars & v) x *= var_value(v, hw);
  return x;
}

std::string term_text(const WidthTerm& t) {
  std::string s;
  if (t.coef != 1 || t.vars == 0) s = std::to_string(t.coef);
  for (const auto& [v, name] : kVarNames) {
    if (!(t.vars & v)) continue;
    if (!s.empty()) s += '*';
    s += name;
  }
  return s;
}

std::string terms_text(const std::vector<WidthTerm>& terms) {
  std::string s;
  for (const WidthTerm& t : terms) {
    if (!s.empty()) s += " + ";
    s += term_text(t);
  }
  return s.empty() ? "0" : s;
}

json terms_json(const std::vector<WidthTerm>& terms) {
  json a = json::array();
  for (const WidthTerm& t : terms) {
    json of = json::array();
    for (const auto& [v, name] : kVarNames)
      if (t.vars & v) of.push_back(name);
    a.push_back({{"coef", t.coef}, {"of", of}});
  }
  return a;
}

std::vector<WidthTerm> used_terms(const Width& w) {
  std::vector<WidthTerm> terms;
  for (const WidthTerm& t : w)
    if (t.coef != 0) terms.push_back(t);
  return terms;
}

const char* to_string(PortItem item) {
  switch (item) {
    case PortItem::Triangle: return "triangle";
    case PortItem::Vertex: return "vertex";
    case PortItem::None: break;
  }
  return "";
}

}  // namespace

std::span<const Port> unit_ports() { return kPorts; }

const Port* find_port(const std::string& name) {
  for (const Port& p : kPorts)
    if (name == p.name) return &p;
  return nullptr;
}

int width_bits(const Width& w, const HardwareConfig& hw) {
  int x = 0;
  for (const WidthTerm& t : w) x += term_bits(t, hw);
  return x;
}

std::string width_text(const Width& w) { return terms_text(used_terms(w)); }

// Terms with equal variables merged, in order of first appearance; a tags-only port's terms
// are multiplied by the variable it is only with (cpg_tags, takes_alpha).
std::vector<WidthTerm> item_terms(PortItem item) {
  std::vector<WidthTerm> terms;
  for (const Port& p : kPorts) {
    if (p.item != item) continue;
    for (WidthTerm t : used_terms(p.width)) {
      t.vars |= p.only_with;
      if ((t.vars & kVarAlphaBits) && (t.vars & kVarTakesAlpha)) t.vars &= ~kVarTakesAlpha;  // A > 0 already
      bool merged = false;
      for (WidthTerm& have : terms) {
        if (have.vars == t.vars) {
          have.coef += t.coef;
          merged = true;
        }
      }
      if (!merged) terms.push_back(t);
    }
  }
  return terms;
}

int item_bits(PortItem item, const HardwareConfig& hw) {
  int x = 0;
  for (const WidthTerm& t : item_terms(item)) x += term_bits(t, hw);
  return x;
}

std::vector<PortCode> port_codes() {
  std::vector<PortCode> codes;
  const std::array<std::pair<NormalMode, const char*>, 3> modes{
      {{NormalMode::Quadratic, "ModeQuadratic"}, {NormalMode::Reflect, "ModeReflect"}, {NormalMode::Linear, "ModeLinear"}}};
  for (const auto& [m, pkg_name] : modes) codes.push_back({"mode_i", std::string(to_string(m)), mode_code(m), pkg_name});
  const std::array<const char*, 4> pattern_pkg{"PatUniform", "PatInteger", "PatFracOdd", "PatFracEven"};
  for (TriPattern p : {TriPattern::uniform, TriPattern::integer, TriPattern::fractional_odd, TriPattern::fractional_even}) {
    const std::string name = p == TriPattern::uniform ? "uniform" : partitioning_name(tri_partitioning(p));
    codes.push_back({"tri_pattern_i", name, static_cast<int>(p), pattern_pkg[static_cast<std::size_t>(p)]});
  }
  codes.push_back({"vtx_flags_o", "saturated", kFlagSaturated, "FlagSaturated"});
  codes.push_back({"vtx_flags_o", "div_by_zero", kFlagDivByZero, "FlagDivByZero"});
  return codes;
}

json interface_json() {
  const HardwareConfig defaults = UnitConfig{}.hardware();
  json ports = json::array();
  for (const Port& p : kPorts) {
    const std::vector<WidthTerm> terms = used_terms(p.width);
    json e = {{"name", p.name},
              {"direction", p.dir == PortDir::In ? "input" : "output"},
              {"width", terms_text(terms)},
              {"terms", terms_json(terms)},
              {"bits_at_defaults", width_bits(p.width, defaults)},
              {"what", p.what}};
    if (p.item != PortItem::None) e["item"] = to_string(p.item);
    for (const auto& [v, name] : kVarNames)
      if (p.only_with == v) e["item_only_with"] = name;
    ports.push_back(e);
  }
  json items = json::object();
  for (PortItem item : {PortItem::Triangle, PortItem::Vertex}) {
    const std::vector<WidthTerm> terms = item_terms(item);
    items[to_string(item)] = {
        {"width", terms_text(terms)}, {"terms", terms_json(terms)}, {"bits_at_defaults", item_bits(item, defaults)}};
  }
  json widths = json::object();
  for (const pkg::Constant& c : pkg::kWidths) widths[c.name] = c.value;

  json codes = json::object();
  for (const PortCode& c : port_codes()) {
    codes[c.port][c.name] = c.value;
  }
  // Partitionings travel as patterns: pow2 as integer (its factors are powers of two already).
  json partitionings = json::object();
  for (Partitioning p : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                         Partitioning::fractional_even}) {
    TriangleFx tri;
    set_d3d11_pattern(tri, D3D11Factors{}, p);
    partitionings[partitioning_name(p)] = static_cast<int>(tri.pattern);
  }
  return {
      {"doc", "rtl/tess_unit.sv, docs/microarchitecture.md §3"},
      {"variables", {{"W", "1 + coord_int_bits + coord_frac_bits"},
                     {"bary_bits", "B"},
                     {"int_blocks", "N"},
                     {"cpg_tags", "0 or 1"},
                     {"alpha_bits", "A"},
                     {"takes_alpha", "1 when alpha_bits > 0, else 0"}}},
      {"ports", ports},
      {"items", items},
      {"package_widths", widths},
      {"codes", codes},
      {"partitioning_codes", partitionings},
  };
}

}  // namespace tessim::sim
