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
#include "model/d3d11_pattern.hpp"
#include "model/error.hpp"
#include "model/output_file.hpp"
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

void write_svg(const D3D11Pattern& p, Partitioning partitioning, const std::filesystem::path& path) {
  constexpr double kSide = 680.0, kMargin = 60.0;
  const double width = kSide + 2 * kMargin, height = 0.5 * std::sqrt(3.0) * kSide + 2 * kMargin + 30.0;
  auto px = [&](double u, double v) {
    const Plane q = to_plane(u, v);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f,%.2f", kMargin + kSide * q.x, height - kMargin - kSide * q.y);
    return std::string(buf);
  };
  const D3D11Factors& f = p.factors;
  AtomicOutput out(path);
  std::ostream& s = out.stream();
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" font-size=\"15\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  char title[256];
  if (f.culled)
    std::snprintf(title, sizeof title, "%s: culled (an outer factor <= 0 or NaN)", partitioning_name(partitioning));
  else
    std::snprintf(title, sizeof title, "%s  outer %g, %g, %g  inner %g  %zu points, %zu triangles",
                  partitioning_name(partitioning), f.outer[0], f.outer[1], f.outer[2], f.inner, p.points.size(),
                  p.triangle_count());
  s << "<text x=\"" << kMargin << "\" y=\"28\">" << title << "</text>\n";
  s << "<g fill=\"#dde6f2\" stroke=\"#5b6b80\" stroke-width=\"0.8\" stroke-linejoin=\"round\">\n";
  for (std::size_t t = 0; t < p.triangle_count(); ++t) {
    s << "<polygon points=\"";
    for (int c = 0; c < 3; ++c) {
      const FixedUV q = p.points[p.indices[3 * t + c]];
      s << (c ? " " : "") << px(fixed16_to_double(q.u), fixed16_to_double(q.v));
    }
    s << "\"/>\n";
  }
  s << "</g>\n";
  s << "<polygon points=\"" << px(0, 0) << " " << px(1, 0) << " " << px(0, 1)
    << "\" fill=\"none\" stroke=\"#1a2230\" stroke-width=\"2\"/>\n";
  const float max_factor = std::max({f.outer[0], f.outer[1], f.outer[2], f.inner, 1.0f});
  const double radius = std::clamp(kSide / (6.0 * max_factor), 1.2, 5.0);
  s << "<g fill=\"#b5402a\">\n";
  for (const FixedUV& q : p.points) {
    const Plane c = to_plane(fixed16_to_double(q.u), fixed16_to_double(q.v));
    s << "<circle cx=\"" << kMargin + kSide * c.x << "\" cy=\"" << height - kMargin - kSide * c.y << "\" r=\""
      << radius << "\"/>\n";
  }
  s << "</g>\n";
  // Corners and the edge each outer factor subdivides.
  const double h = height - kMargin;
  s << "<text x=\"" << kMargin - 45 << "\" y=\"" << h + 20 << "\">w=1</text>\n";
  s << "<text x=\"" << kMargin + kSide + 8 << "\" y=\"" << h + 20 << "\">u=1</text>\n";
  s << "<text x=\"" << kMargin + kSide / 2 - 12 << "\" y=\"" << h - 0.5 * std::sqrt(3.0) * kSide - 10
    << "\">v=1</text>\n";
  if (!f.culled) {
    char label[64];
    std::snprintf(label, sizeof label, "e0=%g (u=0)", f.outer[0]);
    s << "<text x=\"" << kMargin + kSide * 0.25 - 130 << "\" y=\"" << h - kSide * 0.433 << "\">" << label << "</text>\n";
    std::snprintf(label, sizeof label, "e1=%g (v=0)", f.outer[1]);
    s << "<text x=\"" << kMargin + kSide / 2 - 45 << "\" y=\"" << h + 24 << "\">" << label << "</text>\n";
    std::snprintf(label, sizeof label, "e2=%g (w=0)", f.outer[2]);
    s << "<text x=\"" << kMargin + kSide * 0.75 + 14 << "\" y=\"" << h - kSide * 0.433 << "\">" << label << "</text>\n";
  }
  s << "</svg>\n";
  out.commit();
}

// PNG through the mesh renderer: the pattern flat in the z = 0 plane facing the camera, every
// triangle edge drawn, the domain's boundary darker.
void write_png(const D3D11Pattern& p, const std::filesystem::path& path, const std::string& size_text) {
  const glm::ivec2 size = parse_image_size(size_text, "--size");
  RenderMesh mesh;
  if (p.factors.culled) {  // nothing to draw but the empty domain
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.5 * std::sqrt(3.0), 0}};
    mesh.triangles = {{0, 1, 2}};
  } else {
    for (const FixedUV& q : p.points) {
      const Plane c = to_plane(fixed16_to_double(q.u), fixed16_to_double(q.v));
      mesh.positions.emplace_back(c.x, c.y, 0.0);
    }
    for (std::size_t t = 0; t < p.triangle_count(); ++t)
      mesh.triangles.emplace_back(p.indices[3 * t], p.indices[3 * t + 1], p.indices[3 * t + 2]);
  }
  mesh.normals.assign(mesh.positions.size(), glm::dvec3(0, 0, 1));
  mesh.edge_flags.assign(mesh.triangles.size(), 0);
  auto on_boundary = [&](const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 points[2] = {a, b};
    for (int e = 0; e < 3; ++e) {  // both ends on the same domain edge, tested exactly in 16.16
      bool all = true;
      for (const glm::dvec3& q : points) {
        const double v = q.y / (0.5 * std::sqrt(3.0)), u = q.x - 0.5 * v;
        const double coordinate = e == 0 ? u : e == 1 ? v : 1.0 - u - v;
        all = all && std::abs(coordinate) < 0.5 / 65536.0;
      }
      if (all) return true;
    }
    return false;
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      if (on_boundary(mesh.positions[mesh.triangles[t][c]], mesh.positions[mesh.triangles[t][(c + 1) % 3]]))
        mesh.edge_flags[t] |= static_cast<std::uint8_t>(1u << c);
  validate(mesh, "pattern");

  ViewAngles view;
  view.azimuth_deg = 0.0;
  view.elevation_deg = 0.0;
  const Camera camera = frame_camera(mesh.positions, view, size.x, size.y);
  RenderOptions options;
  options.width = size.x;
  options.height = size.y;
  options.wireframe = true;
  options.wire_width_px = 2.0;
  options.wire_opacity = 1.0;
  // Unlit: the plane faces the camera, so shading would only tint it.
  options.albedo = {0.80, 0.86, 0.94};
  options.ambient = 1.0;
  options.diffuse = 0.0;
  options.specular = 0.0;
  write_image(render(mesh, camera, options), path);
}

void print_text(const D3D11Pattern& p, Partitioning partitioning, Winding winding) {
  const D3D11Factors& f = p.factors;
  std::printf("partitioning   %s\n", partitioning_name(partitioning));
  std::printf("winding        %s\n", winding_name(winding));
  if (f.culled) {
    std::printf("culled         yes: an outer factor is <= 0 or NaN; no points, no triangles\n");
    return;
  }
  auto parity = [](bool odd) { return odd ? "odd" : "even"; };
  for (int e = 0; e < 3; ++e)
    std::printf("outer e%d       %-10g (16.16 %s, %s, %d points on edge %s=0)\n", e, f.outer[e],
                hex(f.outer_fixed[e]).c_str(), parity(f.outer_odd[e]), f.outer_points[e], e == 0 ? "u" : e == 1 ? "v" : "w");
  if (f.single_triangle)
    std::printf("inner          %-10g (16.16 %s): all factors 1, the domain triangle itself\n", f.inner,
                hex(f.inner_fixed).c_str());
  else
    std::printf("inner          %-10g (16.16 %s, %s, %d points per inner edge)\n", f.inner, hex(f.inner_fixed).c_str(),
                parity(f.inner_odd), f.inner_points);
  std::printf("points         %zu\n", p.points.size());
  std::printf("triangles      %zu\n", p.triangle_count());
  std::printf("\n# point  u  v  (16.16: u v)\n");
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    const FixedUV q = p.points[i];
    std::printf("%zu %.10f %.10f %s %s\n", i, fixed16_to_double(q.u), fixed16_to_double(q.v), hex(q.u).c_str(),
                hex(q.v).c_str());
  }
  std::printf("\n# triangle  i0 i1 i2\n");
  for (std::size_t t = 0; t < p.triangle_count(); ++t)
    std::printf("%zu %u %u %u\n", t, p.indices[3 * t], p.indices[3 * t + 1], p.indices[3 * t + 2]);
}

void print_json(const D3D11Pattern& p, Partitioning partitioning, Winding winding) {
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
  std::cout << j.dump() << "\n";
}

void run_pattern(const PatternArgs& args) {
  // All options are checked before anything is computed or written.
  const std::array<float, 3> outer = parse_outer_factors("pattern", args.outer);
  const float inner = parse_factor("pattern", "--inner", args.inner);
  const Partitioning partitioning = parse_partitioning_option("pattern", args.partitioning);
  const auto winding = parse_winding(args.winding);
  if (!winding) throw InputError("pattern", "--winding", "'" + args.winding + "' is not one of ccw, cw");
  const std::filesystem::path output = args.output;
  std::string extension = output.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!args.output.empty() && extension != ".svg" && extension != ".png")
    throw InputError(args.output, "output", "unsupported extension '" + output.extension().string() + "' (use .svg or .png)");
  if (extension == ".png") parse_image_size(args.size, "--size");

  const D3D11Pattern p = d3d11_tri_pattern(outer, inner, partitioning, *winding);
  if (extension == ".svg") write_svg(p, partitioning, output);
  if (extension == ".png") write_png(p, output, args.size);

  if (args.json) print_json(p, partitioning, *winding);
  else print_text(p, partitioning, *winding);
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
  cmd->add_option("-o,--output", args->output, "Also write a picture: .svg, or .png (rendered, see --size)");
  cmd->add_option("--size", args->size, "PNG size WxH (1..8192 each)")->capture_default_str();
  cmd->callback([args] { run_pattern(*args); });
}

}  // namespace tessim::app
