#include <string>

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

}  // namespace tessim::app
