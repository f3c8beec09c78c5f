// The unit's configuration on the command line of `tessim sim` and `tessim cosim`: --config
// FILE and one flag per parameter of sim/config/params.hpp (canonical name and aliases from the
// table, help text with the default and the range). A flag overrides the file only when it is
// given.
#pragma once

#include <deque>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>

#include "sim/config/config.hpp"
#include "sim/config/params.hpp"

namespace tessim::app {

class ConfigFlags {
 public:
  // Registers --config and the parameter flags on `cmd`. The object must outlive parsing.
  explicit ConfigFlags(CLI::App& cmd);
  ConfigFlags(const ConfigFlags&) = delete;
  ConfigFlags& operator=(const ConfigFlags&) = delete;

  // Defaults, then the --config file, then the flags given; validated. Bad values are
  // InputErrors naming the file or "command line" and the key.
  sim::UnitConfig config() const;
  // The flags given, as a JSON object of configuration keys.
  nlohmann::json overrides() const;
  const std::string& config_file() const { return config_file_; }

 private:
  struct Entry {
    const sim::ParamSpec* spec = nullptr;
    CLI::Option* option = nullptr;
    long long i = 0;
    std::uint64_t u = 0;
    double d = 0;
    std::string s;
  };
  std::string config_file_;
  std::deque<Entry> entries_;  // options bind to the members: addresses must stay put
};

}  // namespace tessim::app
