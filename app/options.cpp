#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

#include "app/commands.hpp"
#include "model/error.hpp"
#include "model/pattern.hpp"

namespace tessim::app {

void check_tess_factor(const char* command, int factor) {
  if (factor < 1 || factor > kMaxTessFactor)
    throw InputError(command, "-L", std::to_string(factor) + " is outside 1.." + std::to_string(kMaxTessFactor));
}

NormalMode parse_normals_option(const char* command, const std::string& text) {
  const auto mode = parse_normal_mode(text);
  if (!mode)
    throw InputError(command, "--normals", "'" + text + "' is not one of quadratic, reflect, linear, derivative");
  return *mode;
}

void check_output_paths(const std::vector<OutputPath>& outputs) {
  namespace fs = std::filesystem;
  std::vector<fs::path> seen;
  for (const OutputPath& o : outputs) {
    if (o.path.empty()) continue;
    const fs::path path = o.path;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(o.path, o.option, "is a directory");
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(dir, ec))
      throw InputError(o.path, o.option, "cannot open for writing: directory '" + dir.string() + "' does not exist");
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      throw InputError(o.path, o.option, "cannot open for writing: directory '" + dir.string() + "' is not writable");
    const fs::path canonical = fs::weakly_canonical(path, ec);
    const fs::path key = ec ? path.lexically_normal() : canonical;
    for (const fs::path& other : seen)
      if (other == key) throw InputError(o.path, o.option, "is also the path of another output of this command");
    seen.push_back(key);
  }
}

void add_speed_run_options(CLI::App& sub, SpeedRunArgs& args, const char* int_blocks_help) {
  sub.add_option("mesh", args.mesh, "input mesh")->capture_default_str();
  sub.add_option("-L,--tess-factor", args.tess_factor, "segments per edge")
      ->transform(number_check<int>("command line", "-L", "1..64"))
      ->capture_default_str();
  sub.add_option("--int", args.int_blocks, int_blocks_help)
      ->transform(number_check<int>("command line", "--int", type_range<int>()))
      ->capture_default_str();
  sub.add_option("--gpe-cycles", args.gpe_cycles, "GPE cycles per vertex K")
      ->transform(number_check<int>("command line", "--gpe-cycles", type_range<int>()))
      ->capture_default_str();
  sub.add_option("--repeat", args.repeat, "runs per configuration (median reported)")
      ->transform(number_check<int>("command line", "--repeat", type_range<int>()))
      ->capture_default_str();
}

}  // namespace tessim::app
