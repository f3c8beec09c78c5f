#include "model/silhouette.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/base/error.hpp"
#include "model/pn.hpp"

namespace tessim {

namespace {

// |a x b| <= kParallel |a| |b|: the crease direction of two shading normals is undefined.
constexpr double kParallel = 1e-12;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

int corner_of(const glm::uvec3& tri, std::uint32_t vertex) {
  for (int c = 0; c < 3; ++c)
    if (tri[c] == vertex) return c;
  return -1;
}

}  // namespace

double silhouetteness(const glm::dvec3& eye, double beta, const glm::dvec3& a, const glm::dvec3& b,
                      const glm::dvec3& n_s, const glm::dvec3& n_t) {
  const glm::dvec3 to_mid = 0.5 * (a + b) - eye;
  const double distance = glm::length(to_mid);
  if (!(distance > 0.0)) return 1.0;  // the eye on the midpoint: no direction of view
  const glm::dvec3 d = to_mid / distance;
  const double f = glm::dot(d, n_s) * glm::dot(d, n_t);
  if (!(f > 0.0)) return 1.0;  // faces on opposite sides of the view (or one degenerate)
  if (f <= beta) return 1.0 - f / beta;
  return 0.0;
}

glm::dvec3 face_normal(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2) {
  if (is_zero_area(p0, p1, p2)) return glm::dvec3(0.0);
  return glm::normalize(glm::cross(p1 - p0, p2 - p0));
}

glm::dvec3 corner_shading_normal(const Mesh& mesh, std::size_t t, int c) {
  const glm::uvec3& tri = mesh.triangles[t];
  const glm::dvec3& n = mesh.normals[tri[c]];
  if (!mesh.has_tags() || !mesh.tags[tri[c]].tagged()) return n;
  const glm::dvec3& p0 = mesh.positions[tri[0]];
  return sharp_normal(n, mesh.tags[tri[c]], glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0));
}

void validate(const SilhouetteSettings& s, const std::string& source) {
  if (!s.enabled) return;
  if (!s.eye_from_camera && !is_finite(s.eye))
    throw InputError(source, "--silhouette", "eye " + format_vec(s.eye) + " is not finite");
  // The silhouette test takes products of the eye's coordinates (their squares overflow a double
  // beyond about 1e154, and every edge then came out curved): farther than this is refused.
  constexpr double kMaxEyeCoordinate = 1e100;
  if (!s.eye_from_camera && (std::abs(s.eye.x) > kMaxEyeCoordinate || std::abs(s.eye.y) > kMaxEyeCoordinate ||
                             std::abs(s.eye.z) > kMaxEyeCoordinate))
    throw InputError(source, "--silhouette",
                     "eye " + format_vec(s.eye) + " is farther than 1e100 in a coordinate (the test would overflow)");
  if (!(s.beta > 0.0) || !std::isfinite(s.beta))
    throw InputError(source, "--silhouette", "beta " + number(s.beta) + " must be a positive finite number");
}

MeshSilhouette::MeshSilhouette(const Mesh& mesh, const glm::dvec3& eye, double beta) : eye_(eye), beta_(beta) {
  SilhouetteSettings s;
  s.enabled = true;
  s.eye = eye;
  s.beta = beta;
  validate(s, mesh.source.empty() ? std::string("mesh") : mesh.source);

  const std::size_t triangles = mesh.triangles.size();
  std::vector<glm::dvec3> normals(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    normals[t] = face_normal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
  }

  // Every edge of every triangle, keyed by its two vertices in increasing order (the mesh is
  // welded, so equal positions are equal indices); sorted, the faces of an edge are adjacent.
  struct EdgeUse {
    std::uint64_t key;
    std::uint32_t triangle;
    std::uint32_t edge;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    for (std::uint32_t e = 0; e < 3; ++e) {
      const std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
      const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      uses.push_back({key, static_cast<std::uint32_t>(t), e});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key != y.key ? x.key < y.key : x.triangle != y.triangle ? x.triangle < y.triangle : x.edge < y.edge;
  });

  // c - l at the end v of edge (v, w) shaded with normal n: -((w - v)·n)/3 n (smooth); at a feature
  // end, ((e·m) m - e)/3 with e = w - v. Its length across the view direction d (the part that
  // moves the curve on screen; an offset along d only changes depth).
  auto across_view = [](const glm::dvec3& offset, const glm::dvec3& d) {
    return glm::length(offset - glm::dot(offset, d) * d);
  };
  auto smooth_offset = [&](std::uint32_t v, std::uint32_t w, const glm::dvec3& n) {
    return -(glm::dot(mesh.positions[w] - mesh.positions[v], n) / 3.0) * n;
  };
  auto feature_offset = [&](std::uint32_t v, std::uint32_t w, const glm::dvec3& m) {
    const glm::dvec3 e = mesh.positions[w] - mesh.positions[v];
    return (glm::dot(e, m) * m - e) / 3.0;
  };

  alpha_.assign(triangles, {1.0, 1.0, 1.0});
  deviation_.assign(triangles, {0.0, 0.0, 0.0});
  across_.assign(triangles, {kNoFace, kNoFace, kNoFace});
  for (std::size_t first = 0; first < uses.size();) {
    std::size_t last = first + 1;
    while (last < uses.size() && uses[last].key == uses[first].key) ++last;
    ++counts_.edges;
    const std::size_t faces = last - first;
    double alpha = 1.0;
    if (faces == 1) {
      ++counts_.boundary;
    } else if (faces > 2) {
      ++counts_.non_manifold;
    } else {
      const EdgeUse& s = uses[first];
      const EdgeUse& t = uses[first + 1];
      const auto a = static_cast<std::uint32_t>(s.key >> 32), b = static_cast<std::uint32_t>(s.key & 0xFFFFFFFFu);
      alpha = silhouetteness(eye, beta, mesh.positions[a], mesh.positions[b], normals[s.triangle], normals[t.triangle]);
      across_[s.triangle][s.edge] = t.triangle;
      across_[t.triangle][t.edge] = s.triangle;
    }
    // The deviation over every face of the edge and both ends (a feature end's offset replaces
    // the faces' smooth ones there).
    double deviation = 0.0;
    {
      const auto a = static_cast<std::uint32_t>(uses[first].key >> 32);
      const auto b = static_cast<std::uint32_t>(uses[first].key & 0xFFFFFFFFu);
      // The view direction at the midpoint, as α takes it; the eye on the midpoint: none (zero).
      const glm::dvec3 to_mid = 0.5 * (mesh.positions[a] + mesh.positions[b]) - eye;
      const double distance = glm::length(to_mid);
      const glm::dvec3 d = distance > 0.0 ? to_mid / distance : glm::dvec3(0.0);
      for (const auto& [v, w] : {std::pair{a, b}, std::pair{b, a}}) {
        bool feature = false;
        if (faces == 2 && mesh.has_tags()) {
          const std::uint32_t s = uses[first].triangle, t = uses[first + 1].triangle;
          const glm::dvec3 ns = corner_shading_normal(mesh, s, corner_of(mesh.triangles[s], v));
          const glm::dvec3 nt = corner_shading_normal(mesh, t, corner_of(mesh.triangles[t], v));
          if (ns != nt) {
            feature = true;
            ++counts_.feature_ends;
            const glm::dvec3 cross = glm::cross(ns, nt);  // s < t: the lower face first, as patch() does
            const double length = glm::length(cross);
            if (length > kParallel * glm::length(ns) * glm::length(nt))
              deviation = std::max(deviation, across_view(feature_offset(v, w, cross / length), d));
            // Parallel normals: a straight end, offset 0.
          }
        }
        if (feature) continue;
        for (std::size_t u = first; u < last; ++u) {
          const std::uint32_t t = uses[u].triangle;
          const glm::dvec3 n = corner_shading_normal(mesh, t, corner_of(mesh.triangles[t], v));
          deviation = std::max(deviation, across_view(smooth_offset(v, w, n), d));
        }
      }
    }
    for (std::size_t u = first; u < last; ++u) deviation_[uses[u].triangle][uses[u].edge] = deviation;
    if (alpha == 0.0) ++counts_.flat;
    else if (alpha == 1.0) ++counts_.curved;
    else ++counts_.blended;
    for (std::size_t u = first; u < last; ++u) alpha_[uses[u].triangle][uses[u].edge] = alpha;
    first = last;
  }
}

PatchSilhouette MeshSilhouette::patch(const Mesh& mesh, std::size_t t) const {
  PatchSilhouette out;
  out.alpha = alpha_[t];
  for (int c = 0; c < 3; ++c) out.normals[c] = corner_shading_normal(mesh, t, c);
  if (!mesh.has_tags()) return out;  // one normal per vertex: every end is smooth
  const glm::uvec3& tri = mesh.triangles[t];
  for (int e = 0; e < 3; ++e) {
    const std::uint32_t other = across_[t][e];
    if (other == kNoFace) continue;
    // The ends of edge e: corner e (toward e + 1: slot 0) and corner e + 1 (toward e: slot 1).
    for (const auto& [corner, slot] : {std::pair{e, 0}, std::pair{(e + 1) % 3, 1}}) {
      const glm::dvec3 own = out.normals[corner];
      const glm::dvec3 theirs = corner_shading_normal(mesh, other, corner_of(mesh.triangles[other], tri[corner]));
      if (own == theirs) continue;
      PatchSilhouette::End& end = out.end[corner][slot];
      end.feature = true;
      // The lower face's normal first, so that both patches compute the same bits.
      const glm::dvec3 cross = t < other ? glm::cross(own, theirs) : glm::cross(theirs, own);
      const double length = glm::length(cross);
      end.m = length > kParallel * glm::length(own) * glm::length(theirs) ? cross / length : glm::dvec3(0.0);
    }
  }
  return out;
}

PnPatch make_silhouette_patch(const PnInput& in, const PatchSilhouette& s, NormalMode mode) {
  std::array<std::array<glm::dvec3, 3>, 3> tangent{};
  for (int i = 0; i < 3; ++i) {
    for (const int slot : {0, 1}) {
      const int j = (i + 1 + slot) % 3;
      const int edge = slot == 0 ? i : j;  // edge e joins corners e and e + 1
      const double alpha = s.alpha[edge];
      const glm::dvec3& pi = in.p[i];
      const glm::dvec3& pj = in.p[j];
      const glm::dvec3 flat = (2.0 * pi + pj) / 3.0;  // l_ij: the tangent point of the flat triangle
      const PatchSilhouette::End& end = s.end[i][slot];
      glm::dvec3 curved;
      if (!end.feature) curved = pn_tangent_point(pi, pj, s.normals[i]);
      else if (end.m == glm::dvec3(0.0)) curved = flat;
      else curved = pi + (glm::dot(pj - pi, end.m) / 3.0) * end.m;
      // α = 1 and α = 0 are the curved and the flat point bit for bit (a blend could turn a -0 into +0).
      tangent[i][j] = alpha == 1.0 ? curved : alpha == 0.0 ? flat : alpha * curved + (1.0 - alpha) * flat;
    }
  }
  return make_patch_from_tangents(in.p, s.normals, tangent, mode);
}

PnPatch mesh_patch(const Mesh& mesh, std::size_t t, NormalMode mode, const MeshSilhouette* silhouette) {
  const glm::uvec3& tri = mesh.triangles[t];
  PnInput input;
  std::array<VertexTags, 3> tags{};
  for (int c = 0; c < 3; ++c) {
    input.p[c] = mesh.positions[tri[c]];
    input.n[c] = mesh.normals[tri[c]];
    if (mesh.has_tags()) tags[c] = mesh.tags[tri[c]];
  }
  // A tagged mesh takes the scalar-tagged control points (plain PN where tags are neutral).
  return silhouette       ? make_silhouette_patch(input, silhouette->patch(mesh, t), mode)
         : mesh.has_tags() ? make_stpn_patch(input, tags, mode)
                           : make_patch(input, mode);
}

namespace {

// Multinomial d! / (i! j! k!) of a triangular Bernstein index, d <= 7.
double multinomial(int i, int j, int k) {
  static constexpr double kFactorial[8] = {1, 1, 2, 6, 24, 120, 720, 5040};
  return kFactorial[i + j + k] / (kFactorial[i] * kFactorial[j] * kFactorial[k]);
}

// The product of two polynomials in triangular Bernstein form of degrees m and n (nets in
// net_index order), coefficient by coefficient through `op` (a bilinear product of the
// coefficients): c_g = sum over a + b = g of C(m; a) C(n; b) / C(m + n; g) op(x_a, y_b).
template <typename X, typename Y, typename Op>
auto bernstein_product(const std::vector<X>& x, int m, const std::vector<Y>& y, int n, Op op) {
  using Z = decltype(op(x[0], y[0]));
  const int d = m + n;
  std::vector<Z> z(static_cast<std::size_t>((d + 1) * (d + 2) / 2), Z{});
  for (int ka = 0; ka <= m; ++ka)
    for (int ja = 0; ja + ka <= m; ++ja)
      for (int kb = 0; kb <= n; ++kb)
        for (int jb = 0; jb + kb <= n; ++jb) {
          const int j = ja + jb, k = ka + kb;
          const double weight = multinomial(m - ja - ka, ja, ka) * multinomial(n - jb - kb, jb, kb) /
                                multinomial(d - j - k, j, k);
          z[static_cast<std::size_t>(net_index(j, k, d))] +=
              weight * op(x[static_cast<std::size_t>(net_index(ja, ka, m))], y[static_cast<std::size_t>(net_index(jb, kb, n))]);
        }
  return z;
}

}  // namespace

bool contour_can_cross(const PnPatch& patch, const glm::dvec3& eye) {
  // The partial derivatives along u and v (w = 1 - u - v falls): quadratic nets 3 (b_{+u} - b) and
  // 3 (b_{+v} - b).
  std::vector<glm::dvec3> du(6), dv(6), rel(10);
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j + k <= 2; ++j) {
      const glm::dvec3& b = patch.b[static_cast<std::size_t>(net_index(j, k, 3))];
      du[static_cast<std::size_t>(net_index(j, k, 2))] = 3.0 * (patch.b[static_cast<std::size_t>(net_index(j + 1, k, 3))] - b);
      dv[static_cast<std::size_t>(net_index(j, k, 2))] = 3.0 * (patch.b[static_cast<std::size_t>(net_index(j, k + 1, 3))] - b);
    }
  for (std::size_t i = 0; i < 10; ++i) rel[i] = patch.b[i] - eye;  // the Bernstein basis sums to 1
  const std::vector<glm::dvec3> normal =
      bernstein_product(du, 2, dv, 2, [](const glm::dvec3& a, const glm::dvec3& b) { return glm::cross(a, b); });
  const std::vector<double> g =
      bernstein_product(rel, 3, normal, 4, [](const glm::dvec3& a, const glm::dvec3& b) { return glm::dot(a, b); });
  const bool all_positive = std::all_of(g.begin(), g.end(), [](double c) { return c > 0.0; });
  const bool all_negative = std::all_of(g.begin(), g.end(), [](double c) { return c < 0.0; });
  return !(all_positive || all_negative);
}

void MeshSilhouette::mark_contour_patches(const Mesh& mesh, bool blended) {
  contour_.assign(mesh.triangles.size(), 0);
  contour_count_ = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    // The geometry is the same in every normal mode.
    const PnPatch patch = mesh_patch(mesh, t, NormalMode::Quadratic, blended ? this : nullptr);
    contour_[t] = contour_can_cross(patch, eye_) ? 1 : 0;
    contour_count_ += contour_[t];
  }
}

}  // namespace tessim
