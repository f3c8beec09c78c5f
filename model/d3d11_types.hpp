// Plain data of the Direct3D 11 triangle-domain pattern (docs/patterns.md), shared by its two
// implementations: the float reference (model/d3d11_pattern.hpp) and the unit's integer walk
// (sim/values/d3d11_walk.hpp). Nothing here computes a pattern.
//
// Conventions: outer[i] subdivides the edge where barycentric coordinate i is 0 (outer[0]:
// u = 0, outer[1]: v = 0, outer[2]: w = 0), as GL's gl_TessLevelOuter; points are (u, v) with
// w = 1 - u - v.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace tessim {

enum class Partitioning { integer, pow2, fractional_odd, fractional_even };

// ccw: every non-degenerate triangle has positive signed area in the plane x = u, y = v;
// cw: negative. (D3D11 names the same two orders the other way round, as its domain is drawn
// with the opposite handedness: its "triangle_cw" output is tessim's ccw.)
enum class Winding { ccw, cw };

const char* partitioning_name(Partitioning p);
std::optional<Partitioning> parse_partitioning(std::string_view name);
const char* winding_name(Winding w);
std::optional<Winding> parse_winding(std::string_view name);

// Unsigned 16.16 fixed point: 0x10000 is 1.0. The pattern's points are 16.16 values.
using Fixed16 = std::int32_t;
constexpr Fixed16 kFixed16One = 1 << 16;
constexpr double fixed16_to_double(Fixed16 x) { return x / 65536.0; }

struct FixedUV {
  Fixed16 u = 0;
  Fixed16 v = 0;
  bool operator==(const FixedUV&) const = default;
};

// The factors as the tessellator uses them, after clamping and rounding.
struct D3D11Factors {
  bool culled = false;           // an outer factor <= 0 or NaN: no points, no triangles
  bool single_triangle = false;  // all factors 1 (integer, pow2, fractional_odd): the domain itself
  std::array<float, 3> outer{};  // clamped (and for integer/pow2 rounded up) outer factors
  float inner = 0.0f;
  std::array<Fixed16, 3> outer_fixed{};
  Fixed16 inner_fixed = 0;
  std::array<bool, 3> outer_odd{};  // parity: how the edge's points are spread about its midpoint
  bool inner_odd = false;
  std::array<int, 3> outer_points{};  // points on each outer edge, both corners included
  int inner_points = 0;               // points on an edge of the inner factor (rings are cut from it)
  bool operator==(const D3D11Factors&) const = default;
};

struct D3D11Pattern {
  D3D11Factors factors;
  std::vector<FixedUV> points;         // in the tessellator's order: outer ring, then rings inwards
  std::vector<std::uint32_t> indices;  // triangle list, three per triangle
  std::size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace tessim
