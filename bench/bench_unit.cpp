// Google Benchmark of the cycle model: simulated cycles per second of Unit + Gpe (the lock-step
// loop of a co-simulation, without the RTL) and of a whole-mesh run on a real mesh.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <thread>
#include <vector>

#include "model/factors.hpp"
#include "model/mesh_io.hpp"
#include "sim/config/config.hpp"
#include "sim/run/simulate.hpp"
#include "sim/run/testbench.hpp"
#include "sim/system/system_threads.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/host.hpp"

namespace {

using namespace tessim;
using namespace tessim::sim;

const char* const kMesh = "/usr/share/assimp/models/PLY/Wuson.ply";

const Mesh& wuson() {
  static const Mesh mesh = load_mesh(kMesh);
  return mesh;
}

UnitConfig config(int n, int k, int L) {
  UnitConfig c;
  c.int_blocks = n;
  c.gpe_cycles = k;
  c.tess_factor = L;
  c.validate("benchmark");
  return c;
}

// The bare cycle loop: a pre-converted triangle stream, the GPE driving vtx_ready.
void BM_UnitCycles(benchmark::State& state) {
  const UnitConfig cfg = config(static_cast<int>(state.range(0)), 1, 16);
  const Mesh& mesh = wuson();
  const HostScaling s = host_scaling(mesh);
  std::vector<TriangleFx> stream;
  for (std::size_t t = 0; t < 200; ++t) stream.push_back(to_fixed(mesh, t, s, cfg.format, cfg.tess_factor));
  std::uint64_t cycles = 0, vertices = 0;
  for (auto _ : state) {
    Unit unit(cfg);
    Testbench tb(stream, cfg);
    while (!tb.done()) unit.tick(tb.inputs(unit));
    cycles += unit.stats().cycles;
    vertices += tb.accepted();
  }
  state.counters["cycles/s"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(vertices), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_UnitCycles)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

// tessim sim on the real mesh with the default configuration but N (no output files).
void BM_SimulateMesh(benchmark::State& state) {
  const UnitConfig cfg = config(static_cast<int>(state.range(0)), UnitConfig{}.gpe_cycles, 8);
  std::uint64_t cycles = 0, vertices = 0;
  for (auto _ : state) {
    const SimResult r = simulate(wuson(), cfg);
    cycles += r.unit.cycles;
    vertices += r.unit.vertices_out;
  }
  state.counters["cycles/s"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(vertices), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateMesh)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

// tessim sim --units M --threads T on the real mesh: M units at K = 1 with M ports, L = 16 and a
// buffer that never fills (the units run ahead of the coordinator), and an adaptive close view at
// 2 pixels per segment with R = 1024 (the buffer full most of the time: the run goes serial).
// Every simulated cycle is the same whatever T; the counters give the simulator's speed.
void BM_SystemMesh(benchmark::State& state) {
  UnitConfig cfg = config(2, 1, 16);
  cfg.units = static_cast<int>(state.range(0));
  cfg.ge_ports = cfg.units;
  const bool full_buffer = state.range(2) != 0;
  cfg.reorder_slots = full_buffer ? 1024 : 65536;
  cfg.validate("benchmark");
  TessSettings view;
  view.kind = PatternKind::D3D11;
  view.source = FactorSource::Adaptive;
  view.camera.eye = {1.2, 1.5, -2.2};
  view.camera.width = 800;
  view.camera.height = 600;
  view.pixels_per_segment = 2.0;
  const MeshPatterns patterns = full_buffer ? MeshPatterns(&view) : MeshPatterns();
  SimHooks hooks;
  hooks.system_threads = static_cast<int>(state.range(1));
  std::uint64_t cycles = 0, vertices = 0;
  for (auto _ : state) {
    const SimResult r = simulate(wuson(), cfg, hooks, patterns);
    cycles += r.system->stats.cycles;
    vertices += r.unit.vertices_out;
  }
  state.counters["cycles/s"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(vertices), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SystemMesh)
    ->ArgNames({"M", "threads", "full_buffer"})
    ->ArgsProduct({{2, 4, 8, 16}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// `--threads auto` against one thread (docs/results/performance.md): the open case of
// BM_SystemMesh with four units, alone on the machine and beside a CPU hog (one spinning thread
// per hardware thread, started before the run and stopped after it). Args: hog (0/1), threads (0:
// auto, as the command line resolves it now, or a count).
void BM_SystemThreadsAuto(benchmark::State& state) {
  UnitConfig cfg = config(2, 1, 16);
  cfg.units = 4;
  cfg.ge_ports = 4;
  cfg.reorder_slots = 65536;
  cfg.validate("benchmark");
  std::atomic<bool> stop{false};
  std::vector<std::thread> hog;
  if (state.range(0) != 0) {
    const unsigned n = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned i = 0; i < n; ++i)
      hog.emplace_back([&stop] {
        volatile std::uint64_t x = 0;
        while (!stop.load(std::memory_order_relaxed)) x = x + 1;
      });
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the hog shows in /proc/loadavg
  }
  SimHooks hooks;
  std::uint64_t cycles = 0;
  int threads = 0;
  for (auto _ : state) {
    threads = state.range(1) == 0 ? auto_system_threads(cfg.units) : static_cast<int>(state.range(1));
    hooks.system_threads = threads;
    cycles += simulate(wuson(), cfg, hooks).system->stats.cycles;
  }
  stop = true;
  for (std::thread& t : hog) t.join();
  state.counters["cycles/s"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
  state.counters["threads"] = threads;
}
BENCHMARK(BM_SystemThreadsAuto)
    ->ArgNames({"hog", "threads"})
    ->ArgsProduct({{0, 1}, {1, 2, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
