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
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/displace.hpp"
#include "model/d3d11_types.hpp"
#include "model/mesh.hpp"
#include "model/silhouette.hpp"

namespace tessim {

enum class PatternKind { Uniform, D3D11 };
enum class FactorSource { Fixed, Adaptive };
// The adaptive rules (docs/patterns.md, Factors of a mesh): the edge's projected length alone,
// that length scaled by the edge's silhouetteness α (model/silhouette.hpp), that with every edge
// of a patch the view contour can cross taken as fully silhouette (Contour), or enough segments to
// sample the displacement's shortest wavelength along the edge (Nyquist, no camera).
enum class AdaptiveRule { Screen, Silhouette, Contour, Nyquist };

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
  AdaptiveRule rule = AdaptiveRule::Screen;  // adaptive
  ScreenCamera camera;                // adaptive
  double pixels_per_segment = 16.0;   // adaptive, screen rule: target length of one edge segment on screen
  double outline_tolerance = 0.5;     // adaptive, silhouette rule: largest curve-to-segment distance, pixels
  // Adaptive: the Nyquist rule as well as the screen or silhouette rule (the larger factor per
  // edge); implied by rule == Nyquist.
  bool with_nyquist = false;
  double samples_per_wavelength = 4.0;  // the Nyquist rule's S
  // Silhouette blending of the control points (independent of the pattern). The silhouette rule
  // takes its α from it when it is on, else from the camera's eye with the default β.
  SilhouetteSettings silhouette;
  // The α of every edge for the mesh being tessellated, once bind_silhouette() has built it.
  std::shared_ptr<const MeshSilhouette> silhouette_field;
  // Procedural displacement of every evaluated point (independent of the pattern; float reference).
  DisplaceSettings displace;

  bool uses_silhouette() const {
    return silhouette.enabled || (kind == PatternKind::D3D11 && source == FactorSource::Adaptive &&
                                  by_outline());
  }
  // The silhouette and contour rules: factors from the outline tolerance and the edges' α.
  bool by_outline() const { return rule == AdaptiveRule::Silhouette || rule == AdaptiveRule::Contour; }

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

// Contour rule (docs/patterns.md §7): the silhouette rule, with α taken as 1 on every edge of a
// patch the view contour can cross (MeshSilhouette::contour_edge): such a patch and its
// neighbours across those edges get at least the silhouette rule's factors. The mark is one value
// per edge, so the factors stay crack-free.
// Silhouette rule (docs/patterns.md §7): as many segments as keep the blended edge curve within
// `outline_tolerance` pixels of its chords on screen. The curve's largest control-point offset
// from the flat edge across the view is α·deviation (MeshSilhouette::deviation); a cubic with
// end offsets at most h is within 2.25·h/F² of the chords of F equal segments, so
// F = 1.5·sqrt(α·deviation·p / tolerance), p the pixels per mesh unit at the edge's midpoint,
// clamped to 1..64. An edge seen face-on (α = 0, or its bulge along the view) or straight gets
// one segment. α and the deviation are one double per edge and the rest
// is symmetric in a and b, so the factor is crack-free like the screen rule's.
constexpr double kChordErrorFactor = 1.5;  // sqrt(2.25)
float silhouette_edge_factor(const ScreenCamera& camera, double outline_tolerance, double alpha, double deviation,
                             const glm::dvec3& a, const glm::dvec3& b);

// Nyquist rule (docs/patterns.md §9): enough segments that the displacement's shortest wavelength
// along the edge's chord a-b gets at least `samples_per_wavelength` (S) points. Sine: the phase
// f‖P‖ changes along the chord at the rate f·|d‖P‖/ds|, largest at an end (d‖P‖/ds is the cosine
// between P and the chord, monotonic along a line), so F = S·f·ℓ·max(|â·e|, |b̂·e|) / 2π, ℓ the
// chord's length, e its direction, â = a/‖a‖ (an end at the origin counts as 1). Noise: a
// wavelength of one lattice cell, 1/f, in every direction, so F = S·f·ℓ. Clamped to 1..64; the
// ends are taken in a fixed order, so both patches of an edge get the same factor bit for bit.
float nyquist_edge_factor(const DisplaceSettings& displace, double samples_per_wavelength, const glm::dvec3& a,
                          const glm::dvec3& b);
// The segments the Nyquist rule asks of the edge a-b before the clamp to 1..64 (0 without a
// displacement or for a zero-length edge).
double nyquist_segments(const DisplaceSettings& displace, double samples_per_wavelength, const glm::dvec3& a,
                        const glm::dvec3& b);

// The mesh's edges (each pair of welded positions once) whose Nyquist rule asks for more than
// the 64 segments a factor can give: their displacement still aliases. Zero edges unless `s`
// uses the Nyquist rule (nyquist, screen+nyquist, silhouette+nyquist).
struct NyquistShortfall {
  std::size_t edges = 0;      // edges clamped below their Nyquist segments
  double most_segments = 0.0;  // the largest segments asked of one edge
};
NyquistShortfall nyquist_shortfall(const TessSettings& s, const Mesh& mesh);

// Resolves the silhouette's eye (the camera's for --silhouette camera and for the silhouette rule
// without --silhouette) and builds the α of every edge of `mesh` into s.silhouette_field, unless
// it is there or neither the blend nor the rule is on. Throws InputError for bad silhouette
// settings.
void bind_silhouette(TessSettings& s, const Mesh& mesh);

// The factors of the mesh's triangle t. Adaptive: outer factor i from the edge where
// coordinate i is 0 (outer[0]: vertices 0 and 2, outer[1]: vertices 0 and 1, outer[2]: vertices
// 1 and 2), inner = the largest outer factor (the interior as fine as the finest edge). The
// silhouette rule needs bind_silhouette() first (std::logic_error otherwise).
PatchFactors patch_factors(const TessSettings& settings, const Mesh& mesh, std::size_t t);

// Throws InputError(source, element, reason) for settings out of range: L outside 1..64, a
// camera whose eye is its target, a field of view outside (0, 180), a viewport, pixels per
// segment or outline tolerance that is not positive, bad silhouette settings. Every fixed factor is valid: the tessellator clamps it, and one
// <= 0 or NaN culls the patch.
void validate(const TessSettings& settings, const std::string& source);

}  // namespace tessim
