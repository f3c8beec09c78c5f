// PLY structure check: header, then every element instance present in full. The same walk
// collects the values of chosen properties (model/io/ply.hpp), which read_ply_tags uses.
#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

#include "model/io/format.hpp"
#include "model/io/ply.hpp"

namespace tessim::io {

namespace {

// The `size` bytes at `p` in the file's byte order, as the native-order bytes of a value.
void native_bytes(const char* p, int size, bool big_endian, unsigned char* out) {
  std::memcpy(out, p, static_cast<std::size_t>(size));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(out, out + size);
}

std::int64_t read_ply_integer(const char* p, const PlyScalar& type, bool big_endian) {
  unsigned char bytes[8] = {};
  std::memcpy(bytes, p, static_cast<std::size_t>(type.size));
  if (big_endian) std::reverse(bytes, bytes + type.size);
  std::uint64_t u = 0;
  for (int i = type.size - 1; i >= 0; --i) u = (u << 8) | bytes[i];
  if (type.is_signed && (bytes[type.size - 1] & 0x80u)) return static_cast<std::int64_t>(u) - (std::int64_t{1} << (8 * type.size));
  return static_cast<std::int64_t>(u);
}

// One binary scalar as a double: exact for every PLY type (integers have at most 32 bits).
double read_ply_value(const char* p, const PlyScalar& type, bool big_endian) {
  if (type.is_integer) return static_cast<double>(read_ply_integer(p, type, big_endian));
  unsigned char bytes[8] = {};
  native_bytes(p, type.size, big_endian, bytes);
  if (type.size == 4) {
    float f = 0.0f;
    std::memcpy(&f, bytes, sizeof f);
    return static_cast<double>(f);
  }
  double d = 0.0;
  std::memcpy(&d, bytes, sizeof d);
  return d;
}

}  // namespace

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

std::optional<std::size_t> PlyElement::find(std::string_view property) const {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == property) return i;
  return std::nullopt;
}

std::optional<std::size_t> PlyHeader::find(std::string_view element) const {
  for (std::size_t i = 0; i < elements.size(); ++i)
    if (elements[i].name == element) return i;
  return std::nullopt;
}

PlyHeader read_ply_header(const std::string& file, const std::string& data) {
  LineReader lines(data);
  auto header_error = [&](const std::string& reason) {
    return InputError(file, "PLY header line " + std::to_string(lines.line_number()), reason);
  };

  const auto magic = lines.next();
  if (!magic || *magic != "ply") throw InputError(file, "PLY header", "does not start with 'ply'");

  std::optional<PlyFormat> format;
  PlyHeader header;
  std::vector<PlyElement>& elements = header.elements;
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
      // PLY has one version; a file claiming another may mean anything by its body.
      const auto version = tokens.next();
      if (version != "1.0")
        throw header_error("format version '" + std::string(version.value_or("")) + "' (only 1.0 exists)");
      if (tokens.next()) throw header_error("unexpected text after the format version");
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
      // Readers disagree on which copy of a repeated property counts (Assimp takes the last
      // x, the tag reader the first): the file means nothing definite.
      if (elements.back().find(property.name))
        throw header_error("property '" + property.name + "' declared twice in element '" + elements.back().name + "'");
      elements.back().properties.push_back(property);
    }
    // Other lines are skipped, as Assimp does (Blender wrote "Created by ..." without "comment").
  }
  if (!ended) throw InputError(file, "PLY header", "no end_header line (file truncated or not PLY)");
  if (!format) throw InputError(file, "PLY header", "no format line");
  header.format = *format;
  header.body = lines.pos();
  return header;
}

void walk_ply_body(const std::string& file, const std::string& data, const PlyHeader& header, PlyColumns* columns) {
  const std::vector<PlyElement>& elements = header.elements;
  auto truncated = [&](const PlyElement& e, std::uint64_t instance) {
    return InputError(file, "element '" + e.name + "' " + std::to_string(instance) + " of " + std::to_string(e.count),
                      "file ends early (truncated)");
  };
  auto bad_property = [&](const PlyElement& e, std::uint64_t instance, const PlyProperty& p, const std::string& reason) {
    return InputError(file, "element '" + e.name + "' " + std::to_string(instance) + " property '" + p.name + "'", reason);
  };
  // For the element of `columns`: the column of each of its properties (-1: not collected).
  std::vector<int> column_of;
  if (columns) {
    const PlyElement& e = elements.at(columns->element);
    column_of.assign(e.properties.size(), -1);
    for (std::size_t c = 0; c < columns->properties.size(); ++c) {
      if (e.properties.at(columns->properties[c]).is_list) throw std::logic_error("walk_ply_body: a list column");
      column_of[columns->properties[c]] = static_cast<int>(c);
    }
    columns->values.clear();  // grown row by row as instances are read (the count is the file's claim)
  }
  const std::size_t width = columns ? columns->properties.size() : 0;
  auto collecting = [&](std::size_t element) { return columns && columns->element == element; };

  if (header.format == PlyFormat::Ascii) {
    Tokenizer tokens(std::string_view(data).substr(header.body));
    for (std::size_t ei = 0; ei < elements.size(); ++ei) {
      const PlyElement& e = elements[ei];
      if (e.properties.empty()) continue;
      const bool collect = collecting(ei);
      for (std::uint64_t i = 0; i < e.count; ++i) {
        if (collect) columns->values.resize(columns->values.size() + width);
        for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
          const PlyProperty& p = e.properties[pi];
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
            const auto number = parse_number(*token);
            if (!number) throw bad_property(e, i, p, "'" + std::string(*token) + "' is not a number");
            if (collect && column_of[pi] >= 0) columns->values[columns->values.size() - width + static_cast<std::size_t>(column_of[pi])] = *number;
          }
        }
      }
      if (collect) return;
    }
    return;
  }

  const bool big_endian = header.format == PlyFormat::BinaryBig;
  std::size_t offset = header.body;
  for (std::size_t ei = 0; ei < elements.size(); ++ei) {
    const PlyElement& e = elements[ei];
    const bool collect = collecting(ei);
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.is_list; });
    if (fixed) {
      std::uint64_t row = 0;
      for (const PlyProperty& p : e.properties) row += static_cast<std::uint64_t>(p.item.size);
      if (row == 0) continue;
      const std::uint64_t available = (data.size() - offset) / row;
      if (available < e.count) throw truncated(e, available);
      if (collect) {
        // Byte offset of each collected property within a row.
        std::vector<std::size_t> at(width);
        std::size_t position = 0;
        for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
          if (column_of[pi] >= 0) at[static_cast<std::size_t>(column_of[pi])] = position;
          position += static_cast<std::size_t>(e.properties[pi].item.size);
        }
        columns->values.resize(static_cast<std::size_t>(e.count) * width);
        for (std::uint64_t i = 0; i < e.count; ++i) {
          const char* record = data.data() + offset + static_cast<std::size_t>(i * row);
          for (std::size_t c = 0; c < width; ++c)
            columns->values[static_cast<std::size_t>(i) * width + c] =
                read_ply_value(record + at[c], e.properties[columns->properties[c]].item, big_endian);
        }
        return;
      }
      offset += static_cast<std::size_t>(e.count * row);
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      if (collect) columns->values.resize(columns->values.size() + width);
      for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
        const PlyProperty& p = e.properties[pi];
        std::uint64_t bytes = static_cast<std::uint64_t>(p.item.size);
        if (p.is_list) {
          if (data.size() - offset < static_cast<std::size_t>(p.count.size)) throw truncated(e, i);
          const std::int64_t n = read_ply_integer(data.data() + offset, p.count, big_endian);
          offset += static_cast<std::size_t>(p.count.size);
          if (n < 0) throw bad_property(e, i, p, "negative list length " + std::to_string(n));
          bytes *= static_cast<std::uint64_t>(n);
        }
        if (data.size() - offset < bytes) throw truncated(e, i);
        if (collect && column_of[pi] >= 0)
          columns->values[columns->values.size() - width + static_cast<std::size_t>(column_of[pi])] =
              read_ply_value(data.data() + offset, p.item, big_endian);
        offset += static_cast<std::size_t>(bytes);
      }
    }
    if (collect) return;
  }
}

void check_ply(const std::string& file, const std::string& data) { walk_ply_body(file, data, read_ply_header(file, data)); }

std::optional<PlyTags> read_ply_tags(const std::string& file, const std::string& data) {
  const PlyHeader header = read_ply_header(file, data);
  const auto vertex = header.find("vertex");
  if (!vertex) return std::nullopt;
  const PlyElement& element = header.elements[*vertex];
  PlyColumns columns;
  columns.element = *vertex;
  // Columns 0-2: x y z; then the tags the file declares, `tag_column[t]` (-1: absent).
  for (const char* axis : {"x", "y", "z"}) {
    const auto p = element.find(axis);
    if (!p || element.properties[*p].is_list) return std::nullopt;  // Assimp refuses the file
    columns.properties.push_back(*p);
  }
  int tag_column[6];
  bool any = false;
  for (int t = 0; t < 6; ++t) {
    tag_column[t] = -1;
    const auto p = element.find(kPlyTagProperties[t]);
    if (!p) continue;
    if (element.properties[*p].is_list)
      throw InputError(file, "element 'vertex' property '" + element.properties[*p].name + "'",
                       "is a list; scalar tags are single numbers (docs/stpn.md)");
    tag_column[t] = static_cast<int>(columns.properties.size());
    columns.properties.push_back(*p);
    any = true;
  }
  if (!any) return std::nullopt;

  walk_ply_body(file, data, header, &columns);
  const std::size_t width = columns.properties.size();
  const std::size_t count = columns.values.size() / width;
  PlyTags out;
  out.positions.reserve(count);
  out.tags.reserve(count);
  for (std::size_t v = 0; v < count; ++v) {
    const double* row = columns.values.data() + v * width;
    out.positions.emplace_back(static_cast<float>(row[0]), static_cast<float>(row[1]), static_cast<float>(row[2]));
    auto value = [&](int t) { return tag_column[t] >= 0 ? row[tag_column[t]] : 0.0; };
    VertexTags tags;
    tags.delta = glm::dvec3(value(0), value(1), value(2));
    tags.sigma = value(3);
    tags.theta = value(4);
    tags.beta = value(5);
    out.tags.push_back(tags);
  }
  return out;
}

}  // namespace tessim::io
