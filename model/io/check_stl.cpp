// ASCII STL structure check. Assimp's reader stops quietly where the text ends, so a file cut
// off between two facets loads with fewer triangles; here every solid must be closed by
// 'endsolid' and every facet must hold three complete vertices.
#include <cstring>

#include "model/io/format.hpp"

namespace tessim::io {

namespace {

// Assimp's choice (STLLoader): binary when the size matches the triangle count in the header,
// else ASCII when the text starts with "solid" (and its first 500 bytes are 7-bit).
bool is_ascii_stl(const std::string& data) {
  if (data.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, sizeof count);  // little-endian, as the format
    if (84 + 50 * static_cast<std::uint64_t>(count) == data.size()) return false;
  }
  std::size_t pos = 0;
  while (pos < data.size() && is_space(data[pos])) ++pos;
  if (data.compare(pos, 5, "solid") != 0) return false;
  for (std::size_t i = 0; i < std::min<std::size_t>(data.size(), 500); ++i)
    if (static_cast<unsigned char>(data[i]) > 127) return false;
  return true;
}

}  // namespace

void check_stl(const std::string& file, const std::string& data) {
  if (!is_ascii_stl(data)) return;
  enum class State { Outside, InSolid, InFacet } state = State::Outside;
  std::uint64_t facets = 0;  // facets begun so far
  int vertices = 0;          // of the open facet
  int facet_line = 0;
  auto facet_element = [&] {
    return "facet " + std::to_string(facets - 1) + " (line " + std::to_string(facet_line) + ")";
  };
  LineReader lines(data);
  while (const auto line = lines.next()) {
    const auto t = split_tokens(*line);
    if (t.empty()) continue;
    const std::string keyword = to_lower(std::string(t[0]));
    auto line_element = [&] { return "line " + std::to_string(lines.line_number()); };
    if (keyword == "solid") {
      if (state != State::Outside)
        throw InputError(file, line_element(), "'solid' inside another solid (its 'endsolid' is missing)");
      state = State::InSolid;
    } else if (keyword == "endsolid") {
      if (state == State::InFacet) throw InputError(file, facet_element(), "'endsolid' before the facet's 'endfacet'");
      state = State::Outside;
    } else if (keyword == "facet") {
      if (state == State::InFacet) throw InputError(file, facet_element(), "next facet begins before 'endfacet'");
      if (state == State::Outside) throw InputError(file, line_element(), "'facet' outside 'solid' ... 'endsolid'");
      state = State::InFacet;
      ++facets;
      vertices = 0;
      facet_line = lines.line_number();
    } else if (keyword == "vertex") {
      if (state != State::InFacet) throw InputError(file, line_element(), "'vertex' outside a facet");
      bool ok = t.size() == 4;
      for (std::size_t i = 1; ok && i < 4; ++i) ok = parses_as_number(t[i]);
      if (!ok)
        throw InputError(file, facet_element(),
                         "vertex at line " + std::to_string(lines.line_number()) + ": expected 3 numbers, found '" +
                             std::string(*line) + "'");
      ++vertices;
    } else if (keyword == "endfacet") {
      if (state != State::InFacet) throw InputError(file, line_element(), "'endfacet' outside a facet");
      if (vertices != 3)
        throw InputError(file, facet_element(), std::to_string(vertices) + " vertices (a facet has 3)");
      state = State::InSolid;
    }
    // "outer loop", "endloop" and the facet normal need no check: the normal is not used.
  }
  if (state == State::InFacet)
    throw InputError(file, facet_element(),
                     "the file ends inside this facet (truncated: " + std::to_string(vertices) + " of 3 vertices)");
  if (state == State::InSolid)
    throw InputError(file, "endsolid",
                     "missing: an ASCII STL ends with 'endsolid' (the file is truncated after " +
                         std::to_string(facets) + (facets == 1 ? " facet)" : " facets)"));
}

}  // namespace tessim::io
