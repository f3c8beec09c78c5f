// tessim sim: a whole mesh through the cycle model of the unit and its geometry engine;
// statistics, a human summary, a Perfetto trace, the issue schedule, the tessellated mesh.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/config_flags.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/base/progress.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"
#include "model/weld.hpp"
#include "sim/config/config.hpp"
#include "sim/report/report.hpp"
#include "sim/run/chunked.hpp"
#include "sim/run/schedule.hpp"
#include "sim/run/simulate.hpp"
#include "sim/run/trace.hpp"
#include "sim/system/system_threads.hpp"

namespace tessim::app {

namespace {

constexpr const char* kDefaultMesh = "/usr/share/assimp/models/PLY/Wuson.ply";

struct SimArgs {
  std::string mesh = kDefaultMesh;
  std::string stats;
  std::string trace;
  std::uint64_t trace_cycles = 20000;
  std::string trace_window;  // START:END, instead of the first trace_cycles cycles
  std::string output;
  bool weld = false;
  bool schedule = false;
  bool errors = false;
  bool no_fast_forward = false;
  bool quiet = false;
  std::string chunks = "1";  // K, or auto
  std::string threads = "auto";  // T, or auto
  UnitPatternOptions pattern;
};

// The patches of a chunk after the first, kept in a temporary file until the chunks before it
// are written: the output stays streamed in stream order with constant memory, whatever the
// chunks' sizes. The file is removed however the command ends (AtomicOutput, never committed).
class PatchSpool {
 public:
  explicit PatchSpool(const std::filesystem::path& near) : file_(near, true) {}

  void add(const sim::PatchOut& p) {
    const auto L = static_cast<std::int32_t>(p.L);
    const auto n = static_cast<std::uint32_t>(p.positions.size());
    const auto m = static_cast<std::uint32_t>(p.indices.size());  // D3D11 patches: their triangles
    append(&L, sizeof L);
    append(&n, sizeof n);
    append(&m, sizeof m);
    append(p.positions.data(), p.positions.size_bytes());
    append(p.normals.data(), p.normals.size_bytes());
    append(p.indices.data(), p.indices.size_bytes());
    if (buffer_.size() >= kBlock) flush();
  }

  // Every patch in the order added, as sim::PatchOut (triangle left 0).
  void replay(const std::function<void(const sim::PatchOut&)>& emit) {
    flush();
    file_.stream().flush();
    if (!file_.stream()) throw InputError(file_.temp_path().string(), "output", "write failed");
    std::ifstream in(file_.temp_path(), std::ios::binary);
    std::vector<glm::dvec3> pos, nrm;
    std::vector<std::uint32_t> indices;
    std::int32_t L = 0;
    std::uint32_t n = 0, m = 0;
    while (in.read(reinterpret_cast<char*>(&L), sizeof L)) {
      if (!in.read(reinterpret_cast<char*>(&n), sizeof n) || !in.read(reinterpret_cast<char*>(&m), sizeof m)) break;
      pos.resize(n);
      nrm.resize(n);
      indices.resize(m);
      if (!in.read(reinterpret_cast<char*>(pos.data()), static_cast<std::streamsize>(n * sizeof(glm::dvec3))) ||
          !in.read(reinterpret_cast<char*>(nrm.data()), static_cast<std::streamsize>(n * sizeof(glm::dvec3))) ||
          !in.read(reinterpret_cast<char*>(indices.data()), static_cast<std::streamsize>(m * sizeof(std::uint32_t))))
        break;
      emit(sim::PatchOut{0, L, pos, nrm, indices});
    }
    if (!in.eof() || in.gcount() != 0) throw InputError(file_.temp_path().string(), "output", "read back failed");
  }

 private:
  static constexpr std::size_t kBlock = std::size_t{1} << 20;
  void append(const void* data, std::size_t size) { buffer_.append(static_cast<const char*>(data), size); }
  void flush() {
    file_.stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    if (!file_.stream()) throw InputError(file_.temp_path().string(), "output", "write failed");
  }

  AtomicOutput file_;
  std::string buffer_;
};

// A count option of 1..max ("a number of <what>"), or auto: 0.
int parse_count_or_auto(const std::string& text, const char* option, int max, const char* what) {
  if (text == "auto") return 0;
  int k = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), k);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || k < 1 || k > max)
    throw InputError("command line", option,
                     "'" + text + "' is not a number of " + what + " (1.." + std::to_string(max) + ") or auto");
  return k;
}

// --chunks: a count, or 0 for auto (resolved once the mesh's triangles are known).
int parse_chunks(const std::string& text) { return parse_count_or_auto(text, "--chunks", sim::kMaxChunks, "chunks"); }

// --threads: a count (at most one per unit is used), or auto: the idle hardware threads when
// enough are idle for the parallel mode to pay (sim::auto_system_threads), one with chunks.
int system_threads(const std::string& text, int chunks, int units) {
  const int t = parse_count_or_auto(text, "--threads", 64, "threads");
  if (t != 0) return t;
  return chunks != 1 ? 1 : std::min(sim::auto_system_threads(units), 64);
}

void run_sim(const SimArgs& a, const ConfigFlags& flags) {
  sim::UnitConfig cfg = flags.config();
  if (is_scene_file(a.mesh)) {
    // A scene's draws carry their own patterns, and its frames are summarized, not traced.
    const std::pair<bool, const char*> refused[] = {
        {flags.overrides().contains("tess_factor"), "-L (each draw of a scene gives its own L)"},
        {a.pattern.adaptive.given(), "--adaptive (each draw of a scene gives its own pattern)"},
        {!a.pattern.partitioning.empty(), "--partitioning (each draw of a scene gives its own pattern)"},
        {!a.pattern.outer.empty() || !a.pattern.inner.empty(), "--outer/--inner (each draw gives its own pattern)"},
        {a.pattern.silhouette_given(), "--silhouette"},
        {a.pattern.displace.kind_option && a.pattern.displace.kind_option->count() > 0, "--displace"},
        {!a.output.empty(), "-o"}, {!a.trace.empty(), "--trace"}, {a.schedule, "--schedule"}, {a.errors, "--errors"},
        {a.chunks != "1", "--chunks"}};
    for (const auto& [given, what] : refused)
      if (given) throw InputError("command line", what, "is not taken with a scene (" + a.mesh + ")");
    run_sim_scene(a.mesh, a.stats, cfg, a.quiet);
    return;
  }
  int chunks = parse_chunks(a.chunks);
  // A trace and the schedule watch one unit cycle by cycle: there is no one unit to watch.
  if (chunks != 1 && !a.trace.empty())
    throw InputError("command line", "--chunks", "cannot be combined with --trace (a trace follows one unit cycle by cycle)");
  // A chunk's result is one unit's; a system's is its units' counters summed, so merging chunks
  // of a system would add every unit's cycles together. The system runs its units on threads.
  if (chunks != 1 && cfg.units > 1)
    throw InputError("command line", "--chunks",
                     "cannot be combined with --units " + std::to_string(cfg.units) +
                         " (a system of units runs its units on threads of its own; use --threads)");
  // A system's options configure the distributor, the GE's ports and the reassembly buffer of
  // --units M >= 2: for one unit they would be ignored yet written into the statistics.
  if (cfg.units == 1) {
    const nlohmann::json given = flags.overrides();
    for (const char* key : {"ge_ports", "reorder_slots", "distribution", "dispatch_batch", "reassembly"}) {
      if (!given.contains(key)) continue;
      std::string flag = std::string("--") + key;
      std::replace(flag.begin(), flag.end(), '_', '-');
      throw InputError("command line", flag, "has no effect on one unit (it configures a system of --units M >= 2)");
    }
  }
  // A chunk starts from an empty unit and an idle geometry engine; the bound that makes chunks
  // exact (sim/run/chunked.hpp) is derived for a fixed K, not for a core's FIFO and waves.
  if (chunks != 1 && cfg.ge_core())
    throw InputError("command line", "--chunks",
                     "cannot be combined with a shader-core geometry engine (ge_core_lanes " +
                         std::to_string(cfg.ge_core_lanes) + "): chunks are exact for a fixed K only");
  if (!a.trace_window.empty() && a.trace.empty())
    throw InputError("command line", "--trace-window", "needs --trace (it selects the cycles of the trace)");
  if (chunks != 1 && a.schedule)
    throw InputError("command line", "--chunks",
                     "cannot be combined with --schedule (the schedule follows one unit cycle by cycle)");
  if (!a.output.empty() && !is_supported_output(a.output))
    throw InputError(a.output, "output", "unsupported extension (use .ply or .obj)");
  if (a.trace_cycles == 0) throw InputError("command line", "--trace-cycles", "must be at least 1");
  sim::TraceWindow trace_window{0, a.trace_cycles};
  if (!a.trace_window.empty()) {
    const std::size_t colon = a.trace_window.find(':');
    std::uint64_t from = 0, to = 0;
    auto whole = [](std::string_view text, std::uint64_t& value) {
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
      return !text.empty() && ec == std::errc() && end == text.data() + text.size();
    };
    if (colon == std::string::npos || !whole(std::string_view(a.trace_window).substr(0, colon), from) ||
        !whole(std::string_view(a.trace_window).substr(colon + 1), to) || to < from || to == UINT64_MAX)
      throw InputError("command line", "--trace-window",
                       "'" + a.trace_window + "' is not START:END (cycles, START <= END)");
    trace_window = {from, to + 1};
  }
  if (cfg.evaluation == sim::Evaluation::Gpe) {
    // The GE evaluates in float and there is no TE: nothing to trace, schedule or check in fixed point.
    const char* refused = !a.trace.empty() ? "--trace" : a.schedule ? "--schedule" : a.errors ? "--errors" : nullptr;
    if (refused)
      throw InputError("command line", refused,
                       std::string("evaluation gpe has no TE: ") +
                           (a.errors ? "the GE evaluates in float, and --errors measures the unit's fixed-point output"
                                     : "nothing to trace or schedule cycle by cycle"));
  }
  check_output_paths({{"-o", a.output}, {"--trace", a.trace}, {"--stats", a.stats}},
                     {{"MESH", a.mesh}, {"--config", flags.config_file()}});
  std::optional<TessSettings> pattern = a.pattern.settings("sim", cfg.tess_factor, flags.overrides().contains("tess_factor"));
  if (pattern && cfg.format.bary_bits < 16)
    throw InputError(flags.config_file().empty() ? "command line" : flags.config_file(), "bary_bits",
                     "the D3D11 pattern's points are 16.16: it needs bary_bits >= 16, not " +
                         std::to_string(cfg.format.bary_bits));

  const Mesh mesh = load_mesh(a.mesh);
  // First: a feature end (from the tags) is an error, which no warning about the tags precedes.
  const std::shared_ptr<const MeshSilhouette> silhouette = a.pattern.silhouette_for(pattern, cfg.tess_factor, mesh);
  if (!cfg.cpg_tags) warn_tags_ignored(mesh, "sim");
  else warn_tags_lost(mesh, cfg.format);
  if (silhouette && !cfg.format.takes_alpha()) {
    // The blend needs the unit's alpha input: a configuration without one gets the default width.
    cfg.format.alpha_bits = sim::kDefaultAlphaBits;
    std::fprintf(stderr, "tessim: note: --silhouette: the unit takes alpha with alpha_bits %d (the configuration had 0)\n",
                 cfg.format.alpha_bits);
  }
  sim::MeshPatterns patterns(pattern ? &*pattern : nullptr);
  patterns.silhouette = silhouette.get();
  patterns.displace = a.pattern.displace.settings();
  const std::uint64_t triangles = mesh.triangle_count();
  if (chunks == 0)
    chunks = static_cast<int>(std::min<std::uint64_t>({std::max(1u, std::thread::hardware_concurrency()),
                                                       static_cast<std::uint64_t>(sim::kMaxChunks),
                                                       std::max<std::uint64_t>(triangles, 1)}));
  if (static_cast<std::uint64_t>(chunks) > std::max<std::uint64_t>(triangles, 1))
    throw InputError("command line", "--chunks",
                     std::to_string(chunks) + " chunks of a mesh of " + std::to_string(triangles) + " triangles");
  std::uint64_t out_vertices = 0, out_triangles = 0;
  if (pattern) {
    PatternCache cache(*pattern);
    const TessellationCounts counts = count_tessellation(mesh, cache);
    out_vertices = counts.vertices;
    out_triangles = counts.triangles;
  } else {
    out_vertices = mesh.triangle_count() * static_cast<std::uint64_t>(pattern_vertex_count(cfg.tess_factor));
    out_triangles = mesh.triangle_count() * static_cast<std::uint64_t>(pattern_triangle_count(cfg.tess_factor));
  }

  // Every output is opened (as a temporary beside its target) before the run, so that a path
  // that cannot be written stops the command before anything is computed or moved into place.
  std::unique_ptr<AtomicOutput> stats;
  if (!a.stats.empty()) stats = std::make_unique<AtomicOutput>(a.stats);
  sim::SimHooks hooks;
  hooks.measure_errors = a.errors;
  hooks.fast_forward = !a.no_fast_forward;
  hooks.system_threads = system_threads(a.threads, chunks, cfg.units);
  std::unique_ptr<MeshWriter> writer;
  std::unique_ptr<WeldingWriter> welder;
  std::vector<WeldKey> keys;
  std::vector<std::uint32_t> indices;
  int indices_L = 0;
  std::function<void(const sim::PatchOut&)> emit;  // a patch into the output, in stream order
  if (!a.output.empty() && a.weld) {
    // Shared vertices once: the unit computes them bit for bit alike in both patches of an edge.
    welder = std::make_unique<WeldingWriter>();
    emit = [&](const sim::PatchOut& p) {
      keys.clear();
      for (std::size_t i = 0; i < p.positions.size(); ++i) keys.push_back(bits_key(p.positions[i], p.normals[i]));
      if (p.L == 0) {  // a D3D11 patch brings its triangles
        welder->add_patch(p.positions, p.normals, keys, p.indices);
        return;
      }
      if (p.L != indices_L) {
        indices_L = p.L;
        indices.clear();
        for (const glm::uvec3& t : pattern_triangles(p.L)) indices.insert(indices.end(), {t.x, t.y, t.z});
      }
      welder->add_patch(p.positions, p.normals, keys, indices);
    };
  } else if (!a.output.empty()) {
    writer = std::make_unique<MeshWriter>(a.output, out_vertices, out_triangles);
    emit = [&](const sim::PatchOut& p) {
      if (p.L == 0) writer->add_patch(p.positions, p.normals, p.indices);
      else writer->add_patch(p.L, p.positions.data(), p.normals.data());
    };
  }
  hooks.on_patch = emit;
  std::unique_ptr<sim::TraceWriter> trace;
  if (!a.trace.empty()) {
    trace = std::make_unique<sim::TraceWriter>(a.trace, cfg.int_blocks, cfg.te_contexts, trace_window);
    hooks.observers.push_back(trace.get());
  }
  std::unique_ptr<sim::ScheduleRecorder> schedule;
  if (a.schedule) {
    schedule = std::make_unique<sim::ScheduleRecorder>();
    hooks.observers.push_back(schedule.get());
  }

  ProgressDisplay progress("sim", "vertices", out_vertices, a.quiet);
  hooks.vertices_done = progress.counter();
  sim::SimResult result;
  if (chunks == 1) {
    result = sim::simulate(mesh, cfg, hooks, patterns);
  } else {
    // The first chunk writes the output as it runs; each later one into a spool, copied into the
    // output once the chunks before it are written.
    std::vector<std::unique_ptr<PatchSpool>> spools(static_cast<std::size_t>(chunks));
    if (emit) {
      // Beside the output file, or in the temporary directory for standard output, a device or a pipe.
      const std::filesystem::path near =
          output_kind(a.output) != OutputKind::File
              ? std::filesystem::temp_directory_path() / ("tessim-sim-" + std::to_string(::getpid()))
              : resolve_output_path(a.output);
      for (int k = 1; k < chunks; ++k) {
        std::filesystem::path spool = near;
        spool += ".chunk" + std::to_string(k);
        spools[static_cast<std::size_t>(k)] = std::make_unique<PatchSpool>(spool);
      }
    }
    sim::ChunkCallbacks callbacks;
    callbacks.hooks = [&](int k) {
      sim::SimHooks h = hooks;
      if (k > 0 && emit) {
        PatchSpool* spool = spools[static_cast<std::size_t>(k)].get();
        h.on_patch = [spool](const sim::PatchOut& p) { spool->add(p); };
      }
      return h;
    };
    callbacks.done = [&](int k) {
      if (k == 0 || !emit) return;
      auto& spool = spools[static_cast<std::size_t>(k)];
      spool->replay(emit);
      spool.reset();
    };
    result = sim::simulate_chunked(mesh, cfg, chunks, callbacks, patterns);
  }
  progress.finish();

  // All outputs are complete in memory or in temporaries: move them into place (the small
  // statistics are written out first, so that the renames are all that is left to fail).
  if (stats) {
    stats->stream() << sim::stats_json(result).dump(2) << "\n";
    if (!stats->stream().flush()) throw InputError(a.stats, "output", "write failed");
  }
  if (writer) writer->finish();
  if (welder) welder->write(a.output);
  if (trace) trace->finish();
  if (stats) stats->commit();
  // An output on standard output: the summary goes to stderr.
  const bool output_on_stdout = output_kind(a.output) == OutputKind::Stdout ||
                                output_kind(a.trace) == OutputKind::Stdout || output_kind(a.stats) == OutputKind::Stdout;
  std::ostream& report = output_on_stdout ? std::cerr : std::cout;
  report << sim::summary(result);
  if (welder)
    report << "welded   " << welder->vertices_in() << " output vertices into " << welder->vertices_out()
           << " distinct vertices (bit-identical positions and normals)\n";
  if (schedule) {
    char steady[200];
    std::snprintf(steady, sizeof steady,
                  "steady state: %.3f cycles per vertex (retirement interval over 2520-vertex "
                  "periods of the first 8192 vertices, docs/schedule.md)\n",
                  schedule->steady_cycles_per_vertex());
    report << "\nissue schedule (v<vertex>.<op>, first cycles from the first issue):\n"
           << schedule->table(cfg.int_blocks) << steady;
  }
}

}  // namespace

void register_sim(CLI::App& app) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* sub = app.add_subcommand(
      "sim", "Run a mesh through the cycle-level model of the unit and its geometry engine");
  sub->add_option("mesh", args->mesh,
                  "input mesh (OBJ, PLY, STL, OFF, ...), or a scene NAME.scene.json: every frame of its draws "
                  "(docs/scenes.md)")
      ->capture_default_str();
  auto flags = std::make_shared<ConfigFlags>(*sub);  // --config and every parameter (sim/config/params.hpp)
  sub->add_option("--stats", args->stats, "write the statistics as JSON");
  sub->add_option("--trace", args->trace,
                  "write a Chrome/Perfetto trace (JSON; gzip-compressed when the name ends in .gz, e.g. .json.gz)");
  auto* trace_cycles = sub->add_option("--trace-cycles", args->trace_cycles, "cycles recorded in the trace, from cycle 0")
                           ->transform(number_check<std::uint64_t>("command line", "--trace-cycles", "1..2^64-1"))
                           ->capture_default_str();
  sub->add_option("--trace-window", args->trace_window,
                  "START:END: record cycles START to END in the trace instead (docs/statistics.md, Traces)")
      ->excludes(trace_cycles);
  auto* output = sub->add_option("-o,--output", args->output, "write the tessellated mesh (.ply or .obj)");
  sub->add_flag("--weld", args->weld,
                "with -o: write the vertices that patches share once (bit-identical fixed-point positions and "
                "normals)")
      ->needs(output);
  sub->add_flag("--schedule", args->schedule, "print the issue pattern of the first vertices");
  add_unit_pattern_options(*sub, args->pattern, "sim");
  add_displace_options(*sub, args->pattern.displace, true);
  sub->add_flag("--errors", args->errors,
                "compare every vertex with the float reference: end to end against the mesh, and the "
                "arithmetic alone against its derived bound (summary and --stats \"errors\"); the unit's output, "
                "before any --displace");
  sub->add_option("--chunks", args->chunks,
                  "K: cut the triangle stream into K chunks (1.." + std::to_string(sim::kMaxChunks) +
                      ", or auto: one per hardware thread) simulated in parallel, each on a unit fresh from "
                      "reset; the same output, statistics summed, cycles within a bound of one run's "
                      "(docs/statistics.md, Chunked runs)")
      ->capture_default_str();
  sub->add_option("--threads", args->threads,
                  "T: threads that clock a system of --units M units (1..64, at most M are used; or auto: one per "
                  "idle hardware thread when at least 4 are idle, else 1, and 1 with --chunks); every cycle and "
                  "bit the same whatever T "
                  "(docs/microarchitecture.md §13, Threaded runs)")
      ->capture_default_str();
  sub->add_flag("--no-fast-forward", args->no_fast_forward,
                "clock every cycle one by one instead of taking the cycles in which nothing moves at once "
                "(same results, slower; docs/microarchitecture.md §11)");
  sub->add_flag("--quiet", args->quiet, kQuietHelp);
  sub->callback([args, flags] { run_sim(*args, *flags); });
}

}  // namespace tessim::app
