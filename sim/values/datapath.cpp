#include "sim/values/datapath.hpp"

#include <array>

#include "model/pattern.hpp"
#include "model/pn.hpp"

namespace tessim::sim {

namespace {

// One de Casteljau level of degree D -> D - 1 with the unit's INT operation.
template <int D>
std::array<FxVec, D*(D + 1) / 2> casteljau_level(const std::array<FxVec, (D + 1) * (D + 2) / 2>& net, std::int64_t w,
                                                 std::int64_t u, std::int64_t v, int B) {
  std::array<FxVec, D*(D + 1) / 2> next{};
  for (int k = 0; k < D; ++k)
    for (int j = 0; j + k < D; ++j)
      next[static_cast<std::size_t>(net_index(j, k, D - 1))] =
          int_op(w, u, v, net[static_cast<std::size_t>(net_index(j, k, D))],
                 net[static_cast<std::size_t>(net_index(j + 1, k, D))],
                 net[static_cast<std::size_t>(net_index(j, k + 1, D))], B);
  return next;
}

// Position and normal at the weights (w, u, v), B fraction bits, w + u + v = 2^B.
VertexFx evaluate_at(const ControlPointsFx& cp, std::int64_t w, std::int64_t u, std::int64_t v, NormalMode mode,
                     int B) {
  VertexFx out;
  out.pos = casteljau_level<1>(casteljau_level<2>(casteljau_level<3>(cp.b, w, u, v, B), w, u, v, B), w, u, v, B)[0];
  if (mode == NormalMode::Linear)
    out.nrm = int_op(w, u, v, cp.n[0], cp.n[2], cp.n[5], B);  // w N1 + u N2 + v N3
  else
    out.nrm = casteljau_level<1>(casteljau_level<2>(cp.n, w, u, v, B), w, u, v, B)[0];
  out.u = u;
  out.v = v;
  out.flags = cp.flags;
  return out;
}

}  // namespace

VertexFx evaluate_vertex(const ControlPointsFx& cp, int j, int k, int L, std::uint32_t id, NormalMode mode,
                         const NumberFormat& format) {
  const int B = format.bary_bits;
  const std::int64_t u = bary_weight(j, L, B), v = bary_weight(k, L, B);
  const std::int64_t w = format.bary_one() - u - v;  // exact: w + u + v = 2^B
  VertexFx out = evaluate_at(cp, w, u, v, mode, B);
  out.u = u;
  out.v = v;
  out.j = j;
  out.k = k;
  out.L = L;
  out.id = id;
  out.last = k == L;
  out.index = pattern_index(j, k, L);
  return out;
}

std::vector<VertexFx> evaluate_patch(const TriangleFx& tri, NormalMode mode, const NumberFormat& format) {
  const ControlPointsFx cp = compute_control_points(tri, mode, format);
  std::vector<VertexFx> out;
  if (tri.pattern != TriPattern::uniform) {
    const D3D11Setup setup = tri_setup(tri);
    const int B = format.bary_bits;
    out.reserve(static_cast<std::size_t>(setup.point_count));
    for (D3D11PointWalker walk(setup);; walk.next(setup)) {
      const FixedUV uv = walk.point(setup);
      const std::int64_t u = std::int64_t{uv.u} << (B - 16), v = std::int64_t{uv.v} << (B - 16);
      VertexFx x = evaluate_at(cp, format.bary_one() - u - v, u, v, mode, B);
      x.j = walk.ring();
      x.k = walk.edge();
      x.index = walk.index();
      x.id = tri.id;
      x.last = walk.last();
      out.push_back(x);
      if (walk.last()) break;
    }
    return out;
  }
  out.reserve(static_cast<std::size_t>((tri.L + 1) * (tri.L + 2) / 2));
  for (int k = 0; k <= tri.L; ++k)
    for (int j = 0; j + k <= tri.L; ++j) out.push_back(evaluate_vertex(cp, j, k, tri.L, tri.id, mode, format));
  return out;
}

}  // namespace tessim::sim
