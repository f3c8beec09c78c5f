// OBJ: Assimp rejects an out-of-range vertex or texture-coordinate index without saying which
// face, and drops all normals of a mesh where one normal index is out of range (the normals are
// then computed, silently). Every face index is checked here before Assimp reads the file.
#include "model/io/format.hpp"

namespace tessim::io {

std::optional<InputError> find_bad_obj_face(const std::string& file, const std::string& data) {
  const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
  auto kind_of = [](std::string_view keyword) {
    return keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1;
  };
  // Totals first: a positive index may refer to an element defined after the face.
  std::int64_t totals[3] = {0, 0, 0};
  {
    LineReader lines(data);
    while (const auto line = lines.next()) {
      Tokenizer tokens(*line);
      const auto keyword = tokens.next();
      if (!keyword) continue;
      if (const int k = kind_of(*keyword); k >= 0) ++totals[k];
    }
  }
  std::int64_t counts[3] = {0, 0, 0};  // defined before the current line
  LineReader lines(data);
  while (const auto line = lines.next()) {
    const auto t = split_tokens(*line);
    if (t.empty()) continue;
    if (const int k = kind_of(t[0]); k >= 0) {
      ++counts[k];
    } else if (t[0] == "f") {
      for (std::size_t c = 1; c < t.size(); ++c) {
        std::string_view corner = t[c];
        for (int k = 0; k < 3 && !corner.empty(); ++k) {
          const std::size_t slash = corner.find('/');
          const std::string_view part = corner.substr(0, slash);
          corner = slash == std::string_view::npos ? std::string_view() : corner.substr(slash + 1);
          if (part.empty()) continue;
          const auto index = parse_integer<std::int64_t>(part);
          if (!index) continue;
          const bool relative = *index < 0;
          const std::int64_t available = relative ? counts[k] : totals[k];
          const std::int64_t resolved = relative ? counts[k] + *index + 1 : *index;
          if (resolved < 1 || resolved > available)
            return InputError(file, "face at line " + std::to_string(lines.line_number()),
                              std::string(kinds[k]) + " index " + std::to_string(*index) + " out of range (" +
                                  std::to_string(available) +
                                  (relative ? " defined before this line)" : " in the file)"));
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace tessim::io
