#include "render/raster.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "render/annotate.hpp"
#include "render/imageio/imageio_loader.hpp"

namespace tessim::render {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kBandRows = 64;  // output rows rasterized at a time: bounds the sample buffers

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

float srgb_encode(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

void validate(const RenderMesh& mesh, std::string_view what) {
  const std::string name(what);
  if (mesh.normals.size() != mesh.positions.size())
    throw InputError(name, "normals", "count differs from the number of positions");
  if (!mesh.edge_flags.empty() && mesh.edge_flags.size() != mesh.triangles.size())
    throw InputError(name, "edge flags", "count differs from the number of triangles");
  if (!mesh.scalars.empty() && mesh.scalars.size() != mesh.positions.size())
    throw InputError(name, "scalars", "count differs from the number of positions");
  if (!mesh.wire_colours.empty() && mesh.wire_colours.size() != mesh.triangles.size())
    throw InputError(name, "wire colours", "count differs from the number of triangles");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!finite(mesh.positions[i])) throw InputError(name, "vertex " + std::to_string(i), "position is not finite");
    if (!finite(mesh.normals[i])) throw InputError(name, "vertex " + std::to_string(i), "normal is not finite");
  }
  const std::size_t n = mesh.positions.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    if (tri.x >= n || tri.y >= n || tri.z >= n)
      throw InputError(name, "triangle " + std::to_string(t), "vertex index out of range");
  }
}

void validate(const RenderOptions& options) {
  auto check = [](int value, const char* what) {
    if (value < 1 || value > kMaxImageSide)
      throw InputError("render", what,
                       std::to_string(value) + " is outside 1.." + std::to_string(kMaxImageSide));
  };
  check(options.width, "image width");
  check(options.height, "image height");
}

Camera frame_camera(std::span<const glm::dvec3> points, const ViewAngles& view, int width, int height,
                    double fov_y_deg) {
  if (!std::isfinite(view.azimuth_deg)) throw InputError("render", "azimuth", "not a finite angle");
  if (!std::isfinite(view.elevation_deg) || view.elevation_deg < -90.0 || view.elevation_deg > 90.0)
    throw InputError("render", "elevation", "must be within -90..90 degrees");
  if (width < 1 || height < 1) throw InputError("render", "image size", "must be at least 1x1");
  if (points.empty()) throw InputError("render", "mesh", "nothing to draw");

  // World frame of the chosen convention: Y-up models face +Z, Z-up (CAD, Blender) face -Y.
  const glm::dvec3 world_up = view.up == UpAxis::Y ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  const glm::dvec3 world_front = view.up == UpAxis::Y ? glm::dvec3(0, 0, 1) : glm::dvec3(0, -1, 0);
  const glm::dvec3 world_right(1, 0, 0);

  const double az = view.azimuth_deg * kPi / 180.0;
  const double el = view.elevation_deg * kPi / 180.0;
  const glm::dvec3 horizontal = std::cos(az) * world_front + std::sin(az) * world_right;
  const glm::dvec3 back = std::cos(el) * horizontal + std::sin(el) * world_up;  // target -> eye
  // Horizontal right vector: defined even when looking straight down or up.
  const glm::dvec3 right = std::cos(az) * world_right - std::sin(az) * world_front;
  const glm::dvec3 up = glm::cross(right, -back);

  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  double extent = glm::length(hi - lo);
  if (!(extent > 0.0)) extent = 1.0;

  const double aspect = static_cast<double>(width) / height;
  const double tan_v = std::tan(0.5 * fov_y_deg * kPi / 180.0);
  const double tan_h = tan_v * aspect;
  const double margin = 0.92;  // fraction of the half-field the geometry may use

  // Distance at which every point lies inside the margin of the frustum.
  auto fit_distance = [&](const glm::dvec3& center) {
    double dist = 0.0, z_max = -std::numeric_limits<double>::max();
    for (const glm::dvec3& p : points) {
      const glm::dvec3 q = p - center;
      const double x = glm::dot(q, right), y = glm::dot(q, up), z = glm::dot(q, back);
      dist = std::max({dist, z + std::abs(x) / (tan_h * margin), z + std::abs(y) / (tan_v * margin)});
      z_max = std::max(z_max, z);
    }
    return std::max(dist, z_max + 0.01 * extent);
  };

  // The bounding-box centre does not project to the image centre in perspective; shift the
  // target sideways until the projected extents are centred (converges in a few steps).
  glm::dvec3 center = 0.5 * (lo + hi);
  double dist = fit_distance(center);
  for (int iteration = 0; iteration < 8; ++iteration) {
    double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
    for (const glm::dvec3& p : points) {
      const glm::dvec3 q = p - center;
      const double depth = dist - glm::dot(q, back);
      const double nx = glm::dot(q, right) / (depth * tan_h), ny = glm::dot(q, up) / (depth * tan_v);
      x_lo = std::min(x_lo, nx);
      x_hi = std::max(x_hi, nx);
      y_lo = std::min(y_lo, ny);
      y_hi = std::max(y_hi, ny);
    }
    const double mid_x = 0.5 * (x_lo + x_hi), mid_y = 0.5 * (y_lo + y_hi);
    if (std::abs(mid_x) < 1e-4 && std::abs(mid_y) < 1e-4) break;
    center += right * (mid_x * tan_h * dist) + up * (mid_y * tan_v * dist);
    dist = fit_distance(center);
  }

  Camera camera;
  camera.target = center;
  camera.eye = center + back * dist;
  camera.up = up;
  camera.fov_y_deg = fov_y_deg;
  camera.aspect = aspect;
  return camera;
}

// ---------------------------------------------------------------------------------------------
// Renderer: visibility pass (z-buffer of triangle id and screen-space barycentrics per sample),
// then a shading pass per sample, then a box filter over the samples of each pixel. Deferring
// the shading to visible samples also gives the wireframe its depth test for free: an edge is
// drawn where the triangle it belongs to is the visible surface, at the sample's distance from
// that edge in screen space (which also anti-aliases it).

struct Renderer::Impl {
  const RenderMesh& mesh;
  RenderOptions options;
  int samples_per_side = 1;
  int sample_width = 0;
  int sample_height = 0;
  glm::dvec3 eye, right, up, forward;
  glm::dvec3 light;  // unit, world space, towards the light

  struct Projected {
    double x = 0.0, y = 0.0;  // sample units, y down
    double inv_depth = 0.0;   // 1 / view depth: linear in screen space
    bool valid = false;       // in front of the camera
  };
  std::vector<Projected> projected;
  std::vector<glm::dvec3> face_normals;  // unit, or zero for degenerate triangles

  Impl(const RenderMesh& m, const Camera& camera, const RenderOptions& o) : mesh(m), options(o) {
    validate(options);
    samples_per_side = options.supersample ? 2 : 1;
    sample_width = options.width * samples_per_side;
    sample_height = options.height * samples_per_side;

    eye = camera.eye;
    forward = glm::normalize(camera.target - camera.eye);
    right = glm::normalize(glm::cross(forward, camera.up));
    up = glm::cross(right, forward);
    const glm::dvec3 l = options.light_in_view;
    light = glm::normalize(right * l.x + up * l.y - forward * l.z);

    const double tan_v = std::tan(0.5 * camera.fov_y_deg * kPi / 180.0);
    const double tan_h = tan_v * camera.aspect;
    projected.resize(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::dvec3 d = mesh.positions[i] - eye;
      const double depth = glm::dot(d, forward);
      Projected& p = projected[i];
      // No near-plane clipping: framed cameras keep all geometry in front; anything behind
      // (only possible with a hand-made camera) is dropped with its triangles.
      if (!(depth > 1e-9)) continue;
      p.x = (glm::dot(d, right) / (depth * tan_h) + 1.0) * 0.5 * sample_width;
      p.y = (1.0 - glm::dot(d, up) / (depth * tan_v)) * 0.5 * sample_height;
      p.inv_depth = 1.0 / depth;
      p.valid = true;
    }
    face_normals.resize(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3& tri = mesh.triangles[t];
      const glm::dvec3 n = glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x],
                                      mesh.positions[tri.z] - mesh.positions[tri.x]);
      const double len = glm::length(n);
      face_normals[t] = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
  }

  struct Sample {
    float inv_depth = 0.0f;  // 0: background
    std::int32_t triangle = -1;
    float l1 = 0.0f, l2 = 0.0f;  // screen-space barycentrics of corners 1 and 2
  };

  static double edge(double ax, double ay, double bx, double by, double px, double py) {
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
  }

  // Visibility for sample rows [row_begin, row_end).
  // The rows (in samples) triangle t spans; false when a corner is behind the camera.
  bool row_span(std::size_t t, double& y_min, double& y_max) const {
    const glm::uvec3& tri = mesh.triangles[t];
    const Projected& a = projected[tri.x];
    const Projected& b = projected[tri.y];
    const Projected& c = projected[tri.z];
    if (!a.valid || !b.valid || !c.valid) return false;
    y_min = std::min({a.y, b.y, c.y});
    y_max = std::max({a.y, b.y, c.y});
    return true;
  }

  // With `subset`, only those triangles (in order); else all.
  void rasterize(int row_begin, int row_end, std::vector<Sample>& samples,
                 const std::vector<std::uint32_t>* subset = nullptr) const {
    samples.assign(static_cast<std::size_t>(row_end - row_begin) * sample_width, Sample{});
    const std::size_t count = subset ? subset->size() : mesh.triangles.size();
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t t = subset ? (*subset)[k] : k;
      const glm::uvec3& tri = mesh.triangles[t];
      const Projected& a = projected[tri.x];
      const Projected& b = projected[tri.y];
      const Projected& c = projected[tri.z];
      if (!a.valid || !b.valid || !c.valid) continue;
      const double y_min = std::min({a.y, b.y, c.y}), y_max = std::max({a.y, b.y, c.y});
      // Sample (i, j) sits at (i + 0.5, j + 0.5).
      const int j0 = std::max(row_begin, static_cast<int>(std::ceil(y_min - 0.5)));
      const int j1 = std::min(row_end - 1, static_cast<int>(std::floor(y_max - 0.5)));
      if (j0 > j1) continue;
      const double x_min = std::min({a.x, b.x, c.x}), x_max = std::max({a.x, b.x, c.x});
      const int i0 = std::max(0, static_cast<int>(std::ceil(x_min - 0.5)));
      const int i1 = std::min(sample_width - 1, static_cast<int>(std::floor(x_max - 0.5)));
      if (i0 > i1) continue;
      const double area = edge(a.x, a.y, b.x, b.y, c.x, c.y);
      if (area == 0.0 || !std::isfinite(area)) continue;
      const double inv_area = 1.0 / area;  // the sign makes either winding work
      for (int j = j0; j <= j1; ++j) {
        const double py = j + 0.5;
        Sample* row = &samples[static_cast<std::size_t>(j - row_begin) * sample_width];
        for (int i = i0; i <= i1; ++i) {
          const double px = i + 0.5;
          const double l0 = edge(b.x, b.y, c.x, c.y, px, py) * inv_area;
          const double l1 = edge(c.x, c.y, a.x, a.y, px, py) * inv_area;
          const double l2 = edge(a.x, a.y, b.x, b.y, px, py) * inv_area;
          if (l0 < 0.0 || l1 < 0.0 || l2 < 0.0) continue;
          const double inv_depth = l0 * a.inv_depth + l1 * b.inv_depth + l2 * c.inv_depth;
          Sample& s = row[i];
          if (inv_depth > s.inv_depth) {  // nearer: larger 1/depth
            s.inv_depth = static_cast<float>(inv_depth);
            s.triangle = static_cast<std::int32_t>(t);
            s.l1 = static_cast<float>(l1);
            s.l2 = static_cast<float>(l2);
          }
        }
      }
    }
  }

  glm::dvec3 shade(const Sample& s) const {
    if (s.triangle < 0) return options.background;
    const std::size_t t = static_cast<std::size_t>(s.triangle);
    const glm::uvec3& tri = mesh.triangles[t];
    const Projected* corner[3] = {&projected[tri.x], &projected[tri.y], &projected[tri.z]};
    const double screen[3] = {1.0 - s.l1 - s.l2, s.l1, s.l2};

    // Perspective-correct weights for attributes.
    double w[3], sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += (w[k] = std::max(0.0, screen[k]) * corner[k]->inv_depth);
    for (double& x : w) x /= sum;
    const glm::dvec3 position =
        w[0] * mesh.positions[tri.x] + w[1] * mesh.positions[tri.y] + w[2] * mesh.positions[tri.z];
    glm::dvec3 normal = w[0] * mesh.normals[tri.x] + w[1] * mesh.normals[tri.y] + w[2] * mesh.normals[tri.z];

    // Two-sided lighting: orient the geometric normal towards the viewer, then the shading
    // normal to the same side. Winding (consistent or not) and normal orientation then do not
    // matter, and front faces near the silhouette keep their interpolated normals.
    const glm::dvec3 to_eye = glm::normalize(eye - position);
    glm::dvec3 geometric = face_normals[t];
    if (glm::dot(geometric, to_eye) < 0.0) geometric = -geometric;
    const double len = glm::length(normal);
    normal = len > 1e-12 ? normal / len : (glm::length(geometric) > 0.0 ? geometric : to_eye);
    if (glm::length(geometric) > 0.0 && glm::dot(normal, geometric) < 0.0) normal = -normal;

    const double diffuse = std::max(0.0, glm::dot(normal, light));
    const glm::dvec3 half = glm::normalize(light + to_eye);
    const double specular = diffuse > 0.0 ? std::pow(std::max(0.0, glm::dot(normal, half)), options.shininess) : 0.0;
    // Sky-ground ambient: a little more light on surfaces facing up in the image, as a depth cue.
    const double ambient = options.ambient * (0.8 + 0.2 * glm::dot(normal, up));
    glm::dvec3 colour;
    if (mesh.scalars.empty()) {
      colour = options.albedo * (ambient + options.diffuse * diffuse) + glm::dvec3(options.specular * specular);
    } else {
      const double value = w[0] * mesh.scalars[tri.x] + w[1] * mesh.scalars[tri.y] + w[2] * mesh.scalars[tri.z];
      const double span = options.scalar_hi - options.scalar_lo;
      colour = colormap(span > 0.0 ? (value - options.scalar_lo) / span : 0.0) * (0.45 + 0.55 * diffuse + ambient);
    }

    if (options.wireframe) {
      // Distance (in samples) from the sample to the edge opposite corner k is
      // screen[k] * (twice the area) / (edge length).
      const double twice_area = std::abs(edge(corner[0]->x, corner[0]->y, corner[1]->x, corner[1]->y,
                                              corner[2]->x, corner[2]->y));
      const std::uint8_t flags = mesh.edge_flags.empty() ? 0x7 : mesh.edge_flags[t];
      const bool coloured_wires = !mesh.wire_colours.empty();
      const double primary_half = 0.5 * options.wire_width_px * samples_per_side;
      double alpha = 0.0;
      for (int e = 0; e < 3; ++e) {  // edge from corner e to corner e+1, opposite corner e+2
        const Projected& p = *corner[e];
        const Projected& q = *corner[(e + 1) % 3];
        const double length = std::hypot(q.x - p.x, q.y - p.y);
        if (length <= 0.0) continue;
        const double distance = std::max(0.0, screen[(e + 2) % 3]) * twice_area / length;
        const bool primary = (flags >> e) & 1;
        const double half_width = primary ? primary_half : 0.6 * primary_half;
        // Coloured wires (a factor per patch) keep their colour readable inside the patch too.
        const double opacity = primary ? options.wire_opacity : (coloured_wires ? 0.75 : 0.4) * options.wire_opacity;
        const double coverage = std::clamp(half_width + 0.5 - distance, 0.0, 1.0);
        alpha = std::max(alpha, coverage * opacity);
      }
      colour = glm::mix(colour, mesh.wire_colours.empty() ? options.wire_colour : mesh.wire_colours[t], alpha);
    }
    return colour;
  }

  double visible_detail() const {
    // Each sample counts its triangle's density relative to the mean triangle (mean area over its
    // area), capped so that slivers and degenerate triangles cannot dominate.
    double mean_area = 0.0;
    std::vector<double> area(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3& tri = mesh.triangles[t];
      area[t] = 0.5 * glm::length(glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x],
                                             mesh.positions[tri.z] - mesh.positions[tri.x]));
      mean_area += area[t] / static_cast<double>(mesh.triangles.size());
    }
    constexpr double kCap = 100.0;
    std::vector<Sample> samples;
    double detail = 0.0;
    for (int band = 0; band < sample_height; band += kBandRows) {
      rasterize(band, std::min(sample_height, band + kBandRows), samples);
      for (const Sample& s : samples)
        if (s.triangle >= 0) {
          const double a = area[static_cast<std::size_t>(s.triangle)];
          detail += a * kCap > mean_area ? mean_area / a : kCap;
        }
    }
    return detail;
  }

  ContourMap contours(double depth_jump) const {
    ContourMap map;
    map.width = sample_width;
    map.height = sample_height;
    // View depth per sample, infinite for background; each band is rasterized with one row of
    // its neighbours above and below so that contours across band edges are found.
    // The triangles each band (with its neighbour rows) can touch, found once: a dense
    // tessellation drawn at many samples has most triangles outside most bands.
    const int bands = (sample_height + kBandRows - 1) / kBandRows;
    std::vector<std::vector<std::uint32_t>> in_band(static_cast<std::size_t>(bands));
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      double y_min = 0.0, y_max = 0.0;
      if (!row_span(t, y_min, y_max)) continue;
      if (!(y_max >= 0.0) || !(y_min <= sample_height) || !std::isfinite(y_max - y_min)) continue;
      const int first = std::clamp(static_cast<int>(std::floor((y_min - 1.0) / kBandRows)), 0, bands - 1);
      const int last = std::clamp(static_cast<int>(std::floor((y_max + 1.0) / kBandRows)), 0, bands - 1);
      for (int k = first; k <= last; ++k) in_band[static_cast<std::size_t>(k)].push_back(static_cast<std::uint32_t>(t));
    }
    std::vector<Sample> samples;
    std::vector<float> depth;
    for (int band = 0; band < sample_height; band += kBandRows) {
      const int band_end = std::min(sample_height, band + kBandRows);
      const int row_begin = std::max(0, band - 1), row_end = std::min(sample_height, band_end + 1);
      rasterize(row_begin, row_end, samples, &in_band[static_cast<std::size_t>(band / kBandRows)]);
      depth.resize(samples.size());
      for (std::size_t i = 0; i < samples.size(); ++i)
        depth[i] = samples[i].triangle >= 0 ? 1.0f / samples[i].inv_depth : std::numeric_limits<float>::infinity();
      auto at = [&](int x, int y) { return depth[static_cast<std::size_t>(y - row_begin) * sample_width + x]; };
      for (int y = band; y < band_end; ++y) {
        int run_begin = -1;
        for (int x = 0; x <= sample_width; ++x) {
          const bool covered = x < sample_width && std::isfinite(at(x, y));
          if (covered && run_begin < 0) run_begin = x;
          if (!covered && run_begin >= 0) {
            map.coverage.insert(map.coverage.end(), {static_cast<std::uint32_t>(y),
                                                     static_cast<std::uint32_t>(run_begin),
                                                     static_cast<std::uint32_t>(x)});
            run_begin = -1;
          }
          if (!covered) continue;
          const float d = at(x, y);
          // Background is infinitely far, so one comparison finds both kinds of contour.
          const bool contour = (x > 0 && at(x - 1, y) - d > depth_jump) ||
                               (x + 1 < sample_width && at(x + 1, y) - d > depth_jump) ||
                               (y > 0 && at(x, y - 1) - d > depth_jump) ||
                               (y + 1 < sample_height && at(x, y + 1) - d > depth_jump);
          if (contour)
            map.contour.insert(map.contour.end(), {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)});
        }
      }
    }
    return map;
  }

  Image render_rows(int y_begin, int y_end) const {
    if (y_begin < 0 || y_end > options.height || y_begin > y_end)
      throw std::out_of_range("Renderer::render_rows: rows outside the image");
    Image image(options.width, y_end - y_begin);
    std::vector<Sample> samples;
    const int n = samples_per_side;
    const double weight = 1.0 / (n * n);
    for (int band = y_begin; band < y_end; band += kBandRows) {
      const int band_end = std::min(y_end, band + kBandRows);
      rasterize(band * n, band_end * n, samples);
      for (int y = band; y < band_end; ++y) {
        for (int x = 0; x < options.width; ++x) {
          glm::dvec3 sum(0.0);
          for (int sy = 0; sy < n; ++sy)
            for (int sx = 0; sx < n; ++sx)
              sum += shade(samples[static_cast<std::size_t>((y - band) * n + sy) * sample_width + x * n + sx]);
          float* out = image.pixel(x, y - y_begin);
          for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(sum[k] * weight);
        }
      }
    }
    return image;
  }
};

Renderer::Renderer(const RenderMesh& mesh, const Camera& camera, const RenderOptions& options)
    : impl_(std::make_unique<Impl>(mesh, camera, options)) {}
Renderer::~Renderer() = default;
Image Renderer::render_rows(int y_begin, int y_end) const { return impl_->render_rows(y_begin, y_end); }
int Renderer::width() const { return impl_->options.width; }
double Renderer::visible_detail() const { return impl_->visible_detail(); }
ContourMap Renderer::contours(double depth_jump) const {
  if (!(depth_jump > 0.0) || !std::isfinite(depth_jump))
    throw std::invalid_argument("Renderer::contours: depth_jump must be positive and finite");
  return impl_->contours(depth_jump);
}
int Renderer::height() const { return impl_->options.height; }

ViewAngles best_view(const RenderMesh& mesh, UpAxis up) {
  // Small and unsupersampled: only which triangles win a sample matters.
  RenderOptions probe;
  probe.width = 160;
  probe.height = 120;
  probe.supersample = false;
  ViewAngles best;
  best.up = up;
  double best_detail = 0.0;
  for (int step = 0; step < 8; ++step) {
    ViewAngles view = best;
    view.azimuth_deg = ViewAngles{}.azimuth_deg + 45.0 * step;
    const Camera camera = frame_camera(mesh.positions, view, probe.width, probe.height);
    const double detail = Renderer(mesh, camera, probe).visible_detail();
    if (detail > best_detail) {  // ties keep the earlier (the conventional front first)
      best_detail = detail;
      best.azimuth_deg = view.azimuth_deg;
    }
  }
  return best;
}

Image render(const RenderMesh& mesh, const Camera& camera, const RenderOptions& options) {
  return Renderer(mesh, camera, options).render();
}

Image side_by_side(const Image& left, const Image& right, const glm::dvec3& separator_colour) {
  if (left.height != right.height) throw std::invalid_argument("side_by_side: panels differ in height");
  Image out(left.width + kSeparatorWidth + right.width, left.height);
  for (int y = 0; y < out.height; ++y) {
    float* row = out.pixel(0, y);
    std::copy_n(left.pixel(0, y), left.width * 3, row);
    for (int x = 0; x < kSeparatorWidth; ++x)
      for (int k = 0; k < 3; ++k) row[(left.width + x) * 3 + k] = static_cast<float>(separator_colour[k]);
    std::copy_n(right.pixel(0, y), right.width * 3, row + (left.width + kSeparatorWidth) * 3);
  }
  return out;
}

bool is_supported_image(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  // Standard output, a device or a pipe needs no extension: it gets PNG.
  return ext == ".png" || ext == ".exr" || output_kind(path) != OutputKind::File;
}

// ---------------------------------------------------------------------------------------------

struct ImageFileWriter::Impl {
  std::filesystem::path path;
  bool png = true;
  int width = 0;
  int height = 0;
  int next_row = 0;
  const ImageIoPlugin* plugin = nullptr;
  // Declared before `out` so that the image file is closed before the temporary is removed.
  std::unique_ptr<AtomicOutput> atomic;
  struct OutDeleter {
    const ImageIoPlugin* plugin;
    void operator()(tessim_image_out* out) const { plugin->free(out); }
  };
  std::unique_ptr<tessim_image_out, OutDeleter> out{nullptr, OutDeleter{nullptr}};
  std::vector<float> scratch;
  char error[512] = {};

  [[noreturn]] void fail(const std::string& reason) const { throw InputError(path.string(), "image", reason); }
};

ImageFileWriter::ImageFileWriter(const std::filesystem::path& path, int width, int height)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.path = path;
  if (!is_supported_image(path))
    d.fail("unsupported image format '" + path.extension().string() + "' (use .png or .exr)");
  if (width < 1 || height < 1) d.fail("empty image");
  d.png = lower_extension(path) != ".exr";
  d.width = width;
  d.height = height;
  d.plugin = &image_io_plugin(path);  // loads OpenImageIO only now that an image is written
  d.atomic = std::make_unique<AtomicOutput>(path, true);
  tessim_image_out* out = nullptr;
  if (d.plugin->open(d.atomic->temp_path().c_str(), d.png ? 1 : 0, width, height, &out, d.error, sizeof d.error))
    d.fail(d.error);
  d.out = {out, Impl::OutDeleter{d.plugin}};
}

ImageFileWriter::~ImageFileWriter() = default;

void ImageFileWriter::write_rows(const Image& band) {
  Impl& d = *impl_;
  if (!d.out) throw std::logic_error("ImageFileWriter: already finished");
  if (band.width != d.width || d.next_row + band.height > d.height)
    throw std::invalid_argument("ImageFileWriter::write_rows: band does not fit the image");
  const float* data = band.rgb.data();
  if (d.png) {  // PNG holds sRGB-encoded values; the writer quantizes the floats to 8 bits
    d.scratch.resize(band.rgb.size());
    for (std::size_t i = 0; i < band.rgb.size(); ++i) d.scratch[i] = srgb_encode(band.rgb[i]);
    data = d.scratch.data();
  }
  if (d.plugin->write_rows(d.out.get(), d.next_row, band.height, data, d.error, sizeof d.error)) d.fail(d.error);
  d.next_row += band.height;
}

void ImageFileWriter::finish() {
  Impl& d = *impl_;
  if (!d.out) throw std::logic_error("ImageFileWriter: already finished");
  if (d.next_row != d.height) throw std::logic_error("ImageFileWriter::finish: rows missing");
  if (d.plugin->close(d.out.get(), d.error, sizeof d.error)) d.fail(d.error);
  d.out.reset();
  d.atomic->commit_external();
}

void write_image(const Image& image, const std::filesystem::path& path) {
  ImageFileWriter writer(path, image.width, image.height);
  writer.write_rows(image);
  writer.finish();
}

}  // namespace tessim::render
