// tessim tessellate: the float64 reference tessellation of a whole mesh, streamed to PLY or OBJ.
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>

#include "model/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"
#include "app/commands.hpp"

namespace tessim::app {

namespace {

struct TessellateArgs {
  std::string mesh;
  int factor = 4;
  std::string normals = "quadratic";
  std::string output;
};

void run_tessellate(const TessellateArgs& args) {
  // Everything the command line decides is checked before the mesh is read or a file opened.
  check_tess_factor("tessellate", args.factor);
  const NormalMode mode = parse_normals_option("tessellate", args.normals);
  if (!is_supported_output(args.output))
    throw InputError(args.output, "output",
                     "unsupported extension '" + std::filesystem::path(args.output).extension().string() +
                         "' (use .ply or .obj)");

  check_output_paths({{"-o", args.output}});

  const Mesh mesh = load_mesh(args.mesh);
  const int L = args.factor;
  const std::uint64_t patches = mesh.triangle_count();
  MeshWriter writer(args.output, patches * static_cast<std::uint64_t>(pattern_vertex_count(L)),
                    patches * static_cast<std::uint64_t>(pattern_triangle_count(L)));
  const TessellationSummary summary = tessellate_mesh(mesh, L, mode, [&](const PatchView& patch) {
    writer.add_patch(patch.L, patch.positions.data(), patch.normals.data());
  });
  writer.finish();

  const MeshStats stats = mesh_stats(mesh);
  if (summary.degenerate_triangles > 0 || summary.degenerate_edges > 0 || stats.normal_fallbacks > 0)
    std::fprintf(stderr,
                 "tessim: warning: %s: %" PRIu64 " zero-area input triangles, %" PRIu64
                 " mid-edge normal fallbacks (zero-length edges), %zu vertices with the +Z fallback normal\n",
                 mesh.source.c_str(), summary.degenerate_triangles, summary.degenerate_edges, stats.normal_fallbacks);
  std::printf("%s: %" PRIu64 " patches, %" PRIu64 " vertices, %" PRIu64 " triangles, %" PRIu64
              " INT ops, %" PRIu64 " degenerate events (L=%d, %s normals)\n",
              args.output.c_str(), summary.patches, summary.vertices, summary.triangles, summary.int_ops,
              summary.degenerate_triangles + summary.degenerate_edges, L, std::string(to_string(mode)).c_str());
}

}  // namespace

void register_tessellate(CLI::App& app) {
  auto args = std::make_shared<TessellateArgs>();
  CLI::App* cmd = app.add_subcommand("tessellate", "Tessellate a mesh with the float64 PN reference into PLY or OBJ");
  cmd->add_option("mesh", args->mesh, "Input mesh (OBJ, PLY, STL, OFF, ... via Assimp)")->required();
  cmd->add_option("-L,--tess-factor,--factor", args->factor, "Tessellation factor: segments per edge (1..64)")
      ->transform(number_check<int>("tessellate", "-L", "1..64"))
      ->capture_default_str();
  cmd->add_option("--normals", args->normals, "Normal field: quadratic, reflect, linear, derivative")
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Output mesh: .ply (binary, double precision) or .obj")->required();
  cmd->callback([args] { run_tessellate(*args); });
}

}  // namespace tessim::app
