// Exact rounding ties in lock-step (docs/verification.md): every rounding the RTL makes rounds
// half up, and a single-point fault that rounds half down instead (2^(s-1) - 1 added before the
// shift) changes a result only where the dropped bits are exactly one half. Random streams almost
// never hold such a tie, so these streams are searched for (or solved for) with the cycle model's
// own functions: each holds exact ties of one rounding whose half-down result changes an output
// vertex (checked on a copy of the model's arithmetic with that one rounding turned half down,
// which must reproduce the model bit for bit when left half up), and runs in lock-step on every
// fault-free Verilated build. Where no tie can be reached, ExactTiesImpossible proves it for every
// build's format, so that a format change that makes one reachable fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "model/pn.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/base/fixed.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/d3d11_walk.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"

namespace tessim::cosim {
namespace {

using sim::FxVec;
using sim::i128;

// The builds whose InjectBug is 0 (n2_bug* carry the checker's own deliberate faults).
std::vector<std::string> fault_free_builds() {
  std::vector<std::string> names;
  for (const std::string& name : rtl::rtl_variants())
    if (rtl::make_rtl_unit(name)->inject_bug() == 0) names.push_back(name);
  return names;
}

sim::HardwareConfig build_config(const std::string& name) { return rtl::make_rtl_unit(name)->config(); }

CosimOptions build_options(const std::string& name, NormalMode mode, double stall, std::uint64_t seed) {
  CosimOptions o;
  o.variant = name;
  static_cast<sim::HardwareConfig&>(o.unit) = build_config(name);
  o.unit.normals = mode;
  o.unit.gpe_stall_prob = stall;
  o.unit.gpe_cycles = 2;
  o.seed = o.unit.seed = seed;
  return o;
}

void renumber(std::vector<sim::TriangleFx>& stream) {
  for (std::size_t i = 0; i < stream.size(); ++i) stream[i].id = static_cast<std::uint32_t>(i);
}

std::int64_t rand_below(sim::SplitMix64& rng, std::int64_t n) {
  return static_cast<std::int64_t>(rng.next() % static_cast<std::uint64_t>(n));
}
std::int64_t rand_fx(sim::SplitMix64& rng, double lo, double hi, const sim::NumberFormat& f) {
  return sim::quantize(lo + (hi - lo) * rng.uniform(), f);
}

// The geometry net slots of the tangent points (near a, near b) and the normal net slot of the
// mid-edge normal of edge e (corners e -> e + 1), as sim/values/cpg.cpp orders them.
constexpr std::array<std::array<int, 3>, 3> kEdgeSlots{{{net_index(1, 0, 3), net_index(2, 0, 3), net_index(1, 0, 2)},
                                                        {net_index(2, 1, 3), net_index(1, 2, 3), net_index(1, 1, 2)},
                                                        {net_index(0, 2, 3), net_index(0, 1, 3), net_index(0, 1, 2)}}};

// Some vertex of the uniform pattern at factor L differs between two sets of control points.
bool vertex_differs(const sim::ControlPointsFx& a, const sim::ControlPointsFx& b, int L, NormalMode mode,
                    const sim::NumberFormat& f) {
  for (int k = 0; k <= L; ++k)
    for (int j = 0; j + k <= L; ++j)
      if (sim::evaluate_vertex(a, j, k, L, 0, mode, f) != sim::evaluate_vertex(b, j, k, L, 0, mode, f)) return true;
  return false;
}

// ============================================================================ 1. INT operations
// int_op's sum w A + u B + v C is exactly 2^(B-1) mod 2^B: a tie. Weights with a small power of
// two as denominator (j / L = 1/2, 1/4, ... at even L) make ties frequent, in every op of the
// de Casteljau schedule (sim/base/int_ops.hpp), so a uniform stream at even L is full of them.
struct IntTally {
  std::array<std::size_t, sim::int_ops::kOpCount> ties{};  // op-components whose sum is a tie, per op
  std::size_t vertices = 0;
  std::size_t visible_pos = 0, visible_nrm = 0;  // vertices whose position / normal half down changes
  std::size_t mismatches = 0;                    // the copy's half-up result differs from the model's
  std::size_t total() const { return std::accumulate(ties.begin(), ties.end(), std::size_t{0}); }
};

// int_op with `half` added, counting the components whose exact sum is a tie.
FxVec int_op_counted(std::int64_t w, std::int64_t u, std::int64_t v, const FxVec& a, const FxVec& b, const FxVec& c,
                     int B, std::int64_t half, std::size_t* ties) {
  const std::int64_t mask = (std::int64_t{1} << B) - 1, tie = std::int64_t{1} << (B - 1);
  FxVec r{};
  for (int i = 0; i < 3; ++i) {
    const std::int64_t s = w * a[static_cast<std::size_t>(i)] + u * b[static_cast<std::size_t>(i)] + v * c[static_cast<std::size_t>(i)];
    if (ties && (s & mask) == tie) ++*ties;
    r[static_cast<std::size_t>(i)] = (s + half) >> B;
  }
  return r;
}

// One de Casteljau level D -> D - 1; the op of result slot i is first_op + i (the TE's table:
// level-1 geometry ops 0..5, level 2 9..11, level 3 13; normals 6..8 and 12).
std::vector<FxVec> casteljau_counted(const std::vector<FxVec>& net, int D, std::int64_t w, std::int64_t u,
                                     std::int64_t v, int B, std::int64_t half, int first_op, IntTally* tally) {
  std::vector<FxVec> next(static_cast<std::size_t>(D * (D + 1) / 2));
  for (int k = 0; k < D; ++k)
    for (int j = 0; j + k < D; ++j) {
      const int slot = net_index(j, k, D - 1);
      next[static_cast<std::size_t>(slot)] = int_op_counted(
          w, u, v, net[static_cast<std::size_t>(net_index(j, k, D))], net[static_cast<std::size_t>(net_index(j + 1, k, D))],
          net[static_cast<std::size_t>(net_index(j, k + 1, D))], B, half,
          tally ? &tally->ties[static_cast<std::size_t>(first_op + slot)] : nullptr);
    }
  return next;
}

// The vertex at (w, u, v) as sim/values/datapath.cpp evaluates it, every INT op adding `half`.
std::pair<FxVec, FxVec> evaluate_with_half(const sim::ControlPointsFx& cp, std::int64_t w, std::int64_t u,
                                           std::int64_t v, NormalMode mode, int B, std::int64_t half, IntTally* tally) {
  const std::vector<FxVec> b3(cp.b.begin(), cp.b.end());
  const std::vector<FxVec> b2 = casteljau_counted(b3, 3, w, u, v, B, half, 0, tally);
  const std::vector<FxVec> b1 = casteljau_counted(b2, 2, w, u, v, B, half, 9, tally);
  const FxVec pos = casteljau_counted(b1, 1, w, u, v, B, half, 13, tally)[0];
  FxVec nrm{};
  if (mode == NormalMode::Linear) {
    nrm = int_op_counted(w, u, v, cp.n[0], cp.n[2], cp.n[5], B, half, tally ? &tally->ties[6] : nullptr);
  } else {
    const std::vector<FxVec> n2(cp.n.begin(), cp.n.end());
    nrm = casteljau_counted(casteljau_counted(n2, 2, w, u, v, B, half, 6, tally), 1, w, u, v, B, half, 12, tally)[0];
  }
  return {pos, nrm};
}

// Tallies a uniform patch: its ties, and the vertices that an INT rounding half down changes.
std::size_t tally_int_patch(const sim::TriangleFx& tri, NormalMode mode, const sim::NumberFormat& f, IntTally& t) {
  const int B = f.bary_bits;
  const std::int64_t half = std::int64_t{1} << (B - 1);
  const sim::ControlPointsFx cp = sim::compute_control_points(tri, mode, f);
  std::size_t visible = 0;
  for (int k = 0; k <= tri.L; ++k)
    for (int j = 0; j + k <= tri.L; ++j) {
      const std::int64_t u = sim::bary_weight(j, tri.L, B), v = sim::bary_weight(k, tri.L, B), w = f.bary_one() - u - v;
      const auto up = evaluate_with_half(cp, w, u, v, mode, B, half, &t);
      const sim::VertexFx model = sim::evaluate_vertex(cp, j, k, tri.L, tri.id, mode, f);
      t.mismatches += up.first != model.pos || up.second != model.nrm;
      const auto down = evaluate_with_half(cp, w, u, v, mode, B, half - 1, nullptr);
      t.visible_pos += down.first != up.first;
      t.visible_nrm += down.second != up.second;
      visible += down != up;
      ++t.vertices;
    }
  return visible;
}

// Random triangles at even factors, kept while a half-down INT rounding changes one of their
// vertices (nearly all do).
std::vector<sim::TriangleFx> int_tie_stream(const sim::NumberFormat& f, NormalMode mode, std::size_t want,
                                            std::uint64_t seed, IntTally& tally) {
  static constexpr std::array<int, 6> kFactors{2, 4, 8, 6, 4, 2};
  std::vector<sim::TriangleFx> shapes = random_triangles(4 * want, seed, f, 1, 0.0);
  std::vector<sim::TriangleFx> stream;
  for (std::size_t i = 0; i < shapes.size() && stream.size() < want; ++i) {
    sim::TriangleFx tri = shapes[i];
    tri.L = kFactors[i % kFactors.size()];
    IntTally t;
    if (tally_int_patch(tri, mode, f, t) == 0) continue;
    for (std::size_t op = 0; op < t.ties.size(); ++op) tally.ties[op] += t.ties[op];
    tally.vertices += t.vertices;
    tally.visible_pos += t.visible_pos;
    tally.visible_nrm += t.visible_nrm;
    tally.mismatches += t.mismatches;
    stream.push_back(tri);
  }
  renumber(stream);
  return stream;
}

TEST(ExactTiesInt, HalfUpTiesOfEveryIntOpAgreeOnEveryBuild) {
  std::size_t builds = 0;
  for (const std::string& name : fault_free_builds()) {
    ++builds;
    for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Linear}) {
      const CosimOptions o = build_options(name, mode, 0.2, 31 + static_cast<std::uint64_t>(sim::mode_code(mode)));
      IntTally t;
      const std::vector<sim::TriangleFx> stream = int_tie_stream(o.unit.format, mode, 24, o.seed, t);
      SCOPED_TRACE(name + " " + std::string(to_string(mode)) + " B = " + std::to_string(o.unit.format.bary_bits));
      ASSERT_EQ(t.mismatches, 0u) << "the copy of the INT arithmetic reproduces the model";
      ASSERT_EQ(stream.size(), 24u) << "the search finds patches whose vertices a half-down rounding changes";
      // Ties in every op that exists in the mode, the final ones (position, normal) included.
      for (int op = 0; op < sim::int_ops::kOpCount; ++op) {
        if (sim::int_ops::absent_ops(mode) & sim::int_ops::bit(op)) continue;
        EXPECT_GT(t.ties[static_cast<std::size_t>(op)], 0u) << "op " << op;
      }
      EXPECT_GT(t.visible_pos, t.vertices / 8);
      EXPECT_GT(t.visible_nrm, t.vertices / 8);
      const std::string key = name + "_" + std::string(to_string(mode));
      RecordProperty(key + "_ties", static_cast<int>(t.total()));
      RecordProperty(key + "_final_op_ties",
                     static_cast<int>(t.ties[sim::int_ops::kPositionOp] +
                                      t.ties[static_cast<std::size_t>(sim::int_ops::normal_op(mode))]));
      RecordProperty(key + "_changed_positions", static_cast<int>(t.visible_pos));
      RecordProperty(key + "_changed_normals", static_cast<int>(t.visible_nrm));
      RecordProperty(key + "_vertices", static_cast<int>(t.vertices));
      const CosimReport r = run_cosim(stream, o);
      EXPECT_TRUE(r.passed) << format_report(r, o);
      if (!r.passed) return;
    }
  }
  EXPECT_GE(builds, 1u);
}

// ============================================================================ 2. D3D11 pattern
// The DPG's roundings (rtl/tess_dpg.sv, sim/values/d3d11_walk.cpp) and the FSU's half factor
// (rtl/tess_fsu_edge.sv, d3d11_edge): a point's blend (i' fw + i cw + 2^15) >> 16, a ring's
// offset (t_r 0xAAAA + 2^15) >> 16, its half (perp + 1) >> 1, and H = (factor + 2^-16) / 2.
// A copy of the point walk with each of them turned half down tells which ties move a point
// (u and v are outputs, so a moved point is a changed vertex).
struct DpgVariant {
  std::uint64_t bias = 0x8000;       // the point blend's rounding constant
  std::uint64_t ring_bias = 0x8000;  // the ring offset's
  Fixed16 shift_add = 1;             // perp + shift_add, halved
  bool half_factor_down = false;     // H = factor / 2 (rounded down) for an odd 16.16 factor
};

enum DpgSite { kBlend, kRingOffset, kRingShift, kHalfFactor, kDpgSites };
constexpr std::array<const char*, kDpgSites> kDpgSiteNames{"blend", "ring_offset", "ring_shift", "half_factor"};

DpgVariant half_down(DpgSite site) {
  DpgVariant v;
  if (site == kBlend) v.bias = 0x7fff;
  if (site == kRingOffset) v.ring_bias = 0x7fff;
  if (site == kRingShift) v.shift_add = 0;
  if (site == kHalfFactor) v.half_factor_down = true;
  return v;
}

struct Placement {
  Fixed16 t = 0;
  bool tie = false;  // the blend's dropped 16 bits are exactly one half
};

// d3d11_place with the rounding constant `bias`.
Placement place(const sim::D3D11Edge& s, int index, std::uint64_t bias) {
  bool mirrored = false;
  if (index >= s.half_points) {
    index = 2 * s.half_points - index - (s.odd ? 1 : 0);
    mirrored = true;
  }
  if (index == s.half_points) return {0x8000, false};
  const int floor_index = index > s.split_point ? index - 1 : index;
  const std::uint64_t blend =
      static_cast<std::uint64_t>(floor_index) * s.floor_weight + static_cast<std::uint64_t>(index) * s.ceil_weight;
  const auto position = static_cast<Fixed16>((blend + bias) >> 16);
  return {mirrored ? kFixed16One - position : position, (blend & 0xffff) == 0x8000};
}

struct DpgTally {
  std::array<std::size_t, kDpgSites> ties{};     // exact ties of each rounding in the patch
  std::array<std::size_t, kDpgSites> visible{};  // points that rounding half down moves
  std::size_t points = 0;
  std::size_t mismatches = 0;  // the copy's half-up walk differs from the model's
};

sim::D3D11Setup variant_setup(const sim::TriangleFx& tri, const DpgVariant& m) {
  if (!m.half_factor_down) return sim::tri_setup(tri);
  sim::TriangleFx t = tri;
  for (Fixed16& x : t.factors) x &= ~Fixed16{1};  // (x + 1) >> 1 becomes x >> 1 = ((x - 1) + 1) >> 1
  return sim::tri_setup(t);
}

// The patch's points as the DPG walks them (sim::D3D11PointWalker's order and structure), each
// placed by the copy; ties counted when `tally` is given.
std::vector<FixedUV> walk_points(const sim::TriangleFx& tri, const DpgVariant& m, DpgTally* tally) {
  const sim::D3D11Setup setup = variant_setup(tri, m);
  std::vector<FixedUV> out;
  sim::D3D11PointWalker walk(setup);
  int p = 0, ring_seen = 0;
  Fixed16 perp = 0, shift = 0;
  for (;;) {
    const int ring = walk.ring(), edge = walk.edge();
    FixedUV uv;
    if (edge == 3) {
      uv = {0x5555, 0x5555};
    } else if (ring == 0) {
      const sim::D3D11Edge& e = setup.outer[static_cast<std::size_t>(edge)];
      const Placement t = place(e, edge == 1 ? p : e.points - 1 - p, m.bias);
      if (tally) tally->ties[kBlend] += t.tie;
      uv = edge == 0 ? FixedUV{0, t.t} : edge == 1 ? FixedUV{t.t, 0} : FixedUV{t.t, kFixed16One - t.t};
    } else {
      if (ring != ring_seen) {  // entering the ring: its offset and half
        ring_seen = ring;
        const Placement at = place(setup.inner, ring, m.bias);
        const std::uint64_t scaled = static_cast<std::uint64_t>(at.t) * 0xaaaa;
        perp = static_cast<Fixed16>((scaled + m.ring_bias) >> 16);
        shift = (perp + m.shift_add) / 2;
        if (tally) {
          tally->ties[kBlend] += at.tie;
          tally->ties[kRingOffset] += (scaled & 0xffff) == 0x8000;
          tally->ties[kRingShift] += perp & 1;
        }
      }
      const int ring_last = setup.factors.inner_points - 1 - ring;
      const Placement t = place(setup.inner, edge == 1 ? p : ring_last - (p - ring), m.bias);
      if (tally) tally->ties[kBlend] += t.tie;
      const Fixed16 ts = t.t - shift;
      uv = edge == 0 ? FixedUV{perp, ts} : edge == 1 ? FixedUV{ts, perp} : FixedUV{ts, kFixed16One - ts - perp};
    }
    if (tally) tally->mismatches += uv != walk.point(setup);
    out.push_back(uv);
    if (walk.last()) break;
    walk.next(setup);
    p = walk.ring() == ring && walk.edge() == edge ? p + 1 : walk.ring();
  }
  return out;
}

std::size_t points_moved(const std::vector<FixedUV>& a, const std::vector<FixedUV>& b) {
  std::size_t n = std::max(a.size(), b.size()) - std::min(a.size(), b.size());
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) n += a[i] != b[i];
  return n;
}

DpgTally tally_d3d11_patch(const sim::TriangleFx& tri) {
  DpgTally t;
  const std::vector<FixedUV> base = walk_points(tri, DpgVariant{}, &t);
  t.points = base.size();
  for (const Fixed16 x : tri.factors) t.ties[kHalfFactor] += x & 1;
  for (int s = 0; s < kDpgSites; ++s)
    if (t.ties[static_cast<std::size_t>(s)])
      t.visible[static_cast<std::size_t>(s)] = points_moved(base, walk_points(tri, half_down(static_cast<DpgSite>(s)), nullptr));
  return t;
}

// A factor of the partitioning, at most `top`: integers (which give the fractional partitionings
// the half fraction 1/2 where every other blend ties, and the integer partitioning the quarter
// points whose ring offset ties), fractions of few bits, and any fraction.
Fixed16 draw_factor(sim::SplitMix64& rng, sim::TriPattern p, int top) {
  const int lo = p == sim::TriPattern::fractional_even ? 2 : 1;
  const Fixed16 k = static_cast<Fixed16>(lo + rand_below(rng, top - lo + 1)) * kFixed16One;
  if (p == sim::TriPattern::integer) return k;
  Fixed16 x = k;
  switch (rng.next() % 4) {
    case 0: break;
    case 1: x += static_cast<Fixed16>(rand_below(rng, 16)) << 12; break;
    case 2: x += static_cast<Fixed16>(rand_below(rng, 0x10000)); break;
    default: x += static_cast<Fixed16>(rand_below(rng, 256)) << 8 | 1; break;
  }
  // Within the range, and off 1 + 2^-16 (its half factor rounded down is the single triangle's 1).
  return std::clamp<Fixed16>(x, (lo * kFixed16One) + (p == sim::TriPattern::fractional_odd ? 2 : 0),
                             (p == sim::TriPattern::fractional_odd ? 63 : 64) * kFixed16One);
}

// Patches kept while some rounding of the partitioning still wants `want` patches with visible ties.
std::vector<sim::TriangleFx> d3d11_tie_stream(sim::TriPattern p, const sim::NumberFormat& f, std::size_t want,
                                              std::uint64_t seed, DpgTally& total) {
  const bool fractional = p != sim::TriPattern::integer;
  // Integer partitioning: φ = 0 and even factors, no blend or half-factor ties
  // (ExactTiesImpossible.IntegerPartitioningBlendsAndHalvesNeverTie).
  std::array<std::size_t, kDpgSites> need{want, want, want, fractional ? want : 0};
  if (!fractional) need[kBlend] = 0;
  const std::vector<sim::TriangleFx> shapes = random_triangles(16, seed, f, 1, 0.0);
  sim::SplitMix64 rng(seed);
  std::vector<sim::TriangleFx> stream;
  for (int tries = 0; tries < 200000 && std::any_of(need.begin(), need.end(), [](std::size_t n) { return n > 0; });
       ++tries) {
    sim::TriangleFx tri = shapes[stream.size() % shapes.size()];
    tri.pattern = p;
    const int top = 12;
    for (Fixed16& x : tri.factors) x = draw_factor(rng, p, top);
    if (!sim::tri_pattern_problem(tri).empty()) continue;
    // Cheap look first: ring offsets at t_r = 1/4 are what is rare.
    if (need[kBlend] == 0 && need[kHalfFactor] == 0 && need[kRingShift] == 0) {
      const sim::D3D11Setup s = sim::tri_setup(tri);
      bool quarter = false;
      for (int r = 1; r < s.factors.inner_points / 2; ++r) quarter |= place(s.inner, r, 0x8000).t == 0x4000;
      if (!quarter) continue;
    }
    const DpgTally t = tally_d3d11_patch(tri);
    bool useful = false;
    for (std::size_t s = 0; s < need.size(); ++s) useful |= need[s] > 0 && t.visible[s] > 0;
    if (!useful) continue;
    for (std::size_t s = 0; s < need.size(); ++s) {
      if (t.visible[s] > 0 && need[s] > 0) --need[s];
      total.ties[s] += t.ties[s];
      total.visible[s] += t.visible[s];
    }
    total.points += t.points;
    total.mismatches += t.mismatches;
    stream.push_back(tri);
  }
  renumber(stream);
  return stream;
}

TEST(ExactTiesD3d11, BlendRingOffsetShiftAndHalfFactorTiesAgreeOnEveryBuild) {
  for (const std::string& name : fault_free_builds()) {
    const CosimOptions o = build_options(name, NormalMode::Linear, 0.1, 41);
    for (const sim::TriPattern p : {sim::TriPattern::integer, sim::TriPattern::fractional_odd,
                                    sim::TriPattern::fractional_even}) {
      const std::string part = partitioning_name(sim::tri_partitioning(p));
      SCOPED_TRACE(name + " " + part);
      DpgTally t;
      const std::vector<sim::TriangleFx> stream = d3d11_tie_stream(p, o.unit.format, 3, 43 + static_cast<std::uint64_t>(p), t);
      ASSERT_EQ(t.mismatches, 0u) << "the copy of the point walk reproduces the model";
      for (int s = 0; s < kDpgSites; ++s) {
        if (p == sim::TriPattern::integer && (s == kBlend || s == kHalfFactor)) continue;
        ASSERT_GE(t.visible[static_cast<std::size_t>(s)], 3u) << kDpgSiteNames[static_cast<std::size_t>(s)]
                                                              << ": the search finds patches whose points its ties move";
        RecordProperty(name + "_" + part + "_" + kDpgSiteNames[static_cast<std::size_t>(s)] + "_ties",
                       static_cast<int>(t.ties[static_cast<std::size_t>(s)]));
        RecordProperty(name + "_" + part + "_" + kDpgSiteNames[static_cast<std::size_t>(s)] + "_moved_points",
                       static_cast<int>(t.visible[static_cast<std::size_t>(s)]));
      }
      RecordProperty(name + "_" + part + "_patches", static_cast<int>(stream.size()));
      const CosimReport r = run_cosim(stream, o);
      EXPECT_TRUE(r.passed) << format_report(r, o);
      if (!r.passed) return;
    }
  }
}

// ============================================================================ 3. alpha w
// w_alpha = round_half_up(alpha w, A) (sim/values/cpg.cpp, rtl/tess_cpg_edge.sv AHalf). alpha w
// ties exactly when v2(alpha) + v2(w) = A - 1 (for every w with v2(w) < A some alpha ties it);
// alpha w = (2 wa - 1) 2^(A-1) gives w_alpha = wa, and wa - 1 rounded half down. The tangent point
// (2 Pn + Pf - w_alpha Nn) / 3 moves by an LSB only where wa - 1 and wa straddle a rounding step
// of one of its components c, some 2^-F / 3 of all wa, so wa is solved for rather than drawn:
// with Pn, Nn and d_c fixed, the numerator's component c depends on wa alone, and its first step
// past a random start is found by bisection; alpha = k 2^(A-1-t) and w = (2 wa - 1) 2^t / k
// follow, and d's other two components make d . Nn = w exactly (a linear Diophantine equation,
// the gcd of Nn's other two components 1).
std::int64_t ext_gcd(std::int64_t a, std::int64_t b, std::int64_t& x, std::int64_t& y) {
  if (b == 0) {
    x = a >= 0 ? 1 : -1;
    y = 0;
    return a >= 0 ? a : -a;
  }
  std::int64_t x1 = 0, y1 = 0;
  const std::int64_t g = ext_gcd(b, a % b, x1, y1);
  x = y1;
  y = x1 - (a / b) * y1;
  return g;
}

glm::dvec3 random_unit(sim::SplitMix64& rng) {
  glm::dvec3 n;
  do n = glm::dvec3(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
  while (glm::length(n) < 0.2 || glm::length(n) > 1);
  return glm::normalize(n);
}

// The tangent point near Pn on edge Pn -> Pf (sim/values/cpg.cpp tangent_point) from a given w_alpha.
FxVec tangent_from(const FxVec& pn, const FxVec& pf, const FxVec& nn, i128 wa, int sign, const sim::NumberFormat& f) {
  std::uint8_t flags = 0;
  FxVec t{};
  for (std::size_t c = 0; c < 3; ++c) {
    const i128 chord = (i128{2} * pn[c] + pf[c]) << (2 * f.coord_frac_bits);
    t[c] = sim::mul_const(chord - sign * wa * nn[c], 3 * f.coord_frac_bits, sim::one_third(f), f, flags);
  }
  return t;
}

// b111 = (3 sum(tangents) - 2 sum(corners)) / 12 from a net's tangent points (compute_control_points).
constexpr auto kCentre = static_cast<std::size_t>(net_index(1, 1, 3));
FxVec b111_of(const sim::ControlPointsFx& net, const sim::TriangleFx& tri, const sim::NumberFormat& f) {
  std::uint8_t flags = 0;
  FxVec r{};
  for (std::size_t c = 0; c < 3; ++c) {
    i128 sum_t = 0;
    for (const auto& slots : kEdgeSlots)
      sum_t += i128{net.b[static_cast<std::size_t>(slots[0])][c]} + net.b[static_cast<std::size_t>(slots[1])][c];
    const i128 corners = i128{tri.p[0][c]} + tri.p[1][c] + tri.p[2][c];
    r[c] = sim::mul_const(3 * sum_t - 2 * corners, f.coord_frac_bits, sim::one_twelfth(f), f, flags);
  }
  return r;
}

struct AlphaTally {
  std::size_t ties = 0;          // edge ends whose alpha w is an exact tie
  std::size_t moved_points = 0;  // tangent points that half down moves
  std::size_t mismatches = 0;    // the copy's half-up control points differ from the model's
};

// The control points with every alpha w of the triangle rounded half down (the tangent points
// and b111 recomputed), tallying ties; the half-up copy is checked against the model.
sim::ControlPointsFx alpha_half_down(const sim::TriangleFx& tri, NormalMode mode, const sim::NumberFormat& f,
                                     AlphaTally& t) {
  const sim::ControlPointsFx cp = sim::compute_control_points(tri, mode, f);
  t.mismatches += b111_of(cp, tri, f) != cp.b[kCentre];
  sim::ControlPointsFx down = cp;
  const int A = f.alpha_bits;
  for (std::size_t e = 0; e < 3; ++e) {
    const std::size_t a = e, b = (e + 1) % 3;
    const FxVec d{tri.p[b][0] - tri.p[a][0], tri.p[b][1] - tri.p[a][1], tri.p[b][2] - tri.p[a][2]};
    const std::int64_t alpha = sim::alpha_port_value(tri.alpha[e], A);
    for (int end = 0; end < 2; ++end) {
      const std::size_t near = end == 0 ? a : b, far = end == 0 ? b : a;
      const int sign = end == 0 ? 1 : -1;
      const i128 product = alpha * sim::dot_exact(d, tri.n[near]);
      const i128 up = sim::round_shift(product, A), dn = (product + (i128{1} << (A - 1)) - 1) >> A;
      const std::size_t slot = static_cast<std::size_t>(kEdgeSlots[e][static_cast<std::size_t>(end)]);
      t.mismatches += tangent_from(tri.p[near], tri.p[far], tri.n[near], up, sign, f) != cp.b[slot];
      if (up == dn) continue;
      ++t.ties;
      down.b[slot] = tangent_from(tri.p[near], tri.p[far], tri.n[near], dn, sign, f);
      t.moved_points += down.b[slot] != cp.b[slot];
    }
  }
  down.b[kCentre] = b111_of(down, tri, f);
  return down;
}

// One triangle with an exact tie of alpha w on edge 0's end near P1 that moves its tangent
// point, or nothing (the caller draws again).
std::optional<sim::TriangleFx> solve_alpha_tie(const sim::NumberFormat& f, sim::SplitMix64& rng) {
  const int F = f.coord_frac_bits, A = f.alpha_bits;
  const int S = 2 * F + sim::const_frac_bits(f);
  const std::int64_t c3 = sim::one_third(f);
  const FxVec nn = sim::quantize(random_unit(rng), f);
  const std::size_t c = static_cast<std::size_t>(rand_below(rng, 3)), c1 = (c + 1) % 3, c2 = (c + 2) % 3;
  const std::int64_t small = std::int64_t{1} << (F - 3);  // every component at least 1/8
  if (std::abs(nn[c]) < small || std::abs(nn[c1]) < small || std::abs(nn[c2]) < small) return std::nullopt;
  std::int64_t g1 = 0, g2 = 0;
  if (ext_gcd(nn[c1], nn[c2], g1, g2) != 1) return std::nullopt;
  FxVec pn{};
  for (auto& x : pn) x = rand_fx(rng, -0.4, 0.4, f);
  FxVec d{};
  d[c] = rand_fx(rng, -0.3, 0.3, f);
  // alpha 2^(A-1-t) for now, so that v2(alpha) + v2(w) = A - 1; t small keeps w near its start.
  const int t = static_cast<int>(rand_below(rng, std::min(A, 8)));
  std::int64_t alpha = std::int64_t{1} << (A - 1 - t);
  // The numerator's component c as a function of w_alpha, rounded as mul_const rounds it.
  const i128 K = (i128{3} * pn[c] + d[c]) << (2 * F);
  auto rounded = [&](i128 wa) { return ((K - wa * nn[c]) * c3 + (i128{1} << (S - 1))) >> S; };
  const i128 w0 = sim::quantize(0.2 * rng.uniform() - 0.1, f) * (i128{1} << F);
  i128 lo = sim::round_shift(alpha * w0, A);
  // Two periods of the rounding (3 2^2F / |nn_c| steps of w_alpha each) hold a step.
  i128 hi = lo + 2 * ((i128{3} << (2 * F)) / std::abs(nn[c])) + 2;
  const i128 y0 = rounded(lo);
  if (rounded(hi) == y0) return std::nullopt;
  while (hi - lo > 1) {
    const i128 mid = lo + (hi - lo) / 2;
    (rounded(mid) != y0 ? hi : lo) = mid;
  }
  // alpha w = (2 hi - 1) 2^(A-1) (w_alpha = hi, hi - 1 half down) with alpha = k 2^(A-1-t), k an
  // odd divisor of 2 hi - 1 below 2^(t+1): alphas other than powers of two where A allows them.
  const i128 m = 2 * hi - 1;
  std::int64_t k_odd = 1;
  for (std::int64_t k = (std::int64_t{2} << t) - 1; k > 1; k -= 2)
    if (m % k == 0) {
      k_odd = k;
      break;
    }
  alpha *= k_odd;
  const i128 w = m / k_odd * (i128{1} << t);
  // d[c1] nn[c1] + d[c2] nn[c2] = w - d[c] nn[c], the solution nearest the line's closest point.
  const i128 R = w - i128{d[c]} * nn[c];
  const double n1 = static_cast<double>(nn[c1]), n2 = static_cast<double>(nn[c2]);
  const double closest1 = static_cast<double>(R) * n1 / (n1 * n1 + n2 * n2);
  const i128 base1 = R * g1;  // g1 nn[c1] + g2 nn[c2] = 1
  const auto k = static_cast<i128>(std::llround((closest1 - static_cast<double>(base1)) / n2));
  const i128 d1 = base1 + k * nn[c2];
  const i128 rest = R - d1 * nn[c1];
  if (rest % nn[c2] != 0) return std::nullopt;
  const i128 d2 = rest / nn[c2];
  const std::int64_t limit = sim::quantize(0.8, f);
  if (d1 > limit || d1 < -limit || d2 > limit || d2 < -limit) return std::nullopt;
  d[c1] = static_cast<std::int64_t>(d1);
  d[c2] = static_cast<std::int64_t>(d2);
  if (sim::dot_exact(d, nn) != w) return std::nullopt;
  sim::TriangleFx tri;
  tri.p[0] = pn;
  for (std::size_t i = 0; i < 3; ++i) {
    tri.p[1][i] = pn[i] + d[i];
    tri.p[2][i] = pn[i] + rand_fx(rng, -0.5, 0.5, f);
  }
  tri.n[0] = nn;
  tri.n[1] = sim::quantize(random_unit(rng), f);
  tri.n[2] = sim::quantize(random_unit(rng), f);
  tri.alpha[0] = static_cast<std::uint32_t>(alpha) << (sim::kAlphaFracBits - A);
  return tri;
}

// Edge 0's end near P1 moved to edge `rotation`, and to its far end when `reversed`: the same
// geometry, so the same tie, in another lane slot and on the other end's arithmetic (w of -d).
sim::TriangleFx reorient(const sim::TriangleFx& tri, int rotation, bool reversed) {
  // Corner roles: 0 the tie's corner, 1 the edge's other end, 2 the third.
  std::array<std::size_t, 3> at{};  // at[role] = corner index in the result
  const auto r = static_cast<std::size_t>(rotation);
  at[0] = reversed ? (r + 1) % 3 : r;
  at[1] = reversed ? r : (r + 1) % 3;
  at[2] = (r + 2) % 3;
  sim::TriangleFx out = tri;
  for (std::size_t role = 0; role < 3; ++role) {
    out.p[at[role]] = tri.p[role];
    out.n[at[role]] = tri.n[role];
    out.alpha[role] = sim::kAlphaOne;
  }
  out.alpha[r] = tri.alpha[0];
  return out;
}

std::vector<sim::TriangleFx> alpha_tie_stream(const sim::NumberFormat& f, NormalMode mode, std::size_t want,
                                              std::uint64_t seed, AlphaTally& tally) {
  sim::SplitMix64 rng(seed);
  std::vector<sim::TriangleFx> stream;
  for (int tries = 0; tries < 200000 && stream.size() < want; ++tries) {
    const std::optional<sim::TriangleFx> solved = solve_alpha_tie(f, rng);
    if (!solved) continue;
    const int n = static_cast<int>(stream.size());
    sim::TriangleFx tri = reorient(*solved, n % 3, (n / 3) % 2 == 1);
    AlphaTally t;
    const sim::ControlPointsFx down = alpha_half_down(tri, mode, f, t);
    if (t.mismatches != 0) {
      tally.mismatches += t.mismatches;
      continue;
    }
    if (t.moved_points == 0) continue;
    // The smallest factor at which a vertex of the patch moves too.
    const sim::ControlPointsFx cp = sim::compute_control_points(tri, mode, f);
    tri.L = 0;
    for (int L = 1; L <= 8 && tri.L == 0; ++L)
      if (vertex_differs(cp, down, L, mode, f)) tri.L = L;
    if (tri.L == 0) continue;
    tally.ties += t.ties;
    tally.moved_points += t.moved_points;
    stream.push_back(tri);
  }
  renumber(stream);
  return stream;
}

TEST(ExactTiesAlpha, SolvedTiesOfAlphaWAgreeOnEveryBuildThatTakesAlpha) {
  std::size_t builds = 0;
  for (const std::string& name : fault_free_builds()) {
    if (!build_config(name).format.takes_alpha()) continue;
    ++builds;
    const CosimOptions o = build_options(name, NormalMode::Quadratic, 0.2, 53);
    AlphaTally t;
    const std::vector<sim::TriangleFx> stream = alpha_tie_stream(o.unit.format, o.unit.normals, 18, o.seed, t);
    SCOPED_TRACE(name + " A = " + std::to_string(o.unit.format.alpha_bits));
    ASSERT_EQ(t.mismatches, 0u) << "the copy of the tangent points reproduces the model";
    ASSERT_EQ(stream.size(), 18u) << "the solver finds ties that move a tangent point and a vertex";
    int max_L = 0;
    for (const sim::TriangleFx& tri : stream) max_L = std::max(max_L, tri.L);
    RecordProperty(name + "_alpha_ties", static_cast<int>(t.ties));
    RecordProperty(name + "_alpha_moved_tangent_points", static_cast<int>(t.moved_points));
    RecordProperty(name + "_alpha_largest_L", max_L);
    const CosimReport r = run_cosim(stream, o);
    EXPECT_TRUE(r.passed) << format_report(r, o);
    if (!r.passed) return;
  }
  EXPECT_GE(builds, 1u);
}

// ============================================================================ 4. exact corners
// The divisions by 3 and 12 (mul_const) cannot tie (ExactTiesImpossible below). The CPG's other
// roundings are truncations and floors: t_c = trunc(d_c (d.s) / (d.d)) and, in quadratic mode,
// n_c = trunc(m_c 2^F / r) with r = floor(sqrt(m.m)). Their corner is an exact result: a zero
// remainder, a perfect square, where a restoring recurrence that compares strictly (rtl/tess_div.sv,
// tess_isqrt.sv) returns another quotient or root. Exactly representable geometry reaches it:
// edges along the axes (d.d = a^2, t_c = s_c) and the 3-4-5 diagonal between them, unit normals
// on the axes and along Pythagorean directions (3, 4, 0) / 5, (1, 2, 2) / 3, (2, 3, 6) / 7 scaled to
// an exact length r round(2^F / r).
struct ExactTally {
  std::size_t t_exact = 0;   // t_c with a zero remainder and a nonzero numerator
  std::size_t n_exact = 0;   // n_c likewise (quadratic)
  std::size_t squares = 0;   // m.m a nonzero perfect square (quadratic)
  std::size_t div_moved = 0, sqrt_moved = 0;  // mid-edge normals an off-by-one there changes
  std::size_t mismatches = 0;  // the copy's mid-edge normals differ from the model's
};

// The mid-edge normals of sim/values/cpg.cpp (untagged corners), the quotient of every exact
// division (`div_off`) or the root of every perfect square (`sqrt_off`) taken one less.
std::array<FxVec, 3> mid_normals(const sim::TriangleFx& tri, NormalMode mode, const sim::NumberFormat& f,
                                 bool div_off, bool sqrt_off, ExactTally* t) {
  const int F = f.coord_frac_bits;
  std::uint8_t flags = 0;
  auto divide = [&](i128 num, i128 den, std::size_t* exact) -> std::int64_t {
    if (den == 0) return 0;
    i128 q = num / den;
    if (num != 0 && num % den == 0) {
      if (exact) ++*exact;
      if (div_off) q -= num > 0 ? 1 : -1;
    }
    return sim::saturate(q, f, flags);
  };
  std::array<FxVec, 3> mids{};
  for (std::size_t e = 0; e < 3; ++e) {
    const std::size_t a = e, b = (e + 1) % 3;
    FxVec d{}, s{};
    for (std::size_t c = 0; c < 3; ++c) {
      d[c] = tri.p[b][c] - tri.p[a][c];
      s[c] = tri.n[a][c] + tri.n[b][c];
    }
    const i128 p = sim::dot_exact(d, s), q = sim::dot_exact(d, d);
    const int k = mode == NormalMode::Quadratic ? 2 : 4;
    FxVec m{};
    for (std::size_t c = 0; c < 3; ++c)
      m[c] = sim::saturate(i128{s[c]} - i128{k} * divide(i128{d[c]} * p, q, t ? &t->t_exact : nullptr), f, flags);
    if (mode == NormalMode::Reflect) {
      mids[e] = m;
      continue;
    }
    const i128 mm = sim::dot_exact(m, m);
    auto root = static_cast<i128>(sim::isqrt(static_cast<sim::u128>(mm)));
    if (mm != 0 && root * root == mm) {
      if (t) ++t->squares;
      if (sqrt_off) root -= 1;
    }
    for (std::size_t c = 0; c < 3; ++c) mids[e][c] = divide(i128{m[c]} << F, root, t ? &t->n_exact : nullptr);
  }
  return mids;
}

// Normals of exact length: on the axes, and Pythagorean directions with every permutation and sign.
std::vector<FxVec> exact_normals(const sim::NumberFormat& f) {
  static constexpr std::array<std::array<int, 4>, 4> kDirections{{{1, 0, 0, 1}, {3, 4, 0, 5}, {1, 2, 2, 3}, {2, 3, 6, 7}}};
  std::vector<FxVec> out;
  for (const auto& dir : kDirections) {
    const std::int64_t v = (std::int64_t{1} << f.coord_frac_bits) / dir[3];  // length r v exactly
    std::array<int, 3> perm{0, 1, 2};
    do {
      for (int signs = 0; signs < 8; ++signs) {
        FxVec n{};
        for (std::size_t c = 0; c < 3; ++c)
          n[c] = (signs >> c & 1 ? -1 : 1) * dir[static_cast<std::size_t>(perm[c])] * v;
        if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
      }
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
  return out;
}

std::vector<sim::TriangleFx> exact_corner_stream(const sim::NumberFormat& f, NormalMode mode, std::size_t want,
                                                 std::uint64_t seed, ExactTally& total) {
  const std::vector<FxVec> normals = exact_normals(f);
  const std::int64_t unit = std::int64_t{1} << (f.coord_frac_bits - 4);  // 1/16
  sim::SplitMix64 rng(seed);
  std::vector<sim::TriangleFx> stream;
  // Patches whose exact t_c, exact n_c, perfect squares an off-by-one makes visible.
  std::size_t t_found = 0, n_found = 0, sqrt_found = 0;
  const bool quadratic = mode == NormalMode::Quadratic;
  for (int tries = 0;
       tries < 100000 && (t_found < want || (quadratic && (n_found < want || sqrt_found < want))); ++tries) {
    // A right triangle with legs 3 and 4 (times 1 or 2 sixteenths) along two axes: two axis edges
    // and a 3-4-5 diagonal.
    sim::TriangleFx tri;
    for (std::size_t c = 0; c < 3; ++c) tri.p[0][c] = (rand_below(rng, 9) - 4) * 2 * unit;
    const auto i = static_cast<std::size_t>(rand_below(rng, 3));
    const std::size_t j = (i + 1 + static_cast<std::size_t>(rand_below(rng, 2))) % 3;
    const std::int64_t scale = 1 + rand_below(rng, 2);
    tri.p[1] = tri.p[0];
    tri.p[2] = tri.p[0];
    tri.p[1][i] += (rng.next() % 2 ? 3 : -3) * scale * unit;
    tri.p[2][j] += (rng.next() % 2 ? 4 : -4) * scale * unit;
    if (rng.next() % 2) std::swap(tri.p[1], tri.p[2]);
    // Often the same normal at an edge's two ends: s = 2N has an exact length.
    for (auto& n : tri.n) n = normals[static_cast<std::size_t>(rand_below(rng, static_cast<std::int64_t>(normals.size())))];
    if (rng.next() % 2) tri.n[1] = tri.n[0];
    if (rng.next() % 2) tri.n[2] = tri.n[1];
    ExactTally t;
    const std::array<FxVec, 3> base = mid_normals(tri, mode, f, false, false, &t);
    const sim::ControlPointsFx cp = sim::compute_control_points(tri, mode, f);
    for (std::size_t e = 0; e < 3; ++e) t.mismatches += base[e] != cp.n[static_cast<std::size_t>(kEdgeSlots[e][2])];
    // The off-by-one results, and whether a vertex of the patch at L = 2 or 4 shows them.
    auto moved = [&](bool div_off, bool sqrt_off) -> std::size_t {
      const std::array<FxVec, 3> off = mid_normals(tri, mode, f, div_off, sqrt_off, nullptr);
      sim::ControlPointsFx changed = cp;
      std::size_t n = 0;
      for (std::size_t e = 0; e < 3; ++e) {
        changed.n[static_cast<std::size_t>(kEdgeSlots[e][2])] = off[e];
        n += off[e] != base[e];
      }
      if (n == 0) return 0;
      for (const int L : {2, 4})
        if (vertex_differs(cp, changed, L, mode, f)) {
          tri.L = std::max(tri.L, L);
          return n;
        }
      return 0;
    };
    tri.L = 1;
    t.div_moved = t.t_exact + t.n_exact ? moved(true, false) : 0;
    t.sqrt_moved = t.squares ? moved(false, true) : 0;
    const bool t_useful = t.t_exact && t.div_moved, n_useful = t.n_exact && t.div_moved;
    const bool useful = (t_found < want && t_useful) || (quadratic && n_found < want && n_useful) ||
                        (quadratic && sqrt_found < want && t.sqrt_moved);
    if (!useful && t.mismatches == 0) continue;
    t_found += t_useful;
    n_found += n_useful;
    sqrt_found += t.sqrt_moved > 0;
    total.t_exact += t.t_exact;
    total.n_exact += t.n_exact;
    total.squares += t.squares;
    total.div_moved += t.div_moved;
    total.sqrt_moved += t.sqrt_moved;
    total.mismatches += t.mismatches;
    stream.push_back(tri);
  }
  renumber(stream);
  return stream;
}

TEST(ExactTiesDivision, ZeroRemaindersAndPerfectSquaresAgreeOnEveryBuild) {
  std::size_t builds = 0;
  for (const std::string& name : fault_free_builds()) {
    ++builds;
    for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect}) {
      const CosimOptions o = build_options(name, mode, 0.2, 61 + static_cast<std::uint64_t>(sim::mode_code(mode)));
      ExactTally t;
      const std::vector<sim::TriangleFx> stream = exact_corner_stream(o.unit.format, mode, 8, o.seed, t);
      const std::string key = name + "_" + std::string(to_string(mode));
      SCOPED_TRACE(key);
      ASSERT_EQ(t.mismatches, 0u) << "the copy of the mid-edge normals reproduces the model";
      ASSERT_GT(t.t_exact, 0u) << "exact projections t_c";
      ASSERT_GE(t.div_moved, 8u) << "exact divisions whose off-by-one moves a vertex";
      if (mode == NormalMode::Quadratic) {
        ASSERT_GT(t.n_exact, 0u) << "exact normalizations n_c";
        ASSERT_GT(t.squares, 0u) << "perfect squares m.m";
        ASSERT_GE(t.sqrt_moved, 8u) << "perfect squares whose off-by-one root moves a vertex";
      }
      RecordProperty(key + "_exact_t", static_cast<int>(t.t_exact));
      RecordProperty(key + "_exact_n", static_cast<int>(t.n_exact));
      RecordProperty(key + "_perfect_squares", static_cast<int>(t.squares));
      RecordProperty(key + "_div_moved_normals", static_cast<int>(t.div_moved));
      RecordProperty(key + "_sqrt_moved_normals", static_cast<int>(t.sqrt_moved));
      RecordProperty(key + "_patches", static_cast<int>(stream.size()));
      const CosimReport r = run_cosim(stream, o);
      EXPECT_TRUE(r.passed) << format_report(r, o);
      if (!r.passed) return;
    }
  }
  EXPECT_GE(builds, 1u);
}

// ============================================================================ 5. scalar tags
// The tag pass's scale v = round_half_up(N 2^F + s V, F) (add_scaled and the X blend;
// rtl/tess_cpg_tag.sv, scale): with sharpness 1/2 (s = ±2^(F-1)) every odd component of the
// crease vector Δ ties in N + sσΔ, and half of the components of (1 - σ) N + σ N' tie too; bias
// 1/2 ties Y's. The sharp normal N' = normalize(v) is the tagged corner's normal-net entry 2N',
// which its corner vertex outputs exactly, so a tie that moves N' moves that vertex.
struct TagTally {
  std::size_t sharp_ties = 0, y_ties = 0, x_ties = 0;  // components tied in N', Y and X's scales
  std::size_t moved_corners = 0;  // corner normals half down changes
  std::size_t mismatches = 0;     // the copy's corner normal differs from the model's
};

FxVec add_scaled_rounded(const FxVec& a, std::int64_t k, const FxVec& b, const sim::NumberFormat& f, bool down,
                         std::size_t* ties) {
  const int F = f.coord_frac_bits;
  std::uint8_t flags = 0;
  FxVec r{};
  for (std::size_t c = 0; c < 3; ++c) {
    const i128 x = (i128{a[c]} << F) + i128{k} * b[c];
    if (ties && (x & ((i128{1} << F) - 1)) == (i128{1} << (F - 1))) ++*ties;
    r[c] = sim::saturate((x + (i128{1} << (F - 1)) - (down ? 1 : 0)) >> F, f, flags);
  }
  return r;
}

FxVec normalize_copy(const FxVec& v, const sim::NumberFormat& f) {
  std::uint8_t flags = 0;
  const i128 norm = static_cast<i128>(sim::isqrt(static_cast<sim::u128>(sim::dot_exact(v, v))));
  FxVec r{};
  for (std::size_t c = 0; c < 3; ++c) r[c] = sim::div_trunc(i128{v[c]} << f.coord_frac_bits, norm, f, flags);
  return r;
}

std::vector<sim::TriangleFx> tag_tie_stream(const sim::NumberFormat& f, std::size_t want, std::uint64_t seed,
                                            TagTally& total) {
  const int F = f.coord_frac_bits;
  const std::int64_t half = std::int64_t{1} << (F - 1);
  const std::array<int, 3> corner_slot{net_index(0, 0, 2), net_index(2, 0, 2), net_index(0, 2, 2)};
  const std::vector<sim::TriangleFx> shapes = random_triangles(8 * want, seed, f, 2, 0.0);
  sim::SplitMix64 rng(seed);
  std::vector<sim::TriangleFx> stream;
  for (std::size_t i = 0; i < shapes.size() && stream.size() < want; ++i) {
    sim::TriangleFx tri = shapes[i];
    // One or two tagged corners: Δ with odd components, σ = 1/2, β 1/2 or drawn, θ 0 or drawn.
    const int tagged = 1 + static_cast<int>(i % 2);
    for (int v = 0; v < tagged; ++v) {
      sim::TagsFx& tags = tri.tags[static_cast<std::size_t>(v)];
      for (auto& x : tags.delta) x = rand_fx(rng, -0.8, 0.8, f) | 1;
      tags.sigma = half;
      tags.beta = rng.next() % 2 ? half : rand_fx(rng, -1, 1, f);
      tags.theta = rng.next() % 2 ? 0 : rand_fx(rng, -0.5, 0.5, f);
    }
    const sim::ControlPointsFx cp = sim::compute_control_points(tri, NormalMode::Quadratic, f);
    TagTally t;
    FxVec e1{}, e2{};
    for (std::size_t c = 0; c < 3; ++c) {
      e1[c] = tri.p[1][c] - tri.p[0][c];
      e2[c] = tri.p[2][c] - tri.p[0][c];
    }
    const std::array<i128, 3> face{i128{e1[1]} * e2[2] - i128{e1[2]} * e2[1], i128{e1[2]} * e2[0] - i128{e1[0]} * e2[2],
                                   i128{e1[0]} * e2[1] - i128{e1[1]} * e2[0]};
    for (int v = 0; v < tagged; ++v) {
      const sim::TagsFx& tags = tri.tags[static_cast<std::size_t>(v)];
      const FxVec& n = tri.n[static_cast<std::size_t>(v)];
      const i128 side = face[0] * tags.delta[0] + face[1] * tags.delta[1] + face[2] * tags.delta[2];
      const std::int64_t s = side >= 0 ? tags.sigma : -tags.sigma;
      const FxVec sharp = normalize_copy(add_scaled_rounded(n, s, tags.delta, f, false, &t.sharp_ties), f);
      const FxVec sharp_down = normalize_copy(add_scaled_rounded(n, s, tags.delta, f, true, nullptr), f);
      add_scaled_rounded(n, tags.beta, tags.delta, f, false, &t.y_ties);
      FxVec moved{};  // X's scale: N 2^F + σ (N' - N)
      for (std::size_t c = 0; c < 3; ++c) moved[c] = sharp[c] - n[c];
      add_scaled_rounded(n, tags.sigma, moved, f, false, &t.x_ties);
      std::uint8_t flags = 0;
      FxVec entry{}, entry_down{};
      for (std::size_t c = 0; c < 3; ++c) {
        entry[c] = sim::saturate(i128{2} * sharp[c], f, flags);
        entry_down[c] = sim::saturate(i128{2} * sharp_down[c], f, flags);
      }
      t.mismatches += entry != cp.n[static_cast<std::size_t>(corner_slot[static_cast<std::size_t>(v)])];
      t.moved_corners += entry_down != entry;
    }
    if (t.moved_corners == 0 && t.mismatches == 0) continue;
    total.sharp_ties += t.sharp_ties;
    total.y_ties += t.y_ties;
    total.x_ties += t.x_ties;
    total.moved_corners += t.moved_corners;
    total.mismatches += t.mismatches;
    stream.push_back(tri);
  }
  renumber(stream);
  return stream;
}

TEST(ExactTiesTags, ScaleTiesAgreeOnEveryBuildThatTakesTags) {
  std::size_t builds = 0;
  for (const std::string& name : fault_free_builds()) {
    if (build_config(name).cpg_tags == 0) continue;
    ++builds;
    const CosimOptions o = build_options(name, NormalMode::Quadratic, 0.2, 71);
    TagTally t;
    const std::vector<sim::TriangleFx> stream = tag_tie_stream(o.unit.format, 12, o.seed, t);
    SCOPED_TRACE(name);
    ASSERT_EQ(t.mismatches, 0u) << "the copy of the sharp normal reproduces the model";
    ASSERT_EQ(stream.size(), 12u) << "tagged corners whose sharp normal a half-down scale moves";
    EXPECT_GT(t.y_ties, 0u);
    EXPECT_GT(t.x_ties, 0u);
    RecordProperty(name + "_sharp_ties", static_cast<int>(t.sharp_ties));
    RecordProperty(name + "_y_ties", static_cast<int>(t.y_ties));
    RecordProperty(name + "_x_ties", static_cast<int>(t.x_ties));
    RecordProperty(name + "_moved_corner_normals", static_cast<int>(t.moved_corners));
    const CosimReport r = run_cosim(stream, o);
    EXPECT_TRUE(r.passed) << format_report(r, o);
    if (!r.passed) return;
  }
  EXPECT_GE(builds, 1u);
}

// The tag pass's tangent point b = sat(d + round_half_up(Π m, 2F)), d = Pj + round((1 - θ)(Pk - Pj)
// / 3), Π = -n.(d - Pj) (stpn_tangent; rtl/tess_cpg_tag.sv, tan3) ties where Π m_c = 2^(2F-1)
// mod 2^2F. On a crease (both ends tagged) n is the corner's input normal N, which is free: with
// θ = -1 and a long edge (|d - Pj| near 0.8), N is solved for so that N.(d - Pj) = 1/2 exactly (a
// linear Diophantine equation in two of its components), and every odd component of m = Y ties.
struct CornerDirs {
  FxVec sharp{}, y{}, x{};  // N' (N when untagged), Y, X
};

// A non-neutral corner's N', Y and X as compute_control_points makes them.
CornerDirs corner_dirs(const sim::TriangleFx& tri, std::size_t v, const sim::NumberFormat& f) {
  const int F = f.coord_frac_bits;
  const sim::TagsFx& tags = tri.tags[v];
  const FxVec& n = tri.n[v];
  CornerDirs out;
  out.sharp = n;
  if (tags.tagged()) {
    FxVec e1{}, e2{};
    for (std::size_t c = 0; c < 3; ++c) {
      e1[c] = tri.p[1][c] - tri.p[0][c];
      e2[c] = tri.p[2][c] - tri.p[0][c];
    }
    const std::array<i128, 3> face{i128{e1[1]} * e2[2] - i128{e1[2]} * e2[1], i128{e1[2]} * e2[0] - i128{e1[0]} * e2[2],
                                   i128{e1[0]} * e2[1] - i128{e1[1]} * e2[0]};
    const i128 side = face[0] * tags.delta[0] + face[1] * tags.delta[1] + face[2] * tags.delta[2];
    out.sharp = normalize_copy(add_scaled_rounded(n, side >= 0 ? tags.sigma : -tags.sigma, tags.delta, f, false, nullptr), f);
    out.y = normalize_copy(add_scaled_rounded(n, tags.beta, tags.delta, f, false, nullptr), f);
  }
  std::uint8_t flags = 0;
  FxVec blend{};
  for (std::size_t c = 0; c < 3; ++c)
    blend[c] = sim::saturate(sim::round_shift(((i128{1} << F) - tags.sigma) * n[c] + i128{tags.sigma} * out.sharp[c], F), f, flags);
  out.x = normalize_copy(blend, f);
  return out;
}

// stpn_tangent with d + Π m rounded half down when `down`, counting the tied components.
FxVec stpn_tangent_copy(const FxVec& pj, const FxVec& pk, std::int64_t theta, const FxVec& n, const FxVec& m,
                        const sim::NumberFormat& f, bool down, std::size_t* ties) {
  const int F = f.coord_frac_bits;
  std::uint8_t flags = 0;
  FxVec d{}, dj{};
  for (std::size_t c = 0; c < 3; ++c) {
    const i128 step = ((i128{1} << F) - theta) * (i128{pk[c]} - pj[c]);
    d[c] = sim::saturate(i128{pj[c]} + sim::mul_const(step, 2 * F, sim::one_third(f), f, flags), f, flags);
    dj[c] = d[c] - pj[c];
  }
  const i128 project = -sim::dot_exact(n, dj);
  const i128 mask = (i128{1} << (2 * F)) - 1, half = i128{1} << (2 * F - 1);
  FxVec b{};
  for (std::size_t c = 0; c < 3; ++c) {
    const i128 pm = project * m[c];
    if (ties && (pm & mask) == half) ++*ties;
    b[c] = sim::saturate(i128{d[c]} + ((pm + half - (down ? 1 : 0)) >> (2 * F)), f, flags);
  }
  return b;
}

struct CreaseTally {
  std::size_t ties = 0;           // components of tagged tangent points whose d + Π m ties
  std::size_t moved_points = 0;   // tagged tangent points half down moves
  std::size_t mismatches = 0;     // the copy's half-up tangent points differ from the model's
};

// The control points with every tagged tangent point's d + Π m rounded half down (b111 follows).
sim::ControlPointsFx tan_half_down(const sim::TriangleFx& tri, const sim::NumberFormat& f, CreaseTally& t) {
  const sim::ControlPointsFx cp = sim::compute_control_points(tri, NormalMode::Quadratic, f);
  sim::ControlPointsFx down = cp;
  std::array<CornerDirs, 3> dirs{};
  for (std::size_t v = 0; v < 3; ++v)
    if (!tri.tags[v].neutral()) dirs[v] = corner_dirs(tri, v, f);
  for (std::size_t e = 0; e < 3; ++e)
    for (std::size_t end = 0; end < 2; ++end) {
      const std::size_t near = end == 0 ? e : (e + 1) % 3, far = end == 0 ? (e + 1) % 3 : e;
      if (tri.tags[near].neutral()) continue;
      const bool crease = tri.tags[near].tagged() && tri.tags[far].tagged();
      const FxVec& n = crease ? tri.n[near] : dirs[near].x;
      const FxVec& m = crease ? dirs[near].y : dirs[near].x;
      const auto slot = static_cast<std::size_t>(kEdgeSlots[e][end]);
      std::size_t ties = 0;
      t.mismatches += stpn_tangent_copy(tri.p[near], tri.p[far], tri.tags[near].theta, n, m, f, false, &ties) != cp.b[slot];
      if (ties == 0) continue;
      t.ties += ties;
      down.b[slot] = stpn_tangent_copy(tri.p[near], tri.p[far], tri.tags[near].theta, n, m, f, true, nullptr);
      t.moved_points += down.b[slot] != cp.b[slot];
    }
  t.mismatches += b111_of(cp, tri, f) != cp.b[kCentre];
  down.b[kCentre] = b111_of(down, tri, f);
  return down;
}

// A triangle whose crease P1 -> P2 ties d + Π m at P1's tangent point, or nothing.
std::optional<sim::TriangleFx> solve_crease_tie(const sim::NumberFormat& f, sim::SplitMix64& rng) {
  const int F = f.coord_frac_bits;
  const std::int64_t one = std::int64_t{1} << F;
  sim::TriangleFx tri;
  const glm::dvec3 p0(0.6 * (2 * rng.uniform() - 1), 0.6 * (2 * rng.uniform() - 1), 0.6 * (2 * rng.uniform() - 1));
  const glm::dvec3 p1 = p0 + (1.0 + 0.3 * rng.uniform()) * random_unit(rng);
  const glm::dvec3 p2 = 0.5 * (p0 + p1) + 0.6 * random_unit(rng);
  tri.p = {sim::quantize(p0, f), sim::quantize(p1, f), sim::quantize(p2, f)};
  tri.tags[0].theta = -one;
  // d - Pj of P1's tangent point: the model's own rounding of (1 - θ)(P2 - P1) / 3.
  FxVec dj{};
  std::uint8_t flags = 0;
  for (std::size_t c = 0; c < 3; ++c)
    dj[c] = sim::mul_const(2 * (i128{tri.p[1][c]} - tri.p[0][c]) << F, 2 * F, sim::one_third(f), f, flags);
  const std::size_t c2 = static_cast<std::size_t>(rand_below(rng, 3)), c0 = (c2 + 1) % 3, c1 = (c2 + 2) % 3;
  std::int64_t g0 = 0, g1 = 0;
  if (dj[c0] == 0 || dj[c1] == 0 || ext_gcd(dj[c0], dj[c1], g0, g1) != 1) return std::nullopt;
  // N.dj = 2^(2F-1): N[c0] dj[c0] + N[c1] dj[c1] = R, the solution nearest the line's closest
  // point, or a neighbour that brings |N| nearer 1.
  FxVec n{};
  n[c2] = rand_fx(rng, -0.4, 0.4, f);
  const i128 R = (i128{1} << (2 * F - 1)) - i128{n[c2]} * dj[c2];
  const double a0 = static_cast<double>(dj[c0]), a1 = static_cast<double>(dj[c1]);
  const double closest0 = static_cast<double>(R) * a0 / (a0 * a0 + a1 * a1);
  const i128 base0 = R * g0;
  const auto k = static_cast<i128>(std::llround((closest0 - static_cast<double>(base0)) / a1));
  double best = 1e300;
  for (i128 kk = k - 2; kk <= k + 2; ++kk) {
    const i128 n0 = base0 + kk * dj[c1];
    const i128 rest = R - n0 * dj[c0];
    if (rest % dj[c1] != 0) continue;
    const i128 n1 = rest / dj[c1];
    if (n0 > one || n0 < -one || n1 > one || n1 < -one) continue;
    FxVec cand = n;
    cand[c0] = static_cast<std::int64_t>(n0);
    cand[c1] = static_cast<std::int64_t>(n1);
    const double len = std::sqrt(static_cast<double>(sim::dot_exact(cand, cand))) / static_cast<double>(one);
    if (std::abs(len - 1) < best) {
      best = std::abs(len - 1);
      tri.n[0] = cand;
    }
  }
  if (best > 0.35 || sim::dot_exact(tri.n[0], dj) != (i128{1} << (2 * F - 1))) return std::nullopt;
  tri.n[1] = sim::quantize(random_unit(rng), f);
  tri.n[2] = sim::quantize(random_unit(rng), f);
  for (std::size_t v = 0; v < 2; ++v) {  // the crease's two corners tagged
    sim::TagsFx& tags = tri.tags[v];
    tags.delta = sim::quantize(0.5 * random_unit(rng), f);
    tags.sigma = rand_fx(rng, 0, 1, f);
    tags.beta = rand_fx(rng, -1, 1, f);
  }
  tri.tags[1].theta = rand_fx(rng, -1, 1, f);
  return tri;
}

std::vector<sim::TriangleFx> crease_tie_stream(const sim::NumberFormat& f, std::size_t want, std::uint64_t seed,
                                               CreaseTally& tally) {
  sim::SplitMix64 rng(seed);
  std::vector<sim::TriangleFx> stream;
  for (int tries = 0; tries < 100000 && stream.size() < want; ++tries) {
    std::optional<sim::TriangleFx> tri = solve_crease_tie(f, rng);
    if (!tri) continue;
    CreaseTally t;
    const sim::ControlPointsFx down = tan_half_down(*tri, f, t);
    tally.mismatches += t.mismatches;
    if (t.mismatches != 0 || t.moved_points == 0) continue;
    const sim::ControlPointsFx cp = sim::compute_control_points(*tri, NormalMode::Quadratic, f);
    tri->L = 0;
    for (int L = 1; L <= 8 && tri->L == 0; ++L)
      if (vertex_differs(cp, down, L, NormalMode::Quadratic, f)) tri->L = L;
    if (tri->L == 0) continue;
    tally.ties += t.ties;
    tally.moved_points += t.moved_points;
    stream.push_back(*tri);
  }
  renumber(stream);
  return stream;
}

TEST(ExactTiesTags, CreaseTangentTiesAgreeOnEveryBuildThatTakesTags) {
  std::size_t builds = 0;
  for (const std::string& name : fault_free_builds()) {
    if (build_config(name).cpg_tags == 0) continue;
    ++builds;
    const CosimOptions o = build_options(name, NormalMode::Quadratic, 0.2, 73);
    CreaseTally t;
    const std::vector<sim::TriangleFx> stream = crease_tie_stream(o.unit.format, 8, o.seed, t);
    SCOPED_TRACE(name);
    ASSERT_EQ(t.mismatches, 0u) << "the copy of the tagged tangent points reproduces the model";
    ASSERT_EQ(stream.size(), 8u) << "the solver finds creases whose tangent point and a vertex a half-down d + Π m moves";
    RecordProperty(name + "_crease_tangent_ties", static_cast<int>(t.ties));
    RecordProperty(name + "_crease_moved_tangent_points", static_cast<int>(t.moved_points));
    const CosimReport r = run_cosim(stream, o);
    EXPECT_TRUE(r.passed) << format_report(r, o);
    if (!r.passed) return;
  }
  EXPECT_GE(builds, 1u);
}

// ============================================================================ impossible ties
// mul_const(x, frac, c) rounds x c / 2^s, s = frac - F + G. c = round(2^G / 3) and round(2^G / 12)
// are odd, so x c ties exactly when v2(x) = s - 1: |x| >= 2^(s-1) and the tie's value is at least
// c / 2 LSB. Where (c - 1) / 2 exceeds 2^(W-1) both roundings of every tie saturate to the same
// end of the range, and a half-down rounding there changes nothing: the tangent points (3F
// fraction bits in), b111 (F) and the tag pass's (1 - θ)(Pk - Pj) / 3 (2F).
TEST(ExactTiesImpossible, DivisionsByThreeAndTwelveTieOnlyBeyondTheRange) {
  for (const std::string& name : fault_free_builds()) {
    const sim::NumberFormat f = build_config(name).format;
    const int F = f.coord_frac_bits, G = sim::const_frac_bits(f);
    struct Site {
      const char* what;
      int frac;
      std::int64_t c;
    };
    for (const Site& site : {Site{"tangent", 3 * F, sim::one_third(f)}, Site{"b111", F, sim::one_twelfth(f)},
                             Site{"tag_third", 2 * F, sim::one_third(f)}}) {
      SCOPED_TRACE(name + " " + site.what);
      const int s = site.frac - F + G;
      ASSERT_EQ(site.c % 2, 1) << "an odd constant: x c ties only when v2(x) = s - 1";
      EXPECT_GT((site.c - 1) / 2, std::int64_t{1} << (f.coord_width() - 1)) << "the smallest tie lies in the range";
      // The smallest ties and the next ones, both signs: half up and half down give the same.
      for (const i128 x : {i128{1} << (s - 1), -(i128{1} << (s - 1)), i128{3} << (s - 1), -(i128{3} << (s - 1))}) {
        std::uint8_t up_flags = 0, down_flags = 0;
        const std::int64_t up = sim::mul_const(x, site.frac, site.c, f, up_flags);
        const std::int64_t down = sim::saturate((x * site.c + (i128{1} << (s - 1)) - 1) >> s, f, down_flags);
        ASSERT_EQ((x * site.c) & ((i128{1} << s) - 1), i128{1} << (s - 1)) << "a tie";
        EXPECT_EQ(up, down);
        EXPECT_EQ(up_flags, sim::kFlagSaturated);
        EXPECT_EQ(down_flags, sim::kFlagSaturated);
      }
      RecordProperty(name + "_" + site.what + "_smallest_tie_lsb", static_cast<int>(site.c / 2));
      RecordProperty(name + "_" + site.what + "_range_lsb", static_cast<int>(std::int64_t{1} << (f.coord_width() - 1)));
    }
  }
}

// bary_weight(j, L) = round(j 2^B / L) ties when j 2^(B+1) = L mod 2L: never for B >= 7, L <= 64.
TEST(ExactTiesImpossible, BaryWeightsNeverTie) {
  for (const std::string& name : fault_free_builds()) {
    const int B = build_config(name).format.bary_bits;
    std::size_t ties = 0;
    for (int L = 1; L <= kMaxTessFactor; ++L)
      for (int j = 0; j <= L; ++j) {
        ties += ((std::int64_t{j} << (B + 1)) % (2 * L)) == L;
        EXPECT_EQ(sim::bary_weight(j, L, B) + sim::bary_weight(L - j, L, B), std::int64_t{1} << B) << L << " " << j;
      }
    EXPECT_EQ(ties, 0u) << name << " B = " << B;
  }
}

// The FSU's reciprocals R(n) = round(2^16 / n), n = 1..64, tie when 2 (2^16 mod n) = n: never.
TEST(ExactTiesImpossible, ReciprocalTableNeverTies) {
  for (int n = 1; n <= kMaxTessFactor; ++n) {
    EXPECT_NE(2 * (kFixed16One % n), n) << n;
    EXPECT_EQ(sim::fixed16_reciprocal(n), (kFixed16One + n / 2) / n);
  }
}

// Integer partitioning: every half factor is a whole number (φ = 0), so a point's blend
// i' R(n) 2^16 is a multiple of 2^16, and every factor is even in 16.16, so (factor + 1) >> 1
// drops a quarter, never a half: only the ring offset and its half can tie.
TEST(ExactTiesImpossible, IntegerPartitioningBlendsAndHalvesNeverTie) {
  for (int k = 1; k <= kMaxTessFactor; ++k) {
    const Fixed16 factor = k * kFixed16One;
    const sim::D3D11Edge e = sim::d3d11_edge(factor, k % 2 == 1);
    EXPECT_EQ(e.half_fraction, 0) << k;
    EXPECT_EQ(e.ceil_weight, 0u) << k;
    EXPECT_EQ(e.floor_weight % kFixed16One, 0u) << k;
    EXPECT_EQ(factor % 2, 0) << k;
  }
}

}  // namespace
}  // namespace tessim::cosim
