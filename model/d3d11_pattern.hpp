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

struct FixedUV {
  Fixed16 u = 0;
  Fixed16 v = 0;
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
};

D3D11Factors d3d11_tri_factors(const std::array<float, 3>& outer, float inner, Partitioning partitioning);

// The same from factors already clamped, rounded and converted to 16.16 (outer_fixed,
// inner_fixed of d3d11_tri_factors(), which calls it): parity, single triangle, points per edge.
// This is the part a tessellation unit does with the factors it receives (docs/patterns.md §8);
// pow2 is passed as integer, its factors being powers of two already.
D3D11Factors d3d11_factors_from_fixed(const std::array<Fixed16, 3>& outer_fixed, Fixed16 inner_fixed,
                                      Partitioning partitioning);

// How one factor spreads its points along a unit edge (docs/patterns.md §2). Points are placed
// on each half of the edge from its end towards the middle and mirrored; a fractional factor
// blends the positions of floor(half) and ceil(half) segments per half, the extra point
// splitting one segment chosen so that splits appear in ruler-function order as the factor grows.
struct D3D11Edge {
  bool odd = false;
  Fixed16 half_fraction = 0;  // fractional part φ of the (parity-adjusted) half factor
  int half_points = 0;        // points on one half, the end included and the middle excluded
  int split_point = 0;        // the point that only exists on the ceil(half) subdivision
  Fixed16 inv_floor_segments = 0;  // R(n_floor) = round(2^16 / n_floor)
  Fixed16 inv_ceil_segments = 0;   // R(n_ceil)
  // The blend's two weights, R(n_floor)(1 - φ) and R(n_ceil) φ (each < 2^33): a point is
  // (i' floor_weight + i ceil_weight + 2^15) >> 16, two small multiplies per point.
  std::uint64_t floor_weight = 0;
  std::uint64_t ceil_weight = 0;
  int points = 0;  // on the whole edge, both ends included
};

D3D11Edge d3d11_edge(Fixed16 factor, bool odd);

// Position of point `index` (0 .. points - 1) along the edge, 16.16 in [0, 1].
Fixed16 d3d11_place(const D3D11Edge& edge, int index);

// Everything the point walk needs of a patch, computed once from its factors.
struct D3D11Setup {
  D3D11Factors factors;
  std::array<D3D11Edge, 3> outer{};
  D3D11Edge inner;
  int point_count = 0;  // points of the whole pattern
};

D3D11Setup d3d11_setup(const D3D11Factors& factors);

// The pattern's points one at a time, in the tessellator's order (outer ring from the corner
// v = 1, then the rings inwards, then the centre of an even pattern), with O(1) state: the
// walk a domain-point generator does in hardware. d3d11_tri_pattern() lists its points with it.
class D3D11PointWalker {
 public:
  D3D11PointWalker() = default;
  // Starts the walk of a patch (not culled).
  explicit D3D11PointWalker(const D3D11Setup& setup) { start(setup); }
  void start(const D3D11Setup& setup);

  FixedUV point(const D3D11Setup& setup) const;
  // The current point is the pattern's last.
  bool last() const { return last_; }
  int ring() const { return ring_; }   // 0: the outer ring; the centre is a ring of its own
  int edge() const { return edge_; }   // 0, 1, 2 (edges u = 0, v = 0, w = 0 of the ring); 3: the centre
  int index() const { return index_; } // in the pattern's point order
  // On to the next point (not after the last).
  void next(const D3D11Setup& setup);

 private:
  void enter_ring(const D3D11Setup& setup, int ring);

  int ring_ = 0, edge_ = 0, p_ = 0, index_ = 0;
  int ring_last_ = 0;        // ring r >= 1: its edges use inner points p = r .. ring_last_ - 1
  Fixed16 perp_ = 0;         // ring r >= 1: barycentric distance of its edges from the outer ones
  Fixed16 shift_ = 0;        // (perp + 1) / 2, subtracted from the inner edge's positions
  bool last_ = false;
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

// The pattern of a patch whose factors are set up already.
D3D11Pattern d3d11_pattern(const D3D11Setup& setup, Winding winding = Winding::ccw);

}  // namespace tessim
