// tessim power: a mesh through the cycle model, priced in silicon units on the OSU 0.18 um cells:
// area, clock, power and energy per vertex per block (docs/silicon.md, Energy).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/config_flags.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/base/progress.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "sim/config/config.hpp"
#include "sim/report/power.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::app {

namespace {

struct PowerArgs {
  std::string mesh = "/usr/share/assimp/models/PLY/Wuson.ply";
  std::string json;
  std::string energy;  // a characterization file instead of the embedded ones
  bool clock_gating = false;
  double clock_mhz = 0;
  const CLI::Option* clock_option = nullptr;  // --clock-mhz: given, 0 or negative is an error
  bool quiet = false;
  UnitPatternOptions pattern;
};

std::string characterized_list(const std::vector<sim::EnergyCharacterization>& all) {
  std::string out;
  for (const auto& c : all) {
    out += out.empty() ? "" : "; ";
    out += c.name + " (";
    std::string params;
    for (const auto& [k, v] : c.parameters) params += (params.empty() ? "" : " ") + k + "=" + std::to_string(v);
    out += params.empty() ? "the defaults" : params;
    out += ")";
  }
  return out.empty() ? "none" : out;
}

void run_power(const PowerArgs& a, const ConfigFlags& flags) {
  sim::UnitConfig cfg = flags.config();
  if (cfg.units != 1)
    throw InputError("command line", "--units", "power prices one unit (a system's distributor and reassembly buffer "
                                                "are not characterized)");
  if (cfg.evaluation != sim::Evaluation::Unit || cfg.cpg_mapping != sim::CpgMapping::Dedicated)
    throw InputError("command line", cfg.evaluation != sim::Evaluation::Unit ? "--evaluation" : "--cpg-mapping",
                     "power prices the unit's own CPG and TE (evaluation unit, cpg_mapping dedicated)");
  if (a.clock_option && a.clock_option->count() > 0 && !(a.clock_mhz > 0))
    throw InputError("command line", "--clock-mhz", "must be a positive number of MHz");
  std::vector<sim::EnergyCharacterization> loaded;
  if (!a.energy.empty()) {
    std::ifstream in(a.energy);
    if (!in) throw InputError(a.energy, "file", "cannot be read");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(a.energy, "JSON", e.what());
    }
    loaded.push_back(sim::read_energy_characterization(j, a.energy));
  }
  const auto& all = a.energy.empty() ? sim::energy_characterizations() : loaded;
  const sim::EnergyCharacterization* c = sim::find_energy_characterization(all, cfg.hardware());
  if (!c)
    throw InputError(a.energy.empty() ? "configuration" : a.energy, "hardware",
                     "no energy characterization of this configuration (characterized: " + characterized_list(all) +
                         "); scripts/energy.py makes one from a coverage build of its RTL (docs/silicon.md, Energy: "
                         "about 40 minutes on two cores)");
  check_output_paths({{"--json", a.json}}, {{"MESH", a.mesh}, {"--config", flags.config_file()}, {"--energy", a.energy}});
  std::optional<TessSettings> pattern = a.pattern.settings("power", cfg.tess_factor, flags.overrides().contains("tess_factor"));
  const Mesh mesh = load_mesh(a.mesh);
  const std::shared_ptr<const MeshSilhouette> silhouette = a.pattern.silhouette_for(pattern, cfg.tess_factor, mesh);
  if (!cfg.cpg_tags) warn_tags_ignored(mesh, "power");
  if (silhouette && !cfg.format.takes_alpha())
    throw InputError("command line", "--silhouette",
                     "the characterized configuration " + c->name + " takes no alpha (alpha_bits 0)");
  sim::MeshPatterns patterns(pattern ? &*pattern : nullptr);
  patterns.silhouette = silhouette.get();
  patterns.displace = a.pattern.displace.settings();
  std::unique_ptr<AtomicOutput> out;
  if (!a.json.empty()) out = std::make_unique<AtomicOutput>(a.json);
  sim::SimHooks hooks;
  hooks.fast_forward = true;
  ProgressDisplay progress("power", "triangles", mesh.triangle_count(), true);
  const sim::SimResult result = sim::simulate(mesh, cfg, hooks, patterns);
  nlohmann::json stats = sim::stats_json(result);
  stats["mesh"] = a.mesh;
  const nlohmann::json report = sim::power_report(stats, *c, {a.clock_gating, a.clock_mhz});
  if (out) {
    out->stream() << report.dump(1) << "\n";
    if (!out->stream().flush()) throw InputError(a.json, "output", "write failed");
    out->commit();
  }
  if (!a.quiet) {
    std::ostream& os = output_kind(a.json) == OutputKind::Stdout ? std::cerr : std::cout;
    os << sim::power_summary(report);
    if (!os.flush()) throw InputError("standard output", "output", "write failed");
  }
}

}  // namespace

void register_power(CLI::App& app) {
  auto args = std::make_shared<PowerArgs>();
  CLI::App* sub = app.add_subcommand(
      "power", "Area, clock, power and energy per vertex of a run on the OSU 0.18 um cells, per block");
  sub->add_option("mesh", args->mesh, "input mesh (OBJ, PLY, STL, OFF, ...)")->capture_default_str();
  auto flags = std::make_shared<ConfigFlags>(*sub);
  sub->add_option("--json", args->json, "write the report as JSON (- for standard output)");
  sub->add_option("--energy", args->energy,
                  "a characterization written by scripts/energy.py instead of the embedded ones");
  sub->add_flag("--clock-gating", args->clock_gating,
                "gate the clock of idle INT blocks and of the CPG while it does not compute (latch-based gates "
                "of the library's cells, one per 32 flip-flops), and of the whole unit when idle");
  auto* clock = sub->add_option("--clock-mhz", args->clock_mhz, "run at this clock instead of the configuration's own (MHz)")
                    ->transform(number_check<double>("command line", "--clock-mhz", "a positive number"));
  args->clock_option = clock;
  add_unit_pattern_options(*sub, args->pattern, "power");
  add_displace_options(*sub, args->pattern.displace, true);
  sub->add_flag("--quiet", args->quiet, "print nothing (the JSON only)");
  sub->callback([args, flags] { run_power(*args, *flags); });
}

}  // namespace tessim::app
