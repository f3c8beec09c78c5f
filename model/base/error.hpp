// Errors reported to the user (docs/architecture.md, Bad input): every message names the file,
// the element and the reason.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tessim {

// `text` as it may be printed in a message: control bytes (and DEL) as \n, \t, \r or \xHH, so
// that a stray byte cannot hide in a quoted value or end the line; longer than `limit` bytes,
// its middle replaced by "[... N bytes ...]", so that a huge value cannot become a huge
// message (the start and the end of a reason are what explain it).
inline std::string printable_text(std::string_view text, std::size_t limit = 480) {
  std::string escaped;
  escaped.reserve(text.size() < 2 * limit ? text.size() : 2 * limit);
  const char* const hex = "0123456789abcdef";
  auto append = [&](std::string_view part) {
    for (const char c : part) {
      const auto byte = static_cast<unsigned char>(c);
      if (c == '\n') escaped += "\\n";
      else if (c == '\t') escaped += "\\t";
      else if (c == '\r') escaped += "\\r";
      else if (byte < 0x20 || byte == 0x7f) escaped += {'\\', 'x', hex[byte >> 4], hex[byte & 15]};
      else escaped += c;
    }
  };
  if (text.size() <= limit) {
    append(text);
    return escaped;
  }
  // Cut at UTF-8 character boundaries (never before a continuation byte).
  auto boundary = [&](std::size_t i) {
    while (i > 0 && i < text.size() && (static_cast<unsigned char>(text[i]) & 0xc0) == 0x80) --i;
    return i;
  };
  const std::size_t head = boundary(limit * 2 / 3), tail = boundary(text.size() - limit / 3);
  append(text.substr(0, head));
  escaped += " [... " + std::to_string(tail - head) + " bytes ...] ";
  append(text.substr(tail));
  return escaped;
}

// Bad input: a malformed file, a value out of range, an unsupported configuration.
// The CLI prints what() and exits non-zero; nothing is written. Each part is made printable
// (printable_text): the file and the element are short, the reason may quote the value.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& element, const std::string& reason)
      : std::runtime_error(printable_text(file, 240) + ": " + printable_text(element, 240) + ": " +
                           printable_text(reason)) {}
  explicit InputError(const std::string& message) : std::runtime_error(printable_text(message, 960)) {}
};

}  // namespace tessim
