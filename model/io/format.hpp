// What the files of model/io share: the structural checks made before (or, for OBJ, after)
// Assimp reads a file, the text scanning behind them, and extension matching.
//
// Assimp accepts some broken files silently or dangerously: its PLY reader loads truncated
// binary files, loops forever on a header without end_header and trusts element counts for
// allocation; its OFF reader clamps out-of-range indices, drops faces of more than 9 vertices
// and allocates whatever the header declares (invalid/OutOfMemory.off: 16 GB). PLY and OFF
// files are therefore checked structurally before Assimp sees them. Its ASCII STL reader loads
// a file cut off between facets with fewer triangles; its OBJ reader rejects a bad vertex index
// without saying where and drops all normals of a mesh with one bad normal index: ASCII STL
// and OBJ files are checked here first too.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/base/error.hpp"

namespace tessim::io {

// Each throws InputError naming the file, the element and the reason; `data` is the whole file.
void check_ply(const std::string& file, const std::string& data);  // header, every element present in full
void check_off(const std::string& file, const std::string& data);  // header, counts, numbers, indices
void check_stl(const std::string& file, const std::string& data);  // ASCII: closed solids, complete facets
// The first OBJ face with an index out of range, if any. A negative (relative) index counts
// back from the elements defined before its line, a positive one may refer to any element of
// the file (as Assimp resolves them).
std::optional<InputError> find_bad_obj_face(const std::string& file, const std::string& data);

inline std::string to_lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

inline std::string lower_extension(const std::filesystem::path& path) { return to_lower(path.extension().string()); }

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// Splits `text` into whitespace-separated tokens, one at a time.
class Tokenizer {
 public:
  explicit Tokenizer(std::string_view text) : text_(text) {}
  std::optional<std::string_view> next() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

inline std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  Tokenizer tokens(line);
  while (const auto t = tokens.next()) out.push_back(*t);
  return out;
}

// Lines ending in \n (or \r\n), numbered from 1; pos() is where the next line starts.
class LineReader {
 public:
  explicit LineReader(std::string_view data) : data_(data) {}
  std::optional<std::string_view> next() {
    if (pos_ >= data_.size()) return std::nullopt;
    std::size_t end = data_.find('\n', pos_);
    if (end == std::string_view::npos) end = data_.size();
    std::string_view line = data_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }
  int line_number() const { return line_number_; }
  std::size_t pos() const { return std::min(pos_, data_.size()); }

 private:
  std::string_view data_;
  std::size_t pos_ = 0;
  int line_number_ = 0;
};

// The whole token as an integer of type T (a sign only where T has one), or nothing.
template <class T>
std::optional<T> parse_integer(std::string_view token) {
  T value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return value;
}

inline std::optional<std::uint64_t> parse_unsigned(std::string_view token) { return parse_integer<std::uint64_t>(token); }

// The whole token as a double (correctly rounded; "nan" and "inf" included), or nothing.
inline std::optional<double> parse_number(std::string_view token) {
  double value = 0.0;
  const char* first = token.data();
  if (!token.empty() && token.front() == '+') ++first;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return value;
}

inline bool parses_as_number(std::string_view token) { return parse_number(token).has_value(); }

}  // namespace tessim::io
