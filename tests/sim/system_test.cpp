// A system of several units (sim/system/system.hpp): the output is the single unit's vertex for
// vertex whatever the distribution, batch, buffer, ports and stalls; the buffer never holds more
// than R and never deadlocks; the counts add up; M units deliver M times one unit's rate where the
// units limit, and the reassembly buffer's size decides it on adaptive views.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "model/base/error.hpp"
#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/system/system.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kWuson);
  return mesh;
}

Mesh wuson_part(std::size_t n) {
  Mesh m = wuson();
  m.triangles.resize(n);
  return m;
}

TessSettings far_view() {
  TessSettings s;
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.camera.eye = {5.2, 2.0, -5.6};
  s.camera.target = {0.0, 0.6, -0.2};
  s.pixels_per_segment = 6.0;
  return s;
}

struct Outcome {
  std::vector<VertexFx> vertices;
  SimResult result;
};

Outcome run(const Mesh& mesh, const UnitConfig& cfg, const MeshPatterns& patterns = {}) {
  Outcome r;
  SimHooks hooks;
  hooks.on_vertex = [&](const VertexFx& v) { r.vertices.push_back(v); };
  r.result = simulate(mesh, cfg, hooks, patterns);
  return r;
}

std::string describe(const UnitConfig& c) {
  return "M=" + std::to_string(c.units) + " P=" + std::to_string(c.ge_ports) + " R=" + std::to_string(c.reorder_slots) +
         " " + to_string(c.distribution) + " batch " + std::to_string(c.dispatch_batch) + " stall " +
         std::to_string(c.gpe_stall_prob);
}

TEST(UnitSystem, OutputIsTheSingleUnitsVertexForVertexAndTheCountsAddUp) {
  const Mesh mesh = wuson_part(240);
  const TessSettings adaptive = far_view();
  UnitConfig single;
  single.gpe_cycles = 2;
  single.cpg = CpgVariant{3, 4};
  for (const bool d3d11 : {false, true}) {
    const MeshPatterns patterns = d3d11 ? MeshPatterns(&adaptive) : MeshPatterns();
    single.tess_factor = 3;
    const Outcome want = run(mesh, single, patterns);
    for (const int units : {2, 3, 4}) {
      for (const Distribution d : {Distribution::RoundRobin, Distribution::LeastLoaded, Distribution::EarliestFinish}) {
        for (const int batch : {1, 3}) {
          for (const int slots : {2, 5, 64}) {
            UnitConfig cfg = single;
            cfg.units = units;
            cfg.distribution = d;
            cfg.dispatch_batch = batch;
            cfg.reorder_slots = slots;
            cfg.ge_ports = 1 + (slots + batch) % units;
            cfg.gpe_stall_prob = slots == 5 ? 0.3 : 0.0;
            cfg.seed = static_cast<std::uint64_t>(slots * 7 + batch);
            cfg.validate("test");
            const Outcome got = run(mesh, cfg, patterns);
            ASSERT_EQ(got.vertices, want.vertices) << describe(cfg);
            const SystemResult& s = *got.result.system;
            EXPECT_LE(s.stats.max_occupancy, slots) << describe(cfg);
            EXPECT_EQ(std::accumulate(s.stats.occupancy_histogram.begin(), s.stats.occupancy_histogram.end(),
                                      std::uint64_t{0}),
                      s.stats.cycles);
            EXPECT_EQ(std::accumulate(s.stats.unit_vertices.begin(), s.stats.unit_vertices.end(), std::uint64_t{0}),
                      want.vertices.size());
            EXPECT_EQ(std::accumulate(s.stats.unit_triangles.begin(), s.stats.unit_triangles.end(), std::uint64_t{0}),
                      want.result.unit.triangles_in);
            std::uint64_t port_vertices = 0;
            for (const GpeStats& p : s.ports) port_vertices += p.vertices;
            EXPECT_EQ(port_vertices, want.vertices.size());
            EXPECT_EQ(got.result.unit.cycles, s.stats.cycles * static_cast<std::uint64_t>(units));
            if (d == Distribution::RoundRobin && batch == 1) {  // in turn: the counts differ by one at most
              for (std::uint64_t n : s.stats.unit_triangles)
                EXPECT_LE(n, (want.result.unit.triangles_in + units - 1) / units) << describe(cfg);
            }
          }
        }
      }
    }
  }
}

TEST(UnitSystem, UnitsMultiplyTheRateWhereTheyLimit) {
  // L = 4 with the sequential CPG: one unit is CPG-bound at 16.4 cycles a vertex; with a port per
  // unit, M units take M times the vertices per cycle (within the fill and drain).
  const Mesh mesh = wuson_part(400);
  UnitConfig cfg;
  cfg.tess_factor = 4;
  const double one = throughput(run(mesh, cfg).result);
  for (const int m : {2, 4}) {
    cfg.units = m;
    cfg.ge_ports = m;
    const SimResult r = run(mesh, cfg).result;
    EXPECT_NEAR(throughput(r), m * one, 0.02 * m * one) << m;
    EXPECT_EQ(r.run_cycles(), r.system->stats.cycles);
  }
}

TEST(UnitSystem, FourFastUnitsDeliverNinetyPercentOfFourVerticesACycleOnTheFarView) {
  // The target of the scale-out: P = M = 4 ports at K = 1 and units that keep up with small
  // patches (N = 14, ten copies of the three-lane CPG); the buffer of 256 slots is enough here.
  const TessSettings view = far_view();
  UnitConfig cfg;
  cfg.gpe_cycles = 1;
  cfg.int_blocks = 14;
  cfg.te_contexts = 16;
  cfg.cp_buffers = 8;
  cfg.cpg = CpgVariant{3, 4, 10};
  cfg.units = 4;
  cfg.ge_ports = 4;
  cfg.reorder_slots = 256;
  cfg.validate("test");
  const SimResult r = run(wuson(), cfg, MeshPatterns(&view)).result;
  EXPECT_GE(throughput(r), 0.9 * 4);
  // The same with a buffer of 16 slots: the units wait for each other's patches.
  cfg.reorder_slots = 16;
  const SimResult small = run(wuson(), cfg, MeshPatterns(&view)).result;
  EXPECT_LT(throughput(small), 0.6 * throughput(r));
  EXPECT_GT(small.system->stats.unit_blocked, 0u);
}

TEST(UnitSystem, ASystemTakesDedicatedCpgsOnTheirTes) {
  UnitConfig cfg;
  cfg.units = 2;
  EXPECT_NO_THROW(cfg.validate("test"));
  cfg.cpg_mapping = CpgMapping::Gpe;
  EXPECT_THROW(cfg.validate("test"), InputError);
  cfg.cpg_mapping = CpgMapping::Dedicated;
  cfg.evaluation = Evaluation::Gpe;
  EXPECT_THROW(cfg.validate("test"), InputError);
}

}  // namespace
}  // namespace tessim::sim

namespace tessim::sim {
namespace {

// Unordered reassembly (a study's bound): the ports take any unit's vertices, the run hands them
// on in stream order all the same, every slot is anyone's, and with a buffer too small for the
// order it is faster than the ordered system; with room for the order it is as fast.
TEST(UnitSystem, UnorderedReassemblyBoundsWhatTheOrderCosts) {
  const Mesh mesh = wuson_part(300);
  const TessSettings adaptive = far_view();
  const MeshPatterns patterns(&adaptive);
  UnitConfig single;
  single.gpe_cycles = 1;
  single.cpg = CpgVariant{3, 4};
  const Outcome want = run(mesh, single, patterns);
  for (const int units : {2, 4}) {
    for (const int slots : {4, 16, 4096}) {
      UnitConfig cfg = single;
      cfg.units = units;
      cfg.ge_ports = units;
      cfg.reorder_slots = slots;
      cfg.validate("test");
      const Outcome ordered = run(mesh, cfg, patterns);
      cfg.reassembly = Reassembly::Unordered;
      const Outcome unordered = run(mesh, cfg, patterns);
      ASSERT_EQ(unordered.vertices, want.vertices) << describe(cfg);
      const SystemStats& s = unordered.result.system->stats;
      EXPECT_LE(s.max_occupancy, slots);
      EXPECT_EQ(s.vertices, want.vertices.size());
      const double a = throughput(ordered.result), b = throughput(unordered.result);
      if (slots == 4) {
        EXPECT_GT(b, 1.15 * a) << describe(cfg);
      } else if (slots == 4096) {
        EXPECT_NEAR(b, a, 0.02 * a) << describe(cfg);
      }
      EXPECT_GE(b, 0.98 * a) << describe(cfg);
    }
  }
}

}  // namespace
}  // namespace tessim::sim
