// A system of units clocked on several threads (sim/system/system_threads.hpp) is the one-thread
// system cycle for cycle: the same triangle taken and the same vertices out of the ports in every
// cycle, the same counters of every unit, port and buffer at the end — over the distribution
// policies, batches, buffers down to 2 slots (the blocking regime, where units wait for the
// coordinator's decisions), ordered and unordered reassembly, random port stalls, uniform and
// adaptive D3D11 factors, more threads than cores.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/run/simulate.hpp"
#include "sim/run/testbench.hpp"
#include "sim/system/system.hpp"
#include "sim/system/system_threads.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kWuson);
  return mesh;
}

std::string describe(const UnitConfig& c, int threads) {
  return "M=" + std::to_string(c.units) + " P=" + std::to_string(c.ge_ports) + " R=" + std::to_string(c.reorder_slots) +
         " " + to_string(c.distribution) + " batch " + std::to_string(c.dispatch_batch) + " stall " +
         std::to_string(c.gpe_stall_prob) + " L=" + std::to_string(c.tess_factor) + " threads " + std::to_string(threads);
}

// The stream of the first `n` triangles of Wuson at factor L (uniform) or at the far view's
// adaptive D3D11 factors.
std::vector<TriangleFx> stream(const UnitConfig& cfg, std::size_t n, bool adaptive) {
  const Mesh& mesh = wuson();
  const HostScaling s = host_scaling(mesh);
  std::vector<TriangleFx> tris;
  TessSettings view;
  view.kind = PatternKind::D3D11;
  view.source = FactorSource::Adaptive;
  view.camera.eye = {5.2, 2.0, -5.6};
  view.camera.target = {0.0, 0.6, -0.2};
  view.pixels_per_segment = 6.0;
  const MeshPatterns patterns = adaptive ? MeshPatterns(&view) : MeshPatterns();
  MeshSource source(mesh, s, cfg.format, cfg.tess_factor, patterns, cfg.cpg_tags, 0, n);
  while (source.available()) {
    tris.push_back(source.front());
    source.pop();
  }
  return tris;
}

void expect_same_counters(const UnitSystem& a, const UnitSystem& b, const std::string& what) {
  for (int u = 0; u < a.units(); ++u) {
    const UnitCounters& x = a.unit(u).stats();
    const UnitCounters& y = b.unit(u).stats();
    EXPECT_EQ(x.cycles, y.cycles) << what << " unit " << u;
    EXPECT_EQ(x.triangles_in, y.triangles_in) << what << " unit " << u;
    EXPECT_EQ(x.vertices_out, y.vertices_out) << what << " unit " << u;
    EXPECT_EQ(x.te, y.te) << what << " unit " << u;
    EXPECT_EQ(x.cpg, y.cpg) << what << " unit " << u;
    EXPECT_EQ(x.int_busy, y.int_busy) << what << " unit " << u;
  }
  for (int p = 0; p < a.ports(); ++p) {
    EXPECT_EQ(a.port(p).stats().vertices, b.port(p).stats().vertices) << what << " port " << p;
    EXPECT_EQ(a.port(p).stats().cycles, b.port(p).stats().cycles) << what << " port " << p;
  }
  const SystemStats& s = a.stats();
  const SystemStats& t = b.stats();
  EXPECT_EQ(s.cycles, t.cycles) << what;
  EXPECT_EQ(s.unit_blocked, t.unit_blocked) << what;
  EXPECT_EQ(s.dispatch_stalls, t.dispatch_stalls) << what;
  EXPECT_EQ(s.ports_waiting_unit, t.ports_waiting_unit) << what;
  EXPECT_EQ(s.ports_waiting_stream, t.ports_waiting_stream) << what;
  EXPECT_EQ(s.max_occupancy, t.max_occupancy) << what;
  EXPECT_EQ(s.occupancy_histogram, t.occupancy_histogram) << what;
  EXPECT_EQ(s.unit_triangles, t.unit_triangles) << what;
  EXPECT_EQ(s.unit_vertices, t.unit_vertices) << what;
}

// Both systems through the stream in lock-step; false (with a failure) at the first difference.
// `switches`: the threaded run's switches between parallel and serial.
// `alternate_every` > 0: the threaded run switches between parallel and serial every that many
// cycles (else by measured speed).
bool same_run(const UnitConfig& cfg, const std::vector<TriangleFx>& tris, int threads, int* switches = nullptr,
              std::uint64_t alternate_every = 0) {
  const std::string what = describe(cfg, threads) + " alternating every " + std::to_string(alternate_every);
  UnitSystem serial(cfg, cfg.gpe_cycles);
  UnitSystem parallel(cfg, cfg.gpe_cycles);
  ThreadedSystem threaded(parallel, threads, alternate_every);
  std::uint64_t total = 0;
  for (const TriangleFx& t : tris) total += static_cast<std::uint64_t>(patch_vertex_count(t));
  std::size_t next = 0;
  std::uint64_t out = 0, cycle = 0;
  while (out < total) {
    const bool valid = next < tris.size();
    const TriangleFx& tri = tris[valid ? next : 0];
    const bool took = serial.tick(valid, tri);
    const bool took_threaded = threaded.tick(valid, tri);
    if (took != took_threaded || serial.emitted() != parallel.emitted()) {
      ADD_FAILURE() << what << ": first difference in cycle " << cycle << " (triangle taken " << took << " / "
                    << took_threaded << ", vertices out " << serial.emitted().size() << " / " << parallel.emitted().size()
                    << ")";
      return false;
    }
    next += took ? 1 : 0;
    out += serial.emitted().size();
    if (++cycle > 50'000'000) {
      ADD_FAILURE() << what << ": no end";
      return false;
    }
  }
  threaded.finish();
  if (switches) *switches = threaded.mode_switches();
  expect_same_counters(serial, parallel, what);
  return !::testing::Test::HasFailure();
}

// --threads auto: one thread unless at least four hardware threads are idle (on two cores the
// parallel mode was 0.92-1.35x one thread idle and 2-8x slower loaded), then one per idle
// hardware thread, at most one per unit; the caller's own runnable task is not load.
TEST(AutoThreads, OneThreadUnlessFourHardwareThreadsAreIdle) {
  EXPECT_EQ(auto_system_threads(16, 2, 1), 1);   // two idle cores
  EXPECT_EQ(auto_system_threads(16, 2, 3), 1);   // two cores, two hogs
  EXPECT_EQ(auto_system_threads(16, 4, 1), 4);   // four idle
  EXPECT_EQ(auto_system_threads(16, 4, 2), 1);   // one of four busy: three idle
  EXPECT_EQ(auto_system_threads(16, 8, 3), 6);   // two of eight busy
  EXPECT_EQ(auto_system_threads(3, 8, 1), 3);    // at most one per unit
  EXPECT_EQ(auto_system_threads(1, 8, 1), 1);    // one unit
  EXPECT_EQ(auto_system_threads(16, 8, 20), 1);  // overloaded
  EXPECT_EQ(auto_system_threads(16, 8, 0), 8);   // a count without the caller
  EXPECT_GE(auto_system_threads(16), 1);         // this machine, whatever its load
}

TEST(ThreadedSystem, EveryCycleAsOneThreadAcrossPoliciesBuffersStallsAndFactors) {
  int runs = 0;
  for (const bool adaptive : {false, true}) {
    UnitConfig base;
    base.tess_factor = 4;
    base.gpe_cycles = 1;
    const std::vector<TriangleFx> tris = stream(base, 300, adaptive);
    for (const int units : {2, 3, 5}) {
      for (const Distribution d : {Distribution::RoundRobin, Distribution::LeastLoaded, Distribution::EarliestFinish}) {
        for (const int slots : {2, 7, 256}) {
          UnitConfig cfg = base;
          cfg.units = units;
          cfg.ge_ports = units == 5 ? 3 : units;
          cfg.distribution = d;
          cfg.dispatch_batch = slots == 7 ? 2 : 1;
          cfg.reassembly = slots == 7 && d != Distribution::RoundRobin ? Reassembly::Unordered : Reassembly::Ordered;
          cfg.reorder_slots = slots;
          cfg.gpe_stall_prob = slots == 256 ? 0.0 : 0.3;
          cfg.validate("test");
          const std::vector<int> thread_counts = units == 2 ? std::vector<int>{2} : std::vector<int>{2, units};
          for (const int threads : thread_counts) {
            // More threads than cores also switch modes at odd cycles.
            ASSERT_TRUE(same_run(cfg, tris, threads, nullptr, threads > 2 ? 333 : 0));
            ++runs;
          }
        }
      }
    }
  }
  EXPECT_EQ(runs, 2 * 3 * 3 * (1 + 2 + 2));
}

// Sixteen units at K = 1 with a large buffer: the units run far ahead of the coordinator (the
// admission horizon), and the TRI FIFOs' late pushes carry the run.
TEST(ThreadedSystem, SixteenUnitsFarAheadOfTheCoordinator) {
  UnitConfig cfg;
  cfg.tess_factor = 6;
  cfg.gpe_cycles = 1;
  cfg.units = 16;
  cfg.ge_ports = 16;
  cfg.reorder_slots = 4096;
  cfg.distribution = Distribution::LeastLoaded;
  cfg.tri_fifo_depth = 3;
  cfg.validate("test");
  const std::vector<TriangleFx> tris = stream(cfg, 600, true);
  for (const int threads : {2, 4, 16}) EXPECT_TRUE(same_run(cfg, tris, threads));
}

// A whole-mesh run through simulate(): the same result whatever SimHooks::system_threads.
TEST(ThreadedSystem, SimulateGivesTheSameResultOnAnyThreadCount) {
  Mesh mesh = wuson();
  mesh.triangles.resize(400);
  UnitConfig cfg;
  cfg.tess_factor = 5;
  cfg.gpe_cycles = 1;
  cfg.units = 4;
  cfg.ge_ports = 4;
  cfg.reorder_slots = 64;
  cfg.gpe_stall_prob = 0.1;
  cfg.validate("test");
  std::vector<VertexFx> want, got;
  SimHooks one;
  one.on_vertex = [&](const VertexFx& v) { want.push_back(v); };
  const SimResult a = simulate(mesh, cfg, one);
  SimHooks two;
  two.on_vertex = [&](const VertexFx& v) { got.push_back(v); };
  two.system_threads = 3;
  const SimResult b = simulate(mesh, cfg, two);
  EXPECT_EQ(want, got);
  EXPECT_EQ(a.unit.cycles, b.unit.cycles);
  ASSERT_TRUE(a.system && b.system);
  EXPECT_EQ(a.system->stats.cycles, b.system->stats.cycles);
  EXPECT_EQ(a.system->stats.occupancy_histogram, b.system->stats.occupancy_histogram);
}

}  // namespace
}  // namespace tessim::sim

namespace tessim::sim {
namespace {

// Patches of 561 vertices, more than a unit's rings hold: units run the rings' length ahead.
TEST(ThreadedSystem, PatchesLongerThanTheExchangeRings) {
  for (const int slots : {1024, 40}) {
    UnitConfig cfg;
    cfg.tess_factor = 32;
    cfg.gpe_cycles = 1;
    cfg.units = 4;
    cfg.ge_ports = 4;
    cfg.reorder_slots = slots;
    cfg.validate("test");
    const std::vector<TriangleFx> tris = stream(cfg, 400, false);
    EXPECT_TRUE(same_run(cfg, tris, 2));
  }
}

}  // namespace
}  // namespace tessim::sim

namespace tessim::sim {
namespace {

// Long patches fill the buffer, short ones empty it, long ones fill it again; the run switches
// between parallel and serial every 500 or 777 cycles, wherever the units and the buffer stand:
// every cycle as one thread throughout.
TEST(ThreadedSystem, SwitchesBetweenParallelAndSerialAtAnyCycle) {
  UnitConfig cfg;
  cfg.gpe_cycles = 1;
  cfg.units = 4;
  cfg.ge_ports = 4;
  cfg.reorder_slots = 1024;
  cfg.validate("test");
  std::vector<TriangleFx> tris;
  for (const auto& [L, n] : {std::pair{32, 80}, std::pair{3, 900}, std::pair{32, 60}}) {
    cfg.tess_factor = L;
    for (const TriangleFx& t : stream(cfg, static_cast<std::size_t>(n), false)) {
      tris.push_back(t);
      tris.back().id = static_cast<std::uint32_t>(tris.size() - 1);
    }
  }
  for (const std::uint64_t every : {500, 777}) {
    int switches = 0;
    EXPECT_TRUE(same_run(cfg, tris, 2, &switches, every));
    EXPECT_GE(switches, 20) << every;
  }
}

}  // namespace
}  // namespace tessim::sim
