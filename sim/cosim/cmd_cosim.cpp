// tessim cosim: lock-step co-simulation of the Verilated RTL against the cycle model.
#include <cstdio>
#include <iostream>
#include <string>

#include "model/error.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/app/commands.hpp"
#include "sim/config.hpp"
#include "sim/cosim/cosim.hpp"
#include "sim/host.hpp"

namespace tessim::app {

namespace {

struct CosimArgs {
  std::string mesh = "/usr/share/assimp/models/PLY/Wuson.ply";
  std::size_t random_count = 0;
  int random_max_L = 8;
  std::string config_file;
  int int_blocks = 2;
  int tess_factor = 0;
  int gpe_cycles = 0;
  double stall = -1;
  std::string normals;
  std::uint64_t seed = 1;
  int seeds = 1;
  std::string variant;
  bool verif = false;
  std::string wave;
  int wave_window = 200;
};

int run(const CosimArgs& a, const CLI::App& cmd) {
  sim::UnitConfig cfg;
  if (!a.config_file.empty()) cfg = sim::load_config(a.config_file);
  cfg.int_blocks = a.int_blocks;
  if (cmd.count("-L")) cfg.tess_factor = a.tess_factor;
  if (cmd.count("--gpe-cycles")) cfg.gpe_cycles = a.gpe_cycles;
  if (cmd.count("--stall")) cfg.gpe_stall_prob = a.stall;
  if (!a.normals.empty()) {
    const auto m = parse_normal_mode(a.normals);
    if (!m) throw InputError("--normals", a.normals, "not one of quadratic, reflect, linear, derivative");
    cfg.normals = *m;
  }
  cfg.validate("command line");

  std::vector<sim::TriangleFx> stream;
  std::string source;
  if (a.random_count > 0) {
    if (a.random_max_L < 1 || a.random_max_L > kMaxTessFactor)
      throw InputError("--random-max-L", std::to_string(a.random_max_L), "must be in 1..64");
    source = std::to_string(a.random_count) + " random triangles";
  } else {
    const Mesh mesh = load_mesh(a.mesh);
    const sim::HostScaling scaling = sim::host_scaling(mesh);
    stream.reserve(mesh.triangle_count());
    for (std::size_t i = 0; i < mesh.triangle_count(); ++i)
      stream.push_back(sim::to_fixed(mesh, i, scaling, cfg.format, cfg.tess_factor));
    source = a.mesh;
  }

  cosim::CosimOptions opts;
  opts.unit = cfg;
  opts.variant = !a.variant.empty() ? a.variant
                                    : "n" + std::to_string(cfg.int_blocks) + (a.verif ? "_verif" : "");
  opts.wave = a.wave;
  opts.wave_window = a.wave_window;
  int failures = 0;
  for (int s = 0; s < a.seeds; ++s) {
    opts.seed = a.seed + static_cast<std::uint64_t>(s);
    opts.unit.seed = opts.seed;
    if (a.random_count > 0)
      stream = cosim::random_triangles(a.random_count, opts.seed, cfg.format, a.random_max_L);
    std::cout << "stream: " << source << "\n";
    const cosim::CosimReport rep = cosim::run_cosim(stream, opts);
    std::cout << cosim::format_report(rep, opts) << std::flush;
    if (!rep.passed) {
      ++failures;
      break;  // the first failing seed is the one to debug
    }
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

void register_cosim(CLI::App& app) {
  auto args = std::make_shared<CosimArgs>();
  CLI::App* cmd = app.add_subcommand("cosim", "Lock-step co-simulation of the Verilated RTL against the cycle model");
  cmd->add_option("mesh", args->mesh, "Input mesh (default: Debian's assimp-testmodels Wuson.ply)");
  cmd->add_option("--random", args->random_count, "Use N random triangles (with degenerate ones) instead of a mesh");
  cmd->add_option("--random-max-L", args->random_max_L, "Largest factor of the random triangles (1..64)");
  cmd->add_option("--config", args->config_file, "Unit configuration (JSON); flags override it");
  cmd->add_option("--int", args->int_blocks, "INT blocks N (selects the RTL build nN)")->check(CLI::Range(1, 32));
  cmd->add_option("-L", args->tess_factor, "Tessellation factor (segments per edge)");
  cmd->add_option("--gpe-cycles", args->gpe_cycles, "Geometry engine: one vertex every K cycles");
  cmd->add_option("--stall", args->stall, "Geometry engine: probability of a random stall per cycle");
  cmd->add_option("--normals", args->normals, "quadratic | reflect | linear");
  cmd->add_option("--seed", args->seed, "Seed of the backpressure and of the RTL's X randomisation");
  cmd->add_option("--seeds", args->seeds, "Run this many consecutive seeds")->check(CLI::Range(1, 1000000));
  cmd->add_option("--variant", args->variant, "RTL build to use (see docs/rtl.md)");
  cmd->add_flag("--verif", args->verif, "Use the verification build (X randomised)");
  cmd->add_option("--wave", args->wave, "On divergence, write an FST waveform of the window before it");
  cmd->add_option("--wave-window", args->wave_window, "Cycles of waveform before the divergence")->check(CLI::Range(1, 10000000));
  cmd->callback([args, cmd]() {
    const int status = run(*args, *cmd);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace tessim::app
