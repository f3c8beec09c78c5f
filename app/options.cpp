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

}  // namespace tessim::app
