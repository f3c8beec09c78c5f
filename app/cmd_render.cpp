// tessim render: pictures of a PN tessellation, optionally next to the flat-shaded input mesh
// (and, for a scalar-tagged mesh, next to plain PN), optionally coloured by a measured error
// with a colour bar, under a caption.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/input_file.hpp"
#include "model/base/output_file.hpp"
#include "model/base/progress.hpp"
#include "model/factors.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/normal_mode.hpp"
#include "model/pattern.hpp"
#include "model/tessellate.hpp"
#include "render/annotate.hpp"
#include "render/raster.hpp"
#include "sim/config/config.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/values/datapath.hpp"
#include "sim/values/host.hpp"

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
  std::string color = "shaded";
  double color_max = 0.0;  // 0: the largest value drawn
  std::string config;      // unit configuration (number format) of the error modes
  std::string caption;
  bool no_caption = false;
  bool view_given = false;  // --azimuth or --elevation: else the best side is chosen
  bool wireframe = false;
  std::string size = "1024x768";
  double azimuth = render::ViewAngles{}.azimuth_deg;
  double elevation = render::ViewAngles{}.elevation_deg;
  std::string up = "y";
  bool no_supersample = false;
  std::string view_camera;  // --view-camera: the picture's camera without --adaptive
  std::string view_path;    // --view-path: one camera per line, one frame each
  std::string contours;     // --contours: the visible contours and coverage as JSON
  int contour_samples = 4;  // samples per pixel side of the contour map
  double contour_depth_jump = 0.01;  // view-depth step that makes a contour, in bounding-box diagonals
  std::string output;
  bool quiet = false;
};

// The wireframe's colour for a factor at `t` in [0, 1] of the scale: dark blue (coarse) through
// red to orange (fine), dark and saturated enough to read on the surface's light shading.
glm::dvec3 factor_colour(double t) {
  constexpr glm::dvec3 kStops[] = {{0.02, 0.05, 0.45}, {0.35, 0.02, 0.40}, {0.75, 0.03, 0.05}, {0.95, 0.45, 0.0}};
  const double x = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * 3.0;
  const int i = std::min(2, static_cast<int>(x));
  return glm::mix(kStops[i], kStops[i + 1], x - i);
}

// The input mesh with one face normal per triangle: the faceted look of the coarse mesh.
render::RenderMesh flat_shaded(const Mesh& mesh) {
  render::RenderMesh out;
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

// What a heat map colours by: one value per vertex of a patch.
using PatchScalars = std::function<void(const PatchView&, std::span<double>)>;
// The wireframe colour of a patch's triangles (empty: the one wire colour).
using PatchWireColour = std::function<glm::dvec3(const PatchView&)>;

// The PN tessellation of every input triangle, patch boundaries flagged as primary edges so
// that the wireframe shows the input triangles darker than the refinement inside them; with
// `scalars`, each vertex also gets its value, with `wire_colour` each triangle its wire colour.
// `done` (progress) counts the vertices tessellated.
render::RenderMesh pn_tessellated(const Mesh& mesh, const TessSettings& settings, const TessellationCounts& counts,
                          NormalMode mode, std::atomic<std::uint64_t>* done, const PatchScalars& scalars = {},
                          const PatchWireColour& wire_colour = {}) {
  // An edge of the pattern lies on the patch boundary when both ends are on one side of the
  // domain (u = 0, v = 0 or w = 0).
  auto on_same_side = [](const glm::dvec2& p, const glm::dvec2& q) {
    constexpr double eps = 1e-12;
    return (p.x == 0.0 && q.x == 0.0) || (p.y == 0.0 && q.y == 0.0) ||
           (std::abs(p.x + p.y - 1.0) < eps && std::abs(q.x + q.y - 1.0) < eps);
  };
  render::RenderMesh out;
  out.positions.reserve(counts.vertices);
  out.normals.reserve(counts.vertices);
  out.triangles.reserve(counts.triangles);
  out.edge_flags.reserve(counts.triangles);
  if (scalars) out.scalars.reserve(counts.vertices);
  tessellate_mesh(mesh, settings, mode, [&](const PatchView& patch) {
    const auto base = static_cast<unsigned>(out.positions.size());
    out.positions.insert(out.positions.end(), patch.positions.begin(), patch.positions.end());
    out.normals.insert(out.normals.end(), patch.normals.begin(), patch.normals.end());
    if (scalars) {
      out.scalars.resize(out.positions.size());
      scalars(patch, std::span<double>(out.scalars).subspan(base, patch.positions.size()));
    }
    for (std::size_t i = 0; i + 2 < patch.indices.size(); i += 3) {
      const glm::uvec3 t(patch.indices[i], patch.indices[i + 1], patch.indices[i + 2]);
      std::uint8_t flags = 0;
      for (int e = 0; e < 3; ++e)
        if (on_same_side(patch.domain[t[e]], patch.domain[t[(e + 1) % 3]])) flags |= static_cast<std::uint8_t>(1u << e);
      out.triangles.push_back(t + glm::uvec3(base));
      out.edge_flags.push_back(flags);
    }
    if (wire_colour) out.wire_colours.resize(out.triangles.size(), wire_colour(patch));
    if (done) done->fetch_add(patch.positions.size(), std::memory_order_relaxed);
  });
  return out;
}

enum class ColourMode { Shaded, ErrorPosition, ErrorNormal, PnVsFlat, StpnVsPn, Silhouette };

ColourMode parse_colour_mode(const std::string& text) {
  if (text == "shaded") return ColourMode::Shaded;
  if (text == "error-position") return ColourMode::ErrorPosition;
  if (text == "error-normal") return ColourMode::ErrorNormal;
  if (text == "pn-vs-flat") return ColourMode::PnVsFlat;
  if (text == "stpn-vs-pn") return ColourMode::StpnVsPn;
  if (text == "silhouette") return ColourMode::Silhouette;
  throw InputError("command line", "--color",
                   "'" + text + "' is not one of shaded, error-position, error-normal, pn-vs-flat, stpn-vs-pn, silhouette");
}

bool is_error_mode(ColourMode m) { return m == ColourMode::ErrorPosition || m == ColourMode::ErrorNormal; }

// The panels left of the main one: "flat", "pn" or both, in the order drawn.
struct ComparePanels {
  bool flat = false, pn = false;
};

ComparePanels parse_compare(const std::string& text) {
  ComparePanels c;
  if (text.empty()) return c;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item == "flat" && !c.flat) c.flat = true;
    else if (item == "pn" && !c.pn) c.pn = true;
    else throw InputError("command line", "--compare", "'" + text + "' is not one of flat, pn, flat,pn");
  }
  return c;
}

// The unit's configuration for the error modes: defaults, or a configuration file (its number
// format is what matters here).
sim::UnitConfig unit_config(const std::string& path, NormalMode mode) {
  sim::UnitConfig cfg;
  if (!path.empty()) {
    sim::apply_json(cfg, sim::parse_config_text(read_whole_file(path, kConfigFileLimit, "file"), path), path);
  }
  cfg.normals = mode;
  cfg.validate(path.empty() ? "configuration" : path);
  return cfg;
}

// The distance of each vertex to another surface at the same domain point, relative to the
// bounding-box diagonal: the flat input triangle (pn-vs-flat), or the plain PN patch
// (stpn-vs-pn, the tagged surface against what plain PN would make of the mesh).
PatchScalars distance_to(const Mesh& mesh, NormalMode mode, ColourMode colour, double diagonal) {
  return [&mesh, mode, colour, diagonal](const PatchView& patch, std::span<double> out) {
    const glm::uvec3& tri = mesh.triangles[patch.triangle];
    PnInput in;
    for (int c = 0; c < 3; ++c) {
      in.p[c] = mesh.positions[tri[c]];
      in.n[c] = mesh.normals[tri[c]];
    }
    const PnPatch plain = colour == ColourMode::StpnVsPn ? make_patch(in, mode) : PnPatch{};
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double u = patch.domain[i].x, v = patch.domain[i].y;
      // Barycentric (w, u, v) weights P1, P2, P3 (model/pn.hpp).
      const glm::dvec3 other = colour == ColourMode::StpnVsPn ? eval_de_casteljau(plain, u, v).position
                                                              : (1.0 - u - v) * in.p[0] + u * in.p[1] + v * in.p[2];
      out[i] = glm::length(patch.positions[i] - other) / diagonal;
    }
  };
}

// The silhouetteness α of the patch's edges spread over it: at (w, u, v) the edges' α weighted
// by the products of their two ends' barycentric weights, so that each edge shows its own α
// along it; a corner (all products zero) shows the mean of its two edges.
PatchScalars silhouette_alpha(const MeshSilhouette& silhouette) {
  return [&silhouette](const PatchView& patch, std::span<double> out) {
    const std::array<double, 3>& alpha = silhouette.alpha(patch.triangle);  // edges 01, 12, 20
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double u = patch.domain[i].x, v = patch.domain[i].y, w = 1.0 - u - v;
      const double k01 = w * u, k12 = u * v, k20 = v * w;
      const double sum = k01 + k12 + k20;
      if (sum > 0.0) {
        out[i] = (alpha[0] * k01 + alpha[1] * k12 + alpha[2] * k20) / sum;
      } else {  // a corner: the largest of w, u, v is 1
        out[i] = w >= u && w >= v ? 0.5 * (alpha[0] + alpha[2]) : u >= v ? 0.5 * (alpha[0] + alpha[1])
                                                                          : 0.5 * (alpha[1] + alpha[2]);
      }
    }
  };
}

// The unit's fixed-point vertex at each reference vertex (same lattice point), measured against
// the reference as `tessim sim --errors` measures it (sim::MeshErrors). A tagged mesh takes the
// fixed-point scalar-tagged arithmetic against the scalar-tagged reference.
PatchScalars fixed_point_errors(const Mesh& mesh, const sim::UnitConfig& cfg, ColourMode colour,
                                std::shared_ptr<sim::MeshErrors> errors) {
  const sim::HostScaling scaling = sim::host_scaling(mesh);
  return [&mesh, cfg, colour, errors, scaling](const PatchView& patch, std::span<double> out) {
    const sim::TriangleFx tri = sim::to_fixed(mesh, patch.triangle, scaling, cfg.format, patch.L, true);
    const std::vector<sim::VertexFx> fixed = sim::evaluate_patch(tri, cfg.normals, cfg.format);
    sim::check_patch_flags(mesh, patch.triangle, fixed.front().flags, cfg.format);
    const int L = patch.L;
    std::vector<int> at((L + 1) * (L + 1), -1);  // (j, k) -> index in `fixed`
    for (std::size_t i = 0; i < fixed.size(); ++i) at[fixed[i].k * (L + 1) + fixed[i].j] = static_cast<int>(i);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const auto j = static_cast<int>(std::lround(patch.domain[i].x * L));
      const auto k = static_cast<int>(std::lround(patch.domain[i].y * L));
      const sim::VertexErrors e = errors->add(fixed[static_cast<std::size_t>(at[k * (L + 1) + j])]);
      // A vanished normal has no direction: shown as the largest error a direction can have.
      out[i] = colour == ColourMode::ErrorPosition ? e.position : e.normal_angle.value_or(std::acos(-1.0));
    }
  };
}

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// One frame of --view-path: the camera the picture is taken from, and the camera the view-
// dependent tessellation is computed for (the adaptive factors, the blend's eye): the same unless
// the line names a second camera after ';', which freezes the tessellation of another view (what
// a frame shows before its factors are updated: popping is the difference).
struct PathFrame {
  ScreenCamera picture;
  ScreenCamera tessellation;
};

ScreenCamera parse_path_camera(const std::string& text, const glm::ivec2& size, const std::string& path, int number) {
  AdaptiveOptions parse;
  parse.adaptive = "screen";
  const std::size_t first = text.find_first_not_of(" \t\r");
  const std::size_t last = text.find_last_not_of(" \t\r");
  parse.camera = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  parse.viewport = std::to_string(size.x) + "x" + std::to_string(size.y);
  TessSettings with_camera;
  try {
    parse.apply(with_camera, "render");
    validate(with_camera, path);
  } catch (const InputError& e) {
    throw InputError(path, "line " + std::to_string(number), e.what());
  }
  return with_camera.camera;
}

// The frames of --view-path: one eye=x,y,z[,target=x,y,z][,fov=deg] per line (as --camera),
// optionally followed by '; eye=...' for the tessellation's camera; blank lines and lines
// starting with '#' are skipped. The viewport is the picture's size.
std::vector<PathFrame> read_view_path(const std::string& path, const glm::ivec2& size) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "file", "cannot be opened");
  std::vector<PathFrame> frames;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::size_t split = line.find(';');
    if (split != std::string::npos && line.find(';', split + 1) != std::string::npos)
      throw InputError(path, "line " + std::to_string(number), "more than two cameras (picture; tessellation)");
    PathFrame frame;
    frame.picture = parse_path_camera(line.substr(0, split), size, path, number);
    frame.tessellation =
        split == std::string::npos ? frame.picture : parse_path_camera(line.substr(split + 1), size, path, number);
    frames.push_back(frame);
  }
  if (in.bad()) throw InputError(path, "file", "read error");
  if (frames.empty()) throw InputError(path, "file", "no camera (one eye=x,y,z[,target=x,y,z][,fov=deg] per line)");
  return frames;
}

// The output name of frame `index`: the one printf-style %d or %0Nd of `pattern` replaced.
std::string frame_name(const std::string& pattern, std::size_t index) {
  const std::size_t at = pattern.find('%');
  std::size_t end = at + 1;
  while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end]))) ++end;
  const std::string digits = pattern.substr(at + 1, end - at - 1);
  const std::size_t width = digits.empty() ? 0 : static_cast<std::size_t>(std::stoul(digits));
  std::string number = std::to_string(index);
  if (number.size() < width) number.insert(0, width - number.size(), '0');
  return pattern.substr(0, at) + number + pattern.substr(end + 1);
}

// True when `pattern` holds exactly one %d or %0Nd (N < 10) and no other '%'.
bool is_frame_pattern(const std::string& pattern) {
  const std::size_t at = pattern.find('%');
  if (at == std::string::npos || pattern.find('%', at + 1) != std::string::npos) return false;
  std::size_t end = at + 1;
  if (end < pattern.size() && pattern[end] == '0') {
    ++end;
    if (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end]))) ++end;
  }
  return end < pattern.size() && pattern[end] == 'd';
}

render::Camera picture_camera(const ScreenCamera& from, render::UpAxis up, const glm::ivec2& size) {
  render::Camera camera;
  camera.eye = from.eye;
  camera.target = from.target;
  camera.up = up == render::UpAxis::Y ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  if (glm::length(glm::cross(camera.up, camera.target - camera.eye)) == 0.0) camera.up = glm::dvec3(1, 0, 0);
  camera.fov_y_deg = from.fov_deg;
  camera.aspect = static_cast<double>(size.x) / size.y;
  return camera;
}

std::string camera_text(const ScreenCamera& c) {
  char text[256];
  std::snprintf(text, sizeof text, "eye=%.9g,%.9g,%.9g,target=%.9g,%.9g,%.9g,fov=%.9g", c.eye.x, c.eye.y, c.eye.z,
                c.target.x, c.target.y, c.target.z, c.fov_deg);
  return text;
}

// One frame of --contours: the picture's contour map at samples x samples per pixel, in sample
// units, with what was drawn.
nlohmann::json contour_frame(const render::RenderMesh& drawn, const render::Camera& camera, const glm::ivec2& size,
                             int samples, double depth_jump) {
  render::RenderOptions options;
  options.width = size.x * samples;
  options.height = size.y * samples;
  options.supersample = false;
  const render::ContourMap map = render::Renderer(drawn, camera, options).contours(depth_jump);
  return {{"triangles", drawn.triangles.size()}, {"vertices", drawn.positions.size()},
          {"contour_samples", map.contour.size() / 2}, {"contour", map.contour}, {"coverage", map.coverage}};
}

nlohmann::json contour_document(const std::string& mesh_name, const TessSettings& settings, NormalMode mode,
                                const glm::ivec2& size, int samples, double depth_jump) {
  return {{"format", "tessim-contours"},
          {"version", 1},
          {"mesh", mesh_name},
          {"pattern", settings.describe()},
          {"normals", std::string(to_string(mode))},
          {"width", size.x},
          {"height", size.y},
          {"samples_per_pixel", samples},
          {"depth_jump", depth_jump},
          {"frames", nlohmann::json::array()}};
}

void write_json(const std::string& path, const nlohmann::json& doc) {
  AtomicOutput out(path);
  out.stream() << doc.dump() << "\n";
  out.commit();
}

void check_contour_options(const RenderArgs& args) {
  if (args.contour_samples < 1 || args.contour_samples > 16)
    throw InputError("command line", "--contour-samples", "must be 1..16 samples per pixel side");
  if (!(args.contour_depth_jump > 0.0) || !std::isfinite(args.contour_depth_jump))
    throw InputError("command line", "--contour-depth-jump", "must be a positive finite fraction of the diagonal");
}

// tessim render --view-path: one frame per camera of the file, each drawn as a single shaded
// panel (-o with a frame number) and/or measured (--contours: one document, a frame each). With
// --adaptive each frame's camera also sets the factors (and, with --silhouette camera, the
// blend's eye); without it a uniform or fixed pattern is tessellated once for all frames, unless
// --silhouette camera makes the blend follow each frame's eye.
void run_render_path(const RenderArgs& args, const glm::ivec2& size) {
  const std::vector<PathFrame> cameras = read_view_path(args.view_path, size);
  // The frames' cameras stand in for --camera and for --silhouette camera's eye: the pattern is
  // parsed with the first, and each frame then takes its own.
  PatternOptions pattern = args.pattern;
  if (pattern.adaptive.given() && pattern.adaptive.camera.empty())
    pattern.adaptive.camera = camera_text(cameras[0].tessellation);
  bool blend_follows = false;
  if (!pattern.adaptive.given() && pattern.silhouette.starts_with("camera")) {
    const glm::dvec3& e = cameras[0].tessellation.eye;
    pattern.silhouette = "eye=" + std::to_string(e.x) + "," + std::to_string(e.y) + "," + std::to_string(e.z) +
                         pattern.silhouette.substr(6);
    blend_follows = true;
  }
  TessSettings settings = pattern.settings("render");
  if (settings.silhouette.enabled && settings.silhouette.eye_from_camera) blend_follows = true;
  const NormalMode mode = parse_normals_option("render", args.normals);
  for (const auto& [given, option] :
       {std::pair{!args.view_camera.empty(), "--view-camera"}, std::pair{args.view_given, "--azimuth/--elevation"},
        std::pair{!args.compare.empty(), "--compare"}, std::pair{args.color != "shaded", "--color"},
        std::pair{args.color_max > 0.0, "--color-max"}, std::pair{!args.config.empty(), "--config"},
        std::pair{!args.caption.empty(), "--caption"}})
    if (given) throw InputError("command line", option, "is not taken with --view-path (frames are shaded panels)");
  if (settings.kind == PatternKind::D3D11 && settings.source == FactorSource::Adaptive &&
      settings.rule == AdaptiveRule::Nyquist)
    throw InputError("command line", "--view-path", "--adaptive nyquist has no camera to follow");
  if (args.output.empty() && args.contours.empty())
    throw InputError("command line", "--view-path", "needs -o FRAME_%04d.png and/or --contours FILE.json");
  if (!args.output.empty()) {
    if (!is_frame_pattern(args.output))
      throw InputError("command line", "-o", "with --view-path must hold one %d or %0Nd for the frame number");
    if (!render::is_supported_image(frame_name(args.output, 0)))
      throw InputError(args.output, "output", "unsupported image format (use .png or .exr)");
  }
  check_contour_options(args);
  render::UpAxis up = render::UpAxis::Y;
  if (args.up == "z" || args.up == "Z") up = render::UpAxis::Z;
  else if (args.up != "y" && args.up != "Y")
    throw InputError("command line", "--up", "'" + args.up + "' is not one of y, z");
  std::vector<OutputPath> outputs;
  if (!args.contours.empty()) outputs.push_back({"--contours", args.contours});
  if (!args.output.empty()) outputs.push_back({"-o", frame_name(args.output, 0)});
  check_output_paths(outputs, {{"MESH", args.mesh}, {"--view-path", args.view_path}});

  const Mesh mesh = load_mesh(args.mesh);
  const std::string mesh_name = mesh.source.empty() ? args.mesh : mesh.source;
  const bool adaptive = settings.kind == PatternKind::D3D11 && settings.source == FactorSource::Adaptive;
  const bool per_frame = adaptive || blend_follows;
  const double diagonal = bounding_box(mesh).diagonal() > 0.0 ? bounding_box(mesh).diagonal() : 1.0;
  const double depth_jump = args.contour_depth_jump * diagonal;
  nlohmann::json doc = contour_document(mesh_name, settings, mode, size, args.contour_samples, depth_jump);

  render::RenderMesh drawn;
  ProgressDisplay progress("render: frames", "frames", cameras.size(), args.quiet);
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    if (per_frame || k == 0) {
      TessSettings frame = settings;  // a fresh silhouette field per camera
      frame.silhouette_field.reset();
      const ScreenCamera& from = cameras[k].tessellation;
      if (adaptive) {
        frame.camera.eye = from.eye;
        frame.camera.target = from.target;
        frame.camera.fov_deg = from.fov_deg;
      }
      if (blend_follows && !adaptive) frame.silhouette.eye = from.eye;
      bind_silhouette(frame, mesh);
      PatternCache patterns(frame);
      const TessellationCounts counts = count_tessellation(mesh, patterns);
      if (counts.triangles > kMaxRenderedTriangles)
        throw InputError(args.mesh, "frame " + std::to_string(k), std::to_string(counts.triangles) +
                                                                  " tessellated triangles exceed the renderer's limit");
      drawn = pn_tessellated(mesh, frame, counts, mode, nullptr);
      render::validate(drawn, mesh_name);
    }
    const render::Camera camera = picture_camera(cameras[k].picture, up, size);
    if (!args.contours.empty()) {
      nlohmann::json f = contour_frame(drawn, camera, size, args.contour_samples, depth_jump);
      f["frame"] = k;
      f["camera"] = camera_text(cameras[k].picture);
      f["tessellation_camera"] = camera_text(cameras[k].tessellation);
      doc["frames"].push_back(std::move(f));
    }
    if (!args.output.empty()) {
      render::RenderOptions options;
      options.width = size.x;
      options.height = size.y;
      options.wireframe = args.wireframe;
      options.supersample = !args.no_supersample;
      render::write_image(render::Renderer(drawn, camera, options).render(), frame_name(args.output, k));
    }
    if (progress.counter()) progress.counter()->fetch_add(1);
  }
  progress.finish();
  if (!args.contours.empty()) write_json(args.contours, doc);
  std::printf("rendered %zu frames of %s: %s, %s normals, %dx%d", cameras.size(), mesh_name.c_str(),
              settings.describe().c_str(), std::string(to_string(mode)).c_str(), size.x, size.y);
  if (!args.output.empty()) std::printf(", pictures %s", args.output.c_str());
  if (!args.contours.empty()) std::printf(", contours %s (%d x %d samples per pixel)", args.contours.c_str(),
                                          args.contour_samples, args.contour_samples);
  std::printf("\n");
}

void run_render(const RenderArgs& args) {
  // Validate everything before loading or computing anything.
  const glm::ivec2 size = parse_image_size(args.size, "--size");
  if (!args.view_path.empty()) return run_render_path(args, size);
  if (args.output.empty()) throw InputError("command line", "-o", "is required (the picture)");
  check_contour_options(args);
  TessSettings settings = args.pattern.settings("render");
  const NormalMode mode = parse_normals_option("render", args.normals);
  const ComparePanels compare = parse_compare(args.compare);
  const ColourMode colour = parse_colour_mode(args.color);
  if (is_error_mode(colour) && settings.kind != PatternKind::Uniform)
    throw InputError("command line", "--color",
                     args.color + " measures the unit, which tessellates with the uniform pattern: use -L");
  if (is_error_mode(colour) && settings.displace.enabled())
    throw InputError("command line", "--displace",
                     args.color + " measures the unit, which does not displace (float reference only)");
  if (is_error_mode(colour) && mode == NormalMode::Derivative)
    throw InputError("command line", "--normals", "the unit has no derivative normals (float reference only)");
  if (!(args.color_max >= 0.0) || !std::isfinite(args.color_max))
    throw InputError("command line", "--color-max", "must be a positive finite number");
  if (args.color_max > 0.0 && colour == ColourMode::Shaded)
    throw InputError("command line", "--color-max", "scales a heat map: give --color with a measure to colour by");
  if (colour == ColourMode::Silhouette && !settings.uses_silhouette())
    throw InputError("command line", "--color", "silhouette needs --silhouette or --adaptive silhouette");
  // An adaptive rule with a camera takes the picture from it; the Nyquist rule alone has none.
  const bool adaptive_view = settings.kind == PatternKind::D3D11 && settings.source == FactorSource::Adaptive &&
                             settings.rule != AdaptiveRule::Nyquist;
  std::optional<ScreenCamera> view_camera;
  if (!args.view_camera.empty()) {
    if (adaptive_view)
      throw InputError("command line", "--view-camera", "--adaptive takes the picture from its --camera already");
    if (args.view_given)
      throw InputError("command line", "--view-camera", "cannot be combined with --azimuth or --elevation");
    AdaptiveOptions parse;
    parse.adaptive = "screen";
    parse.camera = args.view_camera;
    parse.viewport = std::to_string(size.x) + "x" + std::to_string(size.y);
    TessSettings with_camera;
    parse.apply(with_camera, "render");
    validate(with_camera, "command line");
    view_camera = with_camera.camera;
  }
  if (!args.config.empty() && !is_error_mode(colour))
    throw InputError("command line", "--config", "only the error colour modes use the unit's configuration");
  const sim::UnitConfig cfg = is_error_mode(colour) ? unit_config(args.config, mode) : sim::UnitConfig{};
  render::ViewAngles view;
  view.azimuth_deg = args.azimuth;
  view.elevation_deg = args.elevation;
  if (args.up == "y" || args.up == "Y") view.up = render::UpAxis::Y;
  else if (args.up == "z" || args.up == "Z") view.up = render::UpAxis::Z;
  else throw InputError("command line", "--up", "'" + args.up + "' is not one of y, z");
  if (!std::isfinite(view.azimuth_deg)) throw InputError("command line", "--azimuth", "not a finite angle");
  if (!std::isfinite(view.elevation_deg) || std::abs(view.elevation_deg) > 90.0)
    throw InputError("command line", "--elevation", "must be within -90..90 degrees");
  const std::filesystem::path output = args.output;
  if (!render::is_supported_image(output))
    throw InputError(output.string(), "output",
                     "unsupported image format '" + output.extension().string() + "' (use .png or .exr)");

  std::vector<OutputPath> outputs{{"-o", output.string()}};
  if (!args.contours.empty()) outputs.push_back({"--contours", args.contours});
  check_output_paths(outputs, {{"MESH", args.mesh}, {"--config", args.config}});

  const Mesh mesh = load_mesh(args.mesh);
  bind_silhouette(settings, mesh);
  warn_nyquist_shortfall(settings, mesh);
  const std::string mesh_name = mesh.source.empty() ? args.mesh : mesh.source;
  const bool tagged = mesh.has_tags();
  if (compare.pn && !tagged)
    throw InputError(mesh_name, "tags", "--compare pn needs a scalar-tagged mesh (this one is plain PN already)");
  if (colour == ColourMode::StpnVsPn && !tagged)
    throw InputError(mesh_name, "tags", "--color stpn-vs-pn needs a scalar-tagged mesh");
  Mesh plain;  // the mesh without its tags: what plain PN makes of it
  if (tagged && compare.pn) {
    plain = mesh;
    plain.tags.clear();
  }
  if (is_error_mode(colour)) sim::check_convertible(mesh);
  const Mesh& main_mesh = mesh;

  PatternCache patterns(settings);
  const TessellationCounts counts = count_tessellation(mesh, patterns);
  const std::uint64_t panel_count = 1 + compare.flat + compare.pn;
  if (counts.triangles * (1 + compare.pn) > kMaxRenderedTriangles)
    throw InputError(args.mesh, "-L", std::to_string(counts.triangles) +
                                          " tessellated triangles exceed the renderer's limit of " +
                                          std::to_string(kMaxRenderedTriangles) + "; lower the factors");

  const double diagonal = bounding_box(mesh).diagonal() > 0.0 ? bounding_box(mesh).diagonal() : 1.0;
  std::shared_ptr<sim::MeshErrors> errors;
  PatchScalars scalars;
  if (is_error_mode(colour)) {
    errors = std::make_shared<sim::MeshErrors>(main_mesh, sim::host_scaling(main_mesh), cfg, true);
    scalars = fixed_point_errors(main_mesh, cfg, colour, errors);
  } else if (colour == ColourMode::Silhouette) {
    scalars = silhouette_alpha(*settings.silhouette_field);
  } else if (colour != ColourMode::Shaded) {
    scalars = distance_to(mesh, mode, colour, diagonal);
  }

  // Adaptive factors in the wireframe: each patch's edges coloured by its factor (the inner one,
  // the largest of its edges), so that the density gradient shows, with a colour bar.
  render::ColourScale factor_scale;
  PatchWireColour wire_colour;
  const bool factor_wires = args.wireframe && settings.kind == PatternKind::D3D11 &&
                            settings.source == FactorSource::Adaptive;
  if (factor_wires) {
    float lo = 64.0f, hi = 1.0f;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const float f = patch_factors(settings, mesh, t).inner;
      lo = std::min(lo, f);
      hi = std::max(hi, f);
    }
    factor_scale.lo = std::min<double>(lo, hi);
    factor_scale.hi = hi > factor_scale.lo ? hi : factor_scale.lo + 1.0;
    factor_scale.title = "wireframe colour: tessellation factor of the patch (its largest edge factor)";
    wire_colour = [&settings, &mesh, factor_scale](const PatchView& patch) {
      return factor_colour(factor_scale.position(patch_factors(settings, mesh, patch.triangle).inner));
    };
  }

  const std::string surface =
      settings.silhouette.blends() ? (tagged ? "PN of the tags' normals, silhouette-blended" : "PN, silhouette-blended")
                                : tagged ? "STPN" : "PN";
  ProgressDisplay tessellation_progress("render: tessellate", "vertices",
                                        counts.vertices * (1 + static_cast<std::uint64_t>(compare.pn)), args.quiet);
  std::vector<render::RenderMesh> panels;
  std::vector<std::string> labels;
  if (compare.flat) {
    panels.push_back(flat_shaded(mesh));
    labels.push_back("flat input");
  }
  if (compare.pn) {
    panels.push_back(pn_tessellated(plain, settings, counts, mode, tessellation_progress.counter(), {}, wire_colour));
    labels.push_back("PN (tags ignored)");
  }
  panels.push_back(pn_tessellated(main_mesh, settings, counts, mode, tessellation_progress.counter(), scalars, wire_colour));
  labels.push_back(surface);
  tessellation_progress.finish();

  // One camera for all panels, framed on everything drawn (the PN surface bulges beyond the
  // input vertices).
  std::vector<glm::dvec3> all_points;
  for (const render::RenderMesh& panel : panels) {
    render::validate(panel, mesh_name);
    all_points.insert(all_points.end(), panel.positions.begin(), panel.positions.end());
  }
  // Adaptive factors are chosen for a camera: the picture is taken from it, so that what is near
  // (fine) and what is far (coarse) can be seen as the factors saw them.
  render::Camera camera;
  bool chosen_view = false;
  if (adaptive_view || view_camera) {
    camera = picture_camera(view_camera ? *view_camera : settings.camera, view.up, size);
  } else {
    if (!args.view_given) {
      view = render::best_view(compare.flat ? panels.front() : flat_shaded(mesh), view.up);
      chosen_view = true;
    }
    camera = render::frame_camera(all_points, view, size.x, size.y);
  }
  all_points = {};

  render::RenderOptions options;
  options.width = size.x;
  options.height = size.y;
  options.wireframe = args.wireframe;
  options.supersample = !args.no_supersample;

  // The heat map's scale: from 0 to the largest value, or to --color-max.
  render::ColourScale scale;
  const bool heat = colour != ColourMode::Shaded;
  double largest = 0.0;
  if (heat) {
    for (double v : panels.back().scalars) largest = std::max(largest, v);
    // α lives in [0, 1]: its bar always spans that, so that pictures compare.
    const double natural_top = colour == ColourMode::Silhouette ? 1.0 : largest > 0.0 ? largest : 1.0;
    scale.hi = args.color_max > 0.0 ? args.color_max : natural_top;
    scale.clipped_above = largest > scale.hi;
    options.scalar_lo = scale.lo;
    options.scalar_hi = scale.hi;
    switch (colour) {
      case ColourMode::ErrorPosition:
        scale.title = "position error |fixed point - float64| / bounding-box diagonal";
        break;
      case ColourMode::ErrorNormal: scale.title = "normal error: angle fixed point to float64, radians"; break;
      case ColourMode::PnVsFlat:
        scale.title = "distance " + surface + " surface to flat input / bounding-box diagonal";
        break;
      case ColourMode::Silhouette: scale.title = "silhouetteness alpha of the edges (0 flat, 1 curved)"; break;
      default: scale.title = "distance STPN to plain PN / bounding-box diagonal"; break;
    }
  }

  // Only the main panel (last) carries scalars: the others are shaded plainly.
  std::vector<std::unique_ptr<render::Renderer>> renderers;
  for (const render::RenderMesh& panel : panels)
    renderers.push_back(std::make_unique<render::Renderer>(panel, camera, options));
  const int total_width =
      static_cast<int>(panel_count) * size.x + static_cast<int>(panel_count - 1) * render::kSeparatorWidth;
  const glm::dvec3 separator = options.background * 0.8;
  const int text_scale = size.x >= 1400 ? 2 : 1;

  // Caption: what was drawn, then one label per panel.
  std::vector<render::CaptionLine> caption;
  if (!args.no_caption) {
    std::string header = args.caption;
    if (header.empty()) {
      header = file_name(mesh_name) + ": " + settings.describe() + ", " + std::string(to_string(mode)) + " normals";
      if (is_error_mode(colour))
        header += ", unit Q" + std::to_string(cfg.format.coord_int_bits) + "." +
                  std::to_string(cfg.format.coord_frac_bits) + " vs float64";
    }
    caption.push_back({{header}, {0}, {total_width}});
    if (panel_count > 1 || heat) {
      render::CaptionLine line;
      for (std::size_t i = 0; i < panels.size(); ++i) {
        std::string label = labels[i];
        if (i + 1 == panels.size() && heat) label += " (colour: " + args.color + ")";
        line.cells.push_back(label);
        line.x.push_back(static_cast<int>(i) * (size.x + render::kSeparatorWidth));
        line.width.push_back(size.x);
      }
      caption.push_back(line);
    }
  }
  const render::Image caption_image =
      caption.empty() ? render::Image() : render::caption_strip(caption, total_width, options.background, text_scale);
  render::Image bar_image =
      heat ? render::colour_bar_strip(scale, total_width, options.background, text_scale) : render::Image();
  if (factor_wires) {
    const render::Image factor_bar =
        render::colour_bar_strip(factor_scale, total_width, options.background, text_scale, factor_colour);
    bar_image = heat ? render::stack(bar_image, factor_bar) : factor_bar;
  }

  render::ImageFileWriter writer(output, total_width, caption_image.height + size.y + bar_image.height);
  if (caption_image.height > 0) writer.write_rows(caption_image);
  constexpr int kRowsPerWrite = 64;
  ProgressDisplay raster_progress("render: raster", "rows", static_cast<std::uint64_t>(size.y), args.quiet);
  for (int y = 0; y < size.y; y += kRowsPerWrite) {
    const int y_end = std::min(size.y, y + kRowsPerWrite);
    render::Image band = renderers.front()->render_rows(y, y_end);
    for (std::size_t i = 1; i < renderers.size(); ++i)
      band = render::side_by_side(band, renderers[i]->render_rows(y, y_end), separator);
    writer.write_rows(band);
    if (raster_progress.counter()) raster_progress.counter()->fetch_add(static_cast<std::uint64_t>(y_end - y));
  }
  raster_progress.finish();
  if (bar_image.height > 0) writer.write_rows(bar_image);
  writer.finish();

  if (!args.contours.empty()) {
    nlohmann::json doc = contour_document(mesh_name, settings, mode, size, args.contour_samples,
                                          args.contour_depth_jump * diagonal);
    nlohmann::json f = contour_frame(panels.back(), camera, size, args.contour_samples, doc["depth_jump"]);
    f["frame"] = 0;
    doc["frames"].push_back(std::move(f));
    write_json(args.contours, doc);
  }

  // The image on standard output: the summary goes to stderr.
  std::FILE* summary = output_kind(output) == OutputKind::Stdout ? stderr : stdout;
  std::fprintf(summary, "wrote %s: %dx%d, %zu input triangles, %zu %s triangles (%s, %s normals)",
               output_name(output).c_str(), total_width, caption_image.height + size.y + bar_image.height,
               mesh.triangles.size(), panels.back().triangles.size(), surface.c_str(), settings.describe().c_str(),
               std::string(to_string(mode)).c_str());
  for (std::size_t i = 0; i + 1 < labels.size(); ++i)
    std::fprintf(summary, "%s%s", i == 0 ? ", left: " : " | ", labels[i].c_str());
  std::fprintf(summary, "\n");
  if (chosen_view)
    std::fprintf(summary, "view     azimuth %.0f, elevation %.0f degrees: the side showing most detail\n",
                 view.azimuth_deg, view.elevation_deg);
  if (heat)
    std::fprintf(summary, "colour   %s: 0 .. %.3g (largest value %.9g)\n", args.color.c_str(), scale.hi, largest);
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
                  "Panels left of the tessellation: 'flat' (the flat-shaded input), 'pn' (plain PN, for a "
                  "scalar-tagged mesh), or 'flat,pn'");
  cmd->add_option("--color", args->color,
                  "Surface colour: shaded; or a heat map with colour bar: error-position, error-normal (the "
                  "unit's fixed point against the float64 reference), pn-vs-flat (distance to the flat input), "
                  "stpn-vs-pn (tagged mesh: distance to plain PN), silhouette (each edge's silhouetteness alpha)")
      ->capture_default_str();
  cmd->add_option("--color-max", args->color_max,
                  "Top of the colour bar (0: the largest value); fixes the scale across pictures")
      ->transform(number_check<double>("command line", "--color-max", "positive finite numbers"))
      ->capture_default_str();
  cmd->add_option("--config", args->config,
                  "Unit configuration file (number format) for the error colour modes (default: defaults)");
  CLI::Option* caption =
      cmd->add_option("--caption", args->caption, "Caption text (default: mesh, pattern, normals and panel labels)");
  cmd->add_flag("--no-caption", args->no_caption, "No caption above the picture")->excludes(caption);
  cmd->add_flag("--wireframe", args->wireframe,
                "Overlay triangle edges (input triangles dark, their refinement light)");
  cmd->add_option("--size", args->size, "Image size WxH per panel (1..8192 each)")->capture_default_str();
  CLI::Option* azimuth =
      cmd->add_option("--azimuth", args->azimuth,
                      "View angle around the up axis, degrees from the front (default: the automatic best view: "
                      "of 8 azimuths 45 degrees apart, the one showing most detail, small input triangles face-on; "
                      "35 when only --elevation is given)")
          ->transform(number_check<double>("command line", "--azimuth", "the finite numbers"));
  CLI::Option* elevation =
      cmd->add_option("--elevation", args->elevation,
                      "View angle above the horizon, degrees, -90..90 (default: the automatic best view's, 25)")
          ->transform(number_check<double>("command line", "--elevation", "-90..90"));
  cmd->add_option("--view-camera", args->view_camera,
                  "Take the picture from eye=x,y,z[,target=x,y,z][,fov=deg] (as --adaptive's --camera) instead of the "
                  "automatic view; with --adaptive the picture is taken from its camera");
  cmd->add_option("--up", args->up, "Up axis of the model: y or z (front is +Z or -Y)")->capture_default_str();
  cmd->add_flag("--no-supersample", args->no_supersample, "One sample per pixel instead of 2x2");
  cmd->add_option("--view-path", args->view_path,
                  "Render one frame per camera of this file (one eye=x,y,z[,target=x,y,z][,fov=deg] per line, '#' "
                  "comments): -o then names the frames with %d or %0Nd; with --adaptive each frame's camera sets the "
                  "factors, with --silhouette camera the blend's eye (a second camera after ';' sets them instead)");
  cmd->add_option("--contours", args->contours,
                  "Also write the picture's visible contours (outer outline and interior occluding contours) and "
                  "coverage, per frame, as JSON at --contour-samples per pixel side (docs/images.md)");
  cmd->add_option("--contour-samples", args->contour_samples, "with --contours: samples per pixel side (1..16)")
      ->capture_default_str();
  cmd->add_option("--contour-depth-jump", args->contour_depth_jump,
                  "with --contours: the step in view depth between neighbouring samples that makes a contour, in "
                  "bounding-box diagonals")
      ->transform(number_check<double>("command line", "--contour-depth-jump", "positive finite numbers"))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output,
                  "Output image: .png (8-bit sRGB) or .exr (half-float linear); with --view-path a pattern with %d");
  cmd->add_flag("--quiet", args->quiet, kQuietHelp);
  cmd->callback([args, azimuth, elevation] {
    args->view_given = azimuth->count() > 0 || elevation->count() > 0;
    run_render(*args);
  });
}

}  // namespace tessim::app
