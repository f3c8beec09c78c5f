// tessim rtlbench: simulated cycles per second of the Verilated RTL versus the cycle model on
// the same mesh, configuration and backpressure. Each implementation runs alone (no lock-step
// comparison), driven by its own copy of the same geometry-engine model.
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
#include "model/pattern.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/run/testbench.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/host.hpp"

namespace tessim::app {

namespace {

// The RTL is some 50 times slower than the cycle model: a lighter default workload.
struct RtlBenchArgs : SpeedRunArgs {
  RtlBenchArgs() {
    tess_factor = 4;
    repeat = 3;
  }
};

struct Timing {
  std::uint64_t cycles = 0;
  double wall = 0, cpu = 0;
};

// Runs one implementation over the stream until the GPE has taken every vertex.
template <typename Impl>
Timing run_alone(Impl& impl, const std::vector<sim::TriangleFx>& stream, const sim::UnitConfig& cfg) {
  sim::Testbench tb(stream, cfg);
  std::uint64_t cycles = 0;
  const std::clock_t c0 = std::clock();
  const auto t0 = std::chrono::steady_clock::now();
  while (!tb.done()) {
    impl.tick(tb.inputs(impl));
    ++cycles;
  }
  Timing t;
  t.cycles = cycles;
  t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t.cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  return t;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void run(const RtlBenchArgs& a) {
  if (a.repeat < 1) throw InputError("command line", "--repeat", "must be at least 1");
  // Every N must have its build before anything is printed: a table cut short is no result.
  const std::vector<std::string> builds = rtl::rtl_variants();
  for (int n : a.int_blocks) {
    std::string build = "n";  // appended apart: GCC 12 warns (-Wrestrict) about "n" + std::string
    build += std::to_string(n);
    if (std::find(builds.begin(), builds.end(), build) == builds.end()) {
      std::string have;
      for (const std::string& b : builds)
        if (b.size() == 2 && b[0] == 'n') have += (have.empty() ? "" : ", ") + b.substr(1);
      throw InputError("command line", "--int",
                       std::to_string(n) + " has no RTL build (N with a build of its own: " + have + ")");
    }
  }
  const Mesh mesh = load_mesh(a.mesh);
  std::printf("Verilated RTL versus cycle model on %s (%zu triangles), L=%d, median of %d runs\n",
              mesh.source.c_str(), mesh.triangle_count(), a.tess_factor, a.repeat);
  std::printf("%4s %6s %10s %16s %16s %10s\n", "N", "K", "cycles", "model cycles/s", "RTL cycles/s", "model/RTL");
  for (int k : a.gpe_cycles) {
    for (int n : a.int_blocks) {
      std::string build = "n";  // appended apart: GCC 12 warns (-Wrestrict) about "n" + std::string
      build += std::to_string(n);
      auto rtl = rtl::make_rtl_unit(build, 1);
      sim::UnitConfig cfg = sim::with_hardware(rtl->config());
      cfg.tess_factor = a.tess_factor;
      cfg.gpe_cycles = k;
      cfg.validate("command line");
      const sim::HostScaling scaling = sim::host_scaling(mesh);
      std::vector<sim::TriangleFx> stream;
      stream.reserve(mesh.triangle_count());
      for (std::size_t i = 0; i < mesh.triangle_count(); ++i)
        stream.push_back(sim::to_fixed(mesh, i, scaling, cfg.format, cfg.tess_factor));

      std::vector<double> model_cps, rtl_cps;
      std::uint64_t cycles = 0;
      for (int i = 0; i < a.repeat; ++i) {
        sim::Unit model(cfg);
        const Timing m = run_alone(model, stream, cfg);
        rtl->reset();
        rtl->set_mode(cfg.normals);
        const Timing r = run_alone(*rtl, stream, cfg);
        if (m.cycles != r.cycles)
          throw std::runtime_error("RTL and cycle model took different cycle counts; run tessim cosim");
        cycles = m.cycles;
        model_cps.push_back(static_cast<double>(m.cycles) / m.cpu);
        rtl_cps.push_back(static_cast<double>(r.cycles) / r.cpu);
      }
      const double mc = median(model_cps), rc = median(rtl_cps);
      std::printf("%4d %6d %10llu %16.3e %16.3e %9.1fx\n", n, k, static_cast<unsigned long long>(cycles), mc, rc,
                  mc / rc);
    }
  }
  std::printf("(speeds in simulated cycles per CPU second of this process; both clocked cycle by cycle)\n");
}

}  // namespace

void register_rtlbench(CLI::App& app) {
  auto args = std::make_shared<RtlBenchArgs>();
  CLI::App* sub = app.add_subcommand("rtlbench", "Speed of the Verilated RTL versus the cycle model on a mesh");
  add_speed_run_options(*sub, *args, "INT block counts (RTL builds n1..n4)");
  sub->callback([args] { run(*args); });
}

}  // namespace tessim::app
