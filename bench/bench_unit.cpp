// Google Benchmark of the cycle model: simulated cycles per second of Unit + Gpe (the lock-step
// loop of a co-simulation, without the RTL) and of a whole-mesh run on a real mesh.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <vector>

#include "model/mesh_io.hpp"
#include "sim/config.hpp"
#include "sim/host.hpp"
#include "sim/simulate.hpp"
#include "sim/testbench.hpp"
#include "sim/unit.hpp"

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

}  // namespace

BENCHMARK_MAIN();
