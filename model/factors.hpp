// Which tessellation pattern each patch of a mesh gets (docs/patterns.md, Factors of a mesh):
//  - uniform: the unit's own pattern with one factor L for every patch (model/pattern.hpp);
//  - the Direct3D 11 pattern (model/d3d11_pattern.hpp) with a partitioning and factors that
//    are either the same for every patch (fixed: three outer factors and an inner one) or
//    derived per patch from a camera (adaptive).
// Adaptive edge factors depend only on the edge's two end points and the camera, computed so
// that the order of the two points cannot change the result: the two patches that share an
// edge get the same factor for it, bit for bit, and the D3D11 pattern places the same points on
// it (it mirrors each edge's points about the midpoint), so the surface stays crack-free.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/d3d11_types.hpp"
#include "model/mesh.hpp"

namespace tessim {

enum class PatternKind { Uniform, D3D11 };
enum class FactorSource { Fixed, Adaptive };

// A perspective camera for adaptive factors: eye, the point looked at, vertical field of view
// and the viewport in pixels.
struct ScreenCamera {
  glm::dvec3 eye{0.0, 0.0, 5.0};
  glm::dvec3 target{0.0};
  double fov_deg = 45.0;
  int width = 1280, height = 720;
};

struct TessSettings {
  PatternKind kind = PatternKind::Uniform;
  int L = 4;  // uniform
  Partitioning partitioning = Partitioning::integer;
  FactorSource source = FactorSource::Fixed;
  std::array<float, 3> outer{4.0f, 4.0f, 4.0f};  // fixed: outer[i] on the edge where coordinate i is 0
  float inner = 4.0f;
  ScreenCamera camera;                // adaptive
  double pixels_per_segment = 16.0;   // adaptive: target length of one edge segment on screen

  // One line for summaries: "L=4" (the uniform pattern), "integer outer 3,4,5 inner 4", "fractional_odd
  // adaptive (camera ...)".
  std::string describe() const;
};

struct PatchFactors {
  std::array<float, 3> outer{};
  float inner = 0.0f;
};

// Adaptive rule: the edge's length seen from the eye at the distance of its midpoint, in
// pixels of the viewport's height, divided by the pixels per segment, clamped to 1..64 (an edge
// never culls its patches). Symmetric in a and b: |a - b| and (a + b) / 2 do not depend on the
// order of the operands in IEEE arithmetic.
float adaptive_edge_factor(const ScreenCamera& camera, double pixels_per_segment, const glm::dvec3& a,
                           const glm::dvec3& b);

// The factors of the mesh's triangle t. Adaptive: outer factor i from the edge where
// coordinate i is 0 (outer[0]: vertices 0 and 2, outer[1]: vertices 0 and 1, outer[2]: vertices
// 1 and 2), inner = the largest outer factor (the interior as fine as the finest edge).
PatchFactors patch_factors(const TessSettings& settings, const Mesh& mesh, std::size_t t);

// Throws InputError(source, element, reason) for settings out of range: L outside 1..64, a
// camera whose eye is its target, a field of view outside (0, 180), a viewport or pixels per
// segment that is not positive. Every fixed factor is valid: the tessellator clamps it, and one
// <= 0 or NaN culls the patch.
void validate(const TessSettings& settings, const std::string& source);

}  // namespace tessim
