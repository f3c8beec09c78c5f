// OFF structure check, following the header grammar of Assimp's reader:
// [ST][C][N][4][n]OFF [dimension] nv nf ne, then nv vertex lines and nf face lines.
#include <limits>

#include "model/io/format.hpp"

namespace tessim::io {

void check_off(const std::string& file, const std::string& data) {
  std::size_t pos = 0;
  // Header tokens: skip whitespace and '#' comment lines, as Assimp does.
  auto next_header_token = [&]() -> std::optional<std::string_view> {
    while (true) {
      while (pos < data.size() && is_space(data[pos])) ++pos;
      if (pos >= data.size()) return std::nullopt;
      if (data[pos] != '#') break;
      while (pos < data.size() && data[pos] != '\n' && data[pos] != '\r') ++pos;
    }
    const std::size_t start = pos;
    while (pos < data.size() && !is_space(data[pos])) ++pos;
    return std::string_view(data.data() + start, pos - start);
  };
  auto header_error = [&](const std::string& reason) { return InputError(file, "OFF header", reason); };

  auto token = next_header_token();
  if (!token) throw header_error("file has no content");
  int coordinates = 3;
  bool normals = false;
  std::string_view keyword = *token;
  if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
    std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    auto take = [&](std::string_view p) {
      if (prefix.substr(0, p.size()) != p) return false;
      prefix.remove_prefix(p.size());
      return true;
    };
    take("ST");
    take("C");
    normals = take("N");
    const bool homogeneous = take("4");
    const bool dimension = take("n");
    if (!prefix.empty()) throw header_error("unknown keyword '" + std::string(keyword) + "'");
    if (dimension) {
      const auto dim_token = next_header_token();
      const auto dim = dim_token ? parse_unsigned(*dim_token) : std::nullopt;
      if (!dim || *dim > 3) throw header_error("dimension must be at most 3");
      coordinates = static_cast<int>(*dim);
    }
    if (homogeneous) ++coordinates;
    token = next_header_token();
  }
  std::uint64_t counts[2] = {};
  const char* count_names[2] = {"vertex count", "face count"};
  for (int c = 0; c < 2; ++c) {
    const auto value = token ? parse_unsigned(*token) : std::nullopt;
    if (!value) throw header_error(std::string("expected the ") + count_names[c] + ", found '" + std::string(token.value_or("")) + "'");
    if (*value > std::numeric_limits<std::uint32_t>::max())
      throw header_error(std::string(count_names[c]) + " " + std::to_string(*value) + " does not fit in 32 bits");
    counts[c] = *value;
    token = next_header_token();
  }
  // `token` is the edge count; the data starts at the next token.
  const std::uint64_t nv = counts[0], nf = counts[1];
  if (nv == 0) throw header_error("declares no vertices");
  if (nf == 0) throw header_error("declares no faces");

  while (pos < data.size() && is_space(data[pos])) ++pos;
  // Data lines as Assimp's reader sees them: runs of line ends separate lines.
  std::vector<std::string_view> lines;
  while (pos < data.size() && lines.size() < nv + nf) {
    std::size_t end = pos;
    while (end < data.size() && data[end] != '\n' && data[end] != '\r') ++end;
    lines.emplace_back(data.data() + pos, end - pos);
    pos = end;
    while (pos < data.size() && (data[pos] == '\n' || data[pos] == '\r')) ++pos;
  }
  if (lines.size() < nv + nf)
    throw header_error("declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                       " faces, but only " + std::to_string(lines.size()) + " data lines follow");

  const int numbers_per_vertex = coordinates + (normals ? 3 : 0);
  for (std::uint64_t v = 0; v < nv; ++v) {
    const auto t = split_tokens(lines[v]);
    bool ok = t.size() >= static_cast<std::size_t>(numbers_per_vertex);
    for (int i = 0; ok && i < numbers_per_vertex; ++i) ok = parses_as_number(t[static_cast<std::size_t>(i)]);
    if (!ok)
      throw InputError(file, "vertex " + std::to_string(v),
                       "expected " + std::to_string(numbers_per_vertex) + " numbers, found '" + std::string(lines[v]) + "'");
  }
  for (std::uint64_t f = 0; f < nf; ++f) {
    const auto t = split_tokens(lines[nv + f]);
    const std::string element = "face " + std::to_string(f);
    const auto n = t.empty() ? std::nullopt : parse_unsigned(t[0]);
    if (!n) throw InputError(file, element, "expected a vertex count, found '" + std::string(lines[nv + f]) + "'");
    if (*n == 0) throw InputError(file, element, "has no vertices");
    if (*n > 9) throw InputError(file, element, std::to_string(*n) + " vertices: Assimp's OFF reader supports at most 9");
    if (t.size() < 1 + *n) throw InputError(file, element, "lists fewer than " + std::to_string(*n) + " vertex indices");
    for (std::size_t i = 1; i <= *n; ++i) {
      const auto index = parse_unsigned(t[i]);
      if (!index) throw InputError(file, element, "'" + std::string(t[i]) + "' is not a vertex index");
      if (*index >= nv)
        throw InputError(file, element, "vertex index " + std::to_string(*index) + " out of range (" + std::to_string(nv) + " vertices)");
    }
  }
}

}  // namespace tessim::io
