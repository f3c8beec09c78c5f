// tessim bench: wall-clock speed of the cycle model on a real mesh (simulated cycles per
// second and output vertices per second), median of several runs per INT-block count. The
// process CPU time is shown next to it: on a shared machine the two differ.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "model/error.hpp"
#include "model/mesh_io.hpp"
#include "app/commands.hpp"
#include "sim/config.hpp"
#include "sim/simulate.hpp"

namespace tessim::app {

namespace {

using BenchArgs = SpeedRunArgs;

void run_bench(const BenchArgs& a) {
  if (a.repeat < 1) throw InputError("command line", "--repeat", "must be at least 1");
  const Mesh mesh = load_mesh(a.mesh);
  std::printf("cycle-model speed on %s (%zu triangles), L=%d, GPE K=%d, median of %d runs\n",
              mesh.source.c_str(), mesh.triangle_count(), a.tess_factor, a.gpe_cycles, a.repeat);
  std::printf("%4s %12s %12s %14s %14s %10s %10s\n", "N", "cycles", "vertices", "cycles/s", "vertices/s",
              "wall s", "cpu s");
  for (int n : a.int_blocks) {
    sim::UnitConfig cfg;
    cfg.int_blocks = n;
    cfg.tess_factor = a.tess_factor;
    cfg.gpe_cycles = a.gpe_cycles;
    cfg.validate("command line");
    std::vector<double> wall, cpu;
    sim::SimResult r;
    for (int i = 0; i < a.repeat; ++i) {
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      r = sim::simulate(mesh, cfg);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    std::sort(wall.begin(), wall.end());
    std::sort(cpu.begin(), cpu.end());
    const double median = wall[wall.size() / 2];
    std::printf("%4d %12llu %12llu %14.3e %14.3e %10.4f %10.4f\n", n,
                static_cast<unsigned long long>(r.unit.cycles),
                static_cast<unsigned long long>(r.unit.vertices_out),
                static_cast<double>(r.unit.cycles) / median,
                static_cast<double>(r.unit.vertices_out) / median, median, cpu[cpu.size() / 2]);
  }
}

}  // namespace

void register_bench(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* sub = app.add_subcommand("bench", "Measure the speed of the cycle model on a mesh");
  add_speed_run_options(*sub, *args, "INT block counts to measure");
  sub->callback([args] { run_bench(*args); });
}

}  // namespace tessim::app
