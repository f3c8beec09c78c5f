// The JSON configuration (`--config`, sweep points) under libFuzzer, through the same parsing and
// checks as the CLI: any text must give a valid configuration or an InputError naming the file
// and key; a configuration that validates must build a unit.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "sim/config/config.hpp"
#include "sim/unit/unit.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json j = tessim::sim::parse_config_text(text, "fuzz.json");  // what --config reads
    tessim::sim::UnitConfig cfg;
    tessim::sim::apply_json(cfg, j, "fuzz.json");
    cfg.validate("fuzz.json");
    if (!tessim::sim::hardware_supports(cfg.normals)) return 0;
    tessim::sim::Unit unit(cfg);  // every validated configuration builds
    (void)tessim::sim::to_json(cfg);
  } catch (const tessim::InputError&) {
  }
  return 0;
}
