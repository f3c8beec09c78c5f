// The unit's Direct3D 11 triangle-domain pattern (docs/patterns.md): the integer walk the
// hardware does, as the cycle model's FSU and DPG (sim/blocks/dpg.hpp) and the RTL (tess_fsu.sv,
// tess_dpg.sv) do it. Every step is integer arithmetic on 16.16 values, in the order of the D3D11
// tessellator: the host's part of the factor processing (culling, clamping, rounding, 16.16), the
// unit's (parity, edge subdivisions), a point walk with O(1) state, and the triangles the host
// rebuilds from the factors. model/d3d11_pattern.hpp is the float reference written
// independently from the same definition; the two share the plain data types of
// model/d3d11_types.hpp only, so that each checks the other (tests/sim/d3d11_walk_test.cpp).
#pragma once

#include <array>
#include <cstdint>

#include "model/d3d11_types.hpp"

namespace tessim::sim {

// Round-to-nearest-even conversion of a float in [0, 32768), as the tessellator converts its
// clamped factors (exact for every float with at most 16 fractional bits).
Fixed16 float_to_fixed16(float x);

// 1/n in 16.16, rounded to nearest (n = 3 gives 0x5555), for 1 <= n <= 64.
Fixed16 fixed16_reciprocal(int n);

// The host's factor processing (docs/patterns.md §1): culling, clamping, rounding, 16.16, and
// what the unit derives from the result (d3d11_factors_from_fixed).
D3D11Factors d3d11_host_factors(const std::array<float, 3>& outer, float inner, Partitioning partitioning);

// The same from factors already clamped, rounded and converted to 16.16 (outer_fixed,
// inner_fixed of d3d11_host_factors(), which calls it): parity, single triangle, points per edge.
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
// walk a domain-point generator does in hardware. d3d11_pattern() lists its points with it.
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

// The whole pattern from the factors as the tessellator receives them (floats: a double argument
// should be converted first; values too small for a float then cull the patch, as in D3D11).
D3D11Pattern d3d11_walk_pattern(const std::array<float, 3>& outer, float inner, Partitioning partitioning,
                                Winding winding = Winding::ccw);

// The pattern of a patch whose factors are set up already.
D3D11Pattern d3d11_pattern(const D3D11Setup& setup, Winding winding = Winding::ccw);

}  // namespace tessim::sim
