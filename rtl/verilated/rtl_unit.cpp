#include "rtl/verilated/rtl_unit.hpp"

#include <array>

#include <nlohmann/json.hpp>

#include "model/error.hpp"
#include "rtl/verilated/verilated_unit.hpp"
#include "sim/params.hpp"

#include "Vtess_n1.h"
#include "Vtess_n2.h"
#include "Vtess_n2_bug1.h"
#include "Vtess_n2_bug2.h"
#include "Vtess_n2_verif.h"
#include "Vtess_n3.h"
#include "Vtess_n4.h"

namespace tessim::rtl {

RtlUnit::~RtlUnit() = default;

namespace {

using Maker = std::unique_ptr<RtlUnit> (*)(const VariantSpec&, std::uint64_t);

struct Variant {
  VariantSpec spec;
  Maker make;
};

// One row per verilated configuration (rtl/CMakeLists.txt).
const std::array<Variant, 7> kVariants{{
    {{"n1", 1, 0, false}, &make_variant<Vtess_n1>},
    {{"n2", 2, 0, false}, &make_variant<Vtess_n2>},
    {{"n3", 3, 0, false}, &make_variant<Vtess_n3>},
    {{"n4", 4, 0, false}, &make_variant<Vtess_n4>},
    {{"n2_verif", 2, 0, true}, &make_variant<Vtess_n2_verif>},
    {{"n2_bug1", 2, 1, false}, &make_variant<Vtess_n2_bug1>},
    {{"n2_bug2", 2, 2, false}, &make_variant<Vtess_n2_bug2>},
}};

}  // namespace

std::unique_ptr<RtlUnit> make_rtl_unit(const std::string& variant, std::uint64_t seed) {
  for (const Variant& v : kVariants) {
    if (variant == v.spec.name) return v.make(v.spec, seed);
  }
  std::string known;
  for (const Variant& v : kVariants) known += (known.empty() ? "" : ", ") + std::string(v.spec.name);
  throw std::invalid_argument("unknown RTL variant '" + variant + "' (known: " + known + ")");
}

void check_config(const RtlUnit& unit, const sim::UnitConfig& cfg) {
  const sim::UnitConfig& rtl = unit.config();
  const std::string where = "RTL variant " + unit.variant();
  // Every parameter that is a parameter of tess_unit (sim/params.cpp) must match the build.
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

}  // namespace tessim::rtl
