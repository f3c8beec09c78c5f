#include "rtl/verilated/rtl_unit.hpp"

#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "rtl/verilated/verilated_unit.hpp"
#include "sim/config/params.hpp"

#include "rtl_variant_headers.inc"  // generated: the Verilated model of each variant

namespace tessim::rtl {

RtlUnit::~RtlUnit() = default;

namespace {

using Maker = std::unique_ptr<RtlUnit> (*)(const VariantSpec&, std::uint64_t);

struct Variant {
  VariantSpec spec;
  Maker make;
};

// One row per Verilated configuration, generated from rtl/CMakeLists.txt.
#define TESSIM_RTL_VARIANT(name, model, verif, ...) {{#name, verif, __VA_ARGS__}, &make_variant<model>},
const std::vector<Variant> kVariants{
#include "rtl_variants.inc"
};
#undef TESSIM_RTL_VARIANT

}  // namespace

std::unique_ptr<RtlUnit> make_rtl_unit(const std::string& variant, std::uint64_t seed) {
  for (const Variant& v : kVariants) {
    if (variant == v.spec.name) return v.make(v.spec, seed);
  }
  std::string known;
  for (const Variant& v : kVariants) known += (known.empty() ? "" : ", ") + std::string(v.spec.name);
  throw std::invalid_argument("unknown RTL variant '" + variant + "' (known: " + known + ")");
}

int VariantSpec::inject_bug() const {
  for (const RtlParameter& p : parameters)
    if (std::string_view(p.name) == "InjectBug") return p.value;
  return 0;
}

sim::HardwareConfig VariantSpec::config() const {
  sim::UnitConfig cfg;  // tess_pkg's defaults are UnitConfig's
  for (const RtlParameter& r : parameters) {
    if (std::string_view(r.name) == "InjectBug") continue;  // a test fault, not a hardware parameter
    const sim::ParamSpec* p = sim::find_rtl_param(r.name);
    if (!p) throw std::logic_error(std::string("RTL variant ") + name + ": unknown parameter " + r.name);
    p->set(cfg, r.value);
  }
  cfg.cpg_mapping = sim::CpgMapping::Dedicated;
  return cfg.hardware();
}

void check_config(const RtlUnit& unit, const sim::UnitConfig& cfg) {
  const sim::UnitConfig rtl = sim::with_hardware(unit.config(), cfg);  // the run's workload and environment
  const std::string where = "RTL variant " + unit.variant();
  // Every parameter that is a parameter of tess_unit (sim/config/params.cpp) must match the build.
  for (const sim::ParamSpec& p : sim::unit_params()) {
    if (!p.rtl) continue;
    const nlohmann::json have = p.get(rtl), want = p.get(cfg);
    if (have != want) {
      throw InputError(where, p.key, "the RTL is built with " + have.dump() + ", the configuration asks for " +
                                         want.dump());
    }
  }
  if (cfg.cpg_mapping != sim::CpgMapping::Dedicated) {
    throw InputError(where, "cpg_mapping", "the RTL implements the dedicated CPG only");
  }
  if (!sim::hardware_supports(cfg.normals)) {
    throw InputError(where, "normals", "normal mode " + std::string(to_string(cfg.normals)) +
                                           " is not implemented by the unit");
  }
}

std::vector<std::string> rtl_variants() {
  std::vector<std::string> names;
  for (const Variant& v : kVariants) names.emplace_back(v.spec.name);
  return names;
}

std::optional<std::string> find_rtl_variant(const sim::HardwareConfig& hw, bool verif) {
  sim::HardwareConfig want = hw;
  want.cpg_mapping = sim::CpgMapping::Dedicated;
  for (const Variant& v : kVariants) {
    if (v.spec.inject_bug() == 0 && v.spec.randomize_x == verif && v.spec.config() == want) return v.spec.name;
  }
  return std::nullopt;
}

}  // namespace tessim::rtl
