// tessim bench: speed of the cycle model on a real mesh (simulated cycles and output vertices
// per CPU second of the simulating thread), median of several runs per INT-block count and GPE
// rate. Wall time is shown next to it: on a shared machine the two differ.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/mesh_io.hpp"
#include "sim/config/config.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::app {

namespace {

using BenchArgs = SpeedRunArgs;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void run_bench(const BenchArgs& a) {
  if (a.repeat < 1) throw InputError("command line", "--repeat", "must be at least 1");
  const Mesh mesh = load_mesh(a.mesh);
  std::printf("cycle-model speed on %s (%zu triangles), L=%d, median of %d runs\n", mesh.source.c_str(),
              mesh.triangle_count(), a.tess_factor, a.repeat);
  std::printf("%4s %6s %12s %12s %16s %16s %10s %10s\n", "N", "K", "cycles", "vertices", "cycles/cpu-s",
              "vertices/cpu-s", "cpu s", "wall s");
  for (int k : a.gpe_cycles) {
    for (int n : a.int_blocks) {
      sim::UnitConfig cfg;
      cfg.int_blocks = n;
      cfg.tess_factor = a.tess_factor;
      cfg.gpe_cycles = k;
      cfg.validate("command line");
      std::vector<double> wall, cpu;
      sim::SimResult r;
      for (int i = 0; i < a.repeat; ++i) {
        const double c0 = cpu_seconds();
        const auto t0 = std::chrono::steady_clock::now();
        r = sim::simulate(mesh, cfg);
        cpu.push_back(cpu_seconds() - c0);
        wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
      std::sort(wall.begin(), wall.end());
      std::sort(cpu.begin(), cpu.end());
      const double c = cpu[cpu.size() / 2];
      std::printf("%4d %6d %12llu %12llu %16.3e %16.3e %10.4f %10.4f\n", n, k,
                  static_cast<unsigned long long>(r.unit.cycles), static_cast<unsigned long long>(r.unit.vertices_out),
                  static_cast<double>(r.unit.cycles) / c, static_cast<double>(r.unit.vertices_out) / c, c,
                  wall[wall.size() / 2]);
    }
  }
  std::printf("(per CPU second of this thread; K = 1 lets the TE set the pace, so each N is a different "
              "workload; K = 8 is the default configuration)\n");
}

}  // namespace

void register_bench(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  args->gpe_cycles = {1, sim::EnvironmentConfig{}.gpe_cycles};
  CLI::App* sub = app.add_subcommand("bench", "Measure the speed of the cycle model on a mesh");
  add_speed_run_options(*sub, *args, "INT block counts to measure");
  sub->callback([args] { run_bench(*args); });
}

}  // namespace tessim::app
