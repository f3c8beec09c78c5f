#include "sim/config.hpp"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "model/error.hpp"
#include "model/pattern.hpp"
#include "sim/cpg.hpp"

namespace tessim::sim {

namespace {

void check_range(const std::string& source, const char* key, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    throw InputError(source, key,
                     "value " + nlohmann::json(value).dump() + " out of range [" +
                         nlohmann::json(lo).dump() + ", " + nlohmann::json(hi).dump() + "]");
  }
}

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
      if (v.is_number_integer() && v.get<std::int64_t>() < 0)
        throw InputError(source, key, "expected a non-negative integer");
      return v.get<T>();
    } else {
      const auto x = v.get<std::int64_t>();
      if (x < -1000000000LL || x > 1000000000LL) throw InputError(source, key, "integer out of range");
      return static_cast<T>(x);
    }
  }
}

}  // namespace

std::string to_string(CpgMapping m) { return m == CpgMapping::Dedicated ? "dedicated" : "gpe"; }

void UnitConfig::validate(const std::string& source) const {
  check_range(source, "coord_int_bits", format.coord_int_bits, 1, 8);
  check_range(source, "coord_frac_bits", format.coord_frac_bits, 8, 26);
  if (format.coord_width() > 32)
    throw InputError(source, "coord_int_bits + coord_frac_bits",
                     "coordinate width " + std::to_string(format.coord_width()) + " exceeds 32 bits");
  // B >= 7 keeps every barycentric weight of L <= 64 away from rounding ties (fixed.hpp).
  check_range(source, "bary_bits", format.bary_bits, 7, 20);
  check_range(source, "int_blocks", int_blocks, 1, 32);
  check_range(source, "int_latency", int_latency, 1, 8);
  check_range(source, "te_contexts", te_contexts, 1, 16);
  check_range(source, "tri_fifo_depth", tri_fifo_depth, 1, 64);
  check_range(source, "vtx_fifo_depth", vtx_fifo_depth, 1, 64);
  check_range(source, "cpg_gpe_cycles", cpg_gpe_cycles, 1, 100000);
  check_range(source, "tess_factor", tess_factor, 1, kMaxTessFactor);
  check_range(source, "gpe_cycles", gpe_cycles, 1, 100000);
  check_range(source, "gpe_stall_prob", gpe_stall_prob, 0.0, 0.99);
  if (!hardware_supports(normals))
    throw InputError(source, "normals",
                     "'" + std::string(to_string(normals)) +
                         "' is available in the float reference only; the unit implements "
                         "quadratic, reflect and linear");
}

void apply_json(UnitConfig& cfg, const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, "(top level)", "expected a JSON object");
  for (const auto& [key, v] : j.items()) {
    if (key == "coord_int_bits") cfg.format.coord_int_bits = get_as<int>(v, source, key);
    else if (key == "coord_frac_bits") cfg.format.coord_frac_bits = get_as<int>(v, source, key);
    else if (key == "bary_bits") cfg.format.bary_bits = get_as<int>(v, source, key);
    else if (key == "int_blocks") cfg.int_blocks = get_as<int>(v, source, key);
    else if (key == "int_latency") cfg.int_latency = get_as<int>(v, source, key);
    else if (key == "te_contexts") cfg.te_contexts = get_as<int>(v, source, key);
    else if (key == "tri_fifo_depth") cfg.tri_fifo_depth = get_as<int>(v, source, key);
    else if (key == "vtx_fifo_depth") cfg.vtx_fifo_depth = get_as<int>(v, source, key);
    else if (key == "cpg_gpe_cycles") cfg.cpg_gpe_cycles = get_as<int>(v, source, key);
    else if (key == "tess_factor") cfg.tess_factor = get_as<int>(v, source, key);
    else if (key == "gpe_cycles") cfg.gpe_cycles = get_as<int>(v, source, key);
    else if (key == "gpe_stall_prob") cfg.gpe_stall_prob = get_as<double>(v, source, key);
    else if (key == "seed") cfg.seed = get_as<std::uint64_t>(v, source, key);
    else if (key == "cpg_mapping") {
      const auto s = get_as<std::string>(v, source, key);
      if (s == "dedicated") cfg.cpg_mapping = CpgMapping::Dedicated;
      else if (s == "gpe") cfg.cpg_mapping = CpgMapping::Gpe;
      else throw InputError(source, key, "'" + s + "' is not one of dedicated, gpe");
    } else if (key == "normals") {
      const auto s = get_as<std::string>(v, source, key);
      const auto m = parse_normal_mode(s);
      if (!m) throw InputError(source, key, "'" + s + "' is not one of quadratic, reflect, linear, derivative");
      cfg.normals = *m;
    } else {
      throw InputError(source, key, "unknown configuration key");
    }
  }
}

UnitConfig load_config(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "file", "cannot open");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path.string(), "JSON", e.what());
  }
  UnitConfig cfg;
  apply_json(cfg, j, path.string());
  cfg.validate(path.string());
  return cfg;
}

nlohmann::json to_json(const UnitConfig& c) {
  return {
      {"coord_int_bits", c.format.coord_int_bits},
      {"coord_frac_bits", c.format.coord_frac_bits},
      {"bary_bits", c.format.bary_bits},
      {"int_blocks", c.int_blocks},
      {"int_latency", c.int_latency},
      {"te_contexts", c.te_contexts},
      {"tri_fifo_depth", c.tri_fifo_depth},
      {"vtx_fifo_depth", c.vtx_fifo_depth},
      {"cpg_mapping", to_string(c.cpg_mapping)},
      {"cpg_gpe_cycles", c.cpg_gpe_cycles},
      {"normals", std::string(to_string(c.normals))},
      {"tess_factor", c.tess_factor},
      {"gpe_cycles", c.gpe_cycles},
      {"gpe_stall_prob", c.gpe_stall_prob},
      {"seed", c.seed},
  };
}

}  // namespace tessim::sim
