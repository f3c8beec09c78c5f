#include "sim/params.hpp"

#include <array>
#include <limits>

#include <nlohmann/json.hpp>

#include "model/pattern.hpp"
#include "sim/cpg.hpp"
#include "sim/error_bound.hpp"
#include "sim/gpe.hpp"
#include "sim/int_ops.hpp"
#include "sim/ports.hpp"
#include "sim/rtl_builds.hpp"
#include "sim/simulate.hpp"
#include "sim/unit.hpp"

namespace tessim::sim {

namespace {

using nlohmann::json;

constexpr std::array<const char*, 4> kNormalChoices{"quadratic", "reflect", "linear", "derivative"};
constexpr std::array<const char*, 2> kCpgChoices{"dedicated", "gpe"};

// get/set of a plain field of UnitConfig (FIELD is an expression on `c`).
#define TESSIM_PARAM_FIELD(FIELD)                                                  \
  [](const UnitConfig& c) -> json { return c.FIELD; },                              \
      [](UnitConfig& c, const json& v) { c.FIELD = v.get<decltype(c.FIELD)>(); }

constexpr double kMaxCycles = 100000;
constexpr auto H = ParamKind::Hardware;
constexpr auto E = ParamKind::Environment;
constexpr auto W = ParamKind::Workload;
constexpr auto I = ParamType::Int;

const std::array<ParamSpec, 18> kParams{{
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
     "CPG as its own sequential datapath (dedicated, the RTL's) or on the geometry engine's spare cycles",
     [](const UnitConfig& c) -> json { return to_string(c.cpg_mapping); },
     [](UnitConfig& c, const json& v) {
       c.cpg_mapping = v.get<std::string>() == "gpe" ? CpgMapping::Gpe : CpgMapping::Dedicated;
     }},
    {"cpg_lanes", "--cpg-lanes", "", "CpgLanes", "Ec", H, I, 1, 3, {}, "edges",
     "edge lanes of the dedicated CPG: 1 computes the three edges in turn, 3 all at once",
     TESSIM_PARAM_FIELD(cpg.lanes)},
    {"cpg_digit_bits", "--cpg-digit-bits", "", "CpgDigitBits", "r", H, I, 1, kMaxCpgDigitBits, {}, "bits",
     "quotient / root bits the dedicated CPG's dividers and square root retire per cycle (radix 2^r)",
     TESSIM_PARAM_FIELD(cpg.digit_bits)},
    {"cpg_tags", "--cpg-tags", "", "CpgTags", "", H, I, 0, 1, {}, "",
     "1: the CPG takes scalar tags and computes scalar-tagged PN control points; 0: plain PN",
     TESSIM_PARAM_FIELD(cpg_tags)},
    {"cpg_gpe_cycles", "--cpg-gpe-cycles", "", nullptr, "", E, I, 1, kMaxCycles, {}, "cycles",
     "geometry-engine cycles the CPG needs per triangle when mapped there (cpg_mapping gpe)",
     TESSIM_PARAM_FIELD(cpg_gpe_cycles)},
    {"coord_int_bits", "--coord-int-bits", "", "CoordIntBits", "I", H, I, 1, 8, {}, "bits",
     "integer bits of a coordinate, sign excluded (width W = 1 + I + F <= 32)",
     TESSIM_PARAM_FIELD(format.coord_int_bits)},
    {"coord_frac_bits", "--coord-frac-bits", "", "CoordFracBits", "F", H, I, 8, 26, {}, "bits",
     "fraction bits of a coordinate", TESSIM_PARAM_FIELD(format.coord_frac_bits)},
    // B >= 7 keeps every barycentric weight of L <= 64 away from rounding ties (fixed.hpp).
    {"bary_bits", "--bary-bits", "", "BaryBits", "B", H, I, 7, kMaxBaryBits, {}, "bits",
     "fraction bits of a barycentric weight (weights are B + 1 bits)", TESSIM_PARAM_FIELD(format.bary_bits)},
    {"tri_fifo_depth", "--tri-fifo-depth", "", "TriFifoDepth", "Dt", H, I, 1, 64, {}, "triangles",
     "depth of the input triangle FIFO in front of the CPG", TESSIM_PARAM_FIELD(tri_fifo_depth)},
    {"vtx_fifo_depth", "--vtx-fifo-depth", "", "VtxFifoDepth", "Dv", H, I, 1, 64, {}, "vertices",
     "depth of the output vertex FIFO between the TE and the geometry engine",
     TESSIM_PARAM_FIELD(vtx_fifo_depth)},
}};

#undef TESSIM_PARAM_FIELD

std::string number_text(double x) {
  return x == static_cast<double>(static_cast<long long>(x)) ? std::to_string(static_cast<long long>(x))
                                                             : json(x).dump();
}

json range_json(const ParamSpec& p, bool lo) {
  switch (p.type) {
    case ParamType::Int: return static_cast<long long>(lo ? p.min : p.max);
    case ParamType::Double: return lo ? p.min : p.max;
    case ParamType::UInt64: return lo ? std::uint64_t{0} : std::numeric_limits<std::uint64_t>::max();
    case ParamType::Enum: break;
  }
  return nullptr;
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

nlohmann::json schema_json() {
  const UnitConfig defaults{};
  json params = json::array();
  json rtl = json::object();
  for (const ParamSpec& p : kParams) {
    json aliases = alias_list(p);
    json e = {
        {"key", p.key},
        {"flag", p.flag},
        {"aliases", aliases},
        {"rtl", p.rtl ? json(p.rtl) : json(nullptr)},
        {"symbol", p.symbol},
        {"kind", to_string(p.kind)},
        {"type", to_string(p.type)},
        {"default", p.get(defaults)},
        {"unit", p.unit},
        {"description", p.description},
    };
    if (p.type == ParamType::Enum) {
      e["choices"] = json::array();
      for (const char* c : p.choices) e["choices"].push_back(c);
    } else {
      e["minimum"] = range_json(p, true);
      e["maximum"] = range_json(p, false);
    }
    params.push_back(e);
    if (p.rtl) rtl[p.rtl] = p.key;
  }

  // The INT operations (sim/int_ops.hpp).
  json ops = json::array();
  auto operands_json = [](const std::array<int_ops::Operand, 3>& src) {
    json a = json::array();
    for (const int_ops::Operand& o : src) {
      std::string name = int_ops::to_string(o.net);
      name += std::to_string(o.index);
      a.push_back(name);
    }
    return a;
  };
  for (const int_ops::IntOp& op : int_ops::kIntOps) {
    json deps = json::array();
    for (int d = 0; d < int_ops::kOpCount; ++d) {
      if (op.depends & int_ops::bit(d)) deps.push_back(d);
    }
    json modes = json::array();
    for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
      if (!(int_ops::absent_ops(m) & int_ops::bit(op.op))) modes.push_back(std::string(to_string(m)));
    }
    json e = {{"op", op.op}, {"level", op.level}, {"what", op.what}, {"operands", operands_json(op.operands)},
              {"depends_on", deps}, {"modes", modes}};
    if (op.op == int_ops::kLinearNormalOp) e["operands_linear"] = operands_json(int_ops::kLinearNormalOperands);
    ops.push_back(e);
  }
  json per_mode = json::object();
  for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    per_mode[std::string(to_string(m))] = {{"ops_per_vertex", int_ops::ops_per_vertex(m)},
                                           {"position_op", int_ops::kPositionOp},
                                           {"normal_op", int_ops::normal_op(m)}};
  }

  // Statistics counters: per run, then the classes of each block (each class set sums to cycles).
  json te = json::array(), cpg = json::array(), gpe = json::array();
  for (TeClass c : kTeClasses) te.push_back(to_string(c));
  for (CpgClass c : kCpgClasses) cpg.push_back(to_string(c));
  for (GpeClass c : kGpeClasses) gpe.push_back(to_string(c));
  json per_run = json::array(), counters = json::array(), outputs = json::array();
  for (const CounterField& f : kRunCounters) per_run.push_back(f.name);
  // The RTL's perf_*_o counters in the order the co-simulation compares them.
  for (const CounterField& f : kRunCounters) counters.push_back(f.name);
  counters.push_back("int_busy[0..N-1]");
  for (const CounterField& f : kClassCounters) counters.push_back(f.name);
  for (const VertexField& f : kVertexFields) outputs.push_back({{"port", std::string(f.name) + "_o"}, {"components", f.count}});
  json stats = {
      {"per_run", per_run},
      {"counters", counters},
      {"vertex_outputs", outputs},
      {"classes", {{"int_block", {"busy", "idle"}}, {"te", te}, {"cpg", cpg}, {"gpe", gpe}}},
      {"doc", "docs/microarchitecture.md §10, docs/statistics.md"},
      {"stats_schema_version", kStatsSchemaVersion},
      {"units", stats_units()},
  };

  // Per valid coordinate format (coordinate width <= 32), one row {coord_int_bits,
  // coord_frac_bits, key: value(format)}.
  const ParamSpec& ib = *find_param("coord_int_bits");
  const ParamSpec& fb = *find_param("coord_frac_bits");
  auto per_format = [&](const char* key, auto value) {
    json rows = json::array();
    for (int i = static_cast<int>(ib.min); i <= static_cast<int>(ib.max); ++i) {
      for (int f = static_cast<int>(fb.min); f <= static_cast<int>(fb.max); ++f) {
        NumberFormat fmt = defaults.format;
        fmt.coord_int_bits = i;
        fmt.coord_frac_bits = f;
        if (fmt.coord_width() <= 32) rows.push_back({{"coord_int_bits", i}, {"coord_frac_bits", f}, {key, value(fmt)}});
      }
    }
    return rows;
  };
  // Cycles of the dedicated CPG per triangle (sim::cpg_cycles); they do not depend on bary_bits
  // (tests/sim/params_test.cpp checks it).
  json cpg_cycles_json = json::object();
  for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear})
    cpg_cycles_json[std::string(to_string(m))] =
        per_format("cycles", [m](const NumberFormat& fmt) { return cpg_cycles(m, fmt); });
  // C of every CPG variant at the default coordinate format (sim::cpg_cycles).
  json cpg_variants_json = json::array();
  for (int lanes : {1, 3}) {
    for (int r = 1; r <= defaults.format.coord_width(); ++r) {
      json row = {{"cpg_lanes", lanes}, {"cpg_digit_bits", r}};
      for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear})
        row[std::string(to_string(m))] = cpg_cycles(m, defaults.format, {lanes, r});
      cpg_variants_json.push_back(row);
    }
  }
  // The arithmetic position bound (sim::position_error_budget, docs/number-formats.md §5.1) in
  // unit coordinates: times the mesh's half-extent (tessim info --json) gives mesh units.
  const json position_bound_json =
      per_format("units", [](const NumberFormat& fmt) { return position_error_budget(fmt).position_units; });

  return {
      {"tessim_schema", 1},
      {"parameters", params},
      {"rtl_parameters", rtl},
      {"int_ops", ops},
      {"int_ops_per_mode", per_mode},
      {"statistics", stats},
      {"cpg_cycles", cpg_cycles_json},
      {"cpg_cycles_by_variant", cpg_variants_json},
      {"position_bound", position_bound_json},
      {"interface", interface_json()},
      {"rtl_builds", rtl_builds_json()},
  };
}

}  // namespace tessim::sim
