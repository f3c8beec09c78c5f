// tessim stpn-import: a mesh with hard edges as a scalar-tagged mesh (docs/stpn.md), written as
// PLY with the tags as vertex properties.
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/io/format.hpp"
#include "model/mesh_io.hpp"
#include "model/stpn_import.hpp"

namespace tessim::app {

namespace {

struct StpnImportArgs {
  std::string mesh;
  std::string output;
  double crease_angle = kDefaultCreaseAngle;
  double sigma = 1.0;
  double corner_tension = 1.0;
  bool crease_angle_given = false;
};

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

void run_stpn_import(const StpnImportArgs& args) {
  // Everything the command line decides is checked before the mesh is read.
  if (!(args.crease_angle > 0.0 && args.crease_angle < 180.0))
    throw InputError("command line", "--crease-angle", number_text(args.crease_angle) + " is outside (0, 180) degrees");
  if (!(args.sigma >= 0.0 && args.sigma <= 1000.0))
    throw InputError("command line", "--sigma", number_text(args.sigma) + " is outside 0..1000");
  if (!(args.corner_tension >= -1.0 && args.corner_tension <= 1.0))
    throw InputError("command line", "--corner-tension", number_text(args.corner_tension) + " is outside -1..1");
  // Standard output, a device or a pipe gets the PLY whatever its name.
  const OutputKind kind = output_kind(args.output);
  if (kind == OutputKind::File && io::lower_extension(args.output) != ".ply")
    throw InputError(args.output, "output",
                     "unsupported extension '" + std::filesystem::path(args.output).extension().string() +
                         "' (an ST-mesh is written as .ply)");
  check_output_paths({{"-o", args.output}}, {{"INPUT", args.mesh}});

  StImportOptions options;
  if (args.crease_angle_given) options.crease_angle = args.crease_angle;
  options.sigma = args.sigma;
  options.corner_tension = args.corner_tension;
  const StImport st = import_st_mesh(args.mesh, options);
  write_ply(st.mesh, args.output);

  const StImportSummary& s = st.summary;
  std::string creases;
  if (s.normal_splits) creases = "where the file's normals split";
  if (s.dihedral_test) {
    creases += (creases.empty() ? "" : ", and ") + std::string("faces meeting at more than ") +
               number_text(s.crease_angle) + " degrees";
    if (s.faceted_normals) creases += "; the file's normals are flat, one per face";
  }
  // The mesh on standard output: the summary goes to stderr.
  std::FILE* out = kind == OutputKind::Stdout ? stderr : stdout;
  std::fprintf(out, "%s: %zu vertices, %zu triangles, %zu crease edges (%s)\n", output_name(args.output).c_str(),
               s.vertices, s.triangles, s.crease_edges, creases.c_str());
  std::fprintf(out,
               "crease vertices   %zu: %zu tagged, %zu untagged by the tag rules, %zu untagged (sides facing opposite "
               "ways)\n",
               s.crease_vertices, s.tagged, s.restricted, s.folded);
  std::fprintf(out,
               "  tagged          %zu with sigma %s, %zu softened to sigma 0 (%zu: a crease runs into an untagged "
               "vertex, %zu: the side test disagrees)\n",
               s.tagged - s.softened, number_text(args.sigma).c_str(), s.softened, s.softened_ends, s.softened_sides);
  std::fprintf(out, "corners           %zu (theta %s), %zu of them tagged with sigma 0 to close a crease\n", s.corners,
               number_text(args.corner_tension).c_str(), s.corners_tagged);
  std::fprintf(out, "crease ends       %zu, %zu of them tagged with sigma 0 to close a crease\n", s.crease_ends,
               s.crease_ends_tagged);
  std::fprintf(out, "non-manifold      %zu (untagged)\n", s.non_manifold);
}

}  // namespace

void register_stpn_import(CLI::App& app) {
  auto args = std::make_shared<StpnImportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stpn-import", "Make a mesh with hard edges a scalar-tagged PN mesh (crease tags as PLY vertex properties)");
  cmd->add_option("mesh", args->mesh, "Input mesh (OBJ, PLY, STL, OFF, ... via Assimp)")->required();
  cmd->add_option("-o,--output", args->output, "Output ST-mesh (.ply: binary, double precision, with tags)")->required();
  CLI::Option* angle =
      cmd->add_option("--crease-angle", args->crease_angle,
                      "Degrees between face normals above which an edge is a crease (default 30 without normals "
                      "in the file; with them, their splits are the creases unless this is given)")
          ->transform(number_check<double>("command line", "--crease-angle", "(0, 180)"));
  cmd->add_option("--sigma", args->sigma, "Sharpness of the tagged vertices (1 reproduces both side normals)")
      ->transform(number_check<double>("command line", "--sigma", "0..1000"))
      ->capture_default_str();
  cmd->add_option("--corner-tension", args->corner_tension,
                  "Tension theta of corners, where three or more creases meet (1 keeps them pointed)")
      ->transform(number_check<double>("command line", "--corner-tension", "-1..1"))
      ->capture_default_str();
  cmd->callback([args, angle] {
    args->crease_angle_given = angle->count() > 0;
    run_stpn_import(*args);
  });
}

}  // namespace tessim::app
