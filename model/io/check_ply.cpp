// PLY structure check: header, then every element instance present in full.
#include <algorithm>
#include <cstring>

#include "model/io/format.hpp"

namespace tessim::io {

namespace {

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

}  // namespace

void check_ply(const std::string& file, const std::string& data) {
  LineReader lines(data);
  auto header_error = [&](const std::string& reason) {
    return InputError(file, "PLY header line " + std::to_string(lines.line_number()), reason);
  };

  const auto magic = lines.next();
  if (!magic || *magic != "ply") throw InputError(file, "PLY header", "does not start with 'ply'");

  std::optional<PlyFormat> format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (const auto line = lines.next()) {
    Tokenizer tokens(*line);
    const auto keyword = tokens.next();
    if (!keyword) continue;
    if (*keyword == "end_header") {
      ended = true;
      break;
    }
    if (*keyword == "comment" || *keyword == "obj_info") continue;
    if (*keyword == "format") {
      // Assimp's reader corrupts its heap on some headers that declare things twice (found by
      // fuzz/fuzz_mesh): a second format line or element name is rejected here.
      if (format) throw header_error("a second format line");
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
      for (const PlyElement& e : elements)
        if (e.name == *name) throw header_error("element '" + e.name + "' declared twice");
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
  auto bad_property = [&](const PlyElement& e, std::uint64_t instance, const PlyProperty& p, const std::string& reason) {
    return InputError(file, "element '" + e.name + "' " + std::to_string(instance) + " property '" + p.name + "'", reason);
  };

  if (*format == PlyFormat::Ascii) {
    Tokenizer tokens(std::string_view(data).substr(lines.pos()));
    for (const PlyElement& e : elements) {
      if (e.properties.empty()) continue;
      for (std::uint64_t i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.properties) {
          std::uint64_t values = 1;
          if (p.is_list) {
            const auto count_token = tokens.next();
            if (!count_token) throw truncated(e, i);
            const auto count = parse_unsigned(*count_token);
            if (!count) throw bad_property(e, i, p, "'" + std::string(*count_token) + "' is not a list length");
            values = *count;
          }
          for (std::uint64_t v = 0; v < values; ++v) {
            const auto token = tokens.next();
            if (!token) throw truncated(e, i);
            if (!parses_as_number(*token)) throw bad_property(e, i, p, "'" + std::string(*token) + "' is not a number");
          }
        }
      }
    }
    return;
  }

  const bool big_endian = *format == PlyFormat::BinaryBig;
  std::size_t offset = lines.pos();
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
          if (n < 0) throw bad_property(e, i, p, "negative list length " + std::to_string(n));
          bytes *= static_cast<std::uint64_t>(n);
        }
        if (data.size() - offset < bytes) throw truncated(e, i);
        offset += static_cast<std::size_t>(bytes);
      }
    }
  }
}

}  // namespace tessim::io
