// tessim sim: a whole mesh through the cycle model of the unit and its geometry engine;
// statistics, a human summary, a Perfetto trace, the issue schedule, the tessellated mesh.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "model/error.hpp"
#include "model/mesh_io.hpp"
#include "model/output_file.hpp"
#include "model/pattern.hpp"
#include "sim/app/commands.hpp"
#include "sim/config.hpp"
#include "sim/simulate.hpp"
#include "sim/trace.hpp"

namespace tessim::app {

namespace {

constexpr const char* kDefaultMesh = "/usr/share/assimp/models/PLY/Wuson.ply";

struct SimArgs {
  std::string mesh = kDefaultMesh;
  std::string config;
  int tess_factor = 0;
  int int_blocks = 0;
  int int_latency = 0;
  int contexts = 0;
  int gpe_cycles = 0;
  double stall = 0.0;
  std::uint64_t seed = 0;
  std::string cpg;
  std::string normals;
  std::string stats;
  std::string trace;
  std::uint64_t trace_cycles = 20000;
  std::string output;
  bool schedule = false;
};

// Options given on the command line, as a JSON object of configuration keys: they go through
// the same apply_json as a config file, so a bad value is reported the same way, key named.
struct FlagOptions {
  CLI::Option* tess_factor = nullptr;
  CLI::Option* int_blocks = nullptr;
  CLI::Option* int_latency = nullptr;
  CLI::Option* contexts = nullptr;
  CLI::Option* gpe_cycles = nullptr;
  CLI::Option* stall = nullptr;
  CLI::Option* seed = nullptr;
  CLI::Option* cpg = nullptr;
  CLI::Option* normals = nullptr;
};

nlohmann::json flag_overrides(const SimArgs& a, const FlagOptions& f) {
  nlohmann::json j = nlohmann::json::object();
  if (f.tess_factor->count()) j["tess_factor"] = a.tess_factor;
  if (f.int_blocks->count()) j["int_blocks"] = a.int_blocks;
  if (f.int_latency->count()) j["int_latency"] = a.int_latency;
  if (f.contexts->count()) j["te_contexts"] = a.contexts;
  if (f.gpe_cycles->count()) j["gpe_cycles"] = a.gpe_cycles;
  if (f.stall->count()) j["gpe_stall_prob"] = a.stall;
  if (f.seed->count()) j["seed"] = a.seed;
  if (f.cpg->count()) j["cpg_mapping"] = a.cpg;
  if (f.normals->count()) j["normals"] = a.normals;
  return j;
}

sim::UnitConfig build_config(const SimArgs& a, const FlagOptions& f) {
  sim::UnitConfig cfg;
  std::string source = "command line";
  if (!a.config.empty()) {
    std::ifstream in(a.config);
    if (!in) throw InputError(a.config, "file", "cannot open");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(a.config, "JSON", e.what());
    }
    sim::apply_json(cfg, j, a.config);
    source = a.config;
  }
  const nlohmann::json flags = flag_overrides(a, f);
  sim::apply_json(cfg, flags, "command line");
  if (!flags.empty() && !a.config.empty()) source = a.config + " with command-line overrides";
  cfg.validate(source);
  return cfg;
}

void run_sim(const SimArgs& a, const FlagOptions& f) {
  const sim::UnitConfig cfg = build_config(a, f);
  if (!a.output.empty() && !is_supported_output(a.output))
    throw InputError(a.output, "output", "unsupported extension (use .ply or .obj)");
  if (a.trace_cycles == 0) throw InputError("command line", "--trace-cycles", "must be at least 1");

  const Mesh mesh = load_mesh(a.mesh);
  const int L = cfg.tess_factor;

  sim::SimHooks hooks;
  std::unique_ptr<MeshWriter> writer;
  if (!a.output.empty()) {
    writer = std::make_unique<MeshWriter>(
        a.output, mesh.triangle_count() * static_cast<std::uint64_t>(pattern_vertex_count(L)),
        mesh.triangle_count() * static_cast<std::uint64_t>(pattern_triangle_count(L)));
    hooks.on_patch = [&](const sim::PatchOut& p) {
      writer->add_patch(p.L, p.positions.data(), p.normals.data());
    };
  }
  std::unique_ptr<sim::TraceWriter> trace;
  if (!a.trace.empty()) {
    trace = std::make_unique<sim::TraceWriter>(a.trace, cfg.int_blocks, a.trace_cycles);
    hooks.observers.push_back(trace.get());
  }
  std::unique_ptr<sim::ScheduleRecorder> schedule;
  if (a.schedule) {
    schedule = std::make_unique<sim::ScheduleRecorder>();
    hooks.observers.push_back(schedule.get());
  }

  const sim::SimResult result = sim::simulate(mesh, cfg, hooks);

  // All outputs are complete in memory or in temporaries: move them into place.
  if (writer) writer->finish();
  if (trace) trace->finish();
  if (!a.stats.empty()) {
    AtomicOutput out(a.stats);
    out.stream() << sim::stats_json(result).dump(2) << "\n";
    out.commit();
  }
  std::cout << sim::summary(result);
  if (schedule) {
    std::cout << "\nissue schedule (v<vertex>.<op>, first cycles from the first issue):\n"
              << schedule->table(cfg.int_blocks);
    std::printf("steady state: %.3f cycles per vertex (retirement interval over 2520-vertex "
                "periods of the first 8192 vertices, docs/schedule.md)\n",
                schedule->steady_cycles_per_vertex());
  }
}

}  // namespace

void register_sim(CLI::App& app) {
  auto args = std::make_shared<SimArgs>();
  auto flags = std::make_shared<FlagOptions>();
  CLI::App* sub = app.add_subcommand(
      "sim", "Run a mesh through the cycle-level model of the unit and its geometry engine");
  sub->add_option("mesh", args->mesh, "input mesh (OBJ, PLY, STL, OFF, ...)")->capture_default_str();
  sub->add_option("--config", args->config, "JSON configuration (keys: docs/microarchitecture.md §1, sim/config.hpp)");
  flags->tess_factor = sub->add_option("-L,--tess-factor", args->tess_factor, "segments per edge (1..64)");
  flags->int_blocks = sub->add_option("--int", args->int_blocks, "INT blocks N");
  flags->int_latency = sub->add_option("--int-latency", args->int_latency, "INT latency in cycles");
  flags->contexts = sub->add_option("--contexts", args->contexts, "TE vertex contexts V");
  flags->gpe_cycles = sub->add_option("--gpe-cycles", args->gpe_cycles, "GPE cycles per vertex K");
  flags->stall = sub->add_option("--stall", args->stall, "GPE random stall probability");
  flags->seed = sub->add_option("--seed", args->seed, "seed of the GPE stalls");
  flags->cpg = sub->add_option("--cpg", args->cpg, "CPG mapping: dedicated or gpe");
  flags->normals = sub->add_option("--normals", args->normals, "normal mode: quadratic, reflect or linear");
  sub->add_option("--stats", args->stats, "write the statistics as JSON");
  sub->add_option("--trace", args->trace, "write a Chrome/Perfetto trace (JSON)");
  sub->add_option("--trace-cycles", args->trace_cycles, "cycles recorded in the trace")->capture_default_str();
  sub->add_option("-o,--output", args->output, "write the tessellated mesh (.ply or .obj)");
  sub->add_flag("--schedule", args->schedule, "print the issue pattern of the first vertices");
  sub->callback([args, flags] { run_sim(*args, *flags); });
}

}  // namespace tessim::app
