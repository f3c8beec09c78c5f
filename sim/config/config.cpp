#include "sim/config/config.hpp"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/pattern.hpp"
#include "sim/base/json_input.hpp"
#include "sim/config/params.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

namespace {

template <typename T>
T get_as(const nlohmann::json& v, const std::string& source, const std::string& key) {
  if constexpr (std::is_same_v<T, std::string>) {
    if (!v.is_string()) throw InputError(source, key, "expected a string");
    return v.get<std::string>();
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!v.is_number()) throw InputError(source, key, "expected a number");
    return v.get<T>();
  } else {
    if (!v.is_number_integer() && !v.is_number_unsigned())
      throw InputError(source, key, "expected an integer");
    if constexpr (std::is_unsigned_v<T>) {
      if (!v.is_number_unsigned() && v.get<std::int64_t>() < 0)
        throw InputError(source, key, "expected a non-negative integer");
      return v.get<T>();
    } else {
      const auto x = v.get<std::int64_t>();
      if (x < -1000000000LL || x > 1000000000LL) throw InputError(source, key, "integer out of range");
      return static_cast<T>(x);
    }
  }
}

// Range of an Int or Double parameter (sim/config/params.cpp); the message prints numbers as their
// type.
void check_range(const std::string& source, const ParamSpec& p, const UnitConfig& cfg) {
  if (p.type != ParamType::Int && p.type != ParamType::Double) return;
  const nlohmann::json value = p.get(cfg);
  const double x = value.get<double>();
  if (!(x >= p.min && x <= p.max)) {
    const auto bound = [&](double b) {
      return p.type == ParamType::Int ? nlohmann::json(static_cast<long long>(b)) : nlohmann::json(b);
    };
    // JSON has no NaN or infinity (dump() prints null): such a value is named as what it is.
    const std::string shown = std::isnan(x) ? "NaN" : std::isinf(x) ? (x > 0 ? "infinity" : "-infinity") : value.dump();
    throw InputError(source, p.key,
                     "value " + shown + " out of range [" + bound(p.min).dump() + ", " + bound(p.max).dump() + "]");
  }
}

}  // namespace

std::string to_string(CpgMapping m) {
  switch (m) {
    case CpgMapping::Dedicated: return "dedicated";
    case CpgMapping::Gpe: return "gpe";
    case CpgMapping::Host: return "host";
  }
  return "?";
}

std::string to_string(Evaluation e) { return e == Evaluation::Unit ? "unit" : "gpe"; }

std::string to_string(Distribution d) {
  switch (d) {
    case Distribution::RoundRobin: return "round_robin";
    case Distribution::LeastLoaded: return "least_loaded";
    case Distribution::EarliestFinish: return "earliest_finish";
  }
  return "?";
}

std::string to_string(Reassembly r) { return r == Reassembly::Unordered ? "unordered" : "ordered"; }

void UnitConfig::validate(const std::string& source) const {
  for (const ParamSpec& p : unit_params()) check_range(source, p, *this);
  // Checks across parameters, beyond the ranges of the table.
  if (format.coord_width() > kMaxCoordWidth)
    throw InputError(source, "coord_int_bits + coord_frac_bits",
                     "coordinate width " + std::to_string(format.coord_width()) + " exceeds " + std::to_string(kMaxCoordWidth) + " bits");
  if (cpg.lanes == 2) throw InputError(source, "cpg_lanes", "value 2: the CPG has 1 lane (edges in turn) or 3 (one per edge)");
  if (cpg.digit_bits > format.coord_width())
    throw InputError(source, "cpg_digit_bits",
                     "value " + std::to_string(cpg.digit_bits) + " exceeds the coordinate width " +
                         std::to_string(format.coord_width()) + " (a whole quotient in one cycle)");
  if (cpg_mapping == CpgMapping::Gpe && !(cpg == CpgVariant{}))
    throw InputError(source, "cpg_lanes / cpg_digit_bits / cpg_copies / cpg_product_reg",
                     "describe the dedicated CPG; with cpg_mapping gpe the CPG takes cpg_gpe_cycles");
  if (cpg_mapping == CpgMapping::Host && !(cpg == CpgVariant{}))
    throw InputError(source, "cpg_lanes / cpg_digit_bits / cpg_copies / cpg_product_reg",
                     "describe the dedicated CPG; with cpg_mapping host the host computes the control points");
  if (units > 1 && (cpg_mapping != CpgMapping::Dedicated || evaluation != Evaluation::Unit))
    throw InputError(source, "units",
                     "a system of " + std::to_string(units) +
                         " units takes dedicated CPGs evaluating on their TEs (cpg_mapping dedicated, evaluation unit)");
  if (units > 1 && ge_core())
    throw InputError(source, "ge_core_lanes",
                     "the shader core is one geometry engine behind one unit; a system of " + std::to_string(units) +
                         " units has ge_ports ports of a fixed K (gpe_cycles)");
  if (units > 1 && reorder_slots < 2)
    throw InputError(source, "reorder_slots", "a system of units needs at least 2 (one is kept for the oldest patch)");
  if (cpg_mapping == CpgMapping::Host && evaluation != Evaluation::Gpe)
    throw InputError(source, "cpg_mapping",
                     "'host' sends control points, which only the geometry engine takes (evaluation gpe); the "
                     "unit's input is the triangle");
  if (!hardware_supports(normals))
    throw InputError(source, "normals",
                     "'" + std::string(to_string(normals)) +
                         "' is available in the float reference only; the unit implements "
                         "quadratic, reflect and linear");
}

void apply_json(UnitConfig& cfg, const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, "(top level)", "expected a JSON object");
  for (const auto& [key, v] : j.items()) {
    const ParamSpec* p = find_param(key);
    if (!p) throw InputError(source, key, "unknown configuration key");
    switch (p->type) {
      case ParamType::Int: p->set(cfg, get_as<int>(v, source, key)); break;
      case ParamType::UInt64: p->set(cfg, get_as<std::uint64_t>(v, source, key)); break;
      case ParamType::Double: p->set(cfg, get_as<double>(v, source, key)); break;
      case ParamType::Enum: {
        const auto s = get_as<std::string>(v, source, key);
        bool known = false;
        for (const char* c : p->choices) known = known || s == c;
        if (!known) throw InputError(source, key, "'" + s + "' is not one of " + range_text(*p));
        p->set(cfg, s);
        break;
      }
    }
  }
}

nlohmann::json parse_config_text(const std::string& text, const std::string& source) {
  return parse_json_text(text, source);
}

nlohmann::json to_json(const UnitConfig& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const ParamSpec& p : unit_params()) j[p.key] = p.get(c);
  return j;
}

}  // namespace tessim::sim
