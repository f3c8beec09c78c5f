// Fast-forward (docs/microarchitecture.md §11) is exact: a unit that takes its quiet cycles at
// once is, after every stretch it skips, in the same state as a unit clocked cycle by cycle —
// same counters, outputs, GPE statistics and activity — and a whole-mesh run reports the same
// result and the same vertices with and without it. The same for a system of units
// (UnitSystem::fast_forward), serial and on two threads.
#include <gtest/gtest.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/run/testbench.hpp"
#include "sim/system/system.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kWuson);
  return mesh;
}

// The first `count` triangles of Wuson with factors 1..max_L drawn from `seed`.
std::vector<TriangleFx> stream_of(const UnitConfig& cfg, std::size_t count, int max_L, std::uint64_t seed) {
  const Mesh& mesh = wuson();
  const HostScaling scaling = host_scaling(mesh);
  SplitMix64 rng(seed);
  std::vector<TriangleFx> out;
  for (std::size_t t = 0; t < count && t < mesh.triangle_count(); ++t) {
    const int L = 1 + static_cast<int>(rng.next() % static_cast<std::uint64_t>(max_L));
    out.push_back(to_fixed(mesh, t, scaling, cfg.format, L));
  }
  return out;
}

struct Case {
  std::string name;
  NormalMode normals = NormalMode::Quadratic;
  int n = 2, latency = 1, contexts = 4, k = 8, vtx_fifo = 2, tri_fifo = 2;
  CpgMapping mapping = CpgMapping::Dedicated;
  double stall = 0.0;
  int max_L = 12;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

UnitConfig config_of(const Case& c) {
  UnitConfig cfg;
  cfg.normals = c.normals;
  cfg.int_blocks = c.n;
  cfg.int_latency = c.latency;
  cfg.te_contexts = c.contexts;
  cfg.gpe_cycles = c.k;
  cfg.vtx_fifo_depth = c.vtx_fifo;
  cfg.tri_fifo_depth = c.tri_fifo;
  cfg.cpg_mapping = c.mapping;
  cfg.cpg_gpe_cycles = 37;
  cfg.gpe_stall_prob = c.stall;
  cfg.seed = 11;
  cfg.validate("test");
  return cfg;
}

// Every mode, N = 1..4, latencies, contexts, fast and slow geometry engines, both CPG mappings,
// FIFO depths, and random stalls (where nothing may be skipped).
std::vector<Case> cases() {
  return {
      {"quadratic_n2_k8", NormalMode::Quadratic, 2, 1, 4, 8},
      {"quadratic_n1_k1", NormalMode::Quadratic, 1, 1, 4, 1},
      {"quadratic_n4_k40", NormalMode::Quadratic, 4, 1, 4, 40},
      {"reflect_n3_k3_lat3", NormalMode::Reflect, 3, 3, 4, 3},
      {"reflect_n2_v1_k20", NormalMode::Reflect, 2, 1, 1, 20},
      {"linear_n4_k2", NormalMode::Linear, 4, 1, 4, 2},
      {"linear_n1_lat2_v7_k12", NormalMode::Linear, 1, 2, 7, 12},
      {"quadratic_n3_fifos_k25", NormalMode::Quadratic, 3, 1, 4, 25, 5, 1},
      {"gpe_cpg_quadratic_n2_k4", NormalMode::Quadratic, 2, 1, 4, 4, 2, 2, CpgMapping::Gpe},
      {"gpe_cpg_linear_n4_k9", NormalMode::Linear, 4, 2, 3, 9, 3, 3, CpgMapping::Gpe},
      {"reflect_n2_k8_heavy", NormalMode::Reflect, 2, 1, 4, 8, 2, 2, CpgMapping::Dedicated, 0.0, 40},
      {"quadratic_n2_stall", NormalMode::Quadratic, 2, 1, 4, 6, 2, 2, CpgMapping::Dedicated, 0.3},
  };
}

void expect_same_state(const Unit& a, const Unit& b, const Testbench& ta, const Testbench& tb,
                       std::uint64_t cycle) {
  ASSERT_EQ(a.stats(), b.stats()) << "counters at cycle " << cycle;
  ASSERT_EQ(ta.gpe().stats(), tb.gpe().stats()) << "GPE at cycle " << cycle;
  ASSERT_EQ(ta.accepted(), tb.accepted()) << "cycle " << cycle;
  ASSERT_EQ(a.tri_ready(), b.tri_ready()) << "cycle " << cycle;
  ASSERT_EQ(a.vtx_valid(), b.vtx_valid()) << "cycle " << cycle;
  if (a.vtx_valid()) {
    ASSERT_EQ(a.vtx(), b.vtx()) << "cycle " << cycle;
  }
  ASSERT_EQ(a.cpg_computing(), b.cpg_computing()) << "cycle " << cycle;
  ASSERT_EQ(a.tri_fifo_count(), b.tri_fifo_count()) << "cycle " << cycle;
  ASSERT_EQ(a.vtx_fifo_count(), b.vtx_fifo_count()) << "cycle " << cycle;
  ASSERT_EQ(a.contexts_in_use(), b.contexts_in_use()) << "cycle " << cycle;
  const CycleActivity& x = a.activity();
  const CycleActivity& y = b.activity();
  ASSERT_EQ(x.cycle, y.cycle);
  ASSERT_EQ(x.te, y.te) << "cycle " << cycle;
  ASSERT_EQ(x.cpg, y.cpg) << "cycle " << cycle;
  ASSERT_EQ(x.cpg_action, y.cpg_action) << "cycle " << cycle;
  ASSERT_EQ(x.ops_issued, y.ops_issued) << "cycle " << cycle;
  for (int i = 0; i < x.ops_issued; ++i) {
    const IssuedOp& p = a.issued_ops()[i];
    const IssuedOp& q = b.issued_ops()[i];
    ASSERT_EQ(p.block, q.block) << "cycle " << cycle;
    ASSERT_EQ(p.context, q.context) << "cycle " << cycle;
    ASSERT_EQ(p.op, q.op) << "cycle " << cycle;
    ASSERT_EQ(p.vertex, q.vertex) << "cycle " << cycle;
  }
  ASSERT_EQ(ta.gpe_cycle().ready, tb.gpe_cycle().ready) << "cycle " << cycle;
  ASSERT_EQ(ta.gpe_cycle().spare, tb.gpe_cycle().spare) << "cycle " << cycle;
  ASSERT_EQ(ta.gpe_cycle().cls, tb.gpe_cycle().cls) << "cycle " << cycle;
}

class FastForward : public ::testing::TestWithParam<Case> {};

// Unit `a` fast-forwards wherever it can; unit `b` is clocked through the same cycles one by one.
TEST_P(FastForward, SkippedStretchesLeaveTheStateOfCycleByCycleClocking) {
  const Case& c = GetParam();
  const UnitConfig cfg = config_of(c);
  const std::vector<TriangleFx> stream = stream_of(cfg, 160, c.max_L, 5);
  Unit a(cfg), b(cfg);
  Testbench ta(stream, cfg), tb(stream, cfg);
  std::uint64_t cycle = 0, skipped = 0, stretches = 0, issuing = 0;
  while (!ta.done()) {
    // A small issuing limit now and then: a stretch in which the TE issues may be cut anywhere.
    const std::uint64_t n = ta.fast_forward(a, 1'000'000, cycle % 7 == 0 ? 1 + cycle % 3 : Unit::kForever);
    if (n > 0) {
      for (std::uint64_t i = 0; i < n; ++i) b.tick(tb.inputs(b));
      skipped += n;
      ++stretches;
      if (a.activity().ops_issued > 0) ++issuing;
      cycle += n;
    } else {
      const UnitInputs& ia = ta.inputs(a);
      const UnitInputs& ib = tb.inputs(b);
      ASSERT_EQ(ia.tri_valid, ib.tri_valid);
      ASSERT_EQ(ia.vtx_ready, ib.vtx_ready);
      ASSERT_EQ(ia.cpg_step, ib.cpg_step);
      a.tick(ia);
      b.tick(ib);
      ++cycle;
    }
    expect_same_state(a, b, ta, tb, cycle);
    if (HasFatalFailure()) return;
    ASSERT_LT(cycle, 50'000'000u) << "no end";
  }
  EXPECT_TRUE(tb.done());
  if (c.stall > 0) {
    EXPECT_EQ(skipped, 0u) << "random stalls must be drawn every cycle";
  } else {
    // Every case here has quiet stretches (a slow GPE, a CPG countdown or a full VTX FIFO), and
    // stretches in which only the TE works (ops issued while the GPE counts down).
    EXPECT_GT(stretches, 0u);
    EXPECT_GT(skipped, 0u);
    EXPECT_GT(issuing, 0u);
  }
  RecordProperty("skipped_cycles", std::to_string(skipped));
  RecordProperty("issuing_stretches", std::to_string(issuing));
}

// A whole-mesh run: every field of the result and every vertex, with and without fast-forward.
TEST_P(FastForward, WholeMeshRunsAreIdentical) {
  const Case& c = GetParam();
  UnitConfig cfg = config_of(c);
  cfg.tess_factor = 5;
  const Mesh& mesh = wuson();
  // Per-triangle factors 1..max_L on half of the mesh's triangles, as an adaptive workload.
  std::vector<std::uint8_t> factors(mesh.triangle_count());
  SplitMix64 rng(3);
  for (auto& f : factors) f = static_cast<std::uint8_t>(1 + rng.next() % static_cast<std::uint64_t>(c.max_L));
  for (const bool adaptive : {false, true}) {
    std::vector<VertexFx> with, without;
    SimHooks on, off;
    on.on_vertex = [&](const VertexFx& v) { with.push_back(v); };
    off.on_vertex = [&](const VertexFx& v) { without.push_back(v); };
    off.fast_forward = false;
    const std::span<const std::uint8_t> f = adaptive ? std::span<const std::uint8_t>(factors) : std::span<const std::uint8_t>();
    const SimResult x = simulate(mesh, cfg, on, f);
    const SimResult y = simulate(mesh, cfg, off, f);
    EXPECT_EQ(x.unit, y.unit) << (adaptive ? "adaptive" : "uniform");
    EXPECT_EQ(x.gpe, y.gpe);
    EXPECT_EQ(x.gpe_waited, y.gpe_waited);
    EXPECT_EQ(x.te_late, y.te_late);
    EXPECT_EQ(x.degenerate_patches, y.degenerate_patches);
    EXPECT_EQ(x.zero_normals, y.zero_normals);
    nlohmann::json jx = stats_json(x), jy = stats_json(y);
    jx.erase("wall_seconds");
    jy.erase("wall_seconds");
    EXPECT_EQ(jx, jy);
    ASSERT_EQ(with.size(), without.size());
    EXPECT_TRUE(with == without);
  }
}

INSTANTIATE_TEST_SUITE_P(Configs, FastForward, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// A geometry engine 10^5 times slower than the unit: nearly every cycle is skipped, and the
// run still counts every one of them.
TEST(FastForwardSlowGpe, CountsEveryCycle) {
  UnitConfig cfg;
  cfg.gpe_cycles = 100000;
  cfg.tess_factor = 1;
  cfg.validate("test");
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/cube.ply");
  const SimResult x = simulate(mesh, cfg);
  SimHooks off;
  off.fast_forward = false;
  const SimResult y = simulate(mesh, cfg, off);
  EXPECT_EQ(x.unit, y.unit);
  EXPECT_EQ(x.gpe, y.gpe);
  const std::uint64_t vertices = 3 * mesh.triangle_count();
  EXPECT_EQ(x.unit.vertices_out, vertices);
  EXPECT_GE(x.unit.cycles, (vertices - 1) * 100000);
}

// ---- A system of units (docs/microarchitecture.md §13)

struct SystemCase {
  std::string name;
  int units = 2, ports = 1, slots = 64, k = 8, batch = 1;
  Distribution distribution = Distribution::RoundRobin;
  Reassembly reassembly = Reassembly::Ordered;
  int max_L = 6;
};

void PrintTo(const SystemCase& c, std::ostream* os) { *os << c.name; }

UnitConfig system_config_of(const SystemCase& c) {
  UnitConfig cfg;
  cfg.units = c.units;
  cfg.ge_ports = c.ports;
  cfg.reorder_slots = c.slots;
  cfg.gpe_cycles = c.k;
  cfg.dispatch_batch = c.batch;
  cfg.distribution = c.distribution;
  cfg.reassembly = c.reassembly;
  cfg.seed = 5;
  cfg.validate("test");
  return cfg;
}

// Slow and fast geometry engines, one and several ports, every policy, both reassemblies, a
// buffer that fills (4 slots) and one that does not, batches.
std::vector<SystemCase> system_cases() {
  return {
      {"m2_p1_k8", 2, 1, 64, 8},
      {"m2_p1_k300", 2, 1, 64, 300},
      {"m4_p1_k300_r4", 4, 1, 4, 300},
      {"m4_p2_k40_least_loaded", 4, 2, 16, 40, 1, Distribution::LeastLoaded},
      {"m3_p3_k1_earliest_finish", 3, 3, 64, 1, 1, Distribution::EarliestFinish},
      {"m4_p1_k200_unordered", 4, 1, 8, 200, 1, Distribution::RoundRobin, Reassembly::Unordered},
      {"m2_p2_k120_batch3", 2, 2, 32, 120, 3, Distribution::EarliestFinish},
      {"m16_p4_k1000", 16, 4, 256, 1000, 1, Distribution::LeastLoaded, Reassembly::Ordered, 3},
  };
}

void expect_same_system(const UnitSystem& a, const UnitSystem& b, const std::string& where) {
  const SystemStats &x = a.stats(), &y = b.stats();
  EXPECT_EQ(x.cycles, y.cycles) << where;
  EXPECT_EQ(x.vertices, y.vertices) << where;
  EXPECT_EQ(x.dispatch_stalls, y.dispatch_stalls) << where;
  EXPECT_EQ(x.unit_blocked, y.unit_blocked) << where;
  EXPECT_EQ(x.ports_waiting_unit, y.ports_waiting_unit) << where;
  EXPECT_EQ(x.ports_waiting_stream, y.ports_waiting_stream) << where;
  EXPECT_EQ(x.max_occupancy, y.max_occupancy) << where;
  EXPECT_EQ(x.occupancy_histogram, y.occupancy_histogram) << where;
  EXPECT_EQ(x.unit_triangles, y.unit_triangles) << where;
  EXPECT_EQ(x.unit_vertices, y.unit_vertices) << where;
  EXPECT_EQ(a.occupancy(), b.occupancy()) << where;
  for (int u = 0; u < a.units(); ++u) {
    EXPECT_EQ(a.unit(u).stats(), b.unit(u).stats()) << where << ", unit " << u;
    EXPECT_EQ(a.unit(u).tri_ready(), b.unit(u).tri_ready()) << where << ", unit " << u;
    EXPECT_EQ(a.unit(u).vtx_valid(), b.unit(u).vtx_valid()) << where << ", unit " << u;
  }
  for (int p = 0; p < a.ports(); ++p) EXPECT_EQ(a.port(p).stats(), b.port(p).stats()) << where << ", port " << p;
}

class FastForwardSystem : public ::testing::TestWithParam<SystemCase> {};

// Two systems on one stream: one takes its quiet stretches at once, the other is ticked through
// them with the same inputs (and must take no triangle and emit no vertex there); after every
// stretch and at the end both are in the same state, and they emit the same vertices.
TEST_P(FastForwardSystem, SkippedStretchesLeaveTheStateOfCycleByCycleClocking) {
  const SystemCase& c = GetParam();
  const UnitConfig cfg = system_config_of(c);
  const std::vector<TriangleFx> stream = stream_of(cfg, 120, c.max_L, 9);
  std::uint64_t total = 0;
  for (const TriangleFx& t : stream) total += static_cast<std::uint64_t>(patch_vertex_count(t));
  UnitSystem a(cfg, c.k), b(cfg, c.k);
  std::size_t next = 0;
  std::uint64_t emitted = 0, skipped = 0, stretches = 0, cycles = 0;
  const TriangleFx none{};
  while (emitted < total && cycles < 50'000'000) {
    const bool valid = next < stream.size();
    const TriangleFx& tri = valid ? stream[next] : none;
    if (const std::uint64_t n = a.fast_forward(valid, tri, ~std::uint64_t{0}); n > 0) {
      for (std::uint64_t i = 0; i < n; ++i) {
        ASSERT_FALSE(b.tick(valid, tri)) << "a skipped cycle dispatched a triangle, cycle " << cycles + i;
        ASSERT_TRUE(b.emitted().empty()) << "a skipped cycle emitted a vertex, cycle " << cycles + i;
      }
      cycles += n;
      skipped += n;
      ++stretches;
      expect_same_system(a, b, "after the stretch ending at cycle " + std::to_string(cycles));
      if (::testing::Test::HasFailure()) return;
      continue;
    }
    const bool took_a = a.tick(valid, tri), took_b = b.tick(valid, tri);
    ASSERT_EQ(took_a, took_b) << "cycle " << cycles;
    ASSERT_TRUE(a.emitted() == b.emitted()) << "cycle " << cycles;
    emitted += a.emitted().size();
    if (took_a) ++next;
    ++cycles;
  }
  ASSERT_EQ(emitted, total) << "the run did not end";
  expect_same_system(a, b, "at the end");
  EXPECT_TRUE(a.idle());
  // A slow geometry engine leaves the system quiet most of the time: the stretches must be found.
  if (c.k >= 100) {
    EXPECT_GT(skipped, cycles / 2) << stretches << " stretches";
  }
  RecordProperty("skipped_cycles", std::to_string(skipped));
}

// A whole-mesh run through simulate(): the same statistics and vertices with and without
// fast-forward, on one thread and on two.
TEST_P(FastForwardSystem, WholeMeshRunsAreIdentical) {
  const SystemCase& c = GetParam();
  UnitConfig cfg = system_config_of(c);
  cfg.tess_factor = 2;
  std::vector<VertexFx> off_vertices;
  SimHooks off;
  off.fast_forward = false;
  off.on_vertex = [&](const VertexFx& v) { off_vertices.push_back(v); };
  const SimResult y = simulate_range(wuson(), cfg, 0, 300, off);
  nlohmann::json jy = stats_json(y);
  jy.erase("wall_seconds");
  for (const int threads : {1, 2}) {
    std::vector<VertexFx> on_vertices;
    SimHooks on;
    on.system_threads = threads;
    on.on_vertex = [&](const VertexFx& v) { on_vertices.push_back(v); };
    const SimResult x = simulate_range(wuson(), cfg, 0, 300, on);
    EXPECT_EQ(x.unit, y.unit) << threads << " threads";
    EXPECT_EQ(x.gpe, y.gpe) << threads << " threads";
    nlohmann::json jx = stats_json(x);
    jx.erase("wall_seconds");
    EXPECT_EQ(jx, jy) << threads << " threads";
    EXPECT_TRUE(on_vertices == off_vertices) << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(Configs, FastForwardSystem, ::testing::ValuesIn(system_cases()),
                         [](const ::testing::TestParamInfo<SystemCase>& i) { return i.param.name; });

// The case: sixteen units behind a geometry engine 10^5 cycles a vertex. Cycle by cycle
// it took about half an hour; fast-forwarded, every cycle is still counted.
TEST(FastForwardSystemSlowGpe, CountsEveryCycle) {
  UnitConfig cfg;
  cfg.units = 16;
  cfg.gpe_cycles = 100000;
  cfg.tess_factor = 1;
  cfg.validate("test");
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/cube.ply");
  const SimResult x = simulate(mesh, cfg);
  const std::uint64_t vertices = 3 * mesh.triangle_count();
  EXPECT_EQ(x.gpe.vertices, vertices);
  ASSERT_TRUE(x.system);
  EXPECT_GE(x.system->stats.cycles, (vertices - 1) * 100000);
  EXPECT_LE(x.system->stats.cycles, vertices * 100000 + 1000);
}

}  // namespace
}  // namespace tessim::sim
