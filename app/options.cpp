#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <filesystem>
#include <string>
#include <system_error>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/output_file.hpp"
#include "model/d3d11_pattern.hpp"
#include "model/pattern.hpp"
#include "render/raster.hpp"
#include "sim/values/host.hpp"

namespace tessim::app {

namespace {
// Every option error names its source as the README promises: the command line (not the command).
const char* const kCommandLine = "command line";
}  // namespace

void check_tess_factor(const char* /*command*/, int factor) {
  if (factor < 1 || factor > kMaxTessFactor)
    throw InputError(kCommandLine, "-L", std::to_string(factor) + " is outside 1.." + std::to_string(kMaxTessFactor));
}

NormalMode parse_normals_option(const char* /*command*/, const std::string& text) {
  const auto mode = parse_normal_mode(text);
  if (!mode)
    throw InputError(kCommandLine, "--normals", "'" + text + "' is not one of quadratic, reflect, linear, derivative");
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

void warn_tags_lost(const Mesh& mesh, const sim::NumberFormat& format) {
  const std::string warning = sim::tags_lost_warning(mesh, format);
  if (!warning.empty()) std::fprintf(stderr, "tessim: warning: %s\n", printable_text(warning, 960).c_str());
}

void warn_nyquist_shortfall(const TessSettings& s, const Mesh& mesh) {
  const NyquistShortfall shortfall = nyquist_shortfall(s, mesh);
  if (shortfall.edges == 0) return;
  std::fprintf(stderr,
               "tessim: warning: %s: --adaptive: %zu edges need more than %d segments for %g samples per wavelength "
               "(up to %.0f) and are clamped to %d: their displacement still aliases (docs/patterns.md §9)\n",
               printable_text(mesh.source.empty() ? std::string("mesh") : mesh.source, 960).c_str(), shortfall.edges,
               kMaxTessFactor, s.samples_per_wavelength, std::ceil(shortfall.most_segments), kMaxTessFactor);
}

void check_output_paths(const std::vector<OutputPath>& outputs, const std::vector<InputPath>& inputs) {
  namespace fs = std::filesystem;
  std::vector<fs::path> seen;
  const char* stdout_option = nullptr;
  for (const OutputPath& o : outputs) {
    if (o.path.empty()) continue;
    if (o.path != "-") {
      std::error_code ec;
      // resolve_output_path gives up after the kernel's 40 links: still a link, it is a loop.
      if (fs::is_symlink(fs::symlink_status(resolve_output_path(o.path), ec)))
        throw InputError(o.path, o.option, "is a loop of symbolic links");
      for (const InputPath& in : inputs) {
        if (in.path.empty() || in.path == "-") continue;
        std::error_code eq;
        if (fs::exists(o.path, eq) && fs::exists(in.path, eq) && fs::equivalent(o.path, in.path, eq) && !eq)
          throw InputError(o.path, o.option,
                           std::string("is the same file as the input ") + in.option + " of this command (it would be overwritten)");
      }
    }
    // Standard output, a device or a pipe is written directly (model/base/output_file.hpp): no
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
std::vector<double> parse_numbers(const char* option, const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    // strtod also reads hexadecimal ("0x10" is 16, "0x1p4" too): only decimal is a number here
    // ("nan" and "inf" pass on, to be refused as not finite where that matters).
    const bool hexadecimal = item.find_first_of("xXpP") != std::string::npos;
    if (item.empty() || end != item.c_str() + item.size() || hexadecimal)
      throw InputError(kCommandLine, option, "'" + item + "' in '" + text + "' is not a number");
    out.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

glm::dvec3 parse_point(const std::string& key, const std::string& text, const char* option = "--camera") {
  const std::vector<double> v = parse_numbers(option, text);
  if (v.size() != 3) throw InputError(kCommandLine, option, key + "=" + text + " needs three coordinates x,y,z");
  return {v[0], v[1], v[2]};
}

}  // namespace

float parse_factor(const char* /*command*/, const char* option, const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  const std::string t = first == std::string::npos ? "" : text.substr(first, text.find_last_not_of(" \t") - first + 1);
  // Straight into a float, correctly rounded (through a double, 1 + 2^-24 + tiny would round
  // twice and lose the last bit). from_chars takes no sign '+' and no "0x" prefix.
  std::string_view digits = t;
  const bool negative = !digits.empty() && digits.front() == '-';
  if (!digits.empty() && (digits.front() == '+' || negative)) digits.remove_prefix(1);
  auto format = std::chars_format::general;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    digits.remove_prefix(2);
    format = std::chars_format::hex;
  }
  float value = 0.0f;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value, format);
  if (digits.empty() || digits.front() == '-' || digits.front() == '+' || end != digits.data() + digits.size() ||
      ec == std::errc::invalid_argument)
    throw InputError(kCommandLine, option, "'" + text + "' is not a number");
  if (ec == std::errc::result_out_of_range) {
    // Beyond the float range: an infinity, as D3D11 would see it; below it: zero.
    const std::string again = (format == std::chars_format::hex ? "0x" : "") + std::string(digits);
    const double magnitude = std::strtod(again.c_str(), nullptr);
    value = std::abs(magnitude) >= 1.0 ? std::numeric_limits<float>::infinity() : 0.0f;
  }
  return negative ? -value : value;
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
    throw InputError(kCommandLine, "--outer",
                     "expected 3 comma-separated factors e0,e1,e2 (edges u=0, v=0, w=0), got " +
                         std::to_string(parts.size()));
  return {parse_factor(command, "--outer", parts[0]), parse_factor(command, "--outer", parts[1]),
          parse_factor(command, "--outer", parts[2])};
}

Partitioning parse_partitioning_option(const char* /*command*/, const std::string& text) {
  const std::optional<Partitioning> p = parse_partitioning(text);
  if (!p)
    throw InputError(kCommandLine, "--partitioning",
                     "'" + text + "' is not one of integer, pow2, fractional_odd, fractional_even");
  return *p;
}

void add_adaptive_options(CLI::App& cmd, AdaptiveOptions& o, const char* /*command*/) {
  cmd.add_option("--adaptive", o.adaptive,
                 "'screen': factors per edge from the edge's projected length; 'silhouette': that scaled by the "
                 "edge's silhouetteness, with silhouette blending from the camera's eye; 'contour': the silhouette rule with "
                 "every edge of a patch the view contour can cross taken as silhouette; 'nyquist': enough segments "
                 "to sample the --displace wavelength along each edge --samples-per-wavelength times (no camera); "
                 "'screen+nyquist', 'silhouette+nyquist', 'contour+nyquist': the larger factor of both "
                 "(docs/patterns.md)");
  o.samples_per_wavelength_option =
      cmd.add_option("--samples-per-wavelength", o.samples_per_wavelength,
                     "with --adaptive ...nyquist: points per shortest wavelength of the displacement along an edge (S >= 1)")
          ->transform(number_check<double>(kCommandLine, "--samples-per-wavelength", "finite numbers >= 1"))
          ->capture_default_str();
  cmd.add_option("--camera", o.camera, "with --adaptive: eye=x,y,z[,target=x,y,z][,fov=deg] (fov default 45)");
  o.viewport_option =
      cmd.add_option("--viewport", o.viewport, "with --adaptive: viewport WxH in pixels")->capture_default_str();
  o.pixels_per_segment_option =
      cmd.add_option("--pixels-per-segment", o.pixels_per_segment, "with --adaptive: target on-screen length of a segment")
          ->transform(number_check<double>(kCommandLine, "--pixels-per-segment", "positive numbers"))
          ->capture_default_str();
  o.outline_tolerance_option =
      cmd.add_option("--outline-tolerance", o.outline_tolerance,
                     "with --adaptive silhouette or contour: largest distance in pixels between an edge's curve and its segments")
          ->transform(number_check<double>(kCommandLine, "--outline-tolerance", "positive numbers"))
          ->capture_default_str();
}

SilhouetteSettings parse_silhouette_option(const std::string& text) {
  SilhouetteSettings s;
  s.enabled = true;
  // "camera" or "eye=x,y,z", then optionally ",beta=B" and ",blend=on|off"; the eye's own commas
  // belong to it.
  std::string rest = text;
  // Each key once: a second one would otherwise be read as part of the first one's value.
  for (const char* key : {"eye=", "beta=", "blend="}) {
    const std::size_t first = text.find(key);
    if (first != std::string::npos && text.find(key, first + 1) != std::string::npos)
      throw InputError(kCommandLine, "--silhouette",
                       "'" + std::string(key, std::strlen(key) - 1) + "' is given twice in '" + text + "'");
  }
  const std::size_t blend_at = rest.find(",blend=");
  if (blend_at != std::string::npos) {
    const std::string value = rest.substr(blend_at + 7);
    if (value != "on" && value != "off")
      throw InputError(kCommandLine, "--silhouette", "blend=" + value + " is not on or off (it comes last)");
    s.blend = value == "on";
    rest = rest.substr(0, blend_at);
  }
  const std::size_t beta_at = rest.find(",beta=");
  const std::string head = rest.substr(0, beta_at);
  if (head == "camera") {
    s.eye_from_camera = true;
  } else if (head.rfind("eye=", 0) == 0) {
    s.eye = parse_point("eye", head.substr(4), "--silhouette");
    if (!is_finite(s.eye))
      throw InputError(kCommandLine, "--silhouette", "eye " + head.substr(4) + " is not finite");
  } else {
    throw InputError(kCommandLine, "--silhouette",
                     "'" + text + "' is not eye=x,y,z[,beta=B][,blend=off] or camera[,beta=B][,blend=off]");
  }
  if (beta_at != std::string::npos) {
    const std::vector<double> beta = parse_numbers("--silhouette", rest.substr(beta_at + 6));
    if (beta.size() != 1) throw InputError(kCommandLine, "--silhouette", "beta takes one number in '" + text + "'");
    s.beta = beta[0];
  }
  validate(s, kCommandLine);
  return s;
}

void print_silhouette_counts(std::FILE* out, const MeshSilhouette& silhouette) {
  const SilhouetteCounts& c = silhouette.counts();
  std::fprintf(out,
               "silhouette (eye %s, beta %g): %" PRIu64 " edges: %" PRIu64 " flat (alpha 0), %" PRIu64
               " blended, %" PRIu64 " curved (alpha 1; %" PRIu64 " boundary, %" PRIu64 " non-manifold); %" PRIu64
               " feature ends\n",
               format_vec(silhouette.eye()).c_str(), silhouette.beta(), c.edges, c.flat, c.blended, c.curved,
               c.boundary, c.non_manifold, c.feature_ends);
}

CLI::Option* add_silhouette_option(CLI::App& cmd, std::string& text, bool unit) {
  return cmd.add_option("--silhouette", text,
                 "silhouette enhancement: eye=x,y,z[,beta=B][,blend=off] or camera[,beta=B][,blend=off] (the --camera "
                 "eye); each edge's silhouetteness blends its patch between flat and PN (beta default 0.25; blend=off: "
                 "the silhouetteness only drives --adaptive silhouette, docs/mathematics.md)" +
                     std::string(unit ? "; the host sends each edge's alpha to the unit's CPG (alpha_bits, 8 when the "
                                        "configuration has 0); a feature end is refused" : ""));
}

void add_pattern_options(CLI::App& cmd, PatternOptions& o, const char* command) {
  o.factor_option = cmd.add_option("-L,--tess-factor,--factor", o.factor,
                                   "Tessellation factor: segments per edge (1..64) of the uniform pattern, or every "
                                   "factor of the D3D11 pattern with --partitioning")
                        ->transform(number_check<int>(kCommandLine, "-L", "1..64"))
                        ->capture_default_str();
  cmd.add_option("--partitioning", o.partitioning,
                 "D3D11 pattern spacing: integer, pow2, fractional_odd, fractional_even (default: the uniform "
                 "pattern; integer with --outer or --adaptive)");
  cmd.add_option("--outer", o.outer, "D3D11 outer factors A,B,C (edges u=0, v=0, w=0), the same for every patch");
  cmd.add_option("--inner", o.inner, "D3D11 inner factor with --outer (default: the largest outer factor)");
  add_adaptive_options(cmd, o.adaptive, command);
  o.silhouette_option = add_silhouette_option(cmd, o.silhouette);
  add_displace_options(cmd, o.displace);
}

void add_displace_options(CLI::App& cmd, DisplaceOptions& o, bool unit) {
  o.kind_option = cmd.add_option(
      "--displace", o.kind,
      std::string("procedural displacement of every point along its unit normal, with Blinn's perturbed normal: "
                  "sine (P + a sin(f |P|) N, |P| in the mesh's coordinates) or noise (P + a noise(f P) N, gradient "
                  "noise); docs/mathematics.md §12") +
          (unit ? "; the geometry engine applies it in float to the unit's output, at the cost per vertex of "
                  "docs/microarchitecture.md §12 on top of K"
                : ""));
  o.amplitude_option = cmd.add_option("--amplitude", o.amplitude, "with --displace: the amplitude a, in the mesh's units")
                           ->transform(number_check<double>(kCommandLine, "--amplitude", "finite numbers"));
  o.frequency_option = cmd.add_option("--frequency", o.frequency,
                                      "with --displace: the frequency f >= 0 (sine: radians per unit of |P|; noise: "
                                      "lattice cells per unit)")
                           ->transform(number_check<double>(kCommandLine, "--frequency", "finite numbers"));
}

DisplaceSettings DisplaceOptions::settings() const {
  const std::string& displace = kind;
  DisplaceSettings d;
  const bool amplitude_given = amplitude_option && amplitude_option->count() > 0;
  const bool frequency_given = frequency_option && frequency_option->count() > 0;
  if (!(kind_option && kind_option->count() > 0)) {
    if (amplitude_given) throw InputError(kCommandLine, "--amplitude", "needs --displace sine|noise");
    if (frequency_given) throw InputError(kCommandLine, "--frequency", "needs --displace sine|noise");
    return d;
  }
  if (displace != "sine" && displace != "noise")
    throw InputError(kCommandLine, "--displace", "'" + displace + "' is not sine or noise");
  if (!amplitude_given || !frequency_given)
    throw InputError(kCommandLine, amplitude_given ? "--frequency" : "--amplitude",
                     "--displace needs --amplitude A and --frequency F");
  d.kind = displace == "noise" ? DisplaceKind::Noise : DisplaceKind::Sine;
  d.amplitude = amplitude;
  d.frequency = frequency;
  validate(d, kCommandLine);
  return d;
}

void AdaptiveOptions::check_given_alone() const {
  if (given()) return;
  if (!camera.empty()) throw InputError(kCommandLine, "--camera", "needs --adaptive screen");
  // A viewport or a segment length means nothing without adaptive factors: refused rather
  // than silently ignored.
  if (viewport_option && viewport_option->count() > 0)
    throw InputError(kCommandLine, "--viewport", "needs --adaptive screen");
  if (pixels_per_segment_option && pixels_per_segment_option->count() > 0)
    throw InputError(kCommandLine, "--pixels-per-segment", "needs --adaptive screen");
  if (outline_tolerance_option && outline_tolerance_option->count() > 0)
    throw InputError(kCommandLine, "--outline-tolerance", "needs --adaptive silhouette or contour");
  if (samples_per_wavelength_option && samples_per_wavelength_option->count() > 0)
    throw InputError(kCommandLine, "--samples-per-wavelength",
                     "needs --adaptive nyquist, screen+nyquist, silhouette+nyquist or contour+nyquist");
}

void AdaptiveOptions::apply(TessSettings& s, const char* /*command*/) const {
  static const std::vector<std::string> kRules{"screen",         "silhouette",         "contour",        "nyquist",
                                               "screen+nyquist", "silhouette+nyquist", "contour+nyquist"};
  if (std::find(kRules.begin(), kRules.end(), adaptive) == kRules.end())
    throw InputError(kCommandLine, "--adaptive",
                     "'" + adaptive +
                         "' is not screen, silhouette, contour, nyquist, screen+nyquist, silhouette+nyquist or "
                         "contour+nyquist");
  s.kind = PatternKind::D3D11;
  s.source = FactorSource::Adaptive;
  s.samples_per_wavelength = samples_per_wavelength;
  const bool nyquist_given = samples_per_wavelength_option && samples_per_wavelength_option->count() > 0;
  if (adaptive == "nyquist") {
    // No camera: the rule looks at the displacement alone, and what it does not read is refused.
    s.rule = AdaptiveRule::Nyquist;
    if (!camera.empty()) throw InputError(kCommandLine, "--camera", "--adaptive nyquist takes no camera (screen+nyquist does)");
    if (viewport_option && viewport_option->count() > 0)
      throw InputError(kCommandLine, "--viewport", "--adaptive nyquist takes no camera (screen+nyquist does)");
    if (pixels_per_segment_option && pixels_per_segment_option->count() > 0)
      throw InputError(kCommandLine, "--pixels-per-segment",
                       "is the screen rule's; --adaptive nyquist alone takes --samples-per-wavelength only (the larger "
                       "of both: screen+nyquist)");
    if (outline_tolerance_option && outline_tolerance_option->count() > 0)
      throw InputError(kCommandLine, "--outline-tolerance",
                       "is the silhouette rule's; --adaptive nyquist alone takes --samples-per-wavelength only (the "
                       "larger of both: silhouette+nyquist, contour+nyquist)");
    return;
  }
  s.with_nyquist = adaptive.ends_with("+nyquist");
  if (!s.with_nyquist && nyquist_given)
    throw InputError(kCommandLine, "--samples-per-wavelength",
                     "needs --adaptive nyquist, screen+nyquist, silhouette+nyquist or contour+nyquist");
  const std::string base = adaptive.substr(0, adaptive.find('+'));
  if (camera.empty())
    throw InputError(kCommandLine, "--camera", "--adaptive " + adaptive + " needs --camera eye=x,y,z");
  s.rule = base == "silhouette" ? AdaptiveRule::Silhouette
           : base == "contour"  ? AdaptiveRule::Contour
                                : AdaptiveRule::Screen;
  // Each rule has its own knob: the other one's is refused rather than silently ignored.
  if (s.by_outline() && pixels_per_segment_option && pixels_per_segment_option->count() > 0)
    throw InputError(kCommandLine, "--pixels-per-segment",
                     "is the screen rule's; --adaptive " + base + " takes --outline-tolerance");
  if (s.rule == AdaptiveRule::Screen && outline_tolerance_option && outline_tolerance_option->count() > 0)
    throw InputError(kCommandLine, "--outline-tolerance", "needs --adaptive silhouette or contour");
  // key=value items; a value's own commas belong to it until the next "key=".
  std::vector<std::pair<std::string, std::string>> items;
  std::size_t start = 0;
  while (start < camera.size()) {
    const std::size_t eq = camera.find('=', start);
    if (eq == std::string::npos) throw InputError(kCommandLine, "--camera", "'" + camera + "' is not key=value,...");
    const std::string key = camera.substr(start, eq - start);
    // The next ",word=" starts the next item, a known key or not (an unknown one is named below,
    // not read as a coordinate).
    std::size_t next = camera.size();
    for (std::size_t comma = camera.find(',', eq); comma != std::string::npos; comma = camera.find(',', comma + 1)) {
      std::size_t end = comma + 1;
      while (end < camera.size() && (std::isalpha(static_cast<unsigned char>(camera[end])) || camera[end] == '_')) ++end;
      if (end > comma + 1 && end < camera.size() && camera[end] == '=') {
        next = comma;
        break;
      }
    }
    items.emplace_back(key, camera.substr(eq + 1, next - eq - 1));
    start = next == camera.size() ? next : next + 1;
  }
  bool has_eye = false;
  std::vector<std::string> seen;
  for (const auto& [key, value] : items) {
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      throw InputError(kCommandLine, "--camera", "'" + key + "' is given twice in '" + camera + "'");
    seen.push_back(key);
    if (key == "eye") {
      s.camera.eye = parse_point(key, value);
      has_eye = true;
    } else if (key == "target") {
      s.camera.target = parse_point(key, value);
    } else if (key == "fov") {
      s.camera.fov_deg = parse_numbers("--camera", value).at(0);
    } else {
      throw InputError(kCommandLine, "--camera", "unknown key '" + key + "' (eye, target, fov)");
    }
  }
  if (!has_eye) throw InputError(kCommandLine, "--camera", "needs eye=x,y,z");
  const glm::ivec2 size = parse_image_size(viewport, "--viewport");
  s.camera.width = size.x;
  s.camera.height = size.y;
  s.pixels_per_segment = pixels_per_segment;
  s.outline_tolerance = outline_tolerance;
}

TessSettings PatternOptions::settings(const char* command) const {
  TessSettings s;
  s.L = factor;
  s.displace = displace.settings();
  check_tess_factor(command, factor);
  const bool fixed = !outer.empty() || !inner.empty();
  if (fixed && adaptive.given())  // name the option given: --inner alone is one too
    throw InputError(kCommandLine, outer.empty() ? "--inner" : "--outer", "cannot be combined with --adaptive");
  if (!inner.empty() && outer.empty()) throw InputError(kCommandLine, "--inner", "needs --outer");
  // -L sets every factor of the uniform pattern and of --partitioning alone; beside --outer or
  // --adaptive every patch takes its factors from them, and the L given would be ignored.
  if ((factor_given || (factor_option && factor_option->count() > 0)) && (fixed || adaptive.given()))
    throw InputError(kCommandLine, "-L",
                     std::string("has no effect with ") + (fixed ? "--outer" : "--adaptive") +
                         " (every patch takes its factors from it)");
  adaptive.check_given_alone();
  if (partitioning.empty() && !fixed && !adaptive.given()) {  // the uniform pattern
    if (silhouette_given()) s.silhouette = parse_silhouette_option(silhouette);
    if (s.silhouette.eye_from_camera)
      throw InputError(kCommandLine, "--silhouette", "'camera' takes the eye of --adaptive ... --camera, which is not given");
    return s;
  }

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
  if (silhouette_given()) {
    s.silhouette = parse_silhouette_option(silhouette);
    if (s.silhouette.eye_from_camera && (!adaptive.given() || s.rule == AdaptiveRule::Nyquist))
      throw InputError(kCommandLine, "--silhouette", "'camera' takes the eye of --adaptive ... --camera, which is not given");
  }
  validate(s, kCommandLine);
  // Fixed factors are the same for every patch: if they cull one patch they cull all, and the
  // run would have nothing to tessellate. Refused by every command alike (docs/patterns.md).
  if (fixed && d3d11_tri_factors(s.outer, s.inner, s.partitioning).culled)
    throw InputError(kCommandLine, "--outer",
                     "'" + outer + "': every patch is culled (an outer factor <= 0 or NaN): nothing to tessellate");
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
  o.silhouette_option = add_silhouette_option(cmd, o.silhouette, true);
}

std::optional<TessSettings> UnitPatternOptions::settings(const char* command, int L, bool L_given) const {
  if (!given()) {
    adaptive.check_given_alone();
    if (silhouette_given() && parse_silhouette_option(silhouette).eye_from_camera)
      throw InputError(kCommandLine, "--silhouette", "'camera' takes the eye of --adaptive ... --camera, which is not given");
    return std::nullopt;
  }
  PatternOptions p;
  p.factor = L;
  p.factor_given = L_given;
  p.partitioning = partitioning;
  p.outer = outer;
  p.inner = inner;
  p.adaptive = adaptive;
  p.silhouette = silhouette;
  p.silhouette_option = silhouette_option;
  p.displace = displace;
  return p.settings(command);
}

std::shared_ptr<const MeshSilhouette> UnitPatternOptions::silhouette_for(std::optional<TessSettings>& pattern, int L,
                                                                        const Mesh& mesh) const {
  TessSettings uniform;
  TessSettings* s = pattern ? &*pattern : &uniform;
  if (!pattern) {
    if (!silhouette_given()) return nullptr;
    uniform.L = L;
    uniform.silhouette = parse_silhouette_option(silhouette);
  }
  bind_silhouette(*s, mesh);
  warn_nyquist_shortfall(*s, mesh);
  if (!s->silhouette.blends() || !s->silhouette_field) return nullptr;
  const MeshSilhouette& field = *s->silhouette_field;
  if (field.counts().feature_ends > 0) {
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const PatchSilhouette patch = field.patch(mesh, t);
      for (int i = 0; i < 3; ++i)
        for (const PatchSilhouette::End& end : patch.end[static_cast<std::size_t>(i)])
          if (end.feature)
            throw InputError(mesh.source.empty() ? std::string("mesh") : mesh.source,
                             "vertex " + std::to_string(mesh.triangles[t][i]),
                             "a feature end of the silhouette (its scalar tags give its faces different normals): the "
                             "unit's CPG blends smooth ends only; tessellate and render compute feature ends "
                             "(docs/mathematics.md §11)");
    }
  }
  return s->silhouette_field;
}

glm::ivec2 parse_image_size(std::string_view text, std::string_view option) {
  const std::string name(option);
  const std::string expected = "expected WxH with W and H in 1.." + std::to_string(render::kMaxImageSide) +
                               ", got '" + std::string(text) + "'";
  const std::size_t sep = text.find_first_of("xX");
  if (sep == std::string_view::npos) throw InputError("command line", name, expected);
  auto number = [&](std::string_view digits) {
    if (digits.empty() || digits.size() > 5) throw InputError("command line", name, expected);
    int value = 0;
    for (char c : digits) {
      if (c < '0' || c > '9') throw InputError("command line", name, expected);
      value = value * 10 + (c - '0');
    }
    if (value < 1 || value > render::kMaxImageSide) throw InputError("command line", name, expected);
    return value;
  };
  return {number(text.substr(0, sep)), number(text.substr(sep + 1))};
}

}  // namespace tessim::app
