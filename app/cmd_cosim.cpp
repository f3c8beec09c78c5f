// tessim cosim: lock-step co-simulation of the Verilated RTL against the cycle model.
#include <algorithm>
#include <charconv>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/config_flags.hpp"
#include "cosim/cosim.hpp"
#include "cosim/coverage.hpp"
#include "cosim/wave.hpp"
#include "model/base/error.hpp"
#include "model/base/input_file.hpp"
#include "model/base/output_file.hpp"
#include "model/base/progress.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/base/json_input.hpp"
#include "sim/config/config.hpp"
#include "sim/values/host.hpp"

namespace tessim::app {

namespace {

struct CosimArgs {
  std::string mesh = "/usr/share/assimp/models/PLY/Wuson.ply";
  std::size_t random_count = 0;
  int random_max_L = 8;
  double random_extent = 1.0;
  int seeds = 1;
  std::string variant;
  bool verif = false;
  std::string wave;
  std::string wave_window = "200";  // N cycles before a divergence, or START:END
  UnitPatternOptions pattern;
  std::string coverage;                 // functional coverage file (accumulated)
  std::vector<std::uint64_t> reset_at;  // cycles of a mid-stream reset
  int random_resets = 0;                // resets at random cycles (cosim::RandomResets)
  bool quiet = false;
};

// A decimal number of cycles, the whole text and nothing else.
std::optional<std::uint64_t> parse_cycles(const std::string& text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string known_builds() {
  std::string known;
  for (const std::string& v : rtl::rtl_variants()) known += (known.empty() ? "" : ", ") + v;
  return known;
}

// The RTL build to run: --variant, else the build (the VERIF build with --verif) that
// implements the configuration's hardware. A build that does not exist is bad input, named
// with the builds that do (docs/rtl.md).
std::string choose_variant(const CosimArgs& a, const ConfigFlags& flags, const sim::UnitConfig& cfg) {
  const std::vector<std::string> builds = rtl::rtl_variants();
  auto exists = [&](const std::string& v) { return std::find(builds.begin(), builds.end(), v) != builds.end(); };
  if (!a.variant.empty()) {
    if (!exists(a.variant))
      throw InputError("command line", "--variant",
                       "no RTL build '" + a.variant + "'; the RTL builds are " + known_builds());
    return a.variant;
  }
  if (cfg.evaluation != sim::Evaluation::Unit)
    throw InputError(flags.config_file().empty() || flags.overrides().contains("evaluation") ? "command line"
                                                                                          : flags.config_file(),
                     "evaluation", "the RTL is the unit with its TE (evaluation unit); gpe exists in the cycle model only");
  if (cfg.units != 1)
    throw InputError(flags.config_file().empty() || flags.overrides().contains("units") ? "command line"
                                                                                     : flags.config_file(),
                     "units", "the RTL builds are single units; a system of " + std::to_string(cfg.units) +
                                  " exists in the cycle model only (tessim sim --units)");
  if (const std::optional<std::string> v = rtl::find_rtl_variant(cfg.hardware(), a.verif)) return *v;
  const std::string source = flags.config_file().empty() || flags.overrides().contains("int_blocks")
                                 ? "command line"
                                 : flags.config_file();
  throw InputError(source, "int_blocks",
                   "no RTL build implements this hardware (int_blocks " + std::to_string(cfg.int_blocks) +
                       ", cpg_lanes " + std::to_string(cfg.cpg.lanes) + ", cpg_digit_bits " +
                       std::to_string(cfg.cpg.digit_bits) + ", cpg_product_reg " + std::to_string(cfg.cpg.product_reg) +
                       ", cpg_tags " + std::to_string(cfg.cpg_tags) + ", alpha_bits " +
                       std::to_string(cfg.format.alpha_bits) +
                       (a.verif ? ", --verif" : "") +
                       "); the RTL builds are " + known_builds() + " (docs/rtl.md adds one)");
}

int run(const CosimArgs& a, const ConfigFlags& flags) {
  if (a.seeds < 1 || a.seeds > 1000000)
    throw InputError("command line", "--seeds", std::to_string(a.seeds) + " is outside 1..1000000");
  if (a.random_resets < 0 || a.random_resets > 1000)
    throw InputError("command line", "--random-resets", std::to_string(a.random_resets) + " is outside 0..1000");
  // --wave-window: N cycles before a divergence, or an explicit START:END recorded in any run.
  int wave_before = 200;
  std::optional<cosim::WaveWindow> wave_cycles;
  if (const std::size_t colon = a.wave_window.find(':'); colon != std::string::npos) {
    const auto from = parse_cycles(a.wave_window.substr(0, colon));
    const auto to = parse_cycles(a.wave_window.substr(colon + 1));
    if (!from || !to || *to < *from)
      throw InputError("command line", "--wave-window",
                       "'" + a.wave_window + "' is not START:END with START <= END (cycles)");
    if (a.seeds != 1)
      throw InputError("command line", "--wave-window", "an explicit window records one run: use --seeds 1");
    wave_cycles = cosim::WaveWindow{*from, *to};
  } else {
    const auto n = parse_cycles(a.wave_window);
    if (!n || *n < 1 || *n > 10000000)
      throw InputError("command line", "--wave-window",
                       "'" + a.wave_window + "' is neither a cycle count in 1..10000000 nor START:END");
    wave_before = static_cast<int>(*n);
  }
  // The waveform is written only after the run: check its format and paths now. Its recording is
  // a temporary, removed when the command fails or is interrupted.
  std::optional<cosim::WaveTemporaries> wave_temporaries;
  if (!a.wave.empty()) {
    cosim::check_wave_path(a.wave);
    check_output_paths({{"--wave", a.wave}, {"--wave", cosim::gtkw_path(a.wave).string()}, {"--coverage", a.coverage}},
                       {{"MESH", a.mesh}, {"--config", flags.config_file()}});
    wave_temporaries.emplace(a.wave);
  }
  const sim::UnitConfig cfg = flags.config();  // defaults, --config, the flags given
  const std::string variant = choose_variant(a, flags, cfg);
  // --random draws the factors of a D3D11 pattern: --partitioning P, or mixed (one per triangle).
  const bool mixed = a.pattern.partitioning == "mixed";
  UnitPatternOptions pattern_options = a.pattern;
  if (mixed) {
    if (a.random_count == 0) throw InputError("command line", "--partitioning", "'mixed' needs --random");
    pattern_options.partitioning = "integer";
  }
  std::optional<TessSettings> pattern =
      pattern_options.settings("cosim", cfg.tess_factor, flags.overrides().contains("tess_factor"));
  if (a.pattern.silhouette_given() && a.random_count > 0)
    throw InputError("command line", "--silhouette", "needs a mesh; --random draws every edge's alpha (a build that takes it)");
  if (a.pattern.silhouette_given() && !cfg.format.takes_alpha())
    throw InputError("command line", "--silhouette",
                     "the blend needs a unit that takes alpha (alpha_bits > 0, e.g. --variant n3_lat3 with its "
                     "parameters; docs/rtl.md)");
  if (pattern && a.random_count > 0 && (pattern->source == FactorSource::Adaptive || !a.pattern.outer.empty()))
    throw InputError("command line", a.pattern.outer.empty() ? "--adaptive" : "--outer",
                     "needs a mesh; --random draws the factors (with --partitioning)");
  if (pattern && cfg.format.bary_bits < 16)
    throw InputError(flags.config_file().empty() ? "command line" : flags.config_file(), "bary_bits",
                     "the D3D11 pattern's points are 16.16: it needs bary_bits >= 16, not " +
                         std::to_string(cfg.format.bary_bits));

  std::vector<sim::TriangleFx> stream;
  std::string source;
  std::optional<Partitioning> random_partitioning;
  if (pattern && !mixed) random_partitioning = pattern->partitioning;
  if (a.random_count > 0) {
    if (!(a.random_extent > 0 && a.random_extent <= 1000))
      throw InputError("command line", "--random-extent", std::to_string(a.random_extent) + " is outside (0, 1000]");
    if (a.random_max_L < 1 || a.random_max_L > kMaxTessFactor)
      throw InputError("command line", "--random-max-L", std::to_string(a.random_max_L) + " is outside 1..64");
    source = std::to_string(a.random_count) + " random triangles";
    if (cfg.format.takes_alpha()) source += ", random alpha";
    if (pattern)
      source += std::string(", D3D11 pattern with random factors up to ") + std::to_string(a.random_max_L) + ", " +
                (mixed ? "mixed partitionings" : partitioning_name(pattern->partitioning));
  } else {
    const Mesh mesh = load_mesh(a.mesh);
    const std::shared_ptr<const MeshSilhouette> silhouette = pattern_options.silhouette_for(pattern, cfg.tess_factor, mesh);
    if (!cfg.cpg_tags) warn_tags_ignored(mesh, "cosim");
    else warn_tags_lost(mesh, cfg.format);
    const sim::HostScaling scaling = sim::host_scaling(mesh);
    TessSettings settings;
    settings.L = cfg.tess_factor;
    if (pattern) settings = *pattern;
    stream.reserve(mesh.triangle_count());
    std::size_t culled = 0;
    for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
      std::optional<sim::TriangleFx> tri = sim::to_fixed(mesh, i, scaling, cfg.format, settings, cfg.cpg_tags != 0);
      if (!tri) {
        ++culled;
        continue;
      }
      if (silhouette) sim::set_silhouette_alpha(*tri, *silhouette, i, cfg.format);
      tri->id = static_cast<std::uint32_t>(stream.size());  // stream positions: a culled patch is not sent
      stream.push_back(*tri);
    }
    if (stream.empty())
      throw InputError("command line", "--outer", "the factors cull every patch (an outer factor <= 0 or NaN): nothing to run");
    source = a.mesh + (pattern ? " (" + pattern->describe() + ")" : "") + (silhouette ? ", silhouette blend" : "");
    if (culled) source += ", " + std::to_string(culled) + " culled patches not sent";
  }

  // Functional coverage accumulates into the file across seeds and invocations; it is read
  // (and checked) before the run, so a bad file stops the command before anything runs.
  cosim::FunctionalCoverage coverage;
  // (A device or pipe given as the file has nothing to add to.)
  if (!a.coverage.empty() && output_kind(a.coverage) == OutputKind::File && std::filesystem::exists(a.coverage)) {
    const std::string text = read_whole_file(a.coverage, kDataFileLimit, "file");
    const nlohmann::json j = sim::parse_json_text(text, a.coverage);
    coverage = cosim::FunctionalCoverage::from_json(j, a.coverage);
  }
  std::unique_ptr<AtomicOutput> coverage_out;
  if (!a.coverage.empty()) coverage_out = std::make_unique<AtomicOutput>(a.coverage);

  cosim::CosimOptions opts;
  opts.unit = cfg;
  opts.reset_at = a.reset_at;
  opts.random_resets.count = a.random_resets;
  if (coverage_out) opts.coverage = &coverage;
  opts.variant = variant;
  opts.wave = a.wave;
  opts.wave_window = wave_before;
  opts.wave_cycles = wave_cycles;
  int failures = 0, run = 0;
  std::uint64_t vertices = 0, cycles = 0;
  for (int s = 0; s < a.seeds; ++s) {
    opts.seed = cfg.seed + static_cast<std::uint64_t>(s);
    opts.unit.seed = opts.seed;
    if (a.random_count > 0) {
      stream = cosim::random_triangles(a.random_count, opts.seed, cfg.format, a.random_max_L, 0.1, a.random_extent,
                                       cfg.cpg_tags != 0);
      if (pattern) cosim::assign_random_patterns(stream, opts.seed, a.random_max_L, random_partitioning);
      if (cfg.format.takes_alpha()) cosim::assign_random_alpha(stream, opts.seed, cfg.format.alpha_bits);
    }
    std::cout << "stream: " << source << "\n" << std::flush;
    std::uint64_t stream_vertices = 0;
    for (const sim::TriangleFx& t : stream) stream_vertices += static_cast<std::uint64_t>(sim::patch_vertex_count(t));
    ProgressDisplay progress("cosim", "vertices", stream_vertices, a.quiet);
    opts.vertices_done = progress.counter();
    const cosim::CosimReport rep = cosim::run_cosim(stream, opts);
    progress.finish();
    std::cout << cosim::format_report(rep, opts) << std::flush;
    ++run;
    vertices += rep.vertices;
    cycles += rep.cycles;
    if (!rep.passed) {
      ++failures;
      break;  // the first failing seed is the one to debug
    }
  }
  if (coverage_out) {
    std::cout << coverage.summary();
    coverage_out->stream() << coverage.to_json().dump(1) << "\n";
    coverage_out->commit();
  }
  if (a.seeds > 1)
    std::cout << "seeds: " << run << " of " << a.seeds << " run, " << run - failures << " passed, " << failures
              << " failed" << (failures ? " (stopped at the first failure)" : "") << "; " << vertices
              << " vertices, " << cycles << " cycles\n";
  return failures == 0 ? 0 : 1;
}

}  // namespace

// The random triangles are drawn before the run and held in memory (about 200 bytes each).
constexpr std::size_t kMaxRandomTriangles = 100'000'000;

void register_cosim(CLI::App& app) {
  auto args = std::make_shared<CosimArgs>();
  CLI::App* cmd = app.add_subcommand("cosim", "Lock-step co-simulation of the Verilated RTL against the cycle model");
  cmd->add_option("mesh", args->mesh, "Input mesh (default: Debian's assimp-testmodels Wuson.ply)");
  CLI::Option* random = cmd->add_option("--random", args->random_count,
                  "Use N random triangles (with degenerate ones; with --cpg-tags 1 also random scalar tags) instead "
                  "of a mesh")
      ->transform(number_check<std::size_t>("command line", "--random", "1.." + std::to_string(kMaxRandomTriangles)));
  cmd->add_option("--random-max-L", args->random_max_L, "Largest factor of the random triangles (1..64)")
      ->transform(number_check<int>("command line", "--random-max-L", "1..64"))
      ->capture_default_str();
  cmd->add_option("--random-extent", args->random_extent,
                  "Scale of the random triangles' positions, clamped to the coordinate range (near 2^I the "
                  "arithmetic saturates)")
      ->transform(number_check<double>("command line", "--random-extent", "0.001..1000"))
      ->capture_default_str();
  // --config and every parameter of sim/config/params.hpp (--int-blocks/--int selects the RTL build
  // nN;
  // --seed also seeds the RTL's X randomisation).
  auto flags = std::make_shared<ConfigFlags>(*cmd);
  cmd->add_option("--seeds", args->seeds, "Run this many consecutive seeds (1..1000000)")
      ->transform(number_check<int>("command line", "--seeds", "1..1000000"))
      ->capture_default_str();
  cmd->add_option("--variant", args->variant, "RTL build to use (see docs/rtl.md)");
  add_unit_pattern_options(*cmd, args->pattern, "cosim");
  cmd->add_flag("--verif", args->verif, "Use the verification build (X randomised)");
  cmd->add_option("--coverage", args->coverage,
                  "Sample functional coverage into this JSON file, adding to what it holds (docs/verification.md, "
                  "Coverage)");
  // Split here, not by CLI11, which drops empty items: "1,,2" is refused, not read as 1,2.
  auto reset_at = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--reset-at", *reset_at, "Reset both implementations at these cycles (comma-separated)");
  cmd->add_option("--random-resets", args->random_resets,
                  "Reset both implementations this many times at random cycles: in turn anywhere, inside a D3D11 "
                  "patch's inner rings, with the CPG mid-triangle (0..1000)")
      ->transform(number_check<int>("command line", "--random-resets", "0..1000"));
  CLI::Option* wave = cmd->add_option("--wave", args->wave,
                  "Write a waveform (.fst, or .vcd through gtkwave's fst2vcd) and a gtkwave layout (.gtkw) beside "
                  "it: the cycles before a divergence, or the --wave-window START:END of any run");
  cmd->add_option("--wave-window", args->wave_window,
                  "N: the N cycles before a divergence (1..10000000); START:END: these cycles, passing or not")
      ->capture_default_str()
      ->needs(wave);
  cmd->add_flag("--quiet", args->quiet, kQuietHelp);
  cmd->callback([args, flags, random, reset_at]() {
    for (const std::string& list : *reset_at) {
      std::size_t start = 0;
      for (;;) {
        const std::size_t comma = list.find(',', start);
        std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        number_check<std::uint64_t>("command line", "--reset-at", type_range<std::uint64_t>())(item);
        args->reset_at.push_back(std::stoull(item));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
    }
    // --random 0 would silently run the mesh instead: an explicit count must be at least 1.
    if (random->count() > 0 && args->random_count == 0)
      throw InputError("command line", "--random", "'0' is outside 1.." + std::to_string(kMaxRandomTriangles) +
                                                       " (without --random the mesh is run)");
    if (args->random_count > kMaxRandomTriangles)
      throw InputError("command line", "--random",
                       "'" + std::to_string(args->random_count) + "' is outside 1.." + std::to_string(kMaxRandomTriangles) +
                           " (the triangles are drawn before the run and held in memory)");
    const int status = run(*args, *flags);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace tessim::app
