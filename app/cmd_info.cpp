// tessim info: what a mesh file contains once loaded (welded vertices, normals, degeneracies,
// scalar tags).
#include <cinttypes>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/silhouette.hpp"
#include "model/st_mesh.hpp"
#include "sim/values/host.hpp"

namespace tessim::app {

namespace {

struct InfoArgs {
  std::string mesh;
  bool json = false;
  std::string silhouette;  // --silhouette eye=x,y,z[,beta=B]
  bool silhouette_given = false;
};

const char* normal_source(const Mesh& mesh) {
  return mesh.normals_from_file ? "file" : "computed (area x angle weighted)";
}

void run_info(const InfoArgs& args) {
  std::optional<SilhouetteSettings> silhouette_settings;
  if (args.silhouette_given) {
    silhouette_settings = parse_silhouette_option(args.silhouette);
    if (silhouette_settings->eye_from_camera)
      throw InputError("command line", "--silhouette", "info has no camera: give eye=x,y,z");
  }
  const Mesh mesh = load_mesh(args.mesh);
  std::optional<MeshSilhouette> silhouette;
  if (silhouette_settings) silhouette.emplace(mesh, silhouette_settings->eye, silhouette_settings->beta);
  const MeshStats stats = mesh_stats(mesh);
  const glm::dvec3 lo = stats.bbox.lo, hi = stats.bbox.hi;
  const TagStats tags = tag_stats(mesh);

  if (args.json) {
    nlohmann::json j;
    j["file"] = mesh.source;
    j["vertices"] = stats.vertices;
    j["triangles"] = stats.triangles;
    j["bbox"] = {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
    j["diagonal"] = stats.bbox.diagonal();
    j["half_extent"] = sim::host_scaling(mesh).half_extent;  // unit coordinates x this = mesh units
    j["edges"] = stats.edges;
    j["normals"] = mesh.normals_from_file ? "file" : "computed";
    j["degenerate_triangles"] = stats.degenerate_triangles;
    j["zero_length_edges"] = stats.zero_length_edges;
    j["normal_fallbacks"] = stats.normal_fallbacks;
    // Ranges over no vertex are null, not 0 .. 0.
    auto range = [](std::size_t over, double lo, double hi) {
      return over == 0 ? nlohmann::json(nullptr) : nlohmann::json{lo, hi};
    };
    j["tags"] = {{"present", tags.present},
                 {"acting", tags.tagged + tags.corner_like},
                 {"tagged", tags.tagged},
                 {"crease", tags.crease},
                 {"softened", tags.softened},
                 {"corner_like", tags.corner_like},
                 {"tagged_edges", tags.tagged_edges},
                 {"sigma", range(tags.tagged, tags.sigma_min, tags.sigma_max)},
                 {"theta", range(mesh.tags.size(), tags.theta_min, tags.theta_max)},
                 {"beta", range(tags.tagged, tags.beta_min, tags.beta_max)},
                 {"delta_length", range(tags.tagged, tags.delta_min, tags.delta_max)}};
    if (silhouette) {
      const SilhouetteCounts& c = silhouette->counts();
      const glm::dvec3 eye = silhouette->eye();
      j["silhouette"] = {{"eye", {eye.x, eye.y, eye.z}},     {"beta", silhouette->beta()},
                         {"edges", c.edges},                 {"flat", c.flat},
                         {"blended", c.blended},             {"curved", c.curved},
                         {"boundary", c.boundary},           {"non_manifold", c.non_manifold},
                         {"feature_ends", c.feature_ends}};
    }
    std::cout << j.dump(2) << "\n";
    return;
  }

  // The file name as error messages show it: a newline or ESC in it cannot forge lines.
  std::printf("file                  %s\n", printable_text(mesh.source, 4096).c_str());
  std::printf("vertices              %zu (identical positions welded)\n", stats.vertices);
  std::printf("edges                 %zu\n", stats.edges);
  std::printf("triangles             %zu\n", stats.triangles);
  std::printf("bounding box          min (%.9g, %.9g, %.9g)\n", lo.x, lo.y, lo.z);
  std::printf("                      max (%.9g, %.9g, %.9g)\n", hi.x, hi.y, hi.z);
  std::printf("diagonal              %.9g\n", stats.bbox.diagonal());
  std::printf("half-extent           %.9g (the unit's coordinates times this are mesh units)\n",
              sim::host_scaling(mesh).half_extent);
  std::printf("normals               %s\n", normal_source(mesh));
  std::printf("degenerate triangles  %zu (zero area)\n", stats.degenerate_triangles);
  std::printf("zero-length edges     %zu\n", stats.zero_length_edges);
  if (!mesh.normals_from_file)
    std::printf("normal fallbacks      %zu (vertices with no defined normal, given +Z)\n", stats.normal_fallbacks);
  if (silhouette) {
    const SilhouetteCounts& c = silhouette->counts();
    std::printf("silhouette            eye %s, beta %.9g\n", format_vec(silhouette->eye()).c_str(), silhouette->beta());
    std::printf("  edges alpha = 0     %" PRIu64 " (flat)\n", c.flat);
    std::printf("  edges 0 < alpha < 1 %" PRIu64 " (blended)\n", c.blended);
    std::printf("  edges alpha = 1     %" PRIu64 " (curved; %" PRIu64 " boundary, %" PRIu64 " non-manifold)\n", c.curved,
                c.boundary, c.non_manifold);
    std::printf("  feature ends        %" PRIu64 " (two faces shade an end with different normals)\n", c.feature_ends);
  }
  if (!tags.present) {
    std::printf("tags                  none (plain PN triangles)\n");
    return;
  }
  // What `sim` and `cosim` warn of: every vertex whose tags change the surface, tagged or corner-like.
  std::printf("vertices with tags    %zu (tags that change the surface: tagged + corner-like; sim and cosim "
              "without --cpg-tags 1 ignore them)\n",
              tags.tagged + tags.corner_like);
  std::printf("tagged vertices       %zu (crease vector non-zero; %zu edges between two of them)\n", tags.tagged,
              tags.tagged_edges);
  std::printf("crease vertices       %zu (tagged, sigma > 0), %zu softened (tagged, sigma = 0)\n", tags.crease,
              tags.softened);
  std::printf("corner-like vertices  %zu (untagged, theta > 0)\n", tags.corner_like);
  std::printf("theta                 %.9g .. %.9g (all vertices)\n", tags.theta_min, tags.theta_max);
  if (tags.tagged == 0) {
    std::printf("sigma, beta, |crease vector|  none: no tagged vertex\n");
    return;
  }
  std::printf("sigma                 %.9g .. %.9g (tagged vertices)\n", tags.sigma_min, tags.sigma_max);
  std::printf("beta                  %.9g .. %.9g (tagged vertices)\n", tags.beta_min, tags.beta_max);
  std::printf("|crease vector|       %.9g .. %.9g (tagged vertices)\n", tags.delta_min, tags.delta_max);
}

}  // namespace

void register_info(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand("info", "Print what a mesh contains once loaded: counts, bounds, normals, degeneracies, tags, silhouette edges");
  cmd->add_option("mesh", args->mesh, "Input mesh (OBJ, PLY, STL, OFF, ... via Assimp)")->required();
  cmd->add_flag("--json", args->json, "Machine-readable output");
  CLI::Option* silhouette = cmd->add_option("--silhouette", args->silhouette,
                  "eye=x,y,z[,beta=B]: also count the edges whose silhouetteness from that eye is 0, between 0 and 1, "
                  "and 1 (docs/mathematics.md)");
  cmd->callback([args, silhouette] {
    args->silhouette_given = silhouette->count() > 0;
    run_info(*args);
  });
}

}  // namespace tessim::app
