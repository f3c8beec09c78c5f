#include "sim/config/params.hpp"

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "sim/base/fixed.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/blocks/cpg.hpp"
#include "sim/blocks/int_blocks.hpp"
#include "sim/blocks/te.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

namespace {

using nlohmann::json;

constexpr std::array<const char*, 4> kNormalChoices{"quadratic", "reflect", "linear", "derivative"};
constexpr std::array<const char*, 3> kCpgChoices{"dedicated", "gpe", "host"};
constexpr std::array<const char*, 2> kEvaluationChoices{"unit", "gpe"};
constexpr std::array<const char*, 3> kDistributionChoices{"round_robin", "least_loaded", "earliest_finish"};
constexpr std::array<const char*, 2> kReassemblyChoices{"ordered", "unordered"};

// get/set of a plain field of UnitConfig (FIELD is an expression on `c`).
#define TESSIM_PARAM_FIELD(FIELD)                                                  \
  [](const UnitConfig& c) -> json { return c.FIELD; },                              \
      [](UnitConfig& c, const json& v) { c.FIELD = v.get<decltype(c.FIELD)>(); }

constexpr double kMaxCycles = 100000;
constexpr auto H = ParamKind::Hardware;
constexpr auto E = ParamKind::Environment;
constexpr auto W = ParamKind::Workload;
constexpr auto I = ParamType::Int;

const std::array<ParamSpec, 37> kParams{{
    {"tess_factor", "--tess-factor", "-L", nullptr, "L", W, I, 1, kMaxTessFactor, {}, "segments",
     "tessellation factor: segments per edge, the same for every triangle of a run",
     TESSIM_PARAM_FIELD(tess_factor)},
    {"normals", "--normals", "", nullptr, "", W, ParamType::Enum, 0, 0, kNormalChoices, "",
     "normal field; the unit implements quadratic, reflect and linear (derivative: float reference only)",
     [](const UnitConfig& c) -> json { return std::string(to_string(c.normals)); },
     [](UnitConfig& c, const json& v) { c.normals = *parse_normal_mode(v.get<std::string>()); }},
    {"int_blocks", "--int-blocks", "--int", "IntBlocks", "N", H, I, 1, IntBlocks::kMaxBlocks, {}, "blocks",
     "INT blocks in the TE (each issues one w·A + u·B + v·C operation per cycle)",
     TESSIM_PARAM_FIELD(int_blocks)},
    {"int_latency", "--int-latency", "", "IntLatency", "Λ", H, I, 1, IntBlocks::kMaxLatency, {}, "cycles",
     "INT latency: cycles from issue to a result visible to a dependent operation",
     TESSIM_PARAM_FIELD(int_latency)},
    {"te_contexts", "--te-contexts", "--contexts", "Contexts", "V", H, I, 1, Te::kMaxContexts, {}, "vertices",
     "vertices the TE keeps in flight (temporary-register sets)", TESSIM_PARAM_FIELD(te_contexts)},
    {"gpe_cycles", "--gpe-cycles", "", nullptr, "K", E, I, 1, kMaxCycles, {}, "cycles",
     "the geometry engine accepts at most one vertex every K cycles", TESSIM_PARAM_FIELD(gpe_cycles)},
    {"gpe_stall_prob", "--gpe-stall-prob", "--stall", nullptr, "", E, ParamType::Double, 0.0, 0.99, {}, "",
     "probability that a ready geometry engine stalls a cycle anyway", TESSIM_PARAM_FIELD(gpe_stall_prob)},
    {"seed", "--seed", "", nullptr, "", E, ParamType::UInt64, 0, 0, {}, "",
     "seed of the geometry engine's random stalls (cosim: also of the RTL's X values)",
     TESSIM_PARAM_FIELD(seed)},
    {"cpg_mapping", "--cpg-mapping", "--cpg", nullptr, "", H, ParamType::Enum, 0, 0, kCpgChoices, "",
     "CPG as its own sequential datapath (dedicated, the RTL's), on the geometry engine's spare cycles (gpe), "
     "or control points computed by the host and sent instead of the triangle (host: evaluation gpe only)",
     [](const UnitConfig& c) -> json { return to_string(c.cpg_mapping); },
     [](UnitConfig& c, const json& v) {
       const std::string m = v.get<std::string>();
       c.cpg_mapping = m == "gpe" ? CpgMapping::Gpe : m == "host" ? CpgMapping::Host : CpgMapping::Dedicated;
     }},
    {"evaluation", "--evaluation", "", nullptr, "", H, ParamType::Enum, 0, 0, kEvaluationChoices, "",
     "where each domain point is evaluated: the unit's TE and INT blocks (unit, the RTL's), or the geometry "
     "engine as a shader fed by the DPG, without TE or INT blocks (gpe; its ALU: ge_alu_lanes, ge_sfu_cost)",
     [](const UnitConfig& c) -> json { return to_string(c.evaluation); },
     [](UnitConfig& c, const json& v) {
       c.evaluation = v.get<std::string>() == "gpe" ? Evaluation::Gpe : Evaluation::Unit;
     }},
    {"cpg_lanes", "--cpg-lanes", "", "CpgLanes", "Ec", H, I, 1, 3, {}, "edges",
     "edge lanes of the dedicated CPG: 1 computes the three edges in turn, 3 all at once",
     TESSIM_PARAM_FIELD(cpg.lanes)},
    {"cpg_digit_bits", "--cpg-digit-bits", "", "CpgDigitBits", "r", H, I, 1, kMaxCpgDigitBits, {}, "bits",
     "quotient / root bits the dedicated CPG's dividers and square root retire per cycle (radix 2^r)",
     TESSIM_PARAM_FIELD(cpg.digit_bits)},
    {"cpg_copies", "--cpg-copies", "", "CpgCopies", "Mc", H, I, 1, CpgArray::kMaxCopies, {}, "CPGs",
     "dedicated CPGs taking successive triangles round robin and writing them in order: one starts "
     "every ceil((C + 1) / Mc) cycles",
     TESSIM_PARAM_FIELD(cpg.copies)},
    {"cpg_product_reg", "--cpg-product-reg", "", "CpgProductReg", "", H, I, 0, 1, {}, "",
     "1: the dedicated CPG registers its multipliers' products (a shorter path; 4 to 13 more cycles "
     "per triangle); 0: each product is used in the cycle it is computed",
     TESSIM_PARAM_FIELD(cpg.product_reg)},
    {"cpg_tags", "--cpg-tags", "", "CpgTags", "", H, I, 0, 1, {}, "",
     "1: the CPG takes scalar tags and computes scalar-tagged PN control points; 0: plain PN",
     TESSIM_PARAM_FIELD(cpg_tags)},
    {"cpg_gpe_cycles", "--cpg-gpe-cycles", "", nullptr, "", E, I, 1, kMaxCycles, {}, "cycles",
     "geometry-engine cycles the CPG needs per triangle when mapped there (cpg_mapping gpe)",
     TESSIM_PARAM_FIELD(cpg_gpe_cycles)},
    {"ge_alu_lanes", "--ge-alu-lanes", "", nullptr, "", E, I, 1, 256, {}, "slots",
     "scalar operations the geometry engine's ALU issues per cycle for shader work (evaluation gpe, --displace)",
     TESSIM_PARAM_FIELD(ge_alu_lanes)},
    {"ge_sfu_cost", "--ge-sfu-cost", "", nullptr, "", E, I, 1, 64, {}, "slots",
     "issue slots of a special function on the geometry engine (reciprocal square root, sine, cosine)",
     TESSIM_PARAM_FIELD(ge_sfu_cost)},
    {"ge_lookup_cost", "--ge-lookup-cost", "", nullptr, "", E, I, 1, 64, {}, "slots",
     "issue slots of a table read on the geometry engine (the noise's permutation and gradients)",
     TESSIM_PARAM_FIELD(ge_lookup_cost)},
    {"ge_core_lanes", "--ge-core-lanes", "", nullptr, "W", E, I, 0, 1024, {}, "lanes",
     "the geometry engine as a shader core of W SIMD lanes (one vertex each) on its own clock, K derived from "
     "its per-vertex program; 0: the fixed K of gpe_cycles",
     TESSIM_PARAM_FIELD(ge_core_lanes)},
    {"ge_core_issue", "--ge-core-issue", "", nullptr, "", E, I, 1, 8, {}, "instructions",
     "wave instructions the shader core issues per core cycle (ge_core_lanes > 0)", TESSIM_PARAM_FIELD(ge_core_issue)},
    {"ge_core_mhz", "--ge-core-mhz", "", nullptr, "", E, ParamType::Double, 1, 10000, {}, "MHz",
     "the shader core's clock (ge_core_lanes > 0)", TESSIM_PARAM_FIELD(ge_core_mhz)},
    {"unit_mhz", "--unit-mhz", "", nullptr, "", E, ParamType::Double, 1, 10000, {}, "MHz",
     "the unit's clock, against which the shader core's is set (ge_core_lanes > 0)", TESSIM_PARAM_FIELD(unit_mhz)},
    {"ge_core_fifo", "--ge-core-fifo", "", nullptr, "D", E, I, 1, 65536, {}, "vertices",
     "entries of the cross-clock FIFO from the unit to the shader core (ge_core_lanes > 0)",
     TESSIM_PARAM_FIELD(ge_core_fifo)},
    {"coord_int_bits", "--coord-int-bits", "", "CoordIntBits", "I", H, I, 1, 8, {}, "bits",
     "integer bits of a coordinate, sign excluded (width W = 1 + I + F <= 32)",
     TESSIM_PARAM_FIELD(format.coord_int_bits)},
    {"coord_frac_bits", "--coord-frac-bits", "", "CoordFracBits", "F", H, I, 8, 26, {}, "bits",
     "fraction bits of a coordinate", TESSIM_PARAM_FIELD(format.coord_frac_bits)},
    // B >= 7 keeps every barycentric weight of L <= 64 away from rounding ties (fixed.hpp).
    {"bary_bits", "--bary-bits", "", "BaryBits", "B", H, I, 7, kMaxBaryBits, {}, "bits",
     "fraction bits of a barycentric weight (weights are B + 1 bits)", TESSIM_PARAM_FIELD(format.bary_bits)},
    {"alpha_bits", "--alpha-bits", "", "AlphaBits", "A", H, I, 0, kMaxAlphaBits, {}, "bits",
     "fraction bits of the silhouette weight alpha the CPG takes per edge and blends its tangent points "
     "with (one multiplication each); 0: no alpha input, plain PN",
     TESSIM_PARAM_FIELD(format.alpha_bits)},
    {"units", "--units", "", nullptr, "M", H, I, 1, 16, {}, "units",
     "units sharing the triangle stream behind a distributor, their vertices put back in stream order "
     "(docs/microarchitecture.md §13)",
     TESSIM_PARAM_FIELD(units)},
    {"ge_ports", "--ge-ports", "", nullptr, "P", E, I, 1, 16, {}, "ports",
     "geometry-engine ports behind a system of units, each taking one vertex every K cycles in stream order",
     TESSIM_PARAM_FIELD(ge_ports)},
    {"reorder_slots", "--reorder-slots", "", nullptr, "R", H, I, 2, 65536, {}, "vertices",
     "vertex slots of the reassembly buffer that puts the units' output back in stream order",
     TESSIM_PARAM_FIELD(reorder_slots)},
    {"distribution", "--distribution", "", nullptr, "", H, ParamType::Enum, 0, 0, kDistributionChoices, "",
     "which unit gets the next triangle: in turn, the least vertices outstanding, or the earliest predicted finish",
     [](const UnitConfig& c) -> json { return to_string(c.distribution); },
     [](UnitConfig& c, const json& v) {
       const std::string d = v.get<std::string>();
       c.distribution = d == "least_loaded"      ? Distribution::LeastLoaded
                        : d == "earliest_finish" ? Distribution::EarliestFinish
                                                 : Distribution::RoundRobin;
     }},
    {"reassembly", "--reassembly", "", nullptr, "", H, ParamType::Enum, 0, 0, kReassemblyChoices, "",
     "ordered: the ports take the vertices in stream order (the unit's output); unordered: any unit's vertex, "
     "a bound for what keeping the order costs (the output file is put back in order by the simulator)",
     [](const UnitConfig& c) -> json { return to_string(c.reassembly); },
     [](UnitConfig& c, const json& v) {
       c.reassembly = v.get<std::string>() == "unordered" ? Reassembly::Unordered : Reassembly::Ordered;
     }},
    {"dispatch_batch", "--dispatch-batch", "", nullptr, "", H, I, 1, 64, {}, "triangles",
     "consecutive triangles the distributor sends to the same unit before it chooses again",
     TESSIM_PARAM_FIELD(dispatch_batch)},
    {"tri_fifo_depth", "--tri-fifo-depth", "", "TriFifoDepth", "Dt", H, I, 1, 64, {}, "triangles",
     "depth of the input triangle FIFO in front of the CPG", TESSIM_PARAM_FIELD(tri_fifo_depth)},
    {"vtx_fifo_depth", "--vtx-fifo-depth", "", "VtxFifoDepth", "Dv", H, I, 1, 64, {}, "vertices",
     "depth of the output vertex FIFO between the TE and the geometry engine",
     TESSIM_PARAM_FIELD(vtx_fifo_depth)},
    {"cp_buffers", "--cp-buffers", "", "CpBuffers", "Nb", H, I, 1, ControlPointBuffer::kMaxBuffers, {}, "patches",
     "control-point buffers between the CPG and the TE: patches written and not yet fully retired",
     TESSIM_PARAM_FIELD(cp_buffers)},
}};

#undef TESSIM_PARAM_FIELD

// A range bound as printed: an integer without a fraction.
std::string number_text(double x) {
  return x == static_cast<double>(static_cast<long long>(x)) ? std::to_string(static_cast<long long>(x))
                                                             : json(x).dump();
}




}  // namespace

const char* to_string(ParamKind k) {
  switch (k) {
    case ParamKind::Hardware: return "hardware";
    case ParamKind::Environment: return "environment";
    case ParamKind::Workload: return "workload";
  }
  return "?";
}

const char* to_string(ParamType t) {
  switch (t) {
    case ParamType::Int: return "int";
    case ParamType::UInt64: return "uint64";
    case ParamType::Double: return "double";
    case ParamType::Enum: return "enum";
  }
  return "?";
}

std::span<const ParamSpec> unit_params() { return kParams; }

const ParamSpec* find_param(std::string_view key) {
  for (const ParamSpec& p : kParams) {
    if (key == p.key) return &p;
  }
  return nullptr;
}

const ParamSpec* find_rtl_param(std::string_view rtl_name) {
  for (const ParamSpec& p : kParams) {
    if (p.rtl && rtl_name == p.rtl) return &p;
  }
  return nullptr;
}

std::string range_text(const ParamSpec& p) {
  switch (p.type) {
    case ParamType::Int:
    case ParamType::Double: return number_text(p.min) + ".." + number_text(p.max);
    case ParamType::UInt64: return "0..2^64-1";
    case ParamType::Enum: {
      std::string s;
      for (const char* c : p.choices) s += (s.empty() ? "" : ", ") + std::string(c);
      return s;
    }
  }
  return "";
}

std::vector<std::string> alias_list(const ParamSpec& p) {
  std::vector<std::string> list;
  for (std::string_view rest = p.aliases; !rest.empty();) {
    const auto comma = rest.find(',');
    list.emplace_back(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
  }
  return list;
}

std::string cli_names(const ParamSpec& p) {
  std::string names = p.flag;
  if (*p.aliases) names += std::string(",") + p.aliases;
  return names;
}

}  // namespace tessim::sim
