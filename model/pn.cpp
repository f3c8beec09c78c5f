#include "model/pn.hpp"

#include <limits>

namespace tessim {

namespace {

// A normal-field value shorter than this is treated as vanished. Fields are barycentric
// blends of unit (or, for reflect, at most length-2) vectors, so their natural scale is 1.
constexpr double kVanishingField = 1e-10;
// A cross product a x b with |a x b| <= kParallel |a| |b| has no reliable direction.
constexpr double kParallel = 1e-12;

struct EdgeNormalResult {
  glm::dvec3 n;     // n_ij in monomial form (Bernstein mid-edge point is n / 2)
  bool degenerate;  // zero-length edge: took the (Ni + Nj) fallback
};

// Mid-edge normal of edge (Pi -> Pj), quadratic and reflect modes (docs/mathematics.md §4-§5).
// Both formulas reflect s = Ni + Nj across the plane orthogonal to the edge (quadratic with
// factor 2, reflect with factor 4, see docs/reference-model.md); the computation is symmetric
// in the two ends, so both patches of a shared edge get the same value.
EdgeNormalResult edge_normal(const glm::dvec3& pi, const glm::dvec3& pj, const glm::dvec3& ni,
                             const glm::dvec3& nj, NormalMode mode) {
  const glm::dvec3 edge = pj - pi;
  const glm::dvec3 sum = ni + nj;
  const double edge_len2 = glm::dot(edge, edge);
  // Below DBL_MIN the squared length is zero or has underflowed: the edge has no direction,
  // so there is nothing to reflect across and the mid-edge normal is along Ni + Nj. Quadratic
  // normalizes it as usual; reflect keeps its unnormalized convention (|n_ij| = |Ni + Nj| for
  // every edge), as the unit's control-point generation does (sim/values/cpg.cpp: m = s).
  if (!(edge_len2 >= std::numeric_limits<double>::min())) {
    if (mode == NormalMode::Reflect) return {sum, true};
    const double len = glm::length(sum);
    return {len > kVanishingField ? sum / len : glm::dvec3(0.0), true};
  }
  if (mode == NormalMode::Reflect) {
    const double t = 4.0 * glm::dot(edge, sum) / edge_len2;
    return {sum - t * edge, false};
  }
  const double v = 2.0 * glm::dot(edge, sum) / edge_len2;
  const glm::dvec3 reflected = sum - v * edge;
  const double len = glm::length(reflected);
  // |reflected| = |Ni + Nj|: it vanishes only for opposite normals. The zero vector is then
  // what the reflect formula gives as well; evaluation falls back if the field vanishes.
  return {len > kVanishingField ? reflected / len : glm::dvec3(0.0), false};
}

bool is_zero_length(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 e = b - a;
  return !(glm::dot(e, e) >= std::numeric_limits<double>::min());
}

// Unit vector along a x b; false when a and b are (numerically) parallel or zero.
bool unit_cross(const glm::dvec3& a, const glm::dvec3& b, glm::dvec3& out) {
  const glm::dvec3 c = glm::cross(a, b);
  const double len = glm::length(c);
  if (!(len > kParallel * glm::length(a) * glm::length(b))) return false;
  out = c / len;
  return true;
}

bool unit_field(const glm::dvec3& f, glm::dvec3& out) {
  const double len = glm::length(f);
  if (!(len > kVanishingField)) return false;
  out = f / len;
  return true;
}

// The end of every fallback chain: the corner normal of largest barycentric weight
// (first corner on ties). Input normals are unit, so this is always a valid normal.
glm::dvec3 nearest_corner_normal(const PnPatch& patch, double w, double u, double v) {
  if (w >= u && w >= v) return patch.n_corner[0];
  if (u >= v) return patch.n_corner[1];
  return patch.n_corner[2];
}

glm::dvec3 linear_field(const PnPatch& patch, double w, double u, double v) {
  return w * patch.n_corner[0] + u * patch.n_corner[1] + v * patch.n_corner[2];
}

// Fallback chain shared by both evaluators (docs/reference-model.md):
//   mode field -> surface normal -> linear field -> nearest corner normal.
// `field` is the mode's field value (ignored for derivative), `du`/`dv` span the tangent plane.
glm::dvec3 resolve_normal(const PnPatch& patch, const glm::dvec3& field, const glm::dvec3& du,
                          const glm::dvec3& dv, double w, double u, double v) {
  glm::dvec3 n;
  if (patch.mode != NormalMode::Derivative && unit_field(field, n)) return n;
  if (unit_cross(du, dv, n)) return n;
  if (patch.mode != NormalMode::Linear && unit_field(linear_field(patch, w, u, v), n)) return n;
  return nearest_corner_normal(patch, w, u, v);
}

// One INT operation of the unit: r = w A + u B + v C.
glm::dvec3 int_op(double w, double u, double v, const glm::dvec3& a, const glm::dvec3& b,
                  const glm::dvec3& c) {
  return w * a + u * b + v * c;
}

// One de Casteljau level: degree d -> d - 1. Returns the number of INT operations.
template <std::size_t In, std::size_t Out>
int casteljau_level(const std::array<glm::dvec3, In>& cur, int degree, double w, double u, double v,
                    std::array<glm::dvec3, Out>& next) {
  int ops = 0;
  for (int k = 0; k < degree; ++k) {
    for (int j = 0; j + k < degree; ++j) {
      next[net_index(j, k, degree - 1)] =
          int_op(w, u, v, cur[net_index(j, k, degree)], cur[net_index(j + 1, k, degree)],
                 cur[net_index(j, k + 1, degree)]);
      ++ops;
    }
  }
  return ops;
}

}  // namespace

namespace {

// Tangent coefficient nearest Pi on edge i -> j: plain PN (docs/mathematics.md §2).
glm::dvec3 pn_tangent(const PnInput& in, int i, int j) { return pn_tangent_point(in.p[i], in.p[j], in.n[i]); }

// The nets from the ten tangent coefficients' rule and the corner normals of the normal field.
template <class Tangent>
PnPatch build_patch(const std::array<glm::dvec3, 3>& P, const std::array<glm::dvec3, 3>& field_normals, NormalMode mode,
                    Tangent tangent) {
  PnPatch patch;
  patch.mode = mode;
  const auto& N = field_normals;

  auto& b = patch.b;
  b[net_index(0, 0, 3)] = P[0];           // b300
  b[net_index(3, 0, 3)] = P[1];           // b030
  b[net_index(0, 3, 3)] = P[2];           // b003
  b[net_index(1, 0, 3)] = tangent(0, 1);  // b210
  b[net_index(2, 0, 3)] = tangent(1, 0);  // b120
  b[net_index(2, 1, 3)] = tangent(1, 2);  // b021
  b[net_index(1, 2, 3)] = tangent(2, 1);  // b012
  b[net_index(0, 2, 3)] = tangent(2, 0);  // b102
  b[net_index(0, 1, 3)] = tangent(0, 2);  // b201
  const glm::dvec3 E = (b[net_index(1, 0, 3)] + b[net_index(2, 0, 3)] + b[net_index(2, 1, 3)] +
                        b[net_index(1, 2, 3)] + b[net_index(0, 2, 3)] + b[net_index(0, 1, 3)]) /
                       6.0;
  const glm::dvec3 V = (P[0] + P[1] + P[2]) / 3.0;
  b[net_index(1, 1, 3)] = E + (E - V) / 2.0;  // b111

  patch.n_corner = N;

  // Normal net in Bernstein form. Corners are Ni in every mode; mid-edges are n_ij / 2.
  auto& n = patch.n_bern;
  n[net_index(0, 0, 2)] = N[0];  // n200
  n[net_index(2, 0, 2)] = N[1];  // n020
  n[net_index(0, 2, 2)] = N[2];  // n002
  struct Edge {
    int i, j, index;
  };
  static constexpr Edge kEdges[] = {
      {0, 1, net_index(1, 0, 2)},  // n110
      {1, 2, net_index(1, 1, 2)},  // n011
      {2, 0, net_index(0, 1, 2)},  // n101
  };
  for (const Edge& e : kEdges) {
    if (mode == NormalMode::Quadratic || mode == NormalMode::Reflect) {
      const EdgeNormalResult r = edge_normal(P[e.i], P[e.j], N[e.i], N[e.j], mode);
      n[e.index] = r.n / 2.0;
      if (r.degenerate) ++patch.degenerate_edges;
    } else {
      // Linear and derivative modes do not use this net; it holds the linear field raised to
      // degree 2 (mid-edge (Ni + Nj) / 2), so evaluating it still gives a meaningful field.
      n[e.index] = (N[e.i] + N[e.j]) / 2.0;
      if (is_zero_length(P[e.i], P[e.j])) ++patch.degenerate_edges;
    }
  }
  return patch;
}

}  // namespace

glm::dvec3 pn_tangent_point(const glm::dvec3& pi, const glm::dvec3& pj, const glm::dvec3& ni) {
  const double wij = glm::dot(pj - pi, ni);
  return (2.0 * pi + pj - wij * ni) / 3.0;
}

glm::dvec3 sharp_normal(const glm::dvec3& n, const VertexTags& tags, const glm::dvec3& face) {
  const double side = glm::dot(face, tags.delta) >= 0.0 ? 1.0 : -1.0;
  return glm::normalize(n + side * tags.sigma * tags.delta);
}

PnPatch make_patch(const PnInput& in, NormalMode mode) {
  return build_patch(in.p, in.n, mode, [&](int i, int j) { return pn_tangent(in, i, j); });
}

PnPatch make_patch_from_tangents(const std::array<glm::dvec3, 3>& p, const std::array<glm::dvec3, 3>& field_normals,
                                 const std::array<std::array<glm::dvec3, 3>, 3>& tangent, NormalMode mode) {
  return build_patch(p, field_normals, mode, [&](int i, int j) { return tangent[i][j]; });
}

PnPatch make_stpn_patch(const PnInput& in, const std::array<VertexTags, 3>& tags, NormalMode mode) {
  const auto& P = in.p;
  const auto& N = in.n;
  // The side of each vertex's crease this triangle lies on, decided by its face normal.
  const glm::dvec3 face = glm::cross(P[1] - P[0], P[2] - P[0]);
  std::array<glm::dvec3, 3> sharp = N;  // N'_i: replaces N_i in the normal field
  for (int i = 0; i < 3; ++i) {
    const VertexTags& t = tags[static_cast<std::size_t>(i)];
    if (!t.tagged()) continue;
    sharp[static_cast<std::size_t>(i)] = sharp_normal(N[i], t, face);
  }
  auto tangent = [&](int j, int k) {
    const VertexTags& tj = tags[static_cast<std::size_t>(j)];
    if (tj.neutral()) return pn_tangent(in, j, k);
    const glm::dvec3 d = P[j] + (1.0 - tj.theta) / 3.0 * (P[k] - P[j]);
    // Π(p, n, q) = −n·(q − p): the signed distance that brings q back into the plane (p, n).
    auto project = [&](const glm::dvec3& n) { return -glm::dot(n, d - P[j]); };
    if (tj.tagged() && tags[static_cast<std::size_t>(k)].tagged()) {  // δ = 1: a crease edge
      const glm::dvec3 y = glm::normalize(N[j] + tj.beta * tj.delta);
      return d + project(N[j]) * y;
    }
    const glm::dvec3 x = glm::normalize((1.0 - tj.sigma) * N[j] + tj.sigma * sharp[static_cast<std::size_t>(j)]);
    return d + project(x) * x;
  };
  return build_patch(in.p, sharp, mode, tangent);
}

// The basis is written so that a patch edge gives the same bits from both patches that share it
// (as de Casteljau does): each value is a product whose factors are grouped by variable
// (3 (a a) b, 2 (a b)), so swapping the roles of two variables maps it onto its mirror term;
// and the sums below group the terms by corner and by edge, so that on an edge, where every
// other term is an exact zero, the two corners and the two interior terms are added in pairs.
// Both hold whenever the shared edge's weights are the same doubles in both patches (w = 1 - u
// exactly, e.g. a power-of-two L).
BasisAtPoint basis_at(double u, double v) {
  BasisAtPoint b;
  const double w = 1.0 - u - v;
  b.w = w;
  b.u = u;
  b.v = v;
  auto& c = b.cubic;
  c[net_index(0, 0, 3)] = (w * w) * w;          // b300
  c[net_index(3, 0, 3)] = (u * u) * u;          // b030
  c[net_index(0, 3, 3)] = (v * v) * v;          // b003
  c[net_index(1, 0, 3)] = 3.0 * ((w * w) * u);  // b210
  c[net_index(2, 0, 3)] = 3.0 * ((u * u) * w);  // b120
  c[net_index(2, 1, 3)] = 3.0 * ((u * u) * v);  // b021
  c[net_index(1, 2, 3)] = 3.0 * ((v * v) * u);  // b012
  c[net_index(0, 2, 3)] = 3.0 * ((v * v) * w);  // b102
  c[net_index(0, 1, 3)] = 3.0 * ((w * w) * v);  // b201
  c[net_index(1, 1, 3)] = 6.0 * ((w * u) * v);  // b111
  auto& q = b.quadratic;
  q[net_index(0, 0, 2)] = w * w;          // n200
  q[net_index(2, 0, 2)] = u * u;          // n020
  q[net_index(0, 2, 2)] = v * v;          // n002
  q[net_index(1, 0, 2)] = 2.0 * (w * u);  // n110
  q[net_index(1, 1, 2)] = 2.0 * (u * v);  // n011
  q[net_index(0, 1, 2)] = 2.0 * (w * v);  // n101
  return b;
}

PnVertex eval_bernstein(const PnPatch& patch, double u, double v) { return eval_bernstein(patch, basis_at(u, v)); }

PnVertex eval_bernstein(const PnPatch& patch, const BasisAtPoint& basis) {
  const double w = basis.w, u = basis.u, v = basis.v;
  const auto& c = basis.cubic;
  const auto& b = patch.b;
  auto term = [&](int j, int k) {
    const auto i = static_cast<std::size_t>(net_index(j, k, 3));
    return c[i] * b[i];
  };
  PnVertex out;
  // Corners, then the edges' interior terms pair by pair, then the centre (see basis_at).
  const glm::dvec3 corners = (term(0, 0) + term(3, 0)) + term(0, 3);
  const glm::dvec3 edges = ((term(1, 0) + term(2, 0)) + (term(2, 1) + term(1, 2))) + (term(0, 2) + term(0, 1));
  out.position = (corners + edges) + term(1, 1);

  glm::dvec3 field(0.0);
  if (patch.mode == NormalMode::Quadratic || patch.mode == NormalMode::Reflect) {
    const auto& q = basis.quadratic;
    const auto& n = patch.n_bern;
    auto nterm = [&](int j, int k) {
      const auto i = static_cast<std::size_t>(net_index(j, k, 2));
      return q[i] * n[i];
    };
    field = ((nterm(0, 0) + nterm(2, 0)) + nterm(0, 2)) + ((nterm(1, 0) + nterm(1, 1)) + nterm(0, 1));
  } else if (patch.mode == NormalMode::Linear) {
    field = linear_field(patch, w, u, v);
  }
  // The usual case: the field is the normal. resolve_normal() would return the same vector; the
  // tangents it needs otherwise are computed only when it is called.
  if (patch.mode != NormalMode::Derivative && unit_field(field, out.normal)) return out;

  // Partial derivatives along u and v (w = 1 - u - v), each divided by 3:
  // sum over the degree-2 basis of the forward differences of the cubic net.
  glm::dvec3 du(0.0), dv(0.0);
  for (int k = 0; k <= 2; ++k) {
    for (int j = 0; j + k <= 2; ++j) {
      const double b2 = basis.quadratic[static_cast<std::size_t>(net_index(j, k, 2))];
      const glm::dvec3& base = b[static_cast<std::size_t>(net_index(j, k, 3))];
      du += b2 * (b[static_cast<std::size_t>(net_index(j + 1, k, 3))] - base);
      dv += b2 * (b[static_cast<std::size_t>(net_index(j, k + 1, 3))] - base);
    }
  }
  out.normal = resolve_normal(patch, field, du, dv, w, u, v);
  return out;
}

int de_casteljau_ops(NormalMode mode) {
  switch (mode) {
    case NormalMode::Quadratic:
    case NormalMode::Reflect: return 10 + 4;
    case NormalMode::Linear: return 10 + 1;
    case NormalMode::Derivative: return 10;
  }
  return 10;
}

PnVertex eval_de_casteljau(const PnPatch& patch, double u, double v, std::uint64_t* int_ops) {
  const double w = 1.0 - u - v;
  int ops = 0;

  std::array<glm::dvec3, 6> level1;
  std::array<glm::dvec3, 3> level2;
  std::array<glm::dvec3, 1> level3;
  ops += casteljau_level(patch.b, 3, w, u, v, level1);
  ops += casteljau_level(level1, 2, w, u, v, level2);
  ops += casteljau_level(level2, 1, w, u, v, level3);

  // Level 2 is the tangent triangle q_w, q_u, q_v: (q_u - q_w) and (q_v - q_w) are the
  // partial derivatives divided by 3.
  const glm::dvec3& q_w = level2[net_index(0, 0, 1)];
  const glm::dvec3& q_u = level2[net_index(1, 0, 1)];
  const glm::dvec3& q_v = level2[net_index(0, 1, 1)];

  glm::dvec3 field(0.0);
  switch (patch.mode) {
    case NormalMode::Quadratic:
    case NormalMode::Reflect: {
      std::array<glm::dvec3, 3> n1;
      std::array<glm::dvec3, 1> n2;
      ops += casteljau_level(patch.n_bern, 2, w, u, v, n1);
      ops += casteljau_level(n1, 1, w, u, v, n2);
      field = n2[0];
      break;
    }
    case NormalMode::Linear:
      field = int_op(w, u, v, patch.n_corner[0], patch.n_corner[1], patch.n_corner[2]);
      ++ops;
      break;
    case NormalMode::Derivative:
      break;
  }
  if (int_ops) *int_ops += static_cast<std::uint64_t>(ops);  // de_casteljau_ops(patch.mode)

  // Fallbacks are numerics of the reference, not operations of the unit: not counted.
  return {level3[0], resolve_normal(patch, field, q_u - q_w, q_v - q_w, w, u, v)};
}

}  // namespace tessim
