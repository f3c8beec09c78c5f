// Cycle-level model of the unit (sim/unit/unit.hpp), its geometry engine (sim/ge/gpe.hpp) and
// whole-mesh runs (sim/run/simulate.hpp): docs/microarchitecture.md cycle for cycle, statistics,
// throughput bounds, backpressure, reset, configuration errors. `tessim sim`:
// tests/cli/sim_cli_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "model/base/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/run/trace.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

// A closed, smooth, welded mesh: an icosahedron subdivided `levels` times, pushed onto a bumpy
// sphere off the origin. Every edge is shared by two triangles.
Mesh bumpy_sphere(int levels) {
  Mesh m;
  m.source = "bumpy sphere";
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = glm::normalize(p);
  std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < levels; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto midpoint = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      return mid[key] = static_cast<unsigned>(v.size() - 1);
    };
    std::vector<glm::uvec3> next;
    for (const auto& tri : f) {
      const unsigned a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
      next.insert(next.end(), {{tri.x, a, c}, {tri.y, b, a}, {tri.z, c, b}, {a, b, c}});
    }
    f = std::move(next);
  }
  for (const auto& p : v) {
    m.positions.push_back(p * (3.0 + 0.2 * std::sin(5 * p.x) * std::cos(3 * p.y)) + glm::dvec3(10, -2, 5));
    m.normals.push_back(p);
  }
  m.triangles = f;
  return m;
}

UnitConfig config(int n, int v, int latency, int k, int L = 4) {
  UnitConfig c;
  c.int_blocks = n;
  c.te_contexts = v;
  c.int_latency = latency;
  c.gpe_cycles = k;
  c.tess_factor = L;
  c.validate("test");
  return c;
}

int ops_per_vertex(NormalMode m) { return m == NormalMode::Linear ? 11 : 14; }

std::vector<VertexFx> run_vertices(const Mesh& mesh, const UnitConfig& cfg, SimResult* result = nullptr) {
  std::vector<VertexFx> out;
  SimHooks hooks;
  hooks.on_vertex = [&](const VertexFx& v) { out.push_back(v); };
  const SimResult r = simulate(mesh, cfg, hooks);
  if (result) *result = r;
  return out;
}

// The untimed datapath (sim/values/datapath.hpp) for one vertex of a triangle's patch.
VertexFx direct_vertex(const TriangleFx& tri, int j, int k, const UnitConfig& cfg) {
  return evaluate_vertex(compute_control_points(tri, cfg.normals, cfg.format), j, k, tri.L, tri.id, cfg.normals,
                         cfg.format);
}

// Steady state over a whole number of periods: the retirement interval over a window of
// 2520 vertices (a multiple of every schedule period up to 10 vertices).
double steady_cycles_per_vertex(const Mesh& mesh, const UnitConfig& cfg) {
  std::vector<std::uint64_t> retire;
  struct Recorder : CycleObserver {
    std::vector<std::uint64_t>* out;
    bool on_cycle(const Unit& u, const GpeCycle&) override {
      if (u.activity().retired) out->push_back(u.activity().cycle);
      return out->size() < 6000;
    }
  } rec;
  rec.out = &retire;
  SimHooks hooks;
  hooks.observers.push_back(&rec);
  simulate(mesh, cfg, hooks);
  EXPECT_GE(retire.size(), 6000u);
  return static_cast<double>(retire[5000] - retire[2480]) / 2520.0;
}

// ---------------------------------------------------------------------------------------------
// Cycle-exact timelines derived by hand from docs/microarchitecture.md.

TEST(UnitTimeline, SingleContextSingleBlock) {
  // One triangle, L = 1 (3 vertices), N = 1, V = 1, Λ = 1, K = 1, dedicated CPG (C = 245).
  // Cycle 0: pushed. 1: accepted (counter = C-1). 2..C: compute. C+1: write. C+2: allocate v0.
  // C+3..C+16: 14 ops, one per cycle. C+17: retire v0 (VTX FIFO). C+18: GPE accepts v0 and the
  // context, freed at the end of C+17, takes v1. Each further vertex takes 16 cycles:
  // v2 is accepted in cycle C+50, so the run lasts C + 51 cycles.
  Mesh mesh = bumpy_sphere(0);
  mesh.triangles.resize(1);
  const UnitConfig cfg = config(1, 1, 1, 1, 1);
  const int C = cpg_cycles(cfg.normals, cfg.format);
  ASSERT_EQ(C, 245);
  const SimResult r = simulate(mesh, cfg);
  EXPECT_EQ(r.unit.cycles, static_cast<std::uint64_t>(C + 51));
  EXPECT_EQ(r.unit.vertices_out, 3u);
  // CPG: accept + (C-1) computes + write = C+1 busy cycles, idle otherwise.
  EXPECT_EQ(r.unit.cpg[CpgClass::Busy], static_cast<std::uint64_t>(C + 1));
  // One context with latency 1: the head never waits on a result; 9 ready L1 ops for 1 block.
  EXPECT_EQ(r.unit.te[TeClass::Busy] + r.unit.te[TeClass::IntLimited], 42u);
  EXPECT_EQ(r.unit.te[TeClass::ContextLimited], 0u);
  EXPECT_EQ(r.unit.te[TeClass::StarvedByCpg], static_cast<std::uint64_t>(C + 1));  // cycles 1..C+1
  EXPECT_EQ(r.unit.te[TeClass::Idle], 2u);  // cycle 0 (nothing queued yet) and the last cycle
}

void expect_consistent(const SimResult& r, std::uint64_t triangles, int L, NormalMode mode);

// The CPG variants change C and nothing else: the same vertices, bit for bit, and a
// single-triangle timeline that is longer or shorter by exactly the difference in C.
TEST(UnitTimeline, CpgVariantsChangeOnlyC) {
  Mesh one = bumpy_sphere(0);
  one.triangles.resize(1);
  const Mesh mesh = bumpy_sphere(1);
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    UnitConfig base = config(2, 4, 1, 3, 3);
    base.normals = mode;
    const std::vector<VertexFx> want = run_vertices(mesh, base);
    UnitConfig single_base = config(1, 1, 1, 1, 1);
    single_base.normals = mode;
    const std::uint64_t single_rest = simulate(one, single_base).unit.cycles -
                                      static_cast<std::uint64_t>(cpg_cycles(mode, single_base.format));
    for (const CpgVariant v : {CpgVariant{1, 2}, CpgVariant{1, 7}, CpgVariant{3, 1}, CpgVariant{3, 8},
                               CpgVariant{3, 24}, CpgVariant{1, 1, 1, 1}, CpgVariant{1, 5, 1, 1},
                               CpgVariant{3, 2, 1, 1}, CpgVariant{3, 24, 1, 1}}) {
      UnitConfig cfg = base;
      cfg.cpg = v;
      cfg.validate("test");
      SimResult r;
      EXPECT_EQ(run_vertices(mesh, cfg, &r), want)
          << to_string(mode) << " lanes " << v.lanes << " r " << v.digit_bits << " registered " << v.product_reg;
      EXPECT_EQ(r.cpg_cycles, cpg_cycles(mode, cfg.format, v));
      expect_consistent(r, mesh.triangle_count(), cfg.tess_factor, mode);
      UnitConfig single = single_base;
      single.cpg = v;
      EXPECT_EQ(simulate(one, single).unit.cycles, static_cast<std::uint64_t>(cpg_cycles(mode, single.format, v)) + single_rest);
    }
  }
  // C = 3E + 2 or E + 2 with E = 6, D + 8, 3D + 9 and D = ceil(W / r); W = 24 here.
  const NumberFormat f;
  EXPECT_EQ(cpg_cycles(NormalMode::Quadratic, f, {1, 1}), 245);
  EXPECT_EQ(cpg_cycles(NormalMode::Quadratic, f, {1, 2}), 3 * (36 + 9) + 2);
  EXPECT_EQ(cpg_cycles(NormalMode::Quadratic, f, {3, 1}), 81 + 2);
  EXPECT_EQ(cpg_cycles(NormalMode::Reflect, f, {3, 7}), 4 + 8 + 2);
  EXPECT_EQ(cpg_cycles(NormalMode::Linear, f, {3, 24}), 8);
  // Registered products (rtl/tess_cpg_edge.sv): E = 9, D + 11, 3D + 13 and two b111 cycles.
  EXPECT_EQ(cpg_cycles(NormalMode::Quadratic, f, {1, 1, 1, 1}), 3 * (72 + 13) + 3);
  EXPECT_EQ(cpg_cycles(NormalMode::Reflect, f, {1, 2, 1, 1}), 3 * (12 + 11) + 3);
  EXPECT_EQ(cpg_cycles(NormalMode::Linear, f, {1, 1, 1, 1}), 3 * 9 + 3);
  EXPECT_EQ(cpg_cycles(NormalMode::Quadratic, f, {3, 24, 1, 1}), 16 + 3);
  EXPECT_EQ(cpg_cycles(NormalMode::Linear, f, {3, 24, 1, 1}), 9 + 3);
}

TEST(UnitConfigCheck, CpgVariantOutsideTheDesignSpaceIsRejected) {
  auto reason = [](const UnitConfig& c) {
    try {
      c.validate("cfg.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  UnitConfig c;
  c.cpg.lanes = 2;
  EXPECT_NE(reason(c).find("cfg.json: cpg_lanes: value 2"), std::string::npos) << reason(c);
  c = UnitConfig{};
  c.cpg.lanes = 4;
  EXPECT_NE(reason(c).find("cpg_lanes"), std::string::npos) << reason(c);
  c = UnitConfig{};
  c.cpg.digit_bits = 25;  // W = 24
  EXPECT_NE(reason(c).find("cpg_digit_bits: value 25 exceeds the coordinate width 24"), std::string::npos) << reason(c);
  c.cpg.digit_bits = 0;
  EXPECT_NE(reason(c).find("cpg_digit_bits"), std::string::npos) << reason(c);
  c = UnitConfig{};
  c.cpg = {3, 4};
  EXPECT_EQ(reason(c), "");
  c.cpg_mapping = CpgMapping::Gpe;
  EXPECT_NE(reason(c).find("cpg_mapping gpe"), std::string::npos) << reason(c);
  c = UnitConfig{};
  c.cpg.copies = 2;
  EXPECT_EQ(reason(c), "");
  c.cpg_mapping = CpgMapping::Gpe;  // the GE-mapped CPG is one program on the GE
  EXPECT_NE(reason(c).find("cpg_copies"), std::string::npos) << reason(c);
  c = UnitConfig{};
  c.cpg.copies = 17;
  EXPECT_NE(reason(c).find("cfg.json: cpg_copies: value 17"), std::string::npos) << reason(c);
}

TEST(UnitTimeline, TwoBlocksFourContexts) {
  // N = 2, V = 4: the three points of L = 1 are allocated in C+2, C+3, C+4. v0 issues 7
  // cycles (C+3..C+9: ops 0-1, 2-3, 4-5, 6-7, 8-9, 10-11, 12-13 — the dependences are met
  // just in time), retires in C+10, is accepted in C+11; v1 and v2 follow every 7 cycles:
  // v2 accepted in C+25, run length C + 26.
  Mesh mesh = bumpy_sphere(0);
  mesh.triangles.resize(1);
  const UnitConfig cfg = config(2, 4, 1, 1, 1);
  const int C = cpg_cycles(cfg.normals, cfg.format);
  struct Issues : CycleObserver {
    std::vector<std::pair<std::uint64_t, IssuedOp>> ops;
    bool on_cycle(const Unit& u, const GpeCycle&) override {
      for (int i = 0; i < u.activity().ops_issued; ++i) ops.emplace_back(u.activity().cycle, u.issued_ops()[i]);
      return true;
    }
  } issues;
  SimHooks hooks;
  hooks.observers.push_back(&issues);
  const SimResult r = simulate(mesh, cfg, hooks);
  EXPECT_EQ(r.unit.cycles, static_cast<std::uint64_t>(C + 26));
  ASSERT_EQ(issues.ops.size(), 42u);
  for (std::size_t i = 0; i < issues.ops.size(); ++i) {
    const auto& [cycle, op] = issues.ops[i];
    const std::uint64_t vertex = i / 14;
    EXPECT_EQ(op.vertex, vertex);
    EXPECT_EQ(op.op, static_cast<int>(i % 14));  // ops in number order, two per cycle
    EXPECT_EQ(op.block, static_cast<int>(i % 2));
    EXPECT_EQ(cycle, static_cast<std::uint64_t>(C + 3) + 7 * vertex + (i % 14) / 2);
  }
}

TEST(UnitTimeline, SlowGpeSetsTheRate) {
  // K = 20 with N = 2, L = 4: the TE (7 cycles/vertex) and the CPG (C+1 = 246 cycles per
  // 15-vertex patch) both keep up, so after the first vertex the GPE takes one every K cycles:
  // cycles = first-vertex latency + K (vertices - 1). The first vertex is accepted in cycle
  // C+11 (timeline above with 7 issue cycles), so the fill is C + 12 cycles.
  const Mesh mesh = load_mesh(kWuson);
  const UnitConfig cfg = config(2, 4, 1, 20, 4);
  const SimResult r = simulate(mesh, cfg);
  const std::uint64_t V = r.unit.vertices_out;
  ASSERT_EQ(V, mesh.triangle_count() * 15);
  const std::uint64_t fill = static_cast<std::uint64_t>(r.cpg_cycles + 12);
  EXPECT_EQ(r.unit.cycles, fill + 20 * (V - 1));
  EXPECT_NEAR(throughput(r), 1.0 / 20, 1.0 / 20 * static_cast<double>(fill) / static_cast<double>(r.unit.cycles));
  EXPECT_EQ(r.gpe[GpeClass::Busy], 20 * (V - 1) + 1);
  EXPECT_NE(bottleneck(r).find("GPE"), std::string::npos) << bottleneck(r);
}

// With a fast GPE and Λ = 1 the INT blocks bound the TE: 14/N cycles per vertex in the steady
// state for N = 1..6 with V = 4 (docs/schedule.md), and over a whole run the only overheads
// are the fill (first triangle through the CPG, first vertex through the TE) and the drain.
class FastGpe : public ::testing::TestWithParam<int> {};

TEST_P(FastGpe, SchedulerBound) {
  const int n = GetParam();
  Mesh mesh = bumpy_sphere(0);
  mesh.triangles.resize(4);  // 4 patches of L = 64: 8580 vertices, far more work than CPG
  const UnitConfig cfg = config(n, 4, 1, 1, 64);
  EXPECT_NEAR(steady_cycles_per_vertex(mesh, cfg), 14.0 / n, 1e-9);

  const SimResult r = simulate(mesh, cfg);
  const double bound = 14.0 * static_cast<double>(r.unit.vertices_out) / n;
  // Fill: C + 3 cycles before the first issue (push, accept, C - 1 computes, write, allocate);
  // drain: retirement and acceptance of the last vertex (2 cycles), plus one cycle for N >= 3
  // where the last vertex's dependence chain cannot fill every block (docs/schedule.md).
  const double overhead = static_cast<double>(r.unit.cycles) - bound;
  EXPECT_EQ(overhead, r.cpg_cycles + (n <= 2 ? 5.0 : 6.0)) << "cycles " << r.unit.cycles << " bound " << bound;
  EXPECT_NE(bottleneck(r).find("INT"), std::string::npos) << bottleneck(r);
}

INSTANTIATE_TEST_SUITE_P(N1to6, FastGpe, ::testing::Range(1, 7));

TEST(FastGpe, FewContextsAndLatency) {
  // Measured steady states of docs/schedule.md for a few (V, Λ, N): one context serialises
  // allocation, the dependence chain and retirement; latency needs more contexts.
  Mesh mesh = bumpy_sphere(0);
  mesh.triangles.resize(4);
  struct Case {
    int n, v, latency;
    double cycles;
  };
  for (const Case c : {Case{1, 1, 1, 16}, Case{2, 1, 1, 9}, Case{6, 1, 1, 5}, Case{6, 2, 1, 3},
                       Case{1, 1, 2, 17}, Case{2, 1, 3, 13}, Case{6, 3, 2, 3}, Case{4, 3, 3, 13.0 / 3}}) {
    EXPECT_NEAR(steady_cycles_per_vertex(mesh, config(c.n, c.v, c.latency, 1, 64)), c.cycles, 1e-9)
        << "N=" << c.n << " V=" << c.v << " latency=" << c.latency;
  }
}

// ---------------------------------------------------------------------------------------------
// Values

TEST(UnitValues, EqualTheDirectDatapathInEveryMode) {
  const Mesh mesh = bumpy_sphere(1);
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    UnitConfig cfg = config(3, 3, 2, 1, 5);
    cfg.normals = mode;
    const HostScaling s = host_scaling(mesh);
    const std::vector<VertexFx> got = run_vertices(mesh, cfg);
    ASSERT_EQ(got.size(), mesh.triangle_count() * 21);
    std::size_t i = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const TriangleFx tri = to_fixed(mesh, t, s, cfg.format, 5);
      for (const DomainPoint& p : pattern_points(5)) {
        ASSERT_EQ(got[i], direct_vertex(tri, p.j, p.k, cfg)) << to_string(mode) << " vertex " << i;
        ++i;
      }
    }
  }
}

TEST(UnitValues, IndependentOfScheduleAndBackpressure) {
  const Mesh mesh = bumpy_sphere(1);
  const std::vector<VertexFx> ref = run_vertices(mesh, config(2, 4, 1, 8));
  for (const UnitConfig& base : {config(1, 1, 1, 1), config(5, 2, 3, 1), config(6, 16, 8, 3), config(3, 4, 2, 1)}) {
    UnitConfig cfg = base;
    cfg.gpe_stall_prob = 0.3;
    cfg.vtx_fifo_depth = 1;
    cfg.tri_fifo_depth = 1;
    EXPECT_EQ(run_vertices(mesh, cfg), ref) << "N=" << cfg.int_blocks << " V=" << cfg.te_contexts;
  }
}

// ---------------------------------------------------------------------------------------------
// Backpressure: no vertex lost or duplicated, each patch in pattern order.

TEST(UnitBackpressure, EveryVertexExactlyOnceInOrder) {
  const Mesh mesh = bumpy_sphere(1);  // 80 triangles
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    UnitConfig cfg = config(1 + static_cast<int>(seed % 4), 1 + static_cast<int>(seed % 5),
                            1 + static_cast<int>(seed % 3), 1 + static_cast<int>(seed % 3), 1 + static_cast<int>(seed % 6));
    cfg.gpe_stall_prob = 0.5;
    cfg.seed = seed;
    cfg.vtx_fifo_depth = 1 + static_cast<int>(seed % 2);
    cfg.normals = seed % 3 == 0 ? NormalMode::Linear : NormalMode::Quadratic;
    const int L = cfg.tess_factor;
    SimResult r;
    const std::vector<VertexFx> got = run_vertices(mesh, cfg, &r);
    std::set<std::tuple<std::uint32_t, int, int>> seen;
    std::size_t i = 0;
    for (std::uint32_t id = 0; id < mesh.triangle_count(); ++id) {
      for (const DomainPoint& p : pattern_points(L)) {
        ASSERT_LT(i, got.size());
        EXPECT_EQ(got[i].id, id) << "seed " << seed;
        EXPECT_EQ(got[i].j, p.j);
        EXPECT_EQ(got[i].k, p.k);
        EXPECT_EQ(got[i].last, p.k == L);
        seen.insert({got[i].id, got[i].j, got[i].k});
        ++i;
      }
    }
    EXPECT_EQ(got.size(), i);
    EXPECT_EQ(seen.size(), got.size()) << "duplicates, seed " << seed;
    EXPECT_GT(r.gpe[GpeClass::Stalled], r.unit.cycles / 4) << "stalls happened";
  }
}

// The unit driven cycle by cycle by hand, with an arbitrary consumer (not the GPE model): the
// ready input toggles with a fixed pattern; nothing is lost, duplicated or reordered.
TEST(UnitBackpressure, HandshakeWithArbitraryReady) {
  const Mesh mesh = bumpy_sphere(0);
  const UnitConfig cfg = config(2, 3, 2, 1, 3);
  const HostScaling s = host_scaling(mesh);
  Unit unit(cfg);
  UnitInputs in;
  std::size_t next = 0;
  std::vector<VertexFx> got;
  for (std::uint64_t cycle = 0; got.size() < mesh.triangle_count() * 10 && cycle < 200000; ++cycle) {
    in.tri_valid = next < mesh.triangle_count() && (cycle % 5 != 3);
    if (in.tri_valid) in.tri = to_fixed(mesh, next, s, cfg.format, 3);
    in.vtx_ready = (cycle * 7919) % 11 < 4;
    if (in.tri_valid && unit.tri_ready()) ++next;
    if (in.vtx_ready && unit.vtx_valid()) got.push_back(unit.vtx());
    unit.tick(in);
  }
  ASSERT_EQ(got.size(), mesh.triangle_count() * 10);
  EXPECT_TRUE(unit.idle());
  std::size_t i = 0;
  for (std::uint32_t id = 0; id < mesh.triangle_count(); ++id)
    for (const DomainPoint& p : pattern_points(3)) {
      EXPECT_EQ(got[i].id, id);
      EXPECT_EQ(got[i].j, p.j);
      EXPECT_EQ(got[i].k, p.k);
      ++i;
    }
}

// ---------------------------------------------------------------------------------------------
// Statistics (doc §10)

void expect_consistent(const SimResult& r, std::uint64_t triangles, int L, NormalMode mode) {
  const UnitCounters& u = r.unit;
  const std::uint64_t n = u.cycles;
  EXPECT_EQ(u.int_blocks, r.config.int_blocks);
  std::uint64_t busy = 0;
  for (std::uint64_t b : u.int_busy_used()) {
    EXPECT_LE(b, n);
    busy += b;
  }
  EXPECT_EQ(busy, static_cast<std::uint64_t>(ops_per_vertex(mode)) * u.vertices_out);
  // Every block of classes of the counter registry: its classes sum to the cycles.
  for (const CounterBlockInfo& b : kCounterBlocks) {
    if (b.classes && b.in_unit && b.block != CounterBlock::Int) {
      EXPECT_EQ(class_total(u, b.block), n) << b.label;
    }
  }
  EXPECT_EQ(r.gpe.total(), n);
  EXPECT_EQ(r.gpe.cycles, n);
  EXPECT_EQ(r.gpe.vertices, u.vertices_out);
  EXPECT_EQ(u.triangles_in, triangles);
  EXPECT_EQ(u.vertices_out, triangles * static_cast<std::uint64_t>(pattern_vertex_count(L)));
  // Blocks 0..i-1 are used before block i: the i-th op of a cycle goes to block i.
  for (std::size_t i = 1; i < u.int_busy_used().size(); ++i) EXPECT_LE(u.int_busy[i], u.int_busy[i - 1]);
  // The CPG of the dedicated mapping is busy C + 1 cycles per triangle.
  if (r.config.cpg_mapping == CpgMapping::Dedicated) {
    EXPECT_EQ(u.cpg[CpgClass::Busy], triangles * static_cast<std::uint64_t>(r.cpg_cycles + 1));
  }
}

TEST(UnitStatistics, ClassesAddUpPerBlock) {
  const Mesh mesh = bumpy_sphere(1);
  int variant = 0;
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    for (int n : {1, 2, 4}) {
      for (double stall : {0.0, 0.4}) {
        UnitConfig cfg = config(n, 1 + variant % 4, 1 + variant % 3, 1 + 3 * (variant % 4), 2 + variant % 5);
        cfg.normals = mode;
        cfg.gpe_stall_prob = stall;
        cfg.seed = static_cast<std::uint64_t>(variant);
        cfg.cpg_mapping = variant % 5 == 4 ? CpgMapping::Gpe : CpgMapping::Dedicated;
        ++variant;
        const SimResult r = simulate(mesh, cfg);
        expect_consistent(r, mesh.triangle_count(), cfg.tess_factor, mode);
      }
    }
  }
}

// vtx_stalls counts the cycles the unit offers a vertex the geometry engine refuses. A GE that
// takes one vertex every cycle refuses none; a GE of K cycles per vertex is busy for K - 1
// cycles after each vertex it takes, and when it is the bottleneck a vertex waits in nearly all
// of them.
TEST(UnitStatistics, VtxStallsAreTheCyclesAnOfferedVertexWaits) {
  struct Watch : CycleObserver {
    bool on_cycle(const Unit&, const GpeCycle&) override { return true; }
  };
  const Mesh mesh = bumpy_sphere(1);
  EXPECT_EQ(simulate(mesh, config(2, 4, 1, 1, 4)).unit.vtx_stalls, 0u);
  for (int k : {8, 16}) {
    const UnitConfig cfg = config(4, 4, 1, k, 4);
    Watch watch;
    SimHooks hooks;
    hooks.observers.push_back(&watch);
    const SimResult r = simulate(mesh, cfg, hooks);
    const std::uint64_t busy_after = static_cast<std::uint64_t>(k - 1) * r.unit.vertices_out;
    EXPECT_LE(r.unit.vtx_stalls, busy_after) << "K " << k;
    EXPECT_GE(r.unit.vtx_stalls, busy_after * 8 / 10) << "K " << k;
    EXPECT_LE(r.unit.vtx_stalls + r.unit.vertices_out, r.unit.cycles) << "K " << k;
    // The fast-forwarded run counts the same refusals.
    EXPECT_EQ(simulate(mesh, cfg).unit.vtx_stalls, r.unit.vtx_stalls) << "K " << k;
  }
}

// The host offers a triangle in every cycle until the last one is taken, so every cycle up to
// that one either takes a triangle or refuses it: tri_stalls = last push cycle + 1 - triangles_in.
TEST(UnitStatistics, TriStallsAreTheCyclesAnOfferedTriangleWaits) {
  struct LastPush : CycleObserver {
    std::uint64_t cycle = 0;
    bool on_cycle(const Unit& unit, const GpeCycle&) override {
      if (unit.activity().tri_pushed) cycle = unit.activity().cycle;
      return true;
    }
  };
  const Mesh mesh = bumpy_sphere(1);
  for (int depth : {1, 2, 8}) {
    for (int k : {1, 8}) {
      UnitConfig cfg = config(2, 4, 1, k, 3);
      cfg.tri_fifo_depth = depth;
      cfg.validate("test");
      LastPush last;
      SimHooks hooks;
      hooks.observers.push_back(&last);
      const SimResult r = simulate(mesh, cfg, hooks);
      EXPECT_EQ(r.unit.triangles_in, mesh.triangle_count());
      EXPECT_EQ(r.unit.tri_stalls, last.cycle + 1 - r.unit.triangles_in) << "depth " << depth << ", K " << k;
      // The CPG takes C + 1 cycles per triangle: a FIFO of a few entries fills at once.
      EXPECT_GT(r.unit.tri_stalls, r.unit.cycles / 2) << "depth " << depth << ", K " << k;
      // The fast-forwarded run counts the same refusals.
      EXPECT_EQ(simulate(mesh, cfg).unit.tri_stalls, r.unit.tri_stalls);
    }
  }
}

// The control-point buffers are a ring of cp_buffers entries (docs/microarchitecture.md §6): the
// CPG writes at most Nb patches ahead of the TE's retirement of their last vertices, fills every
// buffer when the geometry engine is the slower side, and the buffer count changes when vertices
// come out, never what they are. With one buffer the TE drains at every patch boundary: the
// slowest run.
TEST(UnitBuffers, CpgRunsAtMostNbPatchesAheadAndVerticesDoNotDependOnNb) {
  struct Resident : CycleObserver {
    std::uint64_t vertices_per_patch = 0, writes = 0, retired = 0, max_resident = 0;
    bool on_cycle(const Unit& unit, const GpeCycle&) override {
      if (unit.activity().cpg_action == CpgAction::Write) ++writes;
      if (unit.activity().retired) ++retired;
      max_resident = std::max(max_resident, writes - retired / vertices_per_patch);
      return true;
    }
  };
  const Mesh mesh = bumpy_sphere(1);
  for (int k : {16, 2}) {
    std::vector<VertexFx> reference;
    std::uint64_t previous_cycles = 0;
    for (int nb = 1; nb <= 5; ++nb) {
      SCOPED_TRACE("K " + std::to_string(k) + ", Nb " + std::to_string(nb));
      UnitConfig cfg = config(1, 4, 1, k, 3);
      cfg.cpg = CpgVariant{3, cfg.format.coord_width()};  // 14 cycles a triangle: faster than the GE at K = 16
      cfg.cp_buffers = nb;
      cfg.validate("test");
      Resident resident;
      resident.vertices_per_patch = 10;  // L = 3
      SimHooks hooks;
      hooks.observers.push_back(&resident);
      std::vector<VertexFx> out;
      hooks.on_vertex = [&](const VertexFx& v) { out.push_back(v); };
      const SimResult r = simulate(mesh, cfg, hooks);
      ASSERT_EQ(resident.writes, mesh.triangle_count());
      EXPECT_LE(resident.max_resident, static_cast<std::uint64_t>(nb));
      if (k == 16) {
        EXPECT_EQ(resident.max_resident, static_cast<std::uint64_t>(nb)) << "every buffer filled";
      }
      if (nb == 1) {
        reference = out;
      } else {
        EXPECT_EQ(out, reference);
        EXPECT_LE(r.unit.cycles, previous_cycles) << "a buffer more never slows the unit";
        if (nb == 2 && k == 2) {
          EXPECT_LT(r.unit.cycles, previous_cycles) << "one buffer drains the TE at every patch";
        }
      }
      previous_cycles = r.unit.cycles;
      // The fast-forwarded run takes the same cycles.
      EXPECT_EQ(simulate(mesh, cfg).unit.cycles, r.unit.cycles);
    }
  }
}

// Copies of the CPG (docs/microarchitecture.md §5): triangles go to Mc copies in turn and their
// control points reach the buffers in input order. At most Mc triangles are in the CPG at once;
// the copies change when vertices come out, never what they are; a CPG-bound run (L = 1, a GE
// that takes a vertex a cycle) starts a triangle every (C + 1) / Mc cycles, as the analytic
// bound says, until the GE's rate is reached.
TEST(UnitCpgCopies, TrianglesInTurnPatchesInOrderOneStartEveryCPlusOneOverMc) {
  struct InFlight : CycleObserver {
    std::uint64_t pushed = 0, writes = 0, max_in_cpg = 0;
    std::int64_t last_written = -1;
    bool in_order = true;
    bool on_cycle(const Unit& unit, const GpeCycle&) override {
      const CycleActivity& a = unit.activity();
      if (a.tri_pushed) ++pushed;
      if (a.cpg_action == CpgAction::Write) {
        ++writes;
        in_order = in_order && static_cast<std::int64_t>(a.cpg_triangle) == last_written + 1;
        last_written = a.cpg_triangle;
      }
      // Accepted (pushed and gone from the TRI FIFO) and not yet written.
      const std::uint64_t accepted = pushed - static_cast<std::uint64_t>(unit.tri_fifo_count());
      max_in_cpg = std::max(max_in_cpg, accepted - writes);
      return true;
    }
  };
  const Mesh mesh = bumpy_sphere(1);
  std::vector<VertexFx> reference;
  std::uint64_t previous_cycles = 0;
  for (int copies = 1; copies <= 6; ++copies) {
    SCOPED_TRACE("Mc " + std::to_string(copies));
    UnitConfig cfg = config(14, 8, 1, 1, 1);
    cfg.cpg = CpgVariant{3, cfg.format.coord_width(), copies};  // C = 14 quadratic
    cfg.cp_buffers = 8;
    cfg.validate("test");
    InFlight seen;
    SimHooks hooks;
    hooks.observers.push_back(&seen);
    std::vector<VertexFx> out;
    hooks.on_vertex = [&](const VertexFx& v) { out.push_back(v); };
    const SimResult r = simulate(mesh, cfg, hooks);
    ASSERT_EQ(seen.writes, mesh.triangle_count());
    EXPECT_TRUE(seen.in_order) << "control points written out of input order";
    EXPECT_EQ(seen.max_in_cpg, static_cast<std::uint64_t>(copies)) << "every copy busy, never more";
    if (copies == 1) {
      reference = out;
    } else {
      EXPECT_EQ(out, reference);
      EXPECT_LE(r.unit.cycles, previous_cycles) << "a copy more never slows the unit";
    }
    previous_cycles = r.unit.cycles;
    // One triangle every (C + 1) / Mc cycles while that is slower than the GE's 3 cycles a patch.
    const double per_triangle = std::max(15.0 / copies, 3.0);
    const double expected = per_triangle * static_cast<double>(mesh.triangle_count());
    EXPECT_NEAR(static_cast<double>(r.unit.cycles), expected, 40.0) << "fill and drain only";
    EXPECT_EQ(simulate(mesh, cfg).unit.cycles, r.unit.cycles) << "fast-forward";
  }
}

TEST(UnitStatistics, RealMeshDefaultConfig) {
  const Mesh mesh = load_mesh(kWuson);
  UnitConfig cfg;
  const SimResult r = simulate(mesh, cfg);
  expect_consistent(r, mesh.triangle_count(), cfg.tess_factor, cfg.normals);
  // L = 4 quadratic: C + 1 = 246 CPG cycles per 15-vertex patch exceed the 8 x 15 = 120 cycles
  // the GPE needs: the CPG limits the run.
  EXPECT_GE(cycles_per_vertex(r), 246.0 / 15);
  EXPECT_NE(bottleneck(r).find("CPG"), std::string::npos) << bottleneck(r);

  const nlohmann::json j = stats_json(r);
  EXPECT_EQ(j["cycles"], r.unit.cycles);
  EXPECT_EQ(j["config"]["int_blocks"], 2);
  EXPECT_EQ(j["int"]["blocks"].size(), 2u);
  EXPECT_EQ(j["te"]["starved_by_cpg"], r.unit.te[TeClass::StarvedByCpg]);
  EXPECT_EQ(j["gpe"]["starved"], r.gpe[GpeClass::Starved]);
  EXPECT_EQ(j["stalls"]["gpe_starved_by_te"], r.gpe[GpeClass::Starved]);
  EXPECT_DOUBLE_EQ(j["cycles_per_vertex"].get<double>(), cycles_per_vertex(r));
  const std::string text = summary(r);
  EXPECT_NE(text.find("cycles/vertex"), std::string::npos);
  EXPECT_LE(std::count(text.begin(), text.end(), '\n'), 12);
}

// ---------------------------------------------------------------------------------------------
// CPG on the geometry engine

TEST(GpeMappedCpg, SameVerticesAndExactlyCSpareCyclesPerTriangle) {
  const Mesh mesh = bumpy_sphere(1);
  for (int C : {1, 40, 300}) {
    UnitConfig ded = config(2, 4, 1, 4, 3);
    UnitConfig gpe = ded;
    gpe.cpg_mapping = CpgMapping::Gpe;
    gpe.cpg_gpe_cycles = C;
    gpe.gpe_stall_prob = 0.2;
    SimResult rd, rg;
    const std::vector<VertexFx> a = run_vertices(mesh, ded, &rd);
    const std::vector<VertexFx> b = run_vertices(mesh, gpe, &rg);
    EXPECT_EQ(a, b);
    EXPECT_EQ(rg.gpe[GpeClass::Cpg], mesh.triangle_count() * static_cast<std::uint64_t>(C));
    EXPECT_EQ(rd.gpe[GpeClass::Cpg], 0u);
    EXPECT_EQ(rg.cpg_cycles, C);
    // Every compute step is one spare GPE cycle; the CPG waited for the others.
    EXPECT_GT(rg.unit.cpg[CpgClass::WaitGpe], 0u);
    expect_consistent(rg, mesh.triangle_count(), 3, NormalMode::Quadratic);
  }
}

// ---------------------------------------------------------------------------------------------
// Reset

TEST(UnitReset, MidStreamRecovers) {
  const Mesh mesh = bumpy_sphere(0);
  UnitConfig cfg = config(2, 3, 2, 2, 3);
  cfg.gpe_stall_prob = 0.25;
  const HostScaling s = host_scaling(mesh);

  // One run from reset: every cycle's outputs and the final statistics.
  struct Trace {
    std::vector<std::tuple<bool, bool, VertexFx>> outputs;
    UnitCounters stats;
  };
  auto run = [&](Unit& unit, Gpe& gpe) {
    Trace t;
    UnitInputs in;
    std::size_t next = 0, received = 0;
    const std::size_t total = mesh.triangle_count() * 10;
    while (received < total) {
      const GpeCycle g = gpe.tick(unit.vtx_valid(), unit.cpg_computing());
      in.tri_valid = next < mesh.triangle_count();
      if (in.tri_valid) in.tri = to_fixed(mesh, next, s, cfg.format, 3);
      in.vtx_ready = g.ready;
      in.cpg_step = g.spare;
      t.outputs.emplace_back(unit.tri_ready(), unit.vtx_valid(), unit.vtx_valid() ? unit.vtx() : VertexFx{});
      if (in.tri_valid && unit.tri_ready()) ++next;
      if (g.accepted) ++received;
      unit.tick(in);
    }
    t.stats = unit.stats();
    return t;
  };

  Unit fresh(cfg);
  Gpe fresh_gpe(cfg);
  const Trace expected = run(fresh, fresh_gpe);

  Unit unit(cfg);
  Gpe gpe(cfg);
  // Leave the unit in the middle of everything: triangles queued, CPG busy, contexts in
  // flight, the VTX FIFO full.
  UnitInputs in;
  in.tri_valid = true;
  in.tri = to_fixed(mesh, 7, s, cfg.format, 3);
  for (int c = 0; c < 700; ++c) unit.tick(in);
  ASSERT_FALSE(unit.idle());
  ASSERT_TRUE(unit.vtx_valid());
  ASSERT_GT(unit.contexts_in_use(), 0);
  unit.reset();
  gpe.reset();
  EXPECT_TRUE(unit.idle());
  EXPECT_EQ(unit.stats().cycles, 0u);
  const Trace after = run(unit, gpe);
  EXPECT_EQ(after.stats, expected.stats);
  ASSERT_EQ(after.outputs.size(), expected.outputs.size());
  EXPECT_TRUE(after.outputs == expected.outputs);
}

// ---------------------------------------------------------------------------------------------
// GPE model

TEST(GpeModel, RateStallsAndReproducibility) {
  Gpe fast(3, 0.0, 5);
  int accepted = 0;
  for (int c = 0; c < 300; ++c) accepted += fast.tick(true, false).accepted;
  EXPECT_EQ(accepted, 100);  // one vertex every K cycles when fed

  Gpe a(1, 0.5, 42), b(1, 0.5, 42), other(1, 0.5, 43);
  int stalls = 0, differ = 0;
  for (int c = 0; c < 10000; ++c) {
    const GpeCycle x = a.tick(c % 3 != 0, false), y = b.tick(c % 3 != 0, false), z = other.tick(c % 3 != 0, false);
    EXPECT_EQ(x.ready, y.ready);
    stalls += !x.ready;
    differ += x.ready != z.ready;
  }
  EXPECT_NEAR(stalls, 5000, 300);
  EXPECT_GT(differ, 3000);
  a.reset();
  Gpe c(1, 0.5, 42);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.tick(true, false).ready, c.tick(true, false).ready);
  EXPECT_EQ(a.stats(), c.stats());
}

// ---------------------------------------------------------------------------------------------
// Configuration errors name the key.

void expect_input_error(const nlohmann::json& j, const std::string& key) {
  UnitConfig cfg;
  try {
    apply_json(cfg, j, "cfg.json");
    cfg.validate("cfg.json");
    FAIL() << "accepted " << j.dump();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cfg.json"), std::string::npos) << e.what();
  }
}

TEST(UnitConfigErrors, NameTheKey) {
  expect_input_error({{"int_blockz", 2}}, "int_blockz");
  expect_input_error({{"int_blocks", 0}}, "int_blocks");
  expect_input_error({{"int_latency", 9}}, "int_latency");
  expect_input_error({{"te_contexts", "four"}}, "te_contexts");
  expect_input_error({{"gpe_stall_prob", 1.5}}, "gpe_stall_prob");
  expect_input_error({{"tess_factor", 65}}, "tess_factor");
  expect_input_error({{"seed", -1}}, "seed");
  expect_input_error({{"cpg_mapping", "fpga"}}, "cpg_mapping");
  expect_input_error({{"normals", "derivative"}}, "normals");
  expect_input_error({{"coord_int_bits", 8}, {"coord_frac_bits", 26}}, "coord_int_bits");
}

// ---------------------------------------------------------------------------------------------
// Trace

TEST(Trace, WindowTracksAndEvents) {
  const Mesh mesh = bumpy_sphere(0);
  const UnitConfig cfg = config(2, 4, 1, 1, 8);
  const auto path = std::filesystem::temp_directory_path() / ("tessim_trace_" + std::to_string(::getpid()) + ".json");
  TraceWriter trace(path, 2, 4, TraceWindow{0, 1000});
  struct OpCounter : CycleObserver {
    std::uint64_t ops = 0;
    bool on_cycle(const Unit& u, const GpeCycle&) override {
      if (u.activity().cycle >= 1000) return false;
      ops += static_cast<std::uint64_t>(u.activity().ops_issued);
      return true;
    }
  } counter;
  SimHooks hooks;
  hooks.observers = {&trace, &counter};
  simulate(mesh, cfg, hooks);
  trace.finish();
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  std::filesystem::remove(path);
  std::uint64_t op_events = 0;
  std::set<std::string> threads;
  double last_ts = 0;
  for (const auto& e : j["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "thread_name") threads.insert(e["args"]["name"].get<std::string>());
    if (e["ph"] == "X" && e["tid"].get<int>() <= 2) {
      ++op_events;
      EXPECT_EQ(e["name"].get<std::string>().rfind("op", 0), 0u);
    }
    if (e.contains("ts")) last_ts = std::max(last_ts, e["ts"].get<double>() + (e.contains("dur") ? e["dur"].get<double>() : 0));
  }
  EXPECT_EQ(op_events, counter.ops);
  EXPECT_GT(op_events, 0u);
  EXPECT_LE(last_ts, 1000.0);
  EXPECT_EQ(threads, (std::set<std::string>{"CPG", "TE", "INT 0", "INT 1", "GPE", "context 0", "context 1",
                                            "context 2", "context 3"}));
}

// A window in the middle of a run, gzip-compressed: only its cycles, triangle ids on the CPG's
// slices, one slice per vertex on its context's track, and a flow from each patch's CPG write to
// the allocation of each of its vertices.
TEST(Trace, WindowInTheMiddleCompressedWithIdsAndFlows) {
  const Mesh mesh = bumpy_sphere(0);
  const UnitConfig cfg = config(2, 3, 1, 2, 3);
  const auto path =
      std::filesystem::temp_directory_path() / ("tessim_trace_" + std::to_string(::getpid()) + ".json.gz");
  constexpr std::uint64_t kFrom = 1500, kTo = 4000;
  TraceWriter trace(path, 2, 3, TraceWindow{kFrom, kTo});
  struct Recorder : CycleObserver {
    std::uint64_t ops = 0;
    std::map<std::uint64_t, std::uint32_t> patch_of;  // vertex -> patch, from the unit
    bool on_cycle(const Unit& u, const GpeCycle&) override {
      const CycleActivity& a = u.activity();
      if (a.allocated) patch_of[a.allocated_vertex] = a.allocated_patch;
      if (a.cycle >= kFrom && a.cycle < kTo) ops += static_cast<std::uint64_t>(a.ops_issued);
      for (int i = 0; i < a.ops_issued; ++i) EXPECT_EQ(u.issued_ops()[i].context, u.issued_ops()[i].vertex % 3);
      return true;
    }
  } rec;
  SimHooks hooks;
  hooks.observers = {&trace, &rec};
  simulate(mesh, cfg, hooks);
  trace.finish();
  std::string text;
  {
    gzFile gz = gzopen(path.c_str(), "rb");
    ASSERT_NE(gz, nullptr);
    char buf[1 << 14];
    for (int n; (n = gzread(gz, buf, sizeof buf)) > 0;) text.append(buf, static_cast<std::size_t>(n));
    gzclose(gz);
  }
  std::filesystem::remove(path);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["otherData"]["first_cycle"], kFrom);
  std::uint64_t ops = 0;
  std::map<std::uint64_t, double> write_at;          // patch -> ts of its CPG write slice
  std::map<std::uint64_t, double> vertex_start;      // vertex -> start of its context slice
  std::map<std::uint64_t, std::pair<double, double>> flows;  // id -> (s ts, f ts)
  std::map<std::uint64_t, std::uint64_t> flow_patch;
  for (const auto& e : j["traceEvents"]) {
    if (e["ph"] == "M") continue;
    const double ts = e["ts"].get<double>();
    if (e["ph"] != "s") {  // a flow may start at a write before the window
      EXPECT_GE(ts, static_cast<double>(kFrom)) << e.dump();
    }
    EXPECT_LE(ts + (e.contains("dur") ? e["dur"].get<double>() : 0), static_cast<double>(kTo)) << e.dump();
    const int tid = e.contains("tid") ? e["tid"].get<int>() : -1;
    const std::string name = e["name"];
    if (e["ph"] == "X" && tid >= 1 && tid <= 2) {
      ++ops;
      if (e["args"].contains("patch")) {
        EXPECT_EQ(e["args"]["patch"], rec.patch_of.at(e["args"]["vertex"].get<std::uint64_t>()));
      }
    }
    if (e["ph"] == "X" && tid == 1000 && name != "idle") {
      ASSERT_TRUE(e["args"].contains("triangle")) << e.dump();
      if (name.rfind("write", 0) == 0) write_at[e["args"]["triangle"].get<std::uint64_t>()] = ts;
    }
    if (e["ph"] == "X" && tid >= 2000) {
      const auto v = e["args"]["vertex"].get<std::uint64_t>();
      EXPECT_EQ(tid - 2000, static_cast<int>(v % 3)) << e.dump();
      EXPECT_EQ(e["args"]["patch"], rec.patch_of.at(v));
      vertex_start[v] = ts;
    }
    if (e["ph"] == "s") {
      flows[e["id"].get<std::uint64_t>()].first = ts;
      flow_patch[e["id"].get<std::uint64_t>()] = std::stoull(name.substr(6));
    }
    if (e["ph"] == "f") flows[e["id"].get<std::uint64_t>()].second = ts;
  }
  EXPECT_EQ(ops, rec.ops);
  EXPECT_GT(flows.size(), 20u);
  for (const auto& [v, sf] : flows) {
    EXPECT_EQ(flow_patch.at(v), rec.patch_of.at(v));
    EXPECT_EQ(sf.first, write_at.at(flow_patch.at(v))) << "flow of vertex " << v << " starts at its patch's write";
    EXPECT_EQ(sf.second, vertex_start.at(v)) << "and ends where the vertex enters its context";
  }
}

}  // namespace
}  // namespace tessim::sim
