#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <filesystem>
#include <string>
#include <system_error>

#include "app/commands.hpp"
#include "model/error.hpp"
#include "model/output_file.hpp"
#include "model/pattern.hpp"
#include "render/raster.hpp"

namespace tessim::app {

void check_tess_factor(const char* command, int factor) {
  if (factor < 1 || factor > kMaxTessFactor)
    throw InputError(command, "-L", std::to_string(factor) + " is outside 1.." + std::to_string(kMaxTessFactor));
}

NormalMode parse_normals_option(const char* command, const std::string& text) {
  const auto mode = parse_normal_mode(text);
  if (!mode)
    throw InputError(command, "--normals", "'" + text + "' is not one of quadratic, reflect, linear, derivative");
  return *mode;
}

void warn_tags_ignored(const Mesh& mesh, const char* command) {
  const auto acting = std::count_if(mesh.tags.begin(), mesh.tags.end(), [](const VertexTags& t) { return !t.neutral(); });
  if (acting == 0) return;
  std::fprintf(stderr,
               "tessim: warning: %s: tags: %td vertices carry scalar tags, which tessim %s ignores: the unit "
               "computes plain PN triangles (tessellate and render use the tags, and sim with --cpg-tags 1; "
               "docs/stpn.md)\n",
               mesh.source.c_str(), acting, command);
}

void check_output_paths(const std::vector<OutputPath>& outputs) {
  namespace fs = std::filesystem;
  std::vector<fs::path> seen;
  const char* stdout_option = nullptr;
  for (const OutputPath& o : outputs) {
    if (o.path.empty()) continue;
    // Standard output, a device or a pipe is written directly (model/output_file.hpp): no
    // temporary beside it. Two outputs cannot share standard output or a pipe; /dev/null and
    // other character devices take any number.
    const OutputKind kind = output_kind(o.path);
    if (kind == OutputKind::Stdout) {
      if (stdout_option)
        throw InputError(o.path, o.option,
                         std::string("is standard output, which ") + stdout_option + " writes already");
      stdout_option = o.option;
      continue;
    }
    std::error_code ec;
    if (kind == OutputKind::Direct) {
      if (fs::is_character_file(fs::status(o.path, ec))) continue;
      const fs::path key = resolve_output_path(o.path);
      for (const fs::path& other : seen)
        if (other == key) throw InputError(o.path, o.option, "is also the path of another output of this command");
      seen.push_back(key);
      continue;
    }
    // A symbolic link is written through: its target's directory holds the temporary.
    const fs::path path = resolve_output_path(o.path);
    if (fs::is_directory(path, ec)) throw InputError(o.path, o.option, "is a directory");
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(dir, ec))
      throw InputError(o.path, o.option, "cannot open for writing: directory '" + dir.string() + "' does not exist");
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      throw InputError(o.path, o.option, "cannot open for writing: directory '" + dir.string() + "' is not writable");
    const fs::path canonical = fs::weakly_canonical(path, ec);
    const fs::path key = ec ? path.lexically_normal() : canonical;
    for (const fs::path& other : seen)
      if (other == key) throw InputError(o.path, o.option, "is also the path of another output of this command");
    seen.push_back(key);
  }
}

void add_speed_run_options(CLI::App& sub, SpeedRunArgs& args, const char* int_blocks_help) {
  sub.add_option("mesh", args.mesh, "input mesh")->capture_default_str();
  sub.add_option("-L,--tess-factor", args.tess_factor, "segments per edge")
      ->transform(number_check<int>("command line", "-L", "1..64"))
      ->capture_default_str();
  sub.add_option("--int", args.int_blocks, int_blocks_help)
      ->delimiter(',')
      ->transform(number_check<int>("command line", "--int", type_range<int>()))
      ->capture_default_str();
  sub.add_option("--gpe-cycles", args.gpe_cycles, "GPE cycles per vertex K (one or more)")
      ->delimiter(',')
      ->transform(number_check<int>("command line", "--gpe-cycles", type_range<int>()))
      ->capture_default_str();
  sub.add_option("--repeat", args.repeat, "runs per configuration (median reported)")
      ->transform(number_check<int>("command line", "--repeat", type_range<int>()))
      ->capture_default_str();
}

namespace {

// "a,b,c" as numbers; each must parse whole.
std::vector<double> parse_numbers(const char* command, const char* option, const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size())
      throw InputError(command, option, "'" + item + "' in '" + text + "' is not a number");
    out.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

glm::dvec3 parse_point(const char* command, const std::string& key, const std::string& text) {
  const std::vector<double> v = parse_numbers(command, "--camera", text);
  if (v.size() != 3) throw InputError(command, "--camera", key + "=" + text + " needs three coordinates x,y,z");
  return {v[0], v[1], v[2]};
}

}  // namespace

float parse_factor(const char* command, const char* option, const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  const std::string t = first == std::string::npos ? "" : text.substr(first, text.find_last_not_of(" \t") - first + 1);
  char* end = nullptr;
  const double value = t.empty() ? 0.0 : std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size()) throw InputError(command, option, "'" + text + "' is not a number");
  if (std::isfinite(value) && std::abs(value) > std::numeric_limits<float>::max())
    return value > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

std::array<float, 3> parse_outer_factors(const char* command, const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (parts.size() != 3)
    throw InputError(command, "--outer",
                     "expected 3 comma-separated factors e0,e1,e2 (edges u=0, v=0, w=0), got " +
                         std::to_string(parts.size()));
  return {parse_factor(command, "--outer", parts[0]), parse_factor(command, "--outer", parts[1]),
          parse_factor(command, "--outer", parts[2])};
}

Partitioning parse_partitioning_option(const char* command, const std::string& text) {
  const std::optional<Partitioning> p = parse_partitioning(text);
  if (!p)
    throw InputError(command, "--partitioning",
                     "'" + text + "' is not one of integer, pow2, fractional_odd, fractional_even");
  return *p;
}

void add_adaptive_options(CLI::App& cmd, AdaptiveOptions& o, const char* command) {
  cmd.add_option("--adaptive", o.adaptive,
                 "'screen': factors per edge from the edge's projected length (docs/patterns.md)");
  cmd.add_option("--camera", o.camera, "with --adaptive: eye=x,y,z[,target=x,y,z][,fov=deg] (fov default 45)");
  cmd.add_option("--viewport", o.viewport, "with --adaptive: viewport WxH in pixels")->capture_default_str();
  cmd.add_option("--pixels-per-segment", o.pixels_per_segment, "with --adaptive: target on-screen length of a segment")
      ->transform(number_check<double>(command, "--pixels-per-segment", "positive numbers"))
      ->capture_default_str();
}

void add_pattern_options(CLI::App& cmd, PatternOptions& o, const char* command) {
  cmd.add_option("-L,--tess-factor,--factor", o.factor,
                 "Tessellation factor: segments per edge (1..64) of the uniform pattern, or every factor of the "
                 "D3D11 pattern with --partitioning")
      ->transform(number_check<int>(command, "-L", "1..64"))
      ->capture_default_str();
  cmd.add_option("--partitioning", o.partitioning,
                 "D3D11 pattern spacing: integer, pow2, fractional_odd, fractional_even (default: the uniform "
                 "pattern; integer with --outer or --adaptive)");
  cmd.add_option("--outer", o.outer, "D3D11 outer factors A,B,C (edges u=0, v=0, w=0), the same for every patch");
  cmd.add_option("--inner", o.inner, "D3D11 inner factor with --outer (default: the largest outer factor)");
  add_adaptive_options(cmd, o.adaptive, command);
}

void AdaptiveOptions::apply(TessSettings& s, const char* command) const {
  if (adaptive != "screen") throw InputError(command, "--adaptive", "'" + adaptive + "' is not 'screen'");
  if (camera.empty()) throw InputError(command, "--camera", "--adaptive screen needs --camera eye=x,y,z");
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  // key=value items; a value's own commas belong to it until the next "key=".
  std::vector<std::pair<std::string, std::string>> items;
  std::size_t start = 0;
  while (start < camera.size()) {
    const std::size_t eq = camera.find('=', start);
    if (eq == std::string::npos) throw InputError(command, "--camera", "'" + camera + "' is not key=value,...");
    const std::string key = camera.substr(start, eq - start);
    std::size_t next = camera.size();
    for (const char* k : {",eye=", ",target=", ",fov="}) next = std::min(next, camera.find(k, eq));
    items.emplace_back(key, camera.substr(eq + 1, next - eq - 1));
    start = next == camera.size() ? next : next + 1;
  }
  bool has_eye = false;
  for (const auto& [key, value] : items) {
    if (key == "eye") {
      s.camera.eye = parse_point(command, key, value);
      has_eye = true;
    } else if (key == "target") {
      s.camera.target = parse_point(command, key, value);
    } else if (key == "fov") {
      s.camera.fov_deg = parse_numbers(command, "--camera", value).at(0);
    } else {
      throw InputError(command, "--camera", "unknown key '" + key + "' (eye, target, fov)");
    }
  }
  if (!has_eye) throw InputError(command, "--camera", "needs eye=x,y,z");
  const glm::ivec2 size = parse_image_size(viewport, "--viewport");
  s.camera.width = size.x;
  s.camera.height = size.y;
  s.pixels_per_segment = pixels_per_segment;
}

TessSettings PatternOptions::settings(const char* command) const {
  TessSettings s;
  s.L = factor;
  check_tess_factor(command, factor);
  const bool fixed = !outer.empty() || !inner.empty();
  if (fixed && adaptive.given()) throw InputError(command, "--outer", "cannot be combined with --adaptive");
  if (!inner.empty() && outer.empty()) throw InputError(command, "--inner", "needs --outer");
  if (!adaptive.given() && !adaptive.camera.empty()) throw InputError(command, "--camera", "needs --adaptive screen");
  if (partitioning.empty() && !fixed && !adaptive.given()) return s;  // the uniform pattern

  s.kind = PatternKind::D3D11;
  if (!partitioning.empty()) s.partitioning = parse_partitioning_option(command, partitioning);
  const auto L = static_cast<float>(factor);
  s.outer = {L, L, L};
  s.inner = L;
  if (fixed) {
    s.outer = parse_outer_factors(command, outer);
    s.inner = inner.empty() ? std::max({s.outer[0], s.outer[1], s.outer[2]}) : parse_factor(command, "--inner", inner);
  }
  if (adaptive.given()) adaptive.apply(s, command);
  validate(s, command);
  return s;
}

void add_unit_pattern_options(CLI::App& cmd, UnitPatternOptions& o, const char* command) {
  const bool random = std::string_view(command) == "cosim";
  cmd.add_option("--partitioning", o.partitioning,
                 std::string("the unit generates the D3D11 pattern with this spacing: integer, pow2, fractional_odd, "
                             "fractional_even (default: the uniform pattern; integer with --outer or --adaptive)") +
                     (random ? "; with --random the factors are drawn, and 'mixed' draws a partitioning per triangle" : ""));
  cmd.add_option("--outer", o.outer, "D3D11 outer factors A,B,C (edges u=0, v=0, w=0), the same for every patch");
  cmd.add_option("--inner", o.inner, "D3D11 inner factor with --outer (default: the largest outer factor)");
  add_adaptive_options(cmd, o.adaptive, command);
}

std::optional<TessSettings> UnitPatternOptions::settings(const char* command, int L) const {
  if (!given()) {
    if (!adaptive.camera.empty()) throw InputError(command, "--camera", "needs --adaptive screen");
    return std::nullopt;
  }
  PatternOptions p;
  p.factor = L;
  p.partitioning = partitioning;
  p.outer = outer;
  p.inner = inner;
  p.adaptive = adaptive;
  return p.settings(command);
}

}  // namespace tessim::app
