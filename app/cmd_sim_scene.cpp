// tessim sim SCENE.scene.json: every frame of a scene through the unit and its geometry engine
// (sim/run/scene.hpp, docs/scenes.md): frame times along the camera path, and with --stats a
// statistics document with a frame list.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/base/progress.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/ge_cost.hpp"
#include "sim/run/scene.hpp"
#include "sim/version.hpp"

namespace tessim::app {

namespace {

const char* tessellation_name(sim::DrawTessellation t) {
  switch (t) {
    case sim::DrawTessellation::None: return "none";
    case sim::DrawTessellation::Uniform: return "uniform";
    default: return "adaptive";
  }
}

nlohmann::json draw_json(const sim::Scene& scene, const sim::DrawRun& run) {
  const sim::SceneDraw& draw = scene.draws[run.draw];
  return {{"draw", run.draw},
          {"name", draw.name},
          {"instance", run.instance},
          {"tessellation", tessellation_name(draw.tessellation)},
          {"triangles", run.triangles},
          {"vertices", run.vertices},
          {"cycles", run.cycles},
          {"unit_cycles", run.unit_cycles}};
}

}  // namespace

bool is_scene_file(const std::string& path) { return path.ends_with(".scene.json"); }

void run_sim_scene(const std::string& path, const std::string& stats_path, const sim::UnitConfig& cfg, bool quiet) {
  if (cfg.units > 1)
    throw InputError("command line", "--units", "a scene runs on one unit (its draws one after another)");
  if (cfg.evaluation == sim::Evaluation::Gpe)
    throw InputError("command line", "--evaluation", "a scene runs the unit (evaluation unit)");
  if (!stats_path.empty()) check_output_paths({{"--stats", stats_path}}, {{"SCENE", path}});
  const sim::Scene scene = sim::load_scene(path);
  // With a shader-core GE the unit's clock is a parameter of the run (unit_mhz, against the
  // core's): it sets the frame times, and a scene's own clock_mhz gives way to it.
  const double clock_mhz = cfg.ge_core() ? cfg.unit_mhz : scene.clock_mhz;
  if (cfg.ge_core() && scene.clock_mhz > 0.0 && std::abs(scene.clock_mhz - cfg.unit_mhz) > 5e-4)
    std::fprintf(stderr, "tessim: note: %s: frame times at unit_mhz %g (the shader core's partner clock), not the scene's clock_mhz %g\n",
                 path.c_str(), cfg.unit_mhz, scene.clock_mhz);
  std::unique_ptr<AtomicOutput> stats;
  if (!stats_path.empty()) stats = std::make_unique<AtomicOutput>(stats_path);
  const bool on_stdout = stats && stats->kind() == OutputKind::Stdout;
  std::FILE* report = on_stdout ? stderr : stdout;
  std::uint64_t instances = 0;
  for (const sim::SceneDraw& d : scene.draws) instances += d.instances.size();
  char k_text[96];
  if (cfg.ge_core())
    std::snprintf(k_text, sizeof k_text, "GE core %d lanes at %g MHz: K = %.3f", cfg.ge_core_lanes, cfg.ge_core_mhz,
                  sim::core_cycles_per_vertex(cfg));
  else
    std::snprintf(k_text, sizeof k_text, "K = %d", cfg.gpe_cycles);
  std::fprintf(report, "scene    %s: %zu draws (%llu instances), %zu frames, N = %d, %s%s\n", path.c_str(),
               scene.draws.size(), static_cast<unsigned long long>(instances), scene.cameras.size(), cfg.int_blocks,
               k_text, clock_mhz > 0.0 ? (", clock " + std::to_string(clock_mhz).substr(0, 8) + " MHz").c_str() : "");
  ProgressDisplay progress("sim: frames", "frames", scene.cameras.size(), quiet || on_stdout);
  nlohmann::json frames = nlohmann::json::array();
  std::uint64_t worst = 0, total = 0;
  const std::vector<sim::FrameRun> runs = sim::run_scene(scene, cfg, [&](const sim::FrameRun& f) {
    nlohmann::json fj = {{"frame", f.frame},
                         {"cycles", f.cycles},
                         {"unit_idle_cycles", f.unit_idle_cycles},
                         {"vertices", f.vertices},
                         {"tessellated_vertices", f.tessellated_vertices},
                         {"draws", nlohmann::json::array()}};
    if (clock_mhz > 0.0) fj["ms"] = static_cast<double>(f.cycles) / (clock_mhz * 1e3);
    for (const sim::DrawRun& d : f.draws) fj["draws"].push_back(draw_json(scene, d));
    frames.push_back(std::move(fj));
    worst = std::max(worst, f.cycles);
    total += f.cycles;
    std::fprintf(report, "frame %3zu %12llu cycles", f.frame, static_cast<unsigned long long>(f.cycles));
    if (clock_mhz > 0.0) std::fprintf(report, " %9.3f ms", static_cast<double>(f.cycles) / (clock_mhz * 1e3));
    std::fprintf(report, "  %llu vertices (%llu tessellated), unit idle %.1f %%\n",
                 static_cast<unsigned long long>(f.vertices), static_cast<unsigned long long>(f.tessellated_vertices),
                 f.cycles ? 100.0 * static_cast<double>(f.unit_idle_cycles) / static_cast<double>(f.cycles) : 0.0);
    if (progress.counter()) progress.counter()->fetch_add(1);
  });
  progress.finish();
  const double mean = static_cast<double>(total) / static_cast<double>(runs.size());
  // The GE's cycles per vertex (unit cycles): the fixed K, or the one derived from the core.
  const double ge_k = cfg.ge_core() ? sim::core_cycles_per_vertex(cfg) : cfg.gpe_cycles;
  nlohmann::json summary = {
      {"frames", runs.size()}, {"mean_cycles", mean}, {"worst_cycles", worst}, {"ge_cycles_per_vertex", ge_k}};
  std::fprintf(report, "frames   mean %.0f cycles, worst %llu", mean, static_cast<unsigned long long>(worst));
  if (clock_mhz > 0.0) {
    // The worst frame decides the frame rate a unit sustains along the path.
    const double fps = clock_mhz * 1e6 / static_cast<double>(worst);
    summary["worst_ms"] = static_cast<double>(worst) / (clock_mhz * 1e3);
    summary["sustained_fps"] = fps;
    std::fprintf(report, " (%.3f ms): sustains %.1f frames per second at %g MHz", static_cast<double>(worst) / (clock_mhz * 1e3),
                 fps, clock_mhz);
  }
  std::fprintf(report, "\n");
  if (stats) {
    nlohmann::json doc = {{"schema", "tessim-scene-stats"},
                          {"version", 1},
                          {"tool", {{"name", "tessim"}, {"version", tool_version()}}},
                          {"scene", path},
                          {"config", sim::to_json(cfg)},
                          {"clock_mhz", clock_mhz > 0.0 ? nlohmann::json(clock_mhz) : nlohmann::json()},
                          {"summary", summary},
                          {"frames", std::move(frames)}};
    stats->stream() << doc.dump(1) << "\n";
    stats->commit();
  }
}

}  // namespace tessim::app
