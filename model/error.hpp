// Errors reported to the user (docs/architecture.md, Bad input): every message names the file,
// the element and the reason.
#pragma once

#include <stdexcept>
#include <string>

namespace tessim {

// Bad input: a malformed file, a value out of range, an unsupported configuration.
// The CLI prints what() and exits non-zero; nothing is written.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& element, const std::string& reason)
      : std::runtime_error(file + ": " + element + ": " + reason) {}
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace tessim
