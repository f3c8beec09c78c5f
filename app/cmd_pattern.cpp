// tessim pattern: the Direct3D 11 triangle-domain tessellation pattern for given factors
// (docs/patterns.md) as text, JSON, an SVG picture or a rendered PNG.
#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/d3d11_pattern.hpp"
#include "render/canvas.hpp"
#include "render/raster.hpp"

namespace tessim::app {

namespace {

struct PatternArgs {
  std::string outer;
  std::string inner;
  std::string partitioning;
  std::string winding = "ccw";
  bool json = false;
  std::string output;
  std::string size = "1024x900";
};


std::string hex(Fixed16 x) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%05x", static_cast<unsigned>(x));
  return buf;
}

// The domain drawn as an equilateral triangle: w = 1 bottom left, u = 1 bottom right, v = 1 at
// the top (an orientation-preserving map of the (u, v) plane).
struct Plane {
  double x, y;
};
Plane to_plane(double u, double v) { return {u + 0.5 * v, 0.5 * std::sqrt(3.0) * v}; }

// The picture of the pattern, for SVG and PNG alike (render/canvas.hpp): the domain's triangles,
// its boundary, the points, the corners, the edge each outer factor subdivides, and a caption.
render::Drawing pattern_drawing(const D3D11Pattern& p, Partitioning partitioning) {
  constexpr double kSide = 680.0, kMargin = 60.0;
  render::Drawing d;
  d.width = kSide + 2 * kMargin;
  d.height = 0.5 * std::sqrt(3.0) * kSide + 2 * kMargin + 30.0;
  auto at = [&](double u, double v) {
    const Plane q = to_plane(u, v);
    return glm::dvec2(kMargin + kSide * q.x, d.height - kMargin - kSide * q.y);
  };
  const glm::dvec3 ink(0x1a / 255.0, 0x22 / 255.0, 0x30 / 255.0);
  const D3D11Factors& f = p.factors;
  char title[256];
  if (f.culled)
    std::snprintf(title, sizeof title, "%s: culled (an outer factor <= 0 or NaN)", partitioning_name(partitioning));
  else
    std::snprintf(title, sizeof title, "%s  outer %g, %g, %g  inner %g  %zu points, %zu triangles",
                  partitioning_name(partitioning), f.outer[0], f.outer[1], f.outer[2], f.inner, p.points.size(),
                  p.triangle_count());
  d.texts.push_back({{kMargin, 28.0}, title, ink});
  for (std::size_t t = 0; t < p.triangle_count(); ++t) {
    render::Drawing::Polygon triangle;
    for (int c = 0; c < 3; ++c) {
      const FixedUV q = p.points[p.indices[3 * t + c]];
      triangle.points.push_back(at(fixed16_to_double(q.u), fixed16_to_double(q.v)));
    }
    triangle.fill = glm::dvec3(0xdd / 255.0, 0xe6 / 255.0, 0xf2 / 255.0);
    triangle.stroke = glm::dvec3(0x5b / 255.0, 0x6b / 255.0, 0x80 / 255.0);
    triangle.stroke_width = 0.8;
    d.polygons.push_back(std::move(triangle));
  }
  d.polygons.push_back({{at(0, 0), at(1, 0), at(0, 1)}, std::nullopt, ink, 2.0});
  const float max_factor = std::max({f.outer[0], f.outer[1], f.outer[2], f.inner, 1.0f});
  const double radius = std::clamp(kSide / (6.0 * max_factor), 1.2, 5.0);
  for (const FixedUV& q : p.points)
    d.dots.push_back({at(fixed16_to_double(q.u), fixed16_to_double(q.v)), radius,
                      glm::dvec3(0xb5 / 255.0, 0x40 / 255.0, 0x2a / 255.0)});
  // Corners and the edge each outer factor subdivides.
  const double h = d.height - kMargin;
  d.texts.push_back({{kMargin - 45, h + 20}, "w=1", ink});
  d.texts.push_back({{kMargin + kSide + 8, h + 20}, "u=1", ink});
  d.texts.push_back({{kMargin + kSide / 2 - 12, h - 0.5 * std::sqrt(3.0) * kSide - 10}, "v=1", ink});
  if (!f.culled) {
    char label[64];
    std::snprintf(label, sizeof label, "e0=%g (u=0)", f.outer[0]);
    d.texts.push_back({{kMargin + kSide * 0.25 - 130, h - kSide * 0.433}, label, ink});
    std::snprintf(label, sizeof label, "e1=%g (v=0)", f.outer[1]);
    d.texts.push_back({{kMargin + kSide / 2 - 45, h + 24}, label, ink});
    std::snprintf(label, sizeof label, "e2=%g (w=0)", f.outer[2]);
    d.texts.push_back({{kMargin + kSide * 0.75 + 14, h - kSide * 0.433}, label, ink});
  }
  return d;
}

void write_svg(const render::Drawing& drawing, const std::filesystem::path& path) {
  AtomicOutput out(path);
  out.stream() << render::to_svg(drawing);
  out.commit();
}

// PNG: the same drawing rasterized, scaled to fit --size.
void write_png(const render::Drawing& drawing, const std::filesystem::path& path, const std::string& size_text) {
  const glm::ivec2 size = parse_image_size(size_text, "--size");
  render::write_image(render::rasterize(drawing, size.x, size.y), path);
}

void print_text(const D3D11Pattern& p, Partitioning partitioning, Winding winding, std::FILE* out) {
  const D3D11Factors& f = p.factors;
  std::fprintf(out, "partitioning   %s\n", partitioning_name(partitioning));
  std::fprintf(out, "winding        %s\n", winding_name(winding));
  if (f.culled) {
    std::fprintf(out, "culled         yes: an outer factor is <= 0 or NaN; no points, no triangles\n");
    return;
  }
  auto parity = [](bool odd) { return odd ? "odd" : "even"; };
  for (int e = 0; e < 3; ++e)
    std::fprintf(out, "outer e%d       %-10g (16.16 %s, %s, %d points on edge %s=0)\n", e, f.outer[e],
                 hex(f.outer_fixed[e]).c_str(), parity(f.outer_odd[e]), f.outer_points[e], e == 0 ? "u" : e == 1 ? "v" : "w");
  if (f.single_triangle)
    std::fprintf(out, "inner          %-10g (16.16 %s): all factors 1, the domain triangle itself\n", f.inner,
                 hex(f.inner_fixed).c_str());
  else
    std::fprintf(out, "inner          %-10g (16.16 %s, %s, %d points per inner edge)\n", f.inner, hex(f.inner_fixed).c_str(),
                 parity(f.inner_odd), f.inner_points);
  std::fprintf(out, "points         %zu\n", p.points.size());
  std::fprintf(out, "triangles      %zu\n", p.triangle_count());
  std::fprintf(out, "\n# point  u  v  (16.16: u v)\n");
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    const FixedUV q = p.points[i];
    std::fprintf(out, "%zu %.10f %.10f %s %s\n", i, fixed16_to_double(q.u), fixed16_to_double(q.v), hex(q.u).c_str(),
                 hex(q.v).c_str());
  }
  std::fprintf(out, "\n# triangle  i0 i1 i2\n");
  for (std::size_t t = 0; t < p.triangle_count(); ++t)
    std::fprintf(out, "%zu %u %u %u\n", t, p.indices[3 * t], p.indices[3 * t + 1], p.indices[3 * t + 2]);
}

void print_json(const D3D11Pattern& p, Partitioning partitioning, Winding winding, std::FILE* out) {
  const D3D11Factors& f = p.factors;
  nlohmann::json j;
  j["points"] = nlohmann::json::array();
  j["points_fixed"] = nlohmann::json::array();
  for (const FixedUV& q : p.points) {
    j["points"].push_back({fixed16_to_double(q.u), fixed16_to_double(q.v)});  // exact in a double
    j["points_fixed"].push_back({q.u, q.v});
  }
  j["indices"] = p.indices;
  j["culled"] = f.culled;
  j["partitioning"] = partitioning_name(partitioning);
  j["winding"] = winding_name(winding);
  if (!f.culled) {
    j["outer"] = {f.outer[0], f.outer[1], f.outer[2]};
    j["inner"] = f.inner;
    j["outer_fixed"] = f.outer_fixed;
    j["inner_fixed"] = f.inner_fixed;
  }
  std::fprintf(out, "%s\n", j.dump().c_str());
}

void run_pattern(const PatternArgs& args) {
  // All options are checked before anything is computed or written.
  const std::array<float, 3> outer = parse_outer_factors("pattern", args.outer);
  const float inner = parse_factor("pattern", "--inner", args.inner);
  const Partitioning partitioning = parse_partitioning_option("pattern", args.partitioning);
  const auto winding = parse_winding(args.winding);
  if (!winding) throw InputError("command line", "--winding", "'" + args.winding + "' is not one of ccw, cw");
  const std::filesystem::path output = args.output;
  std::string extension = output.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  // Standard output, a device or a pipe without an extension gets SVG; the text then goes to stderr.
  const OutputKind kind = output_kind(output);
  if (!args.output.empty() && kind != OutputKind::File && extension != ".png") extension = ".svg";
  if (!args.output.empty() && extension != ".svg" && extension != ".png")
    throw InputError(args.output, "output", "unsupported extension '" + output.extension().string() + "' (use .svg or .png)");
  parse_image_size(args.size, "--size");  // checked for every output: a bad size is never ignored

  const D3D11Pattern p = d3d11_tri_pattern(outer, inner, partitioning, *winding);
  if (extension == ".svg") write_svg(pattern_drawing(p, partitioning), output);
  if (extension == ".png") write_png(pattern_drawing(p, partitioning), output, args.size);

  std::FILE* text = !args.output.empty() && kind == OutputKind::Stdout ? stderr : stdout;
  if (args.json) print_json(p, partitioning, *winding, text);
  else print_text(p, partitioning, *winding, text);
}

}  // namespace

void register_pattern(CLI::App& app) {
  auto args = std::make_shared<PatternArgs>();
  CLI::App* cmd = app.add_subcommand(
      "pattern", "Print or draw the Direct3D 11 tessellation pattern of the triangle domain for given factors");
  cmd->add_option("--outer", args->outer, "Outer factors e0,e1,e2 of the edges u=0, v=0, w=0")->required();
  cmd->add_option("--inner", args->inner, "Inner factor")->required();
  cmd->add_option("--partitioning", args->partitioning, "integer, pow2, fractional_odd or fractional_even")->required();
  cmd->add_option("--winding", args->winding, "Triangle order: ccw (positive area in the u,v plane) or cw")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "One JSON object: points [[u, v], ...], indices [i0, i1, i2, ...], ...");
  cmd->add_option("-o,--output", args->output, "Also write a picture: .svg, or .png (the same picture rasterized, see --size)");
  cmd->add_option("--size", args->size, "PNG size WxH (1..8192 each)")->capture_default_str();
  cmd->callback([args] { run_pattern(*args); });
}

}  // namespace tessim::app
