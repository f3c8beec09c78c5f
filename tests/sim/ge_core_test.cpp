// The geometry engine as a shader core on a clock of its own (sim/ge/gpe.hpp, ge_cost.hpp;
// docs/microarchitecture.md §12): K derived from lanes, issue and the program; the cross-clock
// FIFO's depth and synchronizers; waves; the drain; whole runs and scenes against the derivation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "model/mesh_io.hpp"
#include "sim/ge/ge_cost.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/run/scene.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::sim {
namespace {

EnvironmentConfig core(int lanes, int issue, double core_mhz, double unit_mhz, int fifo) {
  EnvironmentConfig e;
  e.ge_core_lanes = lanes;
  e.ge_core_issue = issue;
  e.ge_core_mhz = core_mhz;
  e.unit_mhz = unit_mhz;
  e.ge_core_fifo = fifo;
  return e;
}

// Vertices the GE takes over `cycles` unit cycles with a vertex always offered.
std::uint64_t accepted_in(Gpe& g, std::uint64_t cycles) {
  std::uint64_t n = 0;
  for (std::uint64_t c = 0; c < cycles; ++c) n += g.tick(true, false).accepted;
  return n;
}

TEST(GeCore, ProgramAndDerivedK) {
  // The GE's own work: 49 one-slot operations and 4 special functions (rsqrt, exp2, log2, 1/w).
  EXPECT_EQ(vertex_work_ops(), (GeOps{49, 4, 0}));
  EnvironmentConfig e = core(32, 1, 200, 200, 64);
  EXPECT_EQ(core_program_slots(e), 49u + 4u * 4u);
  EXPECT_EQ(core_wave_cycles(e), 65u);
  EXPECT_DOUBLE_EQ(core_cycles_per_vertex(e), 65.0 / 32);
  e.ge_core_issue = 2;  // ceil(65 / 2) = 33 cycles a wave
  EXPECT_DOUBLE_EQ(core_cycles_per_vertex(e), 33.0 / 32);
  e.ge_core_mhz = 400;  // a core at twice the unit's clock halves K in the unit's cycles
  EXPECT_DOUBLE_EQ(core_cycles_per_vertex(e), 33.0 / 64);
  e.ge_shader_slots = 100;  // shader work grows the program
  EXPECT_EQ(core_wave_cycles(e), 83u);
  // with_ge_cost carries the shader slots to the core and leaves K the longest wait for one vertex.
  UnitConfig cfg;
  static_cast<EnvironmentConfig&>(cfg) = core(4, 1, 100, 200, 8);
  GeVertexCost cost;
  cost.shader_slots = 7;
  const UnitConfig run = with_ge_cost(cfg, cost);
  EXPECT_EQ(run.ge_shader_slots, 7u);
  EXPECT_EQ(run.gpe_cycles, 2 * 72 + 2 + 4 + 1);
}

TEST(GeCore, SteadyRateIsLanesOverWaveCyclesInTheUnitsClock) {
  struct Case {
    int lanes, issue;
    double core_mhz, unit_mhz;
  };
  for (const Case k : {Case{4, 1, 200, 200}, Case{8, 1, 300, 200}, Case{16, 2, 150, 200}, Case{3, 1, 123.456, 200}}) {
    Gpe g(core(k.lanes, k.issue, k.core_mhz, k.unit_mhz, 4 * k.lanes));
    const double k_derived = core_cycles_per_vertex(core(k.lanes, k.issue, k.core_mhz, k.unit_mhz, 1));
    (void)accepted_in(g, 2000);  // past the fill
    const std::uint64_t cycles = 200000;
    const double rate = static_cast<double>(accepted_in(g, cycles)) / cycles;
    EXPECT_NEAR(rate, 1.0 / k_derived, 0.002 / k_derived) << k.lanes << " lanes at " << k.core_mhz << " MHz";
    EXPECT_NEAR(static_cast<double>(g.core_stats().core_cycles) / g.stats().cycles, k.core_mhz / k.unit_mhz, 1e-4);
    EXPECT_EQ(g.core_stats().fifo_peak, static_cast<std::uint64_t>(4 * k.lanes));  // the core is the limit
  }
}

TEST(GeCore, AShallowFifoCannotCoverTheSynchronizersRoundTrip) {
  // A core far faster than the unit: a deep FIFO passes a vertex every unit cycle; one entry
  // passes one per round trip — the write, two core edges to be seen, the wave's launch, two
  // unit edges for the freed entry to be seen.
  Gpe deep(core(64, 1, 20000, 200, 8));
  EXPECT_EQ(accepted_in(deep, 1000), 1000u);
  Gpe shallow(core(64, 1, 20000, 200, 1));
  const std::uint64_t n = accepted_in(shallow, 999);
  EXPECT_EQ(n, 500u);  // one every 2 unit cycles: the freed entry shows in the second register a cycle later
  EXPECT_EQ(shallow.core_stats().lanes_filled, shallow.core_stats().waves);  // one vertex a wave
}

TEST(GeCore, WavesTakeWhatTheCoreSeesAndTheDrainFinishesThem) {
  Gpe g(core(4, 1, 200, 200, 16));
  // Ten vertices offered back to back, then none.
  std::uint64_t offered = 0;
  while (offered < 10) offered += g.tick(true, false).accepted;
  const std::uint64_t drain = g.drain_cycles();
  Gpe before = g;
  for (std::uint64_t c = 0; c + 1 < drain; ++c) (void)before.tick(false, false);
  for (std::uint64_t c = 0; c < drain; ++c) (void)g.tick(false, false);
  EXPECT_EQ(g.drain_cycles(), 0u);
  EXPECT_EQ(before.drain_cycles(), 1u);
  EXPECT_EQ(g.core_stats().lanes_filled, 10u);
  // The first wave launches on the first vertex the core sees (a partial wave: it cannot know
  // more are coming); the rest wait for the issue and fill up to four lanes.
  EXPECT_EQ(g.core_stats().waves, 4u);  // 1, 4, 4, 1
  EXPECT_EQ(g.core_stats().issue_cycles, 4u * 65u);
  // A fixed K drains the rest of its countdown.
  Gpe fixed(8, 0.0, 1);
  (void)fixed.tick(true, false);
  EXPECT_EQ(fixed.drain_cycles(), 7u);
}

TEST(GeCore, ResetStartsTheCoreAgain) {
  Gpe g(core(4, 1, 150, 200, 8));
  const std::uint64_t first = accepted_in(g, 5000);
  const GeCoreStats stats = g.core_stats();
  g.reset();
  EXPECT_EQ(g.core_stats(), GeCoreStats{});
  EXPECT_EQ(accepted_in(g, 5000), first);
  EXPECT_EQ(g.core_stats(), stats);
}

const Mesh& wuson() {
  static const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  return mesh;
}

TEST(GeCore, ARunIsGeBoundAtTheDerivedKOrUnitBoundBelowIt) {
  Mesh part = wuson();
  part.triangles.resize(200);
  UnitConfig cfg;
  cfg.tess_factor = 8;
  static_cast<EnvironmentConfig&>(cfg) = core(4, 1, 200, 200, 64);  // K = 16.25
  const SimResult slow = simulate(part, cfg);
  // The run ends when the unit has handed over its last vertex, the FIFO full behind it; the
  // drain finishes them, and the whole is K per vertex.
  auto per_vertex = [](const SimResult& r) {
    return static_cast<double>(r.run_cycles() + r.gpe_drain_cycles) / static_cast<double>(r.gpe.vertices);
  };
  EXPECT_NEAR(per_vertex(slow), 16.25, 0.05);
  EXPECT_EQ(slow.gpe.vertices, 200u * 45u);
  EXPECT_EQ(slow.ge_core.fifo_peak, 64u);
  EXPECT_GE(slow.gpe_drain_cycles, 64u / 4u * 65u);
  // At the run's end the FIFO is full but for the wave the core may have just taken.
  EXPECT_LE(slow.gpe.vertices - slow.ge_core.lanes_filled, 64u);
  EXPECT_GE(slow.gpe.vertices - slow.ge_core.lanes_filled, 64u - 4u);
  // A core with K below the unit's own rate: the run takes the unit's cycles with an idle-fast GE
  // (K = 1), to within the FIFO's fill at the start.
  static_cast<EnvironmentConfig&>(cfg) = core(64, 1, 400, 200, 64);
  const SimResult fast = simulate(part, cfg);
  UnitConfig fixed;
  fixed.tess_factor = 8;
  fixed.gpe_cycles = 1;
  const SimResult unit_bound = simulate(part, fixed);
  EXPECT_NEAR(static_cast<double>(fast.run_cycles()), static_cast<double>(unit_bound.run_cycles()), 8.0);
  // Shader work lands on the core: noise displacement's 284 slots slow it down by its share.
  MeshPatterns displaced;
  displaced.displace.kind = DisplaceKind::Noise;
  static_cast<EnvironmentConfig&>(cfg) = core(4, 1, 200, 200, 64);
  const SimResult noisy = simulate(part, cfg, SimHooks{}, displaced);
  EXPECT_NEAR(per_vertex(noisy), (65.0 + 284.0) / 4, 0.2);
}

TEST(GeCore, AnUntessellatedDrawCostsFullWavesOfTheOwnProgram) {
  UnitConfig cfg;
  static_cast<EnvironmentConfig&>(cfg) = core(32, 1, 100, 200, 64);
  // 100 vertices: 4 waves of 65 core cycles = 260 core cycles = 520 unit cycles.
  EXPECT_EQ(untessellated_cycles(cfg, 100), 520u);
  cfg.ge_core_lanes = 0;
  cfg.gpe_cycles = 8;
  EXPECT_EQ(untessellated_cycles(cfg, 100), 800u);
}

}  // namespace
}  // namespace tessim::sim
