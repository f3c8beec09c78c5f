// The PLY header and body walk behind check_ply (model/io/format.hpp), shared with the reader
// of the vertex properties Assimp drops (read_ply_tags: scalar tags, docs/stpn.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/vertex_tags.hpp"

namespace tessim::io {

struct PlyScalar {
  int size = 0;
  bool is_signed = false;
  bool is_integer = false;
};

// char, uchar, short, ..., float64: the scalar types of the PLY format.
std::optional<PlyScalar> ply_scalar(std::string_view name);

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
  // Index of the property called `name`, if the element has one.
  std::optional<std::size_t> find(std::string_view property) const;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  // offset of the first byte after end_header's line
  // Index of the element called `name`, if the header declares one.
  std::optional<std::size_t> find(std::string_view element) const;
};

// Parses the header; throws InputError naming the file, the header line and the reason.
PlyHeader read_ply_header(const std::string& file, const std::string& data);

// The values of some scalar properties of one element, row by row (one row per instance).
struct PlyColumns {
  std::size_t element = 0;              // index into PlyHeader::elements
  std::vector<std::size_t> properties;  // indices of scalar properties of that element
  std::vector<double> values;           // instances x properties.size(), filled by the walk
};

// Walks the body element by element: every instance must be present in full, every ASCII value
// a number, every binary list length non-negative (InputError naming the file, the element
// instance and the reason). With `columns`, collects their values as doubles (exactly, for
// every PLY type) and stops after their element.
void walk_ply_body(const std::string& file, const std::string& data, const PlyHeader& header,
                   PlyColumns* columns = nullptr);

// The scalar tags of a PLY file's vertices: properties dx dy dz (crease vector Δ), sigma, theta,
// beta of element 'vertex', each optional (a missing one is 0). Nothing when the file declares
// none of them. `positions` are x y z as Assimp imports them (rounded to float32), so that a
// vertex Assimp returns can be matched with the file's. Values are not checked here
// (check_tag_values in model/st_mesh.hpp); a tag declared as a list is an InputError.
struct PlyTags {
  std::vector<glm::vec3> positions;
  std::vector<VertexTags> tags;
};
std::optional<PlyTags> read_ply_tags(const std::string& file, const std::string& data);

// The property names of the tags, in the order read_ply_tags and write_ply use.
inline constexpr const char* kPlyTagProperties[] = {"dx", "dy", "dz", "sigma", "theta", "beta"};

}  // namespace tessim::io
