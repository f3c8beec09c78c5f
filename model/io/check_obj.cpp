// OBJ: Assimp rejects out-of-range face indices without saying which face; find it.
#include "model/io/format.hpp"

namespace tessim::io {

std::optional<InputError> find_bad_obj_face(const std::string& file, const std::string& data) {
  std::int64_t counts[3] = {0, 0, 0};  // v, vt, vn
  const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
  LineReader lines(data);
  while (const auto line = lines.next()) {
    const auto t = split_tokens(*line);
    if (t.empty()) continue;
    if (t[0] == "v") ++counts[0];
    else if (t[0] == "vt") ++counts[1];
    else if (t[0] == "vn") ++counts[2];
    else if (t[0] == "f") {
      for (std::size_t c = 1; c < t.size(); ++c) {
        std::string_view corner = t[c];
        for (int k = 0; k < 3 && !corner.empty(); ++k) {
          const std::size_t slash = corner.find('/');
          const std::string_view part = corner.substr(0, slash);
          corner = slash == std::string_view::npos ? std::string_view() : corner.substr(slash + 1);
          if (part.empty()) continue;
          const auto index = parse_integer<std::int64_t>(part);
          if (!index) continue;
          const std::int64_t resolved = *index < 0 ? counts[k] + *index + 1 : *index;
          if (resolved < 1 || resolved > counts[k])
            return InputError(file, "face at line " + std::to_string(lines.line_number()),
                              std::string(kinds[k]) + " index " + std::to_string(*index) + " out of range (" +
                                  std::to_string(counts[k]) + " defined before this line)");
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace tessim::io
