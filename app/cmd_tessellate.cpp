// tessim tessellate: the float64 reference tessellation of a whole mesh, streamed to PLY or OBJ.
#include <algorithm>
#include <cinttypes>
#include <span>
#include <vector>
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/base/progress.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"
#include "model/weld.hpp"

namespace tessim::app {

namespace {

struct TessellateArgs {
  std::string mesh;
  PatternOptions pattern;
  std::string normals = "quadratic";
  std::string output;
  bool weld = false;
  bool quiet = false;
};

void run_tessellate(const TessellateArgs& args) {
  // Everything the command line decides is checked before the mesh is read or a file opened.
  TessSettings settings = args.pattern.settings("tessellate");
  const NormalMode mode = parse_normals_option("tessellate", args.normals);
  if (!is_supported_output(args.output))
    throw InputError(args.output, "output",
                     "unsupported extension '" + std::filesystem::path(args.output).extension().string() +
                         "' (use .ply or .obj, or - for standard output)");
  // "-": binary PLY on standard output (compute measured apart from the file system, or piped);
  // the summary then goes to standard error.
  const bool to_stdout = output_kind(args.output) == OutputKind::Stdout;
  if (!to_stdout) check_output_paths({{"-o", args.output}}, {{"MESH", args.mesh}});
  std::FILE* report = to_stdout ? stderr : stdout;

  const Mesh mesh = load_mesh(args.mesh);
  bind_silhouette(settings, mesh);
  warn_nyquist_shortfall(settings, mesh);
  PatternCache patterns(settings);
  const TessellationCounts counts = count_tessellation(mesh, patterns);
  TessellationSummary summary;
  ProgressDisplay progress("tessellate", "vertices", counts.vertices, args.quiet);
  std::atomic<std::uint64_t>* done = progress.counter();
  if (args.weld) {
    // Shared corners and edge points once (model/weld.hpp); the mesh is held until it is written.
    WeldingWriter writer;
    std::vector<WeldKey> keys;
    std::vector<std::uint32_t> uniform_indices;
    int uniform_L = 0;
    summary = tessellate_mesh(mesh, settings, mode, [&](const PatchView& patch) {
      patch_weld_keys(mesh, patch, keys);
      std::span<const std::uint32_t> indices = patch.indices;
      if (patch.L > 0) {
        if (patch.L != uniform_L) {
          uniform_L = patch.L;
          uniform_indices.clear();
          for (const glm::uvec3& t : pattern_triangles(patch.L)) uniform_indices.insert(uniform_indices.end(), {t.x, t.y, t.z});
        }
        indices = uniform_indices;
      }
      writer.add_patch(patch.positions, patch.normals, keys, indices);
      if (done) done->fetch_add(patch.positions.size(), std::memory_order_relaxed);
    });
    progress.finish();
    writer.write(args.output);
    std::fprintf(report, "welded: %" PRIu64 " patch vertices into %" PRIu64 " distinct vertices\n",
                 writer.vertices_in(), writer.vertices_out());
  } else {
    MeshWriter writer(args.output, counts.vertices, counts.triangles);
    summary = tessellate_mesh(mesh, settings, mode, [&](const PatchView& patch) {
      if (patch.L > 0) writer.add_patch(patch.L, patch.positions.data(), patch.normals.data());
      else writer.add_patch(patch.positions, patch.normals, patch.indices);
      if (done) done->fetch_add(patch.positions.size(), std::memory_order_relaxed);
    });
    progress.finish();
    writer.finish();
  }

  const MeshStats stats = mesh_stats(mesh);
  if (summary.degenerate_triangles > 0 || summary.degenerate_edges > 0 || stats.normal_fallbacks > 0)
    std::fprintf(stderr,
                 "tessim: warning: %s: %" PRIu64 " zero-area input triangles, %" PRIu64
                 " mid-edge normal fallbacks (zero-length edges), %zu vertices with the +Z fallback normal\n",
                 mesh.source.c_str(), summary.degenerate_triangles, summary.degenerate_edges, stats.normal_fallbacks);
  std::fprintf(report, "%s: %" PRIu64 " patches, %" PRIu64 " vertices, %" PRIu64 " triangles, %" PRIu64
              " INT ops, %" PRIu64 " degenerate events (%s, %s normals)\n",
              to_stdout ? "standard output" : args.output.c_str(), summary.patches, summary.vertices, summary.triangles, summary.int_ops,
              summary.degenerate_triangles + summary.degenerate_edges, settings.describe().c_str(),
              std::string(to_string(mode)).c_str());
  if (summary.culled > 0)
    std::fprintf(report, "%" PRIu64 " patches culled (a factor <= 0 or NaN)\n", summary.culled);
  if (settings.silhouette_field) print_silhouette_counts(report, *settings.silhouette_field);
  if (mesh.has_tags() && !settings.silhouette.blends())
    std::fprintf(report, "scalar-tagged PN: %zu tagged vertices (docs/stpn.md)\n",
                static_cast<std::size_t>(std::count_if(mesh.tags.begin(), mesh.tags.end(),
                                                       [](const VertexTags& t) { return t.tagged(); })));
}

}  // namespace

void register_tessellate(CLI::App& app) {
  auto args = std::make_shared<TessellateArgs>();
  CLI::App* cmd = app.add_subcommand("tessellate", "Tessellate a mesh with the float64 PN reference into PLY or OBJ");
  cmd->add_option("mesh", args->mesh, "Input mesh (OBJ, PLY, STL, OFF, ... via Assimp)")->required();
  add_pattern_options(*cmd, args->pattern, "tessellate");
  cmd->add_option("--normals", args->normals, "Normal field: quadratic, reflect, linear, derivative")
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output,
                  "Output mesh: .ply (binary, double precision) or .obj; - writes binary PLY to standard output")
      ->required();
  cmd->add_flag("--weld", args->weld,
                "Write the vertices that patches share (corners, edge points) once, found by their place on the "
                "input mesh and exact barycentric weights");
  cmd->add_flag("--quiet", args->quiet, kQuietHelp);
  cmd->callback([args] { run_tessellate(*args); });
}

}  // namespace tessim::app
