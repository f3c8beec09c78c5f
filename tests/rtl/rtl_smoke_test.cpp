// Smoke tests of every Verilated configuration on its own (no cycle model): the vertex stream
// of each patch against an independent evaluation of compute_control_points and int_op, the
// corners exactly, the CPG's cycle count through the first vertex's timing, the counters'
// bookkeeping, backpressure, the X-randomised build, the injected faults and waveforms.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <numeric>
#include <random>
#include <vector>

#include "model/base/error.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/base/fixed.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim {
namespace {

using sim::FxVec;
using sim::TriangleFx;
using sim::VertexFx;

// ---- the expected output, computed from the C++ definitions of the arithmetic ----

// The untimed datapath (sim/values/datapath.hpp): control points, then de Casteljau level by level.
std::vector<VertexFx> expected_patch(const TriangleFx& tri, NormalMode mode, const sim::NumberFormat& f) {
  return sim::evaluate_patch(tri, mode, f);
}

// Cycles in which the scheduler issues the ops of a vertex that has all N INT blocks to
// itself (the oldest context always does), latency 1: greedy in op order, a dependent op one
// cycle after its inputs issued.
int lone_vertex_issue_cycles(int n_blocks, bool linear) {
  std::uint32_t issued = sim::int_ops::absent_ops(linear ? NormalMode::Linear : NormalMode::Quadratic);
  std::uint32_t done = issued;
  int cycles = 0;
  while (done != (1u << 14) - 1) {
    ++cycles;
    std::uint32_t now = 0;
    int slots = n_blocks;
    for (int o = 0; o < 14 && slots > 0; ++o) {
      const std::uint32_t deps = sim::int_ops::kIntOps[static_cast<std::size_t>(o)].depends;
      if (!(issued >> o & 1u) && (done & deps) == deps) {
        now |= 1u << o;
        --slots;
      }
    }
    issued |= now;
    done |= now;
  }
  return cycles;
}

// ---- stimulus ----

const sim::NumberFormat kFormat{};  // the verilated widths: I = 3, F = 20, B = 16

FxVec fx(double x, double y, double z) {
  auto q = [](double a) { return static_cast<std::int64_t>(std::floor(a * (1 << kFormat.coord_frac_bits) + 0.5)); };
  return {q(x), q(y), q(z)};
}

FxVec unit_fx(double x, double y, double z) {
  const double len = std::sqrt(x * x + y * y + z * z);
  return fx(x / len, y / len, z / len);
}

TriangleFx make_tri(std::array<FxVec, 3> p, std::array<FxVec, 3> n, int L, std::uint32_t id) {
  TriangleFx t;
  t.p = p;
  t.n = n;
  t.L = L;
  t.id = id;
  return t;
}

// A curved patch, a zero-length edge (P1 = P2: division by zero), and one whose tangent points
// leave the coordinate range (saturation).
std::vector<TriangleFx> fixed_triangles() {
  return {
      make_tri({fx(0, 0, 0), fx(1, 0, 0.2), fx(0.1, 1.1, -0.3)},
               {unit_fx(-0.2, -0.1, 1), unit_fx(0.3, 0, 1), unit_fx(0, 0.4, 0.9)}, 4, 7),
      make_tri({fx(0.5, 0.5, 0.5), fx(0.5, 0.5, 0.5), fx(-1, 0.25, 0)},
               {unit_fx(0, 0, 1), unit_fx(0, 1, 1), unit_fx(1, 0, 1)}, 3, 8),
      make_tri({fx(7.5, -7.9, 7.0), fx(-7.9, 7.9, -7.5), fx(7.9, 7.9, -7.9)},
               {unit_fx(1, -1, 1), unit_fx(-1, 1, -1), unit_fx(1, 1, -1)}, 2, 9),
      make_tri({fx(-0.3, 0.2, 0.1), fx(0.4, -0.6, 0.0), fx(0.2, 0.5, 0.7)},
               {unit_fx(-1, 0.5, 0.2), unit_fx(0.1, -1, 0.3), unit_fx(0.2, 0.6, 1)}, 1, 10),
  };
}

// Random triangles over the whole coordinate range, normals of any length (the unit must
// match the reference even on garbage), factors 1..6.
std::vector<TriangleFx> random_triangles(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::int64_t lim = kFormat.coord_max();
  std::uniform_int_distribution<std::int64_t> any(-lim - 1, lim);
  std::uniform_int_distribution<std::int64_t> small(-(lim >> 3), lim >> 3);
  std::uniform_int_distribution<int> factor(1, 6), pick(0, 3);
  std::vector<TriangleFx> tris;
  for (int i = 0; i < count; ++i) {
    TriangleFx t;
    const bool wide = pick(rng) == 0;
    for (int v = 0; v < 3; ++v) {
      for (int c = 0; c < 3; ++c) {
        t.p[v][c] = wide ? any(rng) : small(rng);
        t.n[v][c] = pick(rng) == 0 ? any(rng) : small(rng) >> 1;
      }
    }
    if (pick(rng) == 0) t.p[1] = t.p[0];  // a zero-length edge now and then
    t.L = factor(rng);
    t.id = 1000u + static_cast<std::uint32_t>(i);
    tris.push_back(t);
  }
  return tris;
}

// ---- running a stream ----

struct Received {
  std::uint64_t cycle;  // cycle in which the GPE side accepted it
  VertexFx vertex;
};

struct RunResult {
  std::vector<Received> vertices;
  std::vector<std::uint64_t> tri_accept_cycles;
  sim::UnitCounters counters;
  std::uint64_t cycles = 0;
};

// Feeds `tris` as fast as tri_ready allows and accepts vertices when ready(cycle) says so,
// until `expected` vertices came out (or a generous cycle limit passed).
RunResult run_stream(rtl::RtlUnit& unit, NormalMode mode, const std::vector<TriangleFx>& tris,
                     std::size_t expected, const std::function<bool(std::uint64_t)>& ready) {
  unit.set_mode(mode);
  unit.reset();
  RunResult r;
  std::deque<TriangleFx> queue(tris.begin(), tris.end());
  const std::uint64_t limit = 2000 + 400 * tris.size() + 60 * expected;
  while (r.vertices.size() < expected && unit.cycle() < limit) {
    sim::UnitInputs in;
    in.tri_valid = !queue.empty();
    if (in.tri_valid) in.tri = queue.front();
    in.vtx_ready = ready(unit.cycle());
    if (in.tri_valid && unit.tri_ready()) {
      r.tri_accept_cycles.push_back(unit.cycle());
      queue.pop_front();
    }
    if (in.vtx_ready && unit.vtx_valid()) r.vertices.push_back({unit.cycle(), unit.vtx()});
    unit.tick(in);
  }
  r.counters = unit.counters();
  r.cycles = unit.cycle();
  return r;
}

std::vector<VertexFx> expected_stream(const std::vector<TriangleFx>& tris, NormalMode mode) {
  std::vector<VertexFx> all;
  for (const TriangleFx& t : tris) {
    const std::vector<VertexFx> p = expected_patch(t, mode, kFormat);
    all.insert(all.end(), p.begin(), p.end());
  }
  return all;
}

std::string describe(const VertexFx& v) {
  std::string s = "id " + std::to_string(v.id) + " (j,k)=(" + std::to_string(v.j) + "," +
                  std::to_string(v.k) + ") L " + std::to_string(v.L) + " pos";
  for (auto c : v.pos) s += " " + std::to_string(c);
  s += " nrm";
  for (auto c : v.nrm) s += " " + std::to_string(c);
  s += " u " + std::to_string(v.u) + " v " + std::to_string(v.v) + " last " +
       std::to_string(v.last) + " flags " + std::to_string(v.flags);
  return s;
}

void expect_stream_equal(const std::vector<Received>& got, const std::vector<VertexFx>& want,
                         const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got[i].vertex, want[i]) << what << ": vertex " << i << "\n  got  "
                                      << describe(got[i].vertex) << "\n  want " << describe(want[i]);
  }
}

int ops_per_vertex(NormalMode mode) { return mode == NormalMode::Linear ? 11 : 14; }

void expect_counters_consistent(const RunResult& r, const rtl::RtlUnit& unit, std::size_t triangles,
                                NormalMode mode, const std::string& what) {
  const sim::UnitCounters& k = r.counters;
  EXPECT_EQ(k.cycles, r.cycles) << what;
  EXPECT_EQ(k.triangles_in, triangles) << what;
  EXPECT_EQ(k.vertices_out, r.vertices.size()) << what;
  EXPECT_EQ(k.int_blocks, unit.int_blocks()) << what;
  EXPECT_EQ(k.te.total(), k.cycles) << what;
  // Cycles that may issue: context_limited (younger contexts), int_limited (all N), busy (>= 1).
  using sim::TeClass;
  const std::uint64_t may_issue = k.te[TeClass::ContextLimited] + k.te[TeClass::IntLimited] + k.te[TeClass::Busy];
  EXPECT_EQ(k.cpg.total(), k.cycles) << what;
  EXPECT_EQ(k.cpg[sim::CpgClass::WaitGpe], 0u) << what;
  std::uint64_t ops = 0, max_busy = 0;
  for (int i = 0; i < unit.int_blocks(); ++i) {
    ops += k.int_busy[i];
    max_busy = std::max(max_busy, k.int_busy[i]);
    EXPECT_LE(k.int_busy[i], may_issue) << what << ": INT block " << i;
  }
  for (int i = unit.int_blocks(); i < sim::kMaxIntBlocks; ++i) EXPECT_EQ(k.int_busy[i], 0u) << what;
  // Every op of every vertex issued exactly once; block 0 is busy in every busy and int_limited
  // cycle, and the last block in every int_limited one.
  EXPECT_EQ(ops, r.vertices.size() * static_cast<std::uint64_t>(ops_per_vertex(mode))) << what;
  EXPECT_GE(k.int_busy[0], k.te[TeClass::Busy] + k.te[TeClass::IntLimited]) << what;
  EXPECT_GE(k.int_busy[unit.int_blocks() - 1], k.te[TeClass::IntLimited]) << what;
  // Each triangle keeps one CPG copy busy for C + 1 cycles; at most Mc copies are busy in a cycle.
  EXPECT_GE(k.cpg[sim::CpgClass::Busy],
            triangles * static_cast<std::uint64_t>(sim::cpg_cycles(mode, unit.config().format, unit.config().cpg) + 1) /
                static_cast<std::uint64_t>(unit.config().cpg.copies))
      << what;
}

bool always(std::uint64_t) { return true; }

constexpr std::array<NormalMode, 3> kModes{NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

// ---- tests ----

TEST(RtlSmoke, VariantsAreListedAndUnknownNamesRejected) {
  const std::vector<std::string> names = rtl::rtl_variants();
  EXPECT_EQ(names, (std::vector<std::string>{"n1", "n2", "n3", "n4", "n2_verif", "n3_lat3", "n1_r4", "n2_l3r8",
                                             "n4_l3r24", "n2_w28b20", "n1_w20b18", "n2_bug1", "n2_bug2"}));
  EXPECT_THROW(rtl::make_rtl_unit("n9"), std::invalid_argument);
  auto unit = rtl::make_rtl_unit("n3");
  EXPECT_EQ(unit->int_blocks(), 3);
  EXPECT_EQ(unit->contexts(), 4);
  EXPECT_EQ(unit->int_latency(), 1);
  EXPECT_EQ(unit->format(), kFormat);
  EXPECT_THROW(unit->set_mode(NormalMode::Derivative), std::invalid_argument);
  // The parameters of a variant away from the defaults reach the configuration.
  auto lat3 = rtl::make_rtl_unit("n3_lat3");
  EXPECT_EQ(lat3->int_blocks(), 3);
  EXPECT_EQ(lat3->contexts(), 6);
  EXPECT_EQ(lat3->int_latency(), 3);
  EXPECT_EQ(lat3->config().cpg, (sim::CpgVariant{3, 5, 2, 1}));
  EXPECT_EQ(rtl::make_rtl_unit("n1_r4")->config().cpg, (sim::CpgVariant{1, 4, 3}));
  EXPECT_EQ(rtl::make_rtl_unit("n2_l3r8")->config().cpg, (sim::CpgVariant{3, 8, 2, 1}));
  EXPECT_EQ(rtl::make_rtl_unit("n4_l3r24")->config().cpg, (sim::CpgVariant{3, 24, 5, 1}));
  // The free parameters away from their defaults: FIFO depths and widths.
  const sim::HardwareConfig w28 = rtl::make_rtl_unit("n2_w28b20")->config();
  EXPECT_EQ(w28.tri_fifo_depth, 3);
  EXPECT_EQ(w28.vtx_fifo_depth, 5);
  EXPECT_EQ(w28.cp_buffers, 3);
  EXPECT_EQ(w28.format.coord_width(), 28);
  EXPECT_EQ(w28.format.bary_bits, 20);
  const sim::HardwareConfig w20 = rtl::make_rtl_unit("n1_w20b18")->config();
  EXPECT_EQ(w20.tri_fifo_depth, 5);
  EXPECT_EQ(w20.vtx_fifo_depth, 3);
  EXPECT_EQ(w20.cp_buffers, 1);
  EXPECT_EQ(w20.format.coord_width(), 20);
  EXPECT_EQ(w20.format.bary_bits, 18);
  EXPECT_EQ(w20.int_latency, 2);
  EXPECT_EQ(w20.te_contexts, 3);
  // A configuration finds the build that implements its hardware; fault builds are never chosen.
  sim::HardwareConfig hw;
  EXPECT_EQ(rtl::find_rtl_variant(hw, false), "n2");
  EXPECT_EQ(rtl::find_rtl_variant(hw, true), "n2_verif");
  hw.cpg = {3, 8, 2, 1};
  EXPECT_EQ(rtl::find_rtl_variant(hw, false), std::nullopt) << "n2_l3r8 takes scalar tags";
  hw.cpg_tags = 1;
  EXPECT_EQ(rtl::find_rtl_variant(hw, false), std::nullopt) << "n2_l3r8 takes alpha";
  hw.format.alpha_bits = 8;
  EXPECT_EQ(rtl::find_rtl_variant(hw, false), "n2_l3r8");
  EXPECT_EQ(rtl::make_rtl_unit("n2_l3r8")->config().format.alpha_bits, 8);
  EXPECT_EQ(rtl::make_rtl_unit("n2_l3r8")->config().cpg_tags, 1);
  EXPECT_EQ(rtl::make_rtl_unit("n2")->config().cpg_tags, 0);
  hw.cpg = {3, 7};
  EXPECT_EQ(rtl::find_rtl_variant(hw, false), std::nullopt);
}

TEST(RtlSmoke, ConfigurationCheckNamesTheFirstDifference) {
  auto unit = rtl::make_rtl_unit("n2");
  sim::UnitConfig cfg = sim::with_hardware(unit->config());
  EXPECT_NO_THROW(rtl::check_config(*unit, cfg));
  cfg.int_blocks = 3;
  try {
    rtl::check_config(*unit, cfg);
    ADD_FAILURE() << "N = 3 accepted by the N = 2 build";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("int_blocks"), std::string::npos) << e.what();
  }
  cfg = sim::with_hardware(unit->config());
  cfg.format.coord_frac_bits = 18;
  EXPECT_THROW(rtl::check_config(*unit, cfg), InputError);
  cfg = sim::with_hardware(unit->config());
  cfg.cpg_mapping = sim::CpgMapping::Gpe;
  EXPECT_THROW(rtl::check_config(*unit, cfg), InputError);
}

TEST(RtlSmoke, OutOfResetTheUnitIsEmptyAndReady) {
  for (const std::string& name : rtl::rtl_variants()) {
    auto unit = rtl::make_rtl_unit(name, 5);
    EXPECT_TRUE(unit->tri_ready()) << name;
    EXPECT_FALSE(unit->vtx_valid()) << name;
    sim::UnitCounters zero;
    zero.int_blocks = unit->int_blocks();
    EXPECT_EQ(unit->counters(), zero) << name;
    for (int i = 0; i < 10; ++i) unit->tick(sim::UnitInputs{});
    EXPECT_FALSE(unit->vtx_valid()) << name;
    const sim::UnitCounters k = unit->counters();
    EXPECT_EQ(k.cycles, 10u) << name;
    EXPECT_EQ(k.te[sim::TeClass::Idle], 10u) << name;
    EXPECT_EQ(k.cpg[sim::CpgClass::Idle], 10u) << name;
  }
}

// Every vertex of every patch of `tris` equals the datapath's, in every normal mode, and the
// counters add up, for the RTL build `name` (X randomisation seeded with `seed`).
void expect_build_matches_reference(const char* name, std::uint64_t seed, const std::vector<TriangleFx>& tris) {
  auto unit = rtl::make_rtl_unit(name, seed);
  for (NormalMode mode : kModes) {
    const std::vector<VertexFx> want = expected_stream(tris, mode);
    const RunResult r = run_stream(*unit, mode, tris, want.size(), always);
    const std::string what = std::string(name) + " " + std::string(to_string(mode));
    expect_stream_equal(r.vertices, want, what);
    expect_counters_consistent(r, *unit, tris.size(), mode, what);
  }
}

TEST(RtlSmoke, PatchesMatchTheReferenceArithmeticInEveryMode) {
  const std::vector<TriangleFx> tris = fixed_triangles();
  for (const char* name : {"n1", "n2", "n3", "n4", "n2_verif"}) expect_build_matches_reference(name, 11, tris);
}

// The CPG variants compute the same values as the sequential CPG, only sooner.
TEST(RtlSmoke, CpgVariantsMatchTheReferenceArithmeticInEveryMode) {
  const std::vector<TriangleFx> tris = fixed_triangles();
  for (const char* name : {"n3_lat3", "n1_r4", "n2_l3r8", "n4_l3r24"}) expect_build_matches_reference(name, 12, tris);
}

TEST(RtlSmoke, ReferenceFlagsAreExercised) {
  // The fixed stimulus must reach the divide-by-zero and saturation paths of the CPG.
  const std::vector<TriangleFx> tris = fixed_triangles();
  const auto flags_of = [&](int i) { return sim::compute_control_points(tris[i], NormalMode::Quadratic, kFormat).flags; };
  EXPECT_EQ(flags_of(0), 0);
  EXPECT_NE(flags_of(1) & sim::kFlagDivByZero, 0);
  EXPECT_NE(flags_of(2) & sim::kFlagSaturated, 0);
}

TEST(RtlSmoke, CornersAreTheInputVerticesExactly) {
  const std::vector<TriangleFx> tris = fixed_triangles();
  auto unit = rtl::make_rtl_unit("n2");
  for (NormalMode mode : kModes) {
    std::size_t total = 0;
    for (const TriangleFx& t : tris) total += static_cast<std::size_t>(pattern_vertex_count(t.L));
    const RunResult r = run_stream(*unit, mode, tris, total, always);
    ASSERT_EQ(r.vertices.size(), total);
    std::size_t at = 0;
    for (const TriangleFx& t : tris) {
      const int count = pattern_vertex_count(t.L);
      for (int i = 0; i < count; ++i) {
        const VertexFx& v = r.vertices[at + static_cast<std::size_t>(i)].vertex;
        EXPECT_EQ(v.id, t.id);
        EXPECT_EQ(v.L, t.L);
        EXPECT_EQ(v.last, i == count - 1);
        EXPECT_EQ(pattern_index(v.j, v.k, t.L), i);
        // Corner weights are exactly 1, so the corners are P1, P2, P3 and the corner normals.
        const int corner = v.j == 0 && v.k == 0 ? 0 : v.j == t.L ? 1 : v.k == t.L ? 2 : -1;
        if (corner < 0) continue;
        EXPECT_EQ(v.pos, t.p[corner]) << "corner " << corner << " of patch " << t.id;
        FxVec n = t.n[corner];
        if (mode != NormalMode::Linear) {
          std::uint8_t flags = 0;
          for (auto& c : n) c = sim::saturate(sim::i128{2} * c, kFormat, flags);
        }
        EXPECT_EQ(v.nrm, n) << "corner normal " << corner << " of patch " << t.id;
      }
      at += static_cast<std::size_t>(count);
    }
  }
}

TEST(RtlSmoke, RandomTrianglesMatchTheReference) {
  const std::vector<TriangleFx> tris = random_triangles(120, 2024);
  for (const char* name : {"n1", "n2", "n4", "n2_verif"}) expect_build_matches_reference(name, 3, tris);
}

TEST(RtlSmoke, FirstVertexTimingShowsTheCpgCycleCount) {
  // Cycle 0: the triangle enters the TRI FIFO. 1: CPG accept. 2..C: compute. C+1: write.
  // C+2: the DPG allocates a context. C+3..C+2+S: the vertex's ops issue (S cycles).
  // C+3+S: it retires into the VTX FIFO. C+4+S: vtx_valid, the GPE side accepts it.
  const TriangleFx tri = fixed_triangles()[0];
  for (const char* name : {"n1", "n2", "n3", "n4", "n2_verif", "n1_r4", "n2_l3r8", "n4_l3r24"}) {
    auto unit = rtl::make_rtl_unit(name, 9);
    for (NormalMode mode : kModes) {
      const RunResult r = run_stream(*unit, mode, {tri}, 1, always);
      ASSERT_EQ(r.vertices.size(), 1u);
      const int C = sim::cpg_cycles(mode, unit->config().format, unit->config().cpg);
      const int S = lone_vertex_issue_cycles(unit->int_blocks(), mode == NormalMode::Linear);
      EXPECT_EQ(r.vertices[0].cycle, static_cast<std::uint64_t>(C + 4 + S))
          << name << " " << to_string(mode) << " C = " << C << " S = " << S;
    }
  }
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Quadratic, kFormat), 245);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Reflect, kFormat), 98);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Linear, kFormat), 20);
  // C = 3E + 2 (one lane) or E + 2 (three lanes), E = 6, D + 8, 3D + 9, D = ceil(24 / r).
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Quadratic, kFormat, {1, 4}), 83);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Reflect, kFormat, {1, 4}), 44);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Quadratic, kFormat, {3, 8}), 20);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Reflect, kFormat, {3, 8}), 13);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Linear, kFormat, {3, 8}), 8);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Quadratic, kFormat, {3, 24}), 14);
  EXPECT_EQ(sim::cpg_cycles(NormalMode::Quadratic, kFormat, {3, 5}), 3 * 5 + 9 + 2);
}

TEST(RtlSmoke, CpgOverlapsTheTeOfThePreviousTriangle) {
  // With double buffering, triangle t+1's control points are written while triangle t is
  // still being tessellated: the accept of each triangle follows the previous write.
  const std::vector<TriangleFx> tris(4, fixed_triangles()[0]);
  auto unit = rtl::make_rtl_unit("n1");
  const int C = sim::cpg_cycles(NormalMode::Quadratic, kFormat);
  const std::size_t total = 4 * static_cast<std::size_t>(pattern_vertex_count(tris[0].L));
  const RunResult r = run_stream(*unit, NormalMode::Quadratic, tris, total, always);
  ASSERT_EQ(r.vertices.size(), total);
  // The FIFO takes two triangles at once; the CPG frees a slot every C + 1 cycles.
  ASSERT_EQ(r.tri_accept_cycles.size(), 4u);
  EXPECT_EQ(r.tri_accept_cycles[0], 0u);
  EXPECT_EQ(r.tri_accept_cycles[1], 1u);
  EXPECT_EQ(r.tri_accept_cycles[2], 2u);  // the CPG popped the first one in cycle 1
  EXPECT_EQ(r.tri_accept_cycles[3], static_cast<std::uint64_t>(2 + C + 1));
  // L = 4: 15 vertices of 14 cycles each on one INT block = 210 < C: the TE waits for the CPG.
  EXPECT_GT(r.counters.te[sim::TeClass::StarvedByCpg], 0u);
  EXPECT_EQ(r.counters.cpg[sim::CpgClass::Blocked], 0u);
}

TEST(RtlSmoke, BackpressureNeverLosesOrDuplicatesAVertex) {
  const std::vector<TriangleFx> tris = random_triangles(20, 77);
  const std::vector<VertexFx> want = expected_stream(tris, NormalMode::Quadratic);
  std::mt19937_64 rng(5);
  std::vector<bool> pattern(200000);
  for (std::size_t i = 0; i < pattern.size(); ++i) pattern[i] = (rng() % 3) == 0;
  for (const char* name : {"n1", "n4", "n2_verif"}) {
    auto unit = rtl::make_rtl_unit(name, 21);
    const RunResult every8 = run_stream(*unit, NormalMode::Quadratic, tris, want.size(),
                                        [](std::uint64_t c) { return c % 8 == 0; });
    expect_stream_equal(every8.vertices, want, std::string(name) + " K = 8");
    expect_counters_consistent(every8, *unit, tris.size(), NormalMode::Quadratic, name);
    // 14 ops on N >= 2 blocks take fewer than 8 cycles a vertex: the TE waits for the GPE.
    if (unit->int_blocks() >= 2) {
      EXPECT_GT(every8.counters.te[sim::TeClass::BlockedByGpe], 0u) << name;
    }
    const RunResult random = run_stream(*unit, NormalMode::Quadratic, tris, want.size(),
                                        [&](std::uint64_t c) { return pattern[c % pattern.size()]; });
    expect_stream_equal(random.vertices, want, std::string(name) + " random ready");
    expect_counters_consistent(random, *unit, tris.size(), NormalMode::Quadratic, name);
  }
}

TEST(RtlSmoke, LargestFactorProducesTheWholeLattice) {
  const TriangleFx tri = make_tri(fixed_triangles()[0].p, fixed_triangles()[0].n, kMaxTessFactor, 3);
  auto unit = rtl::make_rtl_unit("n4");
  const std::vector<VertexFx> want = expected_stream({tri}, NormalMode::Quadratic);
  ASSERT_EQ(want.size(), 2145u);
  const RunResult r = run_stream(*unit, NormalMode::Quadratic, {tri}, want.size(), always);
  expect_stream_equal(r.vertices, want, "L = 64");
}

TEST(RtlSmoke, RandomisedInitialStateDoesNotReachTheOutputs) {
  // The X-randomised build with different seeds, and the fast build, agree cycle for cycle.
  const std::vector<TriangleFx> tris = random_triangles(10, 99);
  const std::size_t total = expected_stream(tris, NormalMode::Reflect).size();
  auto ready = [](std::uint64_t c) { return c % 3 != 1; };
  auto fast = rtl::make_rtl_unit("n2");
  const RunResult base = run_stream(*fast, NormalMode::Reflect, tris, total, ready);
  for (std::uint64_t seed : {1u, 2u, 12345u}) {
    auto verif = rtl::make_rtl_unit("n2_verif", seed);
    const RunResult r = run_stream(*verif, NormalMode::Reflect, tris, total, ready);
    ASSERT_EQ(r.vertices.size(), base.vertices.size());
    for (std::size_t i = 0; i < r.vertices.size(); ++i) {
      EXPECT_EQ(r.vertices[i].cycle, base.vertices[i].cycle) << "seed " << seed << " vertex " << i;
      EXPECT_EQ(r.vertices[i].vertex, base.vertices[i].vertex) << "seed " << seed << " vertex " << i;
    }
    EXPECT_EQ(r.counters, base.counters) << "seed " << seed;
  }
}

TEST(RtlSmoke, AssertionsOfTheVerificationBuildFire) {
  auto unit = rtl::make_rtl_unit("n2_verif", 4);
  sim::UnitInputs in;
  in.tri_valid = true;
  in.tri = fixed_triangles()[0];
  in.tri.L = 0;  // outside 1..64
  EXPECT_THROW(unit->tick(in), rtl::RtlAssertionError);
  // The fast build has no assertions compiled in.
  auto fast = rtl::make_rtl_unit("n2", 4);
  EXPECT_NO_THROW(fast->tick(in));
}

TEST(RtlSmoke, InjectedFaultsChangeTheOutput) {
  const std::vector<TriangleFx> tris = random_triangles(8, 31);
  const std::vector<VertexFx> want = expected_stream(tris, NormalMode::Quadratic);
  auto slow = [](std::uint64_t c) { return c % 8 == 0; };
  auto good = rtl::make_rtl_unit("n2");
  const RunResult ok = run_stream(*good, NormalMode::Quadratic, tris, want.size(), slow);
  expect_stream_equal(ok.vertices, want, "n2");

  auto bug1 = rtl::make_rtl_unit("n2_bug1");
  const RunResult r1 = run_stream(*bug1, NormalMode::Quadratic, tris, want.size(), slow);
  ASSERT_EQ(r1.vertices.size(), want.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < want.size(); ++i) differing += r1.vertices[i].vertex == want[i] ? 0 : 1;
  EXPECT_GT(differing, want.size() / 4) << "rounding fault should corrupt most vertices";

  // The dropped stall loses the last vertex of a patch that finds the VTX FIFO full.
  auto bug2 = rtl::make_rtl_unit("n2_bug2");
  const RunResult r2 = run_stream(*bug2, NormalMode::Quadratic, tris, want.size(), slow);
  EXPECT_LT(r2.vertices.size(), want.size());
  EXPECT_LT(r2.counters.vertices_out, want.size());
}

TEST(RtlSmoke, WaveformIsWrittenOnlyWhileEnabled) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "tessim_rtl_smoke";
  std::filesystem::create_directories(dir);
  auto unit = rtl::make_rtl_unit("n1");
  unit->open_wave(dir / "short.fst");
  for (int i = 0; i < 20; ++i) unit->tick(sim::UnitInputs{});
  unit->close_wave();
  unit->open_wave(dir / "gated.fst");
  unit->set_wave_enabled(false);
  for (int i = 0; i < 2000; ++i) unit->tick(sim::UnitInputs{});
  unit->close_wave();
  unit->open_wave(dir / "long.fst");
  for (int i = 0; i < 2000; ++i) unit->tick(sim::UnitInputs{});
  unit->close_wave();
  ASSERT_TRUE(std::filesystem::exists(dir / "short.fst"));
  EXPECT_GT(std::filesystem::file_size(dir / "short.fst"), 0u);
  EXPECT_LT(std::filesystem::file_size(dir / "gated.fst"), std::filesystem::file_size(dir / "long.fst"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessim
