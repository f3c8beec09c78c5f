#include "app/config_flags.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/input_file.hpp"

namespace tessim::app {

namespace {

std::string help_text(const sim::ParamSpec& p, const sim::UnitConfig& defaults) {
  std::string h = p.description;
  if (*p.symbol) h = std::string(p.symbol) + ": " + h;
  const nlohmann::json d = p.get(defaults);
  h += " [default " + (d.is_string() ? d.get<std::string>() : d.dump());
  h += p.type == sim::ParamType::Enum ? "; one of " : "; range ";
  h += sim::range_text(p);
  h += "; config key " + std::string(p.key) + "]";
  return h;
}

// The JSON object of a --config file. Every failure is an InputError naming the file and, for a
// value JSON cannot hold (a number beyond double's range, such as 1e400), its key.
nlohmann::json read_config_file(const std::string& file) {
  return sim::parse_config_text(read_whole_file(file, kConfigFileLimit, "file"), file);
}

}  // namespace

ConfigFlags::ConfigFlags(CLI::App& cmd) {
  cmd.add_option("--config", config_file_,
                 "JSON configuration, keys as in `tessim schema` (README.md, Configuration files); "
                 "flags given override it");
  const sim::UnitConfig defaults{};
  for (const sim::ParamSpec& p : sim::unit_params()) {
    Entry& e = entries_.emplace_back();
    e.spec = &p;
    const std::string names = sim::cli_names(p);
    const std::string help = help_text(p, defaults);
    switch (p.type) {
      case sim::ParamType::Int:
        e.option = cmd.add_option(names, e.i, help)->transform(number_check<int>("command line", p.flag, sim::range_text(p)));
        break;
      case sim::ParamType::UInt64:
        e.option = cmd.add_option(names, e.u, help)
                       ->transform(number_check<std::uint64_t>("command line", p.flag, sim::range_text(p)));
        break;
      case sim::ParamType::Double:
        e.option =
            cmd.add_option(names, e.d, help)->transform(number_check<double>("command line", p.flag, sim::range_text(p)));
        break;
      case sim::ParamType::Enum: e.option = cmd.add_option(names, e.s, help); break;
    }
    e.option->group("Unit configuration");
  }
}

nlohmann::json ConfigFlags::overrides() const {
  nlohmann::json j = nlohmann::json::object();
  for (const Entry& e : entries_) {
    if (!e.option->count()) continue;
    switch (e.spec->type) {
      case sim::ParamType::Int: j[e.spec->key] = e.i; break;
      case sim::ParamType::UInt64: j[e.spec->key] = e.u; break;
      case sim::ParamType::Double: j[e.spec->key] = e.d; break;
      case sim::ParamType::Enum: j[e.spec->key] = e.s; break;
    }
  }
  return j;
}

sim::UnitConfig ConfigFlags::config() const {
  sim::UnitConfig cfg;
  std::string source = "command line";
  if (!config_file_.empty()) {
    nlohmann::json j = read_config_file(config_file_);
    sim::apply_json(cfg, j, config_file_);
    source = config_file_;
  }
  const nlohmann::json flags = overrides();
  sim::apply_json(cfg, flags, "command line");
  if (!flags.empty() && !config_file_.empty()) source = config_file_ + " with command-line overrides";
  cfg.validate(source);
  return cfg;
}

}  // namespace tessim::app
