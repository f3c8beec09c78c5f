// Float64 reference of PN triangles (docs/mathematics.md): control points, the four normal fields,
// evaluation by Bernstein sums and by de Casteljau (counting INT operations).
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "model/normal_mode.hpp"
#include "model/vertex_tags.hpp"

namespace tessim {

// Control-net layout used by every form of the unit: a degree-d net is stored row by row,
// rows of increasing k (power of v), within a row increasing j (power of u); i = d - j - k.
//   cubic (10):    b300 b210 b120 b030 | b201 b111 b021 | b102 b012 | b003
//   quadratic (6): n200 n110 n020 | n101 n011 | n002
constexpr int net_index(int j, int k, int degree) { return k * (degree + 1) - k * (k - 1) / 2 + j; }

struct PnInput {
  std::array<glm::dvec3, 3> p;  // P1, P2, P3
  std::array<glm::dvec3, 3> n;  // N1, N2, N3 (unit)
};

struct PnPatch {
  std::array<glm::dvec3, 10> b;        // geometry, Bernstein form
  std::array<glm::dvec3, 6> n_bern;    // quadratic normal net in Bernstein form (mid-edges = n_ij/2)
  std::array<glm::dvec3, 3> n_corner;  // N1, N2, N3 (linear mode)
  NormalMode mode = NormalMode::Quadratic;
  int degenerate_edges = 0;            // zero-length edges that took the (Ni+Nj) fallback
};

struct PnVertex {
  glm::dvec3 position;
  glm::dvec3 normal;  // unit length (normalized field value)
};

// Builds the control nets of docs/mathematics.md §2-§4 for the chosen normal mode.
PnPatch make_patch(const PnInput& in, NormalMode mode);

// The PN tangent point nearest pi on the edge to pj: (2 pi + pj - ((pj - pi)·ni) ni) / 3.
glm::dvec3 pn_tangent_point(const glm::dvec3& pi, const glm::dvec3& pj, const glm::dvec3& ni);

// A tagged vertex's sharp normal N' = normalize(N + s σ Δ) on the side s of its crease that a
// face with (unnormalized) normal `face` lies on: s = +1 if face·Δ >= 0, else -1 (docs/stpn.md).
glm::dvec3 sharp_normal(const glm::dvec3& n, const VertexTags& tags, const glm::dvec3& face);

// The nets from given tangent points (tangent[i][j]: the one nearest corner i on the edge to
// corner j), b111 from them, and the normal field of the corner normals `field_normals`.
PnPatch make_patch_from_tangents(const std::array<glm::dvec3, 3>& p, const std::array<glm::dvec3, 3>& field_normals,
                                 const std::array<std::array<glm::dvec3, 3>, 3>& tangent, NormalMode mode);

// Scalar-tagged PN control points (docs/mathematics.md §9): each vertex's sharp normal on the
// triangle's side of its crease replaces its normal in the normal field, and each tangent
// coefficient follows the vertex's tags. A vertex whose tags are neutral takes exactly the
// plain PN formulas, so all-neutral tags give make_patch()'s patch bit for bit.
PnPatch make_stpn_patch(const PnInput& in, const std::array<VertexTags, 3>& tags, NormalMode mode);

// The Bernstein basis of degrees 3 and 2 at one domain point (w, u, v) = (1-u-v, u, v), in net
// order: what every patch evaluated at that point shares. Whole-mesh tessellation computes it
// once per point of a pattern and reuses it for every patch.
struct BasisAtPoint {
  double w = 1.0, u = 0.0, v = 0.0;
  std::array<double, 10> cubic{};     // B^3_{ijk}(w, u, v)
  std::array<double, 6> quadratic{};  // B^2_{ijk}(w, u, v)
};
BasisAtPoint basis_at(double u, double v);

// Direct evaluation by Bernstein sums at barycentric (w, u, v) = (1-u-v, u, v). The two forms
// give the same bits: the first is the second with basis_at(u, v).
PnVertex eval_bernstein(const PnPatch& patch, double u, double v);
PnVertex eval_bernstein(const PnPatch& patch, const BasisAtPoint& basis);

// The INT operations de Casteljau performs per vertex in a mode (what eval_de_casteljau adds).
int de_casteljau_ops(NormalMode mode);

// Evaluation by de Casteljau. Adds the number of INT operations (barycentric combinations of
// three points) it performs to *int_ops when given: 10 for the geometry, +4 quadratic/reflect,
// +1 linear, +0 derivative (which reuses geometry levels 1-2 and takes a cross product).
PnVertex eval_de_casteljau(const PnPatch& patch, double u, double v, std::uint64_t* int_ops = nullptr);

}  // namespace tessim
