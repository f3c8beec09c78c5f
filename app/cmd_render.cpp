// tessim render: pictures of a PN tessellation, optionally next to the flat-shaded input mesh.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "model/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"
#include "app/commands.hpp"
#include "render/raster.hpp"

namespace tessim::app {

namespace {

// Rendering keeps every tessellated triangle in memory (~80 bytes each with its share of
// vertices and the projection): refuse beyond this instead of exhausting memory.
constexpr std::uint64_t kMaxRenderedTriangles = std::uint64_t{1} << 24;

struct RenderArgs {
  std::string mesh;
  PatternOptions pattern;
  std::string normals = "quadratic";
  std::string compare;
  bool wireframe = false;
  std::string size = "1024x768";
  double azimuth = ViewAngles{}.azimuth_deg;
  double elevation = ViewAngles{}.elevation_deg;
  std::string up = "y";
  bool no_supersample = false;
  std::string output;
};

// The input mesh with one face normal per triangle: the faceted look of the coarse mesh.
RenderMesh flat_shaded(const Mesh& mesh) {
  RenderMesh out;
  out.positions.reserve(mesh.triangles.size() * 3);
  out.normals.reserve(mesh.triangles.size() * 3);
  out.triangles.reserve(mesh.triangles.size());
  for (const glm::uvec3& tri : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
    glm::dvec3 n = glm::cross(b - a, c - a);
    // A zero-area triangle has no face normal; it covers no pixels either, any unit vector does.
    n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 0.0, 1.0);
    const auto base = static_cast<unsigned>(out.positions.size());
    for (const glm::dvec3& p : {a, b, c}) {
      out.positions.push_back(p);
      out.normals.push_back(n);
    }
    out.triangles.emplace_back(base, base + 1, base + 2);
  }
  return out;
}

// The PN tessellation of every input triangle, patch boundaries flagged as primary edges so
// that the wireframe shows the input triangles darker than the refinement inside them.
RenderMesh pn_tessellated(const Mesh& mesh, const TessSettings& settings, const TessellationCounts& counts,
                          NormalMode mode) {
  // An edge of the pattern lies on the patch boundary when both ends are on one side of the
  // domain (u = 0, v = 0 or w = 0).
  auto on_same_side = [](const glm::dvec2& p, const glm::dvec2& q) {
    constexpr double eps = 1e-12;
    return (p.x == 0.0 && q.x == 0.0) || (p.y == 0.0 && q.y == 0.0) ||
           (std::abs(p.x + p.y - 1.0) < eps && std::abs(q.x + q.y - 1.0) < eps);
  };
  RenderMesh out;
  out.positions.reserve(counts.vertices);
  out.normals.reserve(counts.vertices);
  out.triangles.reserve(counts.triangles);
  out.edge_flags.reserve(counts.triangles);
  tessellate_mesh(mesh, settings, mode, [&](const PatchView& patch) {
    const auto base = static_cast<unsigned>(out.positions.size());
    out.positions.insert(out.positions.end(), patch.positions.begin(), patch.positions.end());
    out.normals.insert(out.normals.end(), patch.normals.begin(), patch.normals.end());
    for (std::size_t i = 0; i + 2 < patch.indices.size(); i += 3) {
      const glm::uvec3 t(patch.indices[i], patch.indices[i + 1], patch.indices[i + 2]);
      std::uint8_t flags = 0;
      for (int e = 0; e < 3; ++e)
        if (on_same_side(patch.domain[t[e]], patch.domain[t[(e + 1) % 3]])) flags |= static_cast<std::uint8_t>(1u << e);
      out.triangles.push_back(t + glm::uvec3(base));
      out.edge_flags.push_back(flags);
    }
  });
  return out;
}

void run_render(const RenderArgs& args) {
  // Validate everything before loading or computing anything.
  const glm::ivec2 size = parse_image_size(args.size, "--size");
  const TessSettings settings = args.pattern.settings("render");
  const NormalMode mode = parse_normals_option("render", args.normals);
  const bool compare = !args.compare.empty();
  if (compare && args.compare != "flat")
    throw InputError("render", "--compare", "'" + args.compare + "' is not supported (only 'flat')");
  ViewAngles view;
  view.azimuth_deg = args.azimuth;
  view.elevation_deg = args.elevation;
  if (args.up == "y" || args.up == "Y") view.up = UpAxis::Y;
  else if (args.up == "z" || args.up == "Z") view.up = UpAxis::Z;
  else throw InputError("render", "--up", "'" + args.up + "' is not one of y, z");
  if (!std::isfinite(view.azimuth_deg)) throw InputError("render", "--azimuth", "not a finite angle");
  if (!std::isfinite(view.elevation_deg) || std::abs(view.elevation_deg) > 90.0)
    throw InputError("render", "--elevation", "must be within -90..90 degrees");
  const std::filesystem::path output = args.output;
  if (!is_supported_image(output))
    throw InputError(output.string(), "output",
                     "unsupported image format '" + output.extension().string() + "' (use .png or .exr)");

  check_output_paths({{"-o", output.string()}});

  const Mesh mesh = load_mesh(args.mesh);
  PatternCache patterns(settings);
  const TessellationCounts counts = count_tessellation(mesh, patterns);
  if (counts.triangles > kMaxRenderedTriangles)
    throw InputError(args.mesh, "-L", std::to_string(counts.triangles) +
                                          " tessellated triangles exceed the renderer's limit of " +
                                          std::to_string(kMaxRenderedTriangles) + "; lower the factors");

  std::vector<RenderMesh> panels;
  if (compare) panels.push_back(flat_shaded(mesh));
  panels.push_back(pn_tessellated(mesh, settings, counts, mode));

  // One camera for all panels, framed on everything drawn (the PN surface bulges beyond the
  // input vertices).
  std::vector<glm::dvec3> all_points;
  for (const RenderMesh& panel : panels) {
    validate(panel, mesh.source.empty() ? args.mesh : mesh.source);
    all_points.insert(all_points.end(), panel.positions.begin(), panel.positions.end());
  }
  // Adaptive factors are chosen for a camera: the picture is taken from it, so that what is near
  // (fine) and what is far (coarse) can be seen as the factors saw them.
  Camera camera;
  if (settings.kind == PatternKind::D3D11 && settings.source == FactorSource::Adaptive) {
    camera.eye = settings.camera.eye;
    camera.target = settings.camera.target;
    camera.up = view.up == UpAxis::Y ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    if (glm::length(glm::cross(camera.up, camera.target - camera.eye)) == 0.0) camera.up = glm::dvec3(1, 0, 0);
    camera.fov_y_deg = settings.camera.fov_deg;
    camera.aspect = static_cast<double>(size.x) / size.y;
  } else {
    camera = frame_camera(all_points, view, size.x, size.y);
  }
  all_points = {};

  RenderOptions options;
  options.width = size.x;
  options.height = size.y;
  options.wireframe = args.wireframe;
  options.supersample = !args.no_supersample;

  std::vector<std::unique_ptr<Renderer>> renderers;
  for (const RenderMesh& panel : panels) renderers.push_back(std::make_unique<Renderer>(panel, camera, options));
  const int total_width = compare ? 2 * size.x + kSeparatorWidth : size.x;
  const glm::dvec3 separator = options.background * 0.8;

  ImageFileWriter writer(output, total_width, size.y);
  constexpr int kRowsPerWrite = 64;
  for (int y = 0; y < size.y; y += kRowsPerWrite) {
    const int y_end = std::min(size.y, y + kRowsPerWrite);
    Image band = renderers.front()->render_rows(y, y_end);
    if (compare) band = side_by_side(band, renderers.back()->render_rows(y, y_end), separator);
    writer.write_rows(band);
  }
  writer.finish();

  std::printf("wrote %s: %dx%d, %zu input triangles, %zu PN triangles (%s, %s normals)%s\n",
              output.string().c_str(), total_width, size.y, mesh.triangles.size(),
              panels.back().triangles.size(), settings.describe().c_str(), std::string(to_string(mode)).c_str(),
              compare ? ", left: flat-shaded input" : "");
}

}  // namespace

void register_render(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render the PN tessellation of a mesh to PNG or EXR");
  cmd->add_option("mesh", args->mesh, "Input mesh (OBJ, PLY, STL, OFF, ... via Assimp)")->required();
  add_pattern_options(*cmd, args->pattern, "render");
  cmd->add_option("--normals", args->normals, "Normal field: quadratic, reflect, linear, derivative")
      ->capture_default_str();
  cmd->add_option("--compare", args->compare,
                  "'flat': the flat-shaded input mesh on the left, the PN tessellation on the right");
  cmd->add_flag("--wireframe", args->wireframe,
                "Overlay triangle edges (input triangles dark, their refinement light)");
  cmd->add_option("--size", args->size, "Image size WxH per panel (1..8192 each)")->capture_default_str();
  cmd->add_option("--azimuth", args->azimuth, "View angle around the up axis, degrees from the front")
      ->transform(number_check<double>("render", "--azimuth", "the finite numbers"))
      ->capture_default_str();
  cmd->add_option("--elevation", args->elevation, "View angle above the horizon, degrees (-90..90)")
      ->transform(number_check<double>("render", "--elevation", "-90..90"))
      ->capture_default_str();
  cmd->add_option("--up", args->up, "Up axis of the model: y or z (front is +Z or -Y)")->capture_default_str();
  cmd->add_flag("--no-supersample", args->no_supersample, "One sample per pixel instead of 2x2");
  cmd->add_option("-o,--output", args->output, "Output image: .png (8-bit sRGB) or .exr (half-float linear)")
      ->required();
  cmd->callback([args] { run_render(*args); });
}

}  // namespace tessim::app
