// Error bounds of the unit's fixed-point results against the float reference evaluated at the
// same (quantized) barycentric weights, derived from the number formats and the rounding points
// of sim/base/fixed.hpp and sim/values/cpg.cpp. The derivation is in docs/number-formats.md §Error
// analysis; the co-simulation checks every output vertex against these bounds.
#pragma once

#include "model/normal_mode.hpp"
#include "sim/base/fixed.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

struct ErrorBudget {
  double tangent_lsb = 0;       // per component, tangent control points
  double center_lsb = 0;        // per component, b111
  double position_lsb = 0;      // per component, output position (3 INT levels)
  double position_units = 0;    // Euclidean, in unit coordinates
};

ErrorBudget position_error_budget(const NumberFormat& fmt);

// Per-component bound (unit coordinates) of the unnormalized output normal of a patch, or a
// negative value when the patch's normal field is not bounded (a mid-edge normal of quadratic
// mode that normalizes a vector shorter than `min_norm`).
double normal_error_bound(const TriangleFx& tri, NormalMode mode, const NumberFormat& fmt);

// Bound on the angle between the output normal and the reference normal, given the
// per-component bound and the length of the output normal (unit coordinates). Negative when the
// direction is not determined (the normal is no longer than its error).
double normal_angle_bound(double component_bound, double output_length);

}  // namespace tessim::sim
