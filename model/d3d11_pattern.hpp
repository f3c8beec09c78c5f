// The Direct3D 11 fixed-function tessellation pattern of the triangle domain (docs/patterns.md):
// per-edge outer factors, one inner factor, four partitionings, concentric rings stitched to
// one another, 16.16 fixed-point parameters. Same points, same order, same triangles as the
// D3D11 tessellator; the uniform pattern of model/pattern.hpp is a different, simpler one.
//
// Conventions: outer[i] subdivides the edge where barycentric coordinate i is 0 (outer[0]:
// u = 0, outer[1]: v = 0, outer[2]: w = 0), as GL's gl_TessLevelOuter; points are (u, v) with
// w = 1 - u - v.
#pragma once

#include <array>
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

// Unsigned 16.16 fixed point: 0x10000 is 1.0.
using Fixed16 = std::int32_t;
constexpr Fixed16 kFixed16One = 1 << 16;
constexpr double fixed16_to_double(Fixed16 x) { return x / 65536.0; }

// Round-to-nearest-even conversion of a float in [0, 32768), as the tessellator converts its
// clamped factors (exact for every float with at most 16 fractional bits).
Fixed16 float_to_fixed16(float x);

// 1/n in 16.16, rounded to nearest (n = 3 gives 0x5555), for 1 <= n <= 64.
Fixed16 fixed16_reciprocal(int n);

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
};

D3D11Factors d3d11_tri_factors(const std::array<float, 3>& outer, float inner, Partitioning partitioning);

struct FixedUV {
  Fixed16 u = 0;
  Fixed16 v = 0;
};

struct D3D11Pattern {
  D3D11Factors factors;
  std::vector<FixedUV> points;         // in the tessellator's order: outer ring, then rings inwards
  std::vector<std::uint32_t> indices;  // triangle list, three per triangle
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Factors are floats because the tessellator receives floats: a double argument should be
// converted first (values too small for a float then cull the patch, as they would in D3D11).
D3D11Pattern d3d11_tri_pattern(const std::array<float, 3>& outer, float inner, Partitioning partitioning,
                               Winding winding = Winding::ccw);

}  // namespace tessim
