// The Direct3D 11 fixed-function tessellation pattern of the triangle domain (docs/patterns.md):
// per-edge outer factors, one inner factor, four partitionings, concentric rings stitched to
// one another. Same points, same order, same triangles as the D3D11 tessellator; the uniform
// pattern of model/pattern.hpp is a different, simpler one.
//
// This is the float reference, written from the tessellator's definition: factors and positions
// are doubles, each of the definition's 16.16 roundings an explicit rounding to the 2^-16 grid,
// and the pattern is built as the definition builds it (ring edges as lists of points, then the
// rows of two neighbouring rings stitched). The unit's integer walk (sim/values/d3d11_walk.hpp) is
// an independent implementation of the same definition; the two share only the plain data of
// model/d3d11_types.hpp and are compared point for point and triangle for triangle
// (tests/sim/d3d11_walk_test.cpp).
#pragma once

#include <array>

#include "model/d3d11_types.hpp"

namespace tessim {

// The factor processing of docs/patterns.md §1: culling, clamping, rounding per partitioning,
// the 16.16 grid, parity, the single-triangle case and the points per edge.
D3D11Factors d3d11_tri_factors(const std::array<float, 3>& outer, float inner, Partitioning partitioning);

// Factors are floats because the tessellator receives floats: a double argument should be
// converted first (values too small for a float then cull the patch, as they would in D3D11).
D3D11Pattern d3d11_tri_pattern(const std::array<float, 3>& outer, float inner, Partitioning partitioning,
                               Winding winding = Winding::ccw);

}  // namespace tessim
