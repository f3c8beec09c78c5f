// Silhouette enhancement after Dyken & Reimers (docs/mathematics.md §11): every edge of the mesh
// gets a silhouetteness α in [0, 1] from the eye and its two faces, and each patch blends its six
// tangent points between the flat triangle's (α = 0) and the curved ones (α = 1). α depends on the
// edge alone (its end points, its two faces and the eye), so the two patches of an edge take the
// same α and the surface stays crack-free.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "model/mesh.hpp"
#include "model/normal_mode.hpp"
#include "model/pn.hpp"

namespace tessim {

constexpr double kDefaultSilhouetteBeta = 0.25;

// --silhouette eye=x,y,z[,beta=B][,blend=off] or --silhouette camera[,beta=B][,blend=off].
struct SilhouetteSettings {
  bool enabled = false;
  bool eye_from_camera = false;  // the eye of the adaptive camera (--silhouette camera)
  glm::dvec3 eye{0.0};
  double beta = kDefaultSilhouetteBeta;  // the width of the transition band in f; > 0
  bool blend = true;  // false: α only drives the silhouette rule's factors; the patches stay plain PN
  bool blends() const { return enabled && blend; }
};

// α of edge (a, b) whose two faces have unit geometric normals n_s and n_t, seen from `eye`:
// d = (m - eye) / |m - eye| with m = (a + b) / 2, f = (d·n_s)(d·n_t); α = 1 for f <= 0,
// 1 - f/β for 0 < f <= β, 0 beyond. An eye on the midpoint (d undefined) gives α = 1, and so
// does a zero face normal (a degenerate face): f = 0. Symmetric in a and b and in s and t.
double silhouetteness(const glm::dvec3& eye, double beta, const glm::dvec3& a, const glm::dvec3& b,
                      const glm::dvec3& n_s, const glm::dvec3& n_t);

// The unit geometric normal of triangle (p0, p1, p2) in its winding; zero for a degenerate one.
glm::dvec3 face_normal(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2);

// What one patch's control points need: per edge its α, the corner normals this face shades
// with, and per tangent point whether its end is a feature end and the crease direction m there.
// Edge e of a triangle runs from corner e to corner (e + 1) mod 3; tangent point (i -> j) is the
// one nearest corner i on the edge between corners i and j.
struct PatchSilhouette {
  std::array<double, 3> alpha{1.0, 1.0, 1.0};
  std::array<glm::dvec3, 3> normals{};
  // end[i][0]: corner i on the edge to corner (i + 1) mod 3; end[i][1]: on the edge to (i + 2) mod 3.
  struct End {
    bool feature = false;
    glm::dvec3 m{0.0};  // unit crease direction; zero: the two normals are parallel (straight end)
  };
  std::array<std::array<End, 2>, 3> end{};
};

struct SilhouetteCounts {
  std::uint64_t edges = 0;        // distinct edges (unordered vertex pairs)
  std::uint64_t flat = 0;         // α = 0
  std::uint64_t blended = 0;      // 0 < α < 1
  std::uint64_t curved = 0;       // α = 1
  std::uint64_t boundary = 0;     // one face (α = 1)
  std::uint64_t non_manifold = 0; // three or more faces (α = 1)
  std::uint64_t feature_ends = 0; // edge ends whose two faces shade with different normals
};

// The silhouetteness of every edge of a mesh for one eye, and the adjacency the feature ends
// need. Built once per mesh and eye (O(T log T)); patches then read it.
class MeshSilhouette {
 public:
  // Throws InputError(mesh.source, "--silhouette", reason) for a non-finite eye or β <= 0 / NaN.
  MeshSilhouette(const Mesh& mesh, const glm::dvec3& eye, double beta);

  // α of triangle t's edges 0, 1, 2.
  const std::array<double, 3>& alpha(std::size_t t) const { return alpha_[t]; }
  // How far the curved edge strays from the flat one on screen, at α = 1: the larger of c_ij − l_ij
  // and c_ji − l_ji over the edge's faces, each measured across the view direction d at the edge's
  // midpoint (the part along d only changes depth), in mesh units; the blended edge's is α times
  // it. An edge seen face-on has little, one on the outline all of it. One value per edge,
  // computed once, so both patches read the same double.
  const std::array<double, 3>& deviation(std::size_t t) const { return deviation_[t]; }
  // Everything patch t needs (the mesh must be the one it was built from).
  PatchSilhouette patch(const Mesh& mesh, std::size_t t) const;
  const SilhouetteCounts& counts() const { return counts_; }
  // The contour rule's per-patch test (contour_can_cross) on every patch of the mesh, on the
  // patches as they are tessellated (blended with this α when `blended`); before it, no patch is
  // marked. Edge e of triangle t is a contour edge when either of its faces is marked: one value
  // per edge, so the factors it raises stay crack-free.
  void mark_contour_patches(const Mesh& mesh, bool blended);
  bool contour_patch(std::size_t t) const { return !contour_.empty() && contour_[t] != 0; }
  bool contour_edge(std::size_t t, int e) const {
    if (contour_patch(t)) return true;
    const std::uint32_t other = across_[t][static_cast<std::size_t>(e)];
    return other != kNoFace && contour_patch(other);
  }
  std::size_t contour_patches() const { return contour_count_; }
  const glm::dvec3& eye() const { return eye_; }
  double beta() const { return beta_; }

  static constexpr std::uint32_t kNoFace = 0xFFFFFFFFu;

 private:
  glm::dvec3 eye_;
  double beta_;
  std::vector<std::array<double, 3>> alpha_;
  std::vector<std::array<double, 3>> deviation_;
  // The other face of each edge when the edge has exactly two faces, else kNoFace.
  std::vector<std::array<std::uint32_t, 3>> across_;
  SilhouetteCounts counts_;
  std::vector<std::uint8_t> contour_;  // per triangle: the contour can cross its patch
  std::size_t contour_count_ = 0;
};

// The normal triangle t shades corner c with: the vertex normal, or for a tagged vertex its
// sharp normal on the triangle's side of the crease (docs/stpn.md), as make_stpn_patch uses it.
glm::dvec3 corner_shading_normal(const Mesh& mesh, std::size_t t, int c);

// The control points of one patch with silhouette blending: each tangent point is
// α·c + (1 − α)·l of its edge's α, with c the curved point (the PN tangent point of the face's
// shading normal at a smooth end, p_i + ((p_j − p_i)·m)/3·m at a feature end) and l = (2p_i + p_j)/3;
// b111 and the normal field as in plain PN, with the face's shading normals. All α = 1 on an
// untagged mesh gives make_patch()'s patch bit for bit; all α = 0 the flat triangle.
PnPatch make_silhouette_patch(const PnInput& in, const PatchSilhouette& silhouette, NormalMode mode);

// The float control points of the mesh's triangle t as the reference evaluates them: blended by
// `silhouette` when given, scalar-tagged where the mesh has tags, else plain PN.
PnPatch mesh_patch(const Mesh& mesh, std::size_t t, NormalMode mode, const MeshSilhouette* silhouette = nullptr);

// Whether the view contour of a patch's surface can cross it: where the surface turns from facing
// `eye` to facing away, g = (P - eye) . (P_u x P_v) changes sign. g is a polynomial of degree 7 on
// the domain (cubic P, quartic P_u x P_v); its 36 Bernstein coefficients bound it, so a patch whose
// coefficients all share one strict sign has no contour point. Conservative: true may also mean
// a patch the contour only passes near; a degenerate patch (g = 0) counts as crossed.
bool contour_can_cross(const PnPatch& patch, const glm::dvec3& eye);

// Checks settings before any mesh is read: InputError(source, "--silhouette", reason).
void validate(const SilhouetteSettings& settings, const std::string& source);

}  // namespace tessim
