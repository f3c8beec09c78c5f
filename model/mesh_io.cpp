// Mesh import through Assimp, with the checks Assimp does not make, and streamed PLY/OBJ export.
//
// Assimp accepts some broken files silently or dangerously: its PLY reader loads truncated
// binary files, loops forever on a header without end_header and trusts element counts for
// allocation; its OFF reader clamps out-of-range indices, drops faces of more than 9 vertices
// and allocates whatever the header declares (invalid/OutOfMemory.off: 16 GB). PLY and OFF
// files are therefore checked structurally before Assimp sees them, and Assimp's error log
// is watched for the messages that mean geometry was altered. Assimp's OBJ reader rejects a
// bad face index without saying where; the face is then located here.
//
// Welding is exact: one vertex per distinct position (after node transforms, in double).
// Normals: the file's, averaged over the distinct normals found at a welded position (STL's
// facet normals excepted); otherwise the sum over incident triangles of area x corner angle x
// unit face normal, with +Z where that sum vanishes.
#include "model/mesh_io.hpp"

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/Logger.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "model/error.hpp"
#include "model/output_file.hpp"
#include "model/pattern.hpp"

namespace tessim {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the PLY writer stores native doubles and uint32 as binary_little_endian");

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string format_vec(const glm::dvec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool is_finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string read_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "file", "cannot be opened for reading");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, "file", "read error");
  return data;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

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

bool parses_as_number(std::string_view token) {
  double value = 0.0;
  const char* first = token.data();
  if (!token.empty() && token.front() == '+') ++first;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

std::optional<std::uint64_t> parse_unsigned(std::string_view token) {
  std::uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return value;
}

// ---------------------------------------------------------------------------------------------
// PLY structure check: header, then every element instance present in full.

struct PlyScalar {
  int size = 0;
  bool is_signed = false;
  bool is_integer = false;
};

std::optional<PlyScalar> ply_scalar(std::string_view name) {
  if (name == "char" || name == "int8") return PlyScalar{1, true, true};
  if (name == "uchar" || name == "uint8") return PlyScalar{1, false, true};
  if (name == "short" || name == "int16") return PlyScalar{2, true, true};
  if (name == "ushort" || name == "uint16") return PlyScalar{2, false, true};
  if (name == "int" || name == "int32") return PlyScalar{4, true, true};
  if (name == "uint" || name == "uint32") return PlyScalar{4, false, true};
  if (name == "float" || name == "float32") return PlyScalar{4, true, false};
  if (name == "double" || name == "float64") return PlyScalar{8, true, false};
  return std::nullopt;
}

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyScalar count;  // lists only
  PlyScalar item;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

std::int64_t read_ply_integer(const char* p, const PlyScalar& type, bool big_endian) {
  unsigned char bytes[8] = {};
  std::memcpy(bytes, p, static_cast<std::size_t>(type.size));
  if (big_endian) std::reverse(bytes, bytes + type.size);
  std::uint64_t u = 0;
  for (int i = type.size - 1; i >= 0; --i) u = (u << 8) | bytes[i];
  if (type.is_signed && (bytes[type.size - 1] & 0x80u)) return static_cast<std::int64_t>(u) - (std::int64_t{1} << (8 * type.size));
  return static_cast<std::int64_t>(u);
}

void check_ply(const std::string& file, const std::string& data) {
  // Header lines end with \n (or \r\n).
  std::size_t pos = 0;
  int line_number = 0;
  auto next_line = [&]() -> std::optional<std::string_view> {
    if (pos >= data.size()) return std::nullopt;
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    std::string_view line(data.data() + pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  };
  auto header_error = [&](const std::string& reason) {
    return InputError(file, "PLY header line " + std::to_string(line_number), reason);
  };

  const auto magic = next_line();
  if (!magic || *magic != "ply") throw InputError(file, "PLY header", "does not start with 'ply'");

  std::optional<PlyFormat> format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (const auto line = next_line()) {
    Tokenizer tokens(*line);
    const auto keyword = tokens.next();
    if (!keyword) continue;
    if (*keyword == "end_header") {
      ended = true;
      break;
    }
    if (*keyword == "comment" || *keyword == "obj_info") continue;
    if (*keyword == "format") {
      const auto kind = tokens.next();
      if (kind == "ascii") format = PlyFormat::Ascii;
      else if (kind == "binary_little_endian") format = PlyFormat::BinaryLittle;
      else if (kind == "binary_big_endian") format = PlyFormat::BinaryBig;
      else throw header_error("unknown format '" + std::string(kind.value_or("")) + "'");
    } else if (*keyword == "element") {
      const auto name = tokens.next();
      const auto count_token = tokens.next();
      const auto count = count_token ? parse_unsigned(*count_token) : std::nullopt;
      if (!name || !count) throw header_error("expected 'element <name> <count>'");
      elements.push_back({std::string(*name), *count, {}});
    } else if (*keyword == "property") {
      if (elements.empty()) throw header_error("property before any element");
      PlyProperty property;
      auto type = tokens.next();
      if (type == "list") {
        property.is_list = true;
        const auto count_type = tokens.next();
        const auto count_scalar = count_type ? ply_scalar(*count_type) : std::nullopt;
        if (!count_scalar || !count_scalar->is_integer) throw header_error("list count type must be an integer type");
        property.count = *count_scalar;
        type = tokens.next();
      }
      const auto item = type ? ply_scalar(*type) : std::nullopt;
      if (!item) throw header_error("unknown property type '" + std::string(type.value_or("")) + "'");
      property.item = *item;
      property.name = std::string(tokens.next().value_or(""));
      elements.back().properties.push_back(property);
    }
    // Other lines are skipped, as Assimp does (Blender wrote "Created by ..." without "comment").
  }
  if (!ended) throw InputError(file, "PLY header", "no end_header line (file truncated or not PLY)");
  if (!format) throw InputError(file, "PLY header", "no format line");

  auto truncated = [&](const PlyElement& e, std::uint64_t instance) {
    return InputError(file, "element '" + e.name + "' " + std::to_string(instance) + " of " + std::to_string(e.count),
                      "file ends early (truncated)");
  };

  if (*format == PlyFormat::Ascii) {
    Tokenizer tokens(std::string_view(data).substr(std::min(pos, data.size())));
    for (const PlyElement& e : elements) {
      if (e.properties.empty()) continue;
      for (std::uint64_t i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.properties) {
          auto bad_value = [&](std::string_view token) {
            return InputError(file, "element '" + e.name + "' " + std::to_string(i) + " property '" + p.name + "'",
                              "'" + std::string(token) + "' is not a number");
          };
          std::uint64_t values = 1;
          if (p.is_list) {
            const auto count_token = tokens.next();
            if (!count_token) throw truncated(e, i);
            const auto count = parse_unsigned(*count_token);
            if (!count)
              throw InputError(file, "element '" + e.name + "' " + std::to_string(i) + " property '" + p.name + "'",
                               "'" + std::string(*count_token) + "' is not a list length");
            values = *count;
          }
          for (std::uint64_t v = 0; v < values; ++v) {
            const auto token = tokens.next();
            if (!token) throw truncated(e, i);
            if (!parses_as_number(*token)) throw bad_value(*token);
          }
        }
      }
    }
    return;
  }

  const bool big_endian = *format == PlyFormat::BinaryBig;
  std::size_t offset = std::min(pos, data.size());
  for (const PlyElement& e : elements) {
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.is_list; });
    if (fixed) {
      std::uint64_t row = 0;
      for (const PlyProperty& p : e.properties) row += static_cast<std::uint64_t>(p.item.size);
      if (row == 0) continue;
      const std::uint64_t available = (data.size() - offset) / row;
      if (available < e.count) throw truncated(e, available);
      offset += static_cast<std::size_t>(e.count * row);
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        std::uint64_t bytes = static_cast<std::uint64_t>(p.item.size);
        if (p.is_list) {
          if (data.size() - offset < static_cast<std::size_t>(p.count.size)) throw truncated(e, i);
          const std::int64_t n = read_ply_integer(data.data() + offset, p.count, big_endian);
          offset += static_cast<std::size_t>(p.count.size);
          if (n < 0)
            throw InputError(file, "element '" + e.name + "' " + std::to_string(i) + " property '" + p.name + "'",
                             "negative list length " + std::to_string(n));
          bytes *= static_cast<std::uint64_t>(n);
        }
        if (data.size() - offset < bytes) throw truncated(e, i);
        offset += static_cast<std::size_t>(bytes);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// OFF structure check, following the header grammar of Assimp's reader:
// [ST][C][N][4][n]OFF [dimension] nv nf ne, then nv vertex lines and nf face lines.

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  Tokenizer tokens(line);
  while (const auto t = tokens.next()) out.push_back(*t);
  return out;
}

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

// ---------------------------------------------------------------------------------------------
// OBJ: Assimp rejects out-of-range face indices without saying which face; find it.

std::optional<InputError> find_bad_obj_face(const std::string& file, const std::string& data) {
  std::int64_t counts[3] = {0, 0, 0};  // v, vt, vn
  const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
  std::size_t pos = 0;
  int line_number = 0;
  while (pos < data.size()) {
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    const std::string_view line(data.data() + pos, end - pos);
    pos = end + 1;
    ++line_number;
    const auto t = split_tokens(line);
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
          std::int64_t index = 0;
          const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
          if (ec != std::errc() || ptr != part.data() + part.size()) continue;
          const std::int64_t resolved = index < 0 ? counts[k] + index + 1 : index;
          if (resolved < 1 || resolved > counts[k])
            return InputError(file, "face at line " + std::to_string(line_number),
                              std::string(kinds[k]) + " index " + std::to_string(index) + " out of range (" +
                                  std::to_string(counts[k]) + " defined before this line)");
        }
      }
    }
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Assimp's error log: some readers report altered geometry only there.

class ErrorCollector : public Assimp::Logger {
 public:
  explicit ErrorCollector(std::vector<std::string>* errors) : Logger(NORMAL), errors_(errors) {}
  void OnDebug(const char*) override {}
  void OnVerboseDebug(const char*) override {}
  void OnInfo(const char*) override {}
  void OnWarn(const char*) override {}
  void OnError(const char* message) override { errors_->emplace_back(message); }
  bool attachStream(Assimp::LogStream*, unsigned int) override { return false; }
  bool detachStream(Assimp::LogStream*, unsigned int) override { return false; }

 private:
  std::vector<std::string>* errors_;
};

// Logged errors that mean vertices or faces were dropped, clamped or invented. Other logged
// errors (missing materials or textures, ignored animation tracks) leave the geometry intact.
bool alters_geometry(std::string message) {
  std::transform(message.begin(), message.end(), message.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* key : {"out of range", "incorrect", "not allowed", "aren't allowed", "truncat", "unexpected end"})
    if (message.find(key) != std::string::npos) return true;
  return false;
}

// The DefaultLogger is a process-wide singleton: imports are serialized.
std::mutex& assimp_mutex() {
  static std::mutex m;
  return m;
}

// ---------------------------------------------------------------------------------------------
// Welding and normals.

struct WeldKey {
  std::uint64_t x, y, z;
  bool operator==(const WeldKey&) const = default;
};

struct WeldKeyHash {
  std::size_t operator()(const WeldKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= k.y + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= k.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

WeldKey weld_key(const glm::dvec3& p) {
  // + 0.0 turns -0.0 into +0.0 so that both weld together.
  return {std::bit_cast<std::uint64_t>(p.x + 0.0), std::bit_cast<std::uint64_t>(p.y + 0.0),
          std::bit_cast<std::uint64_t>(p.z + 0.0)};
}

// Sum of area x corner-angle weighted face normals at every vertex; a vertex whose sum
// vanishes (only zero-area triangles around it, or faces that cancel) gets +Z.
constexpr double kCancelTolerance = 1e-12;
const glm::dvec3 kFallbackNormal{0.0, 0.0, 1.0};

std::vector<glm::dvec3> weighted_normals(const std::vector<glm::dvec3>& positions,
                                         const std::vector<glm::uvec3>& triangles, std::size_t* fallbacks) {
  std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
  std::vector<double> magnitude(positions.size(), 0.0);
  for (const glm::uvec3& t : triangles) {
    const glm::dvec3 p[3] = {positions[t[0]], positions[t[1]], positions[t[2]]};
    const glm::dvec3 twice_area_normal = glm::cross(p[1] - p[0], p[2] - p[0]);
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 e1 = p[(c + 1) % 3] - p[c];
      const glm::dvec3 e2 = p[(c + 2) % 3] - p[c];
      const double angle = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
      const glm::dvec3 contribution = 0.5 * angle * twice_area_normal;  // area x angle x unit normal
      sum[t[c]] += contribution;
      magnitude[t[c]] += glm::length(contribution);
    }
  }
  std::size_t count = 0;
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double length = glm::length(sum[v]);
    if (magnitude[v] > 0.0 && length > kCancelTolerance * magnitude[v] && std::isfinite(length)) {
      sum[v] /= length;
    } else {
      sum[v] = kFallbackNormal;
      ++count;
    }
  }
  if (fallbacks) *fallbacks = count;
  return sum;
}

glm::dmat4 to_glm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row-major (a1..a4 is the first row); glm is column-major.
  return glm::dmat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

struct MeshInstance {
  unsigned mesh = 0;
  glm::dmat4 transform{1.0};
};

void collect_instances(const aiNode* node, const glm::dmat4& parent, std::vector<MeshInstance>& out, int depth) {
  if (depth > 1024) return;  // a cyclic or absurdly deep node graph
  const glm::dmat4 transform = parent * to_glm(node->mTransformation);
  for (unsigned i = 0; i < node->mNumMeshes; ++i) out.push_back({node->mMeshes[i], transform});
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect_instances(node->mChildren[c], transform, out, depth + 1);
}

std::string vertex_element(const aiScene* scene, unsigned mesh, unsigned vertex) {
  std::string element = "vertex " + std::to_string(vertex);
  if (scene->mNumMeshes > 1) element = "mesh " + std::to_string(mesh) + " " + element;
  return element;
}

// Index and value checks on the scene as read, before triangulation touches it.
void check_scene(const std::string& file, const aiScene* scene) {
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const std::string mesh_prefix = scene->mNumMeshes > 1 ? "mesh " + std::to_string(m) + " " : "";
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0) throw InputError(file, mesh_prefix + "face " + std::to_string(f), "has no vertices");
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        const unsigned v = face.mIndices[i];
        if (v >= mesh->mNumVertices)
          throw InputError(file, mesh_prefix + "face " + std::to_string(f),
                           "vertex index " + std::to_string(v) + " out of range (" +
                               std::to_string(mesh->mNumVertices) + " vertices)");
        const aiVector3D& p = mesh->mVertices[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          throw InputError(file, vertex_element(scene, m, v),
                           "coordinate is NaN or infinite " + format_vec(glm::dvec3(p.x, p.y, p.z)));
        if (mesh->mNormals) {
          const aiVector3D& n = mesh->mNormals[v];
          if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
            throw InputError(file, vertex_element(scene, m, v),
                             "normal in the file is NaN or infinite " + format_vec(glm::dvec3(n.x, n.y, n.z)));
        }
      }
    }
  }
}

}  // namespace

// -----------------------------------------------------------------------------------------------

Mesh load_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(file, "file", "does not exist");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "file", "is not a regular file");
  const std::string ext = lower_extension(path);
  if (std::filesystem::file_size(path, ec) == 0 && !ec) throw InputError(file, "file", "is empty");
  if (ext == ".ply") check_ply(file, read_file(file));
  if (ext == ".off") check_off(file, read_file(file));

  std::lock_guard<std::mutex> lock(assimp_mutex());
  std::vector<std::string> logged_errors;
  Assimp::DefaultLogger::set(new ErrorCollector(&logged_errors));
  struct LoggerReset {
    ~LoggerReset() { Assimp::DefaultLogger::set(nullptr); }
  } logger_reset;

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, 0);
  if (!scene) {
    if (ext == ".obj") {
      if (auto located = find_bad_obj_face(file, read_file(file))) throw *located;
    }
    throw InputError(file, "import", std::string("Assimp cannot read it: ") + importer.GetErrorString());
  }
  for (const std::string& message : logged_errors)
    if (alters_geometry(message)) throw InputError(file, "import", "Assimp reported: " + message);
  if (scene->mNumMeshes == 0 || !scene->mRootNode) throw InputError(file, "faces", "the file contains no mesh");

  check_scene(file, scene);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
  if (!scene) throw InputError(file, "import", std::string("Assimp cannot triangulate it: ") + importer.GetErrorString());

  std::vector<MeshInstance> instances;
  collect_instances(scene->mRootNode, glm::dmat4(1.0), instances, 0);
  for (const MeshInstance& inst : instances)
    if (inst.mesh >= scene->mNumMeshes)
      throw InputError(file, "node graph",
                       "refers to mesh " + std::to_string(inst.mesh) + " of " + std::to_string(scene->mNumMeshes));
  // Readers that build no node graph for their meshes: take every mesh as it is.
  if (instances.empty())
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) instances.push_back({m, glm::dmat4(1.0)});

  // STL stores one facet normal per triangle (often zero or rounded), not vertex normals:
  // vertex normals are computed from the geometry instead.
  bool use_file_normals = ext != ".stl";
  std::size_t vertices = 0, points = 0, lines = 0, triangle_faces = 0;
  for (const MeshInstance& inst : instances) {
    const aiMesh* mesh = scene->mMeshes[inst.mesh];
    vertices += mesh->mNumVertices;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n == 1) ++points;
      else if (n == 2) ++lines;
      else if (n == 3) ++triangle_faces;
    }
    if (!mesh->mNormals) use_file_normals = false;
  }
  if (triangle_faces == 0)
    throw InputError(file, "faces",
                     "no triangles (" + std::to_string(vertices) + " vertices, " + std::to_string(points) +
                         " point and " + std::to_string(lines) + " line primitives)");

  Mesh out;
  out.source = file;
  std::unordered_map<WeldKey, std::uint32_t, WeldKeyHash> welded;
  // First source vertex of each welded vertex, for messages.
  std::vector<std::pair<unsigned, unsigned>> origin;
  // File normals (unit) of every copy, keyed by welded vertex; deduplicated below.
  std::vector<std::pair<std::uint32_t, glm::dvec3>> normal_copies;

  for (const MeshInstance& inst : instances) {
    const aiMesh* mesh = scene->mMeshes[inst.mesh];
    const glm::dmat3 linear(inst.transform);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    // A mirroring transform reverses the winding in world space; swap to keep faces outward.
    const bool mirrored = glm::determinant(linear) < 0.0;
    std::vector<std::uint32_t> remap(mesh->mNumVertices, std::numeric_limits<std::uint32_t>::max());
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      glm::uvec3 tri;
      for (int c = 0; c < 3; ++c) {
        const unsigned v = face.mIndices[c];
        if (remap[v] == std::numeric_limits<std::uint32_t>::max()) {
          const aiVector3D& a = mesh->mVertices[v];
          const glm::dvec3 p = glm::dvec3(inst.transform * glm::dvec4(a.x, a.y, a.z, 1.0));
          if (!is_finite(p))
            throw InputError(file, vertex_element(scene, inst.mesh, v),
                             "position is not finite after the node transform " + format_vec(p));
          if (out.positions.size() >= std::numeric_limits<std::uint32_t>::max())
            throw InputError(file, "vertices", "more than 2^32 - 1 distinct positions");
          const auto [it, inserted] = welded.try_emplace(weld_key(p), static_cast<std::uint32_t>(out.positions.size()));
          if (inserted) {
            out.positions.push_back(p);
            origin.emplace_back(inst.mesh, v);
          }
          remap[v] = it->second;
          if (use_file_normals) {
            const aiVector3D& a_n = mesh->mNormals[v];
            const glm::dvec3 n = normal_matrix * glm::dvec3(a_n.x, a_n.y, a_n.z);
            const double length = glm::length(n);
            // A zero-length copy carries no direction; it is an error only if no copy at
            // this position has one (checked below).
            if (length > 0.0 && std::isfinite(length)) normal_copies.emplace_back(it->second, n / length);
          }
        }
        tri[c] = remap[v];
      }
      if (mirrored) std::swap(tri[1], tri[2]);
      out.triangles.push_back(tri);
    }
  }

  if (use_file_normals) {
    // Average the distinct normals at each position, so that the result does not depend on
    // how many corner copies the reader made of each (position, normal) pair.
    std::sort(normal_copies.begin(), normal_copies.end(), [](const auto& a, const auto& b) {
      if (a.first != b.first) return a.first < b.first;
      if (a.second.x != b.second.x) return a.second.x < b.second.x;
      if (a.second.y != b.second.y) return a.second.y < b.second.y;
      return a.second.z < b.second.z;
    });
    normal_copies.erase(std::unique(normal_copies.begin(), normal_copies.end()), normal_copies.end());
    out.normals.assign(out.positions.size(), glm::dvec3(0.0));
    std::vector<std::size_t> copies(out.positions.size(), 0);
    for (const auto& [v, n] : normal_copies) {
      out.normals[v] += n;
      ++copies[v];
    }
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
      const std::string element = vertex_element(scene, origin[v].first, origin[v].second);
      if (copies[v] == 0)
        throw InputError(file, element, "normal in the file has zero length (at " + format_vec(out.positions[v]) + ")");
      const double length = glm::length(out.normals[v]);
      if (!(length > kCancelTolerance * static_cast<double>(copies[v])))
        throw InputError(file, element,
                         "the file's normals at " + format_vec(out.positions[v]) + " cancel out (" +
                             std::to_string(copies[v]) + " distinct normals summing to zero)");
      out.normals[v] /= length;
    }
    out.normals_from_file = true;
  } else {
    out.normals = weighted_normals(out.positions, out.triangles, nullptr);
    out.normals_from_file = false;
  }
  return out;
}

MeshStats mesh_stats(const Mesh& mesh) {
  MeshStats stats;
  stats.vertices = mesh.vertex_count();
  stats.triangles = mesh.triangle_count();
  stats.bbox = bounding_box(mesh);
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3& p1 = mesh.positions[t[0]];
    const glm::dvec3& p2 = mesh.positions[t[1]];
    const glm::dvec3& p3 = mesh.positions[t[2]];
    // Same zero-area test as the tessellator, so that both report the same count.
    const glm::dvec3 e1 = p2 - p1, e2 = p3 - p1;
    if (!(glm::length(glm::cross(e1, e2)) > 1e-12 * glm::length(e1) * glm::length(e2))) ++stats.degenerate_triangles;
    stats.zero_length_edges += (p1 == p2) + (p2 == p3) + (p3 == p1);
  }
  if (!mesh.normals_from_file) weighted_normals(mesh.positions, mesh.triangles, &stats.normal_fallbacks);
  return stats;
}

// -----------------------------------------------------------------------------------------------
// Writer

bool is_supported_output(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".ply" || ext == ".obj";
}

struct MeshWriter::Impl {
  Impl(const std::filesystem::path& target, bool ply, std::uint64_t vertices, std::uint64_t triangles)
      : path(target), is_ply(ply), out(target, ply), total_vertices(vertices), total_triangles(triangles) {}

  std::filesystem::path path;
  bool is_ply;
  AtomicOutput out;
  std::uint64_t total_vertices;
  std::uint64_t total_triangles;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  bool finished = false;
  // PLY keeps all faces after all vertices; the faces follow from the pattern, so only the
  // sequence of factors is kept (run-length coded) and the face list is generated in finish().
  std::vector<std::pair<int, std::uint64_t>> factor_runs;
  std::string buffer;

  void write_buffer() {
    out.stream().write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
    if (!out.stream()) throw InputError(path.string(), "output", "write failed");
  }
};

namespace {

void append_number(std::string& s, double x) {
  char buf[32];
  // Shortest representation that reads back as the same double.
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, x);
  s.append(buf, ec == std::errc() ? ptr : buf);
}

void append_raw(std::string& s, const void* data, std::size_t size) { s.append(static_cast<const char*>(data), size); }

}  // namespace

MeshWriter::MeshWriter(const std::filesystem::path& path, std::uint64_t total_vertices, std::uint64_t total_triangles) {
  if (!is_supported_output(path))
    throw InputError(path.string(), "output", "unsupported extension '" + path.extension().string() + "' (use .ply or .obj)");
  const bool ply = lower_extension(path) == ".ply";
  if (ply && total_vertices > std::numeric_limits<std::uint32_t>::max())
    throw InputError(path.string(), "output", std::to_string(total_vertices) + " vertices do not fit PLY's 32-bit indices");
  impl_ = std::make_unique<Impl>(path, ply, total_vertices, total_triangles);
  std::string& h = impl_->buffer;
  if (ply) {
    h += "ply\nformat binary_little_endian 1.0\ncomment tessim tessellated mesh\n";
    h += "element vertex " + std::to_string(total_vertices) + "\n";
    for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) h += std::string("property double ") + p + "\n";
    h += "element face " + std::to_string(total_triangles) + "\n";
    h += "property list uchar uint vertex_indices\nend_header\n";
  } else {
    h += "# tessim tessellated mesh: " + std::to_string(total_vertices) + " vertices, " +
         std::to_string(total_triangles) + " triangles\n";
  }
  impl_->write_buffer();
}

MeshWriter::~MeshWriter() = default;

void MeshWriter::add_patch(int L, const glm::dvec3* positions, const glm::dvec3* normals) {
  Impl& w = *impl_;
  if (w.finished) throw std::logic_error("MeshWriter::add_patch after finish()");
  if (L < 1 || L > kMaxTessFactor) throw std::logic_error("MeshWriter::add_patch: factor " + std::to_string(L) + " out of range");
  const auto n = static_cast<std::uint64_t>(pattern_vertex_count(L));
  const auto t = static_cast<std::uint64_t>(pattern_triangle_count(L));
  if (w.vertices + n > w.total_vertices || w.triangles + t > w.total_triangles)
    throw std::logic_error("MeshWriter::add_patch: more than the declared " + std::to_string(w.total_vertices) +
                           " vertices / " + std::to_string(w.total_triangles) + " triangles");

  std::string& s = w.buffer;
  if (w.is_ply) {
    for (std::uint64_t i = 0; i < n; ++i) {
      const double record[6] = {positions[i].x, positions[i].y, positions[i].z, normals[i].x, normals[i].y, normals[i].z};
      append_raw(s, record, sizeof record);
    }
    if (!w.factor_runs.empty() && w.factor_runs.back().first == L) ++w.factor_runs.back().second;
    else w.factor_runs.emplace_back(L, 1);
  } else {
    for (std::uint64_t i = 0; i < n; ++i) {
      s += "v ";
      append_number(s, positions[i].x);
      s += ' ';
      append_number(s, positions[i].y);
      s += ' ';
      append_number(s, positions[i].z);
      s += "\nvn ";
      append_number(s, normals[i].x);
      s += ' ';
      append_number(s, normals[i].y);
      s += ' ';
      append_number(s, normals[i].z);
      s += '\n';
    }
    for (const glm::uvec3& tri : pattern_triangles(L)) {
      s += 'f';
      for (int c = 0; c < 3; ++c) {
        const std::string index = std::to_string(w.vertices + tri[c] + 1);  // OBJ counts from 1
        s += ' ';
        s += index;
        s += "//";
        s += index;
      }
      s += '\n';
    }
  }
  w.vertices += n;
  w.triangles += t;
  w.write_buffer();
}

void MeshWriter::finish() {
  Impl& w = *impl_;
  if (w.finished) throw std::logic_error("MeshWriter::finish called twice");
  if (w.vertices != w.total_vertices || w.triangles != w.total_triangles)
    throw std::logic_error("MeshWriter::finish: " + std::to_string(w.vertices) + " of " + std::to_string(w.total_vertices) +
                           " vertices and " + std::to_string(w.triangles) + " of " + std::to_string(w.total_triangles) +
                           " triangles were written");
  if (w.is_ply) {
    std::uint32_t base = 0;
    for (const auto& [L, count] : w.factor_runs) {
      const std::vector<glm::uvec3> pattern = pattern_triangles(L);
      for (std::uint64_t p = 0; p < count; ++p) {
        for (const glm::uvec3& tri : pattern) {
          const unsigned char corners = 3;
          const std::uint32_t indices[3] = {base + tri[0], base + tri[1], base + tri[2]};
          append_raw(w.buffer, &corners, 1);
          append_raw(w.buffer, indices, sizeof indices);
        }
        base += static_cast<std::uint32_t>(pattern_vertex_count(L));
        if (w.buffer.size() > (1u << 20)) w.write_buffer();
      }
    }
    w.write_buffer();
  }
  w.out.commit();
  w.finished = true;
}

}  // namespace tessim
