#include "sim/report/schema.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "sim/base/counter_registry.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/config/params.hpp"
#include "sim/config/ports.hpp"
#include "sim/config/rtl_builds.hpp"
#include "sim/report/report.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/error_bound.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

namespace {

using nlohmann::json;

// The range of a parameter as JSON numbers of its type.
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

nlohmann::json schema_json() {
  const UnitConfig defaults{};
  json params = json::array();
  json rtl = json::object();
  for (const ParamSpec& p : unit_params()) {
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

  // The INT operations (sim/base/int_ops.hpp).
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
  // The RTL's counters (perf_ctr_o) in the order the co-simulation compares them.
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
  for (int product_reg : {0, 1}) {
    for (int lanes : {1, 3}) {
      for (int r = 1; r <= defaults.format.coord_width(); ++r) {
        json row = {{"cpg_lanes", lanes}, {"cpg_digit_bits", r}, {"cpg_product_reg", product_reg}};
        for (NormalMode m : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear})
          row[std::string(to_string(m))] = cpg_cycles(m, defaults.format, {lanes, r, 1, product_reg});
        cpg_variants_json.push_back(row);
      }
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
