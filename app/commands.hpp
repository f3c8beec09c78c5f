// Registration of the tessim subcommands. Each lives in its own cmd_*.cpp; a subcommand
// reports bad input by throwing tessim::InputError, which main() turns into a message and a
// non-zero exit status.
#pragma once

#include <charconv>
#include <cstdio>
#include <cmath>
#include <limits>
#include <string>
#include <memory>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "model/base/error.hpp"

#include "model/factors.hpp"
#include "model/mesh.hpp"
#include "model/normal_mode.hpp"
#include "model/silhouette.hpp"
#include "sim/config/config.hpp"

namespace tessim::app {

// Checks of options shared by the reference commands (tessellate, render): InputError naming
// the command and the option. The cycle-model commands check theirs through sim/config/params.hpp.
void check_tess_factor(const char* command, int factor);
NormalMode parse_normals_option(const char* command, const std::string& text);

// A tessellation factor as the tessellator receives it: a float. NaN and infinities are
// accepted (NaN and values <= 0 cull the patch, large values clamp; a number beyond the float
// range becomes an infinity, as D3D11 would see it), so only non-numbers are errors.
float parse_factor(const char* command, const char* option, const std::string& text);
// "e0,e1,e2": the three outer factors (edges u = 0, v = 0, w = 0).
std::array<float, 3> parse_outer_factors(const char* command, const std::string& text);
Partitioning parse_partitioning_option(const char* command, const std::string& text);
// An image size option, "WxH" (decimal, 1..render::kMaxImageSide each). Throws InputError
// naming the command line and `option`.
glm::ivec2 parse_image_size(std::string_view text, std::string_view option);

// The pattern options of the reference commands (tessellate, render; docs/patterns.md):
//   -L N                                  uniform pattern (the unit's own), the default
//   --partitioning P [-L N]               D3D11 pattern, every factor N
//   --outer A,B,C [--inner F] [--partitioning P]   D3D11 pattern, these factors (inner
//                                         default: the largest outer factor)
//   --adaptive screen|silhouette --camera eye=x,y,z[,target=x,y,z][,fov=deg] [--viewport WxH]
//          [--pixels-per-segment P | --outline-tolerance T] [--partitioning P]   D3D11 pattern, factors per edge
//   --silhouette eye=x,y,z[,beta=B] | camera[,beta=B]    silhouette-blended control points
struct AdaptiveOptions {
  std::string adaptive, camera, viewport = "1280x720";
  double pixels_per_segment = 16.0;  // the screen rule's
  double outline_tolerance = 0.5;    // the silhouette rule's
  double samples_per_wavelength = 4.0;  // the Nyquist rule's
  const CLI::Option* samples_per_wavelength_option = nullptr;

  // Set by add_adaptive_options: whether --viewport, --pixels-per-segment and
  // --outline-tolerance were given.
  const CLI::Option* viewport_option = nullptr;
  const CLI::Option* pixels_per_segment_option = nullptr;
  const CLI::Option* outline_tolerance_option = nullptr;

  bool given() const { return !adaptive.empty(); }
  // Without --adaptive: InputError when --camera, --viewport or --pixels-per-segment was given.
  void check_given_alone() const;
  // Makes `s` adaptive with this camera (InputError(command, option, reason) when malformed).
  void apply(TessSettings& s, const char* command) const;
};
void add_adaptive_options(CLI::App& cmd, AdaptiveOptions& options, const char* command);

// --displace sine|noise --amplitude A --frequency F (docs/mathematics.md §12).
struct DisplaceOptions {
  std::string kind;
  double amplitude = 0.0, frequency = 0.0;
  const CLI::Option* kind_option = nullptr;  // set by add_displace_options
  const CLI::Option* amplitude_option = nullptr;
  const CLI::Option* frequency_option = nullptr;
  // The displacement the options ask for (none without --displace); InputError for a bad kind, a
  // missing or bad amplitude or frequency, or either without --displace.
  DisplaceSettings settings() const;
};
// `unit`: the help of sim, where the geometry engine displaces the unit's output.
void add_displace_options(CLI::App& cmd, DisplaceOptions& options, bool unit = false);

struct PatternOptions {
  int factor = 4;
  std::string partitioning;
  std::string outer, inner;
  AdaptiveOptions adaptive;
  std::string silhouette;  // --silhouette eye=x,y,z[,beta=B] | camera[,beta=B]
  const CLI::Option* silhouette_option = nullptr;  // set by add_pattern_options
  const CLI::Option* factor_option = nullptr;      // -L, set by add_pattern_options
  bool factor_given = false;  // -L on the command line of sim, cosim or power (their -L is a parameter)

  bool silhouette_given() const { return !silhouette.empty() || (silhouette_option && silhouette_option->count() > 0); }
  DisplaceOptions displace;  // set by add_pattern_options

  // Throws InputError(command, option, reason).
  TessSettings settings(const char* command) const;
};
void add_pattern_options(CLI::App& cmd, PatternOptions& options, const char* command);
// --silhouette's text (docs/mathematics.md §11): "eye=x,y,z[,beta=B]" or "camera[,beta=B]".
// Throws InputError(command line, --silhouette, reason) for malformed text, a non-finite eye or
// beta <= 0 / not finite.
SilhouetteSettings parse_silhouette_option(const std::string& text);
// `unit`: the option of sim and cosim, whose help says what reaches the unit.
CLI::Option* add_silhouette_option(CLI::App& cmd, std::string& text, bool unit = false);
// One line: how many edges the silhouette makes flat, blended and curved (tessellate, render, info).
void print_silhouette_counts(std::FILE* out, const MeshSilhouette& silhouette);

// The pattern the unit generates in `tessim sim` and `tessim cosim`: the uniform pattern with
// the configuration's L (nothing given), or the D3D11 pattern with --partitioning, --outer /
// --inner or --adaptive, which the unit takes per patch (docs/patterns.md §8).
struct UnitPatternOptions {
  std::string partitioning, outer, inner;
  AdaptiveOptions adaptive;
  std::string silhouette;  // --silhouette, as PatternOptions
  const CLI::Option* silhouette_option = nullptr;
  DisplaceOptions displace;  // sim only: the geometry engine displaces the unit's output

  bool silhouette_given() const { return !silhouette.empty() || (silhouette_option && silhouette_option->count() > 0); }
  // The silhouette weights the host sends with the mesh's triangles (--silhouette with the blend
  // on), or nullptr. Builds them into `pattern` first when it is a D3D11 pattern (its silhouette
  // rule needs them too). InputError naming the mesh's first feature-end vertex: the unit's CPG
  // blends smooth ends only.
  std::shared_ptr<const MeshSilhouette> silhouette_for(std::optional<TessSettings>& pattern, int L,
                                                      const Mesh& mesh) const;

  bool given() const { return !partitioning.empty() || !outer.empty() || !inner.empty() || adaptive.given(); }
  // std::nullopt: the uniform pattern. Otherwise the D3D11 settings, every factor L unless
  // --outer or --adaptive says otherwise (an L given on the command line, `L_given`, is then
  // refused: it would be ignored). Checked before any mesh is read: InputError(command, option,
  // reason).
  std::optional<TessSettings> settings(const char* command, int L, bool L_given = false) const;
};
void add_unit_pattern_options(CLI::App& cmd, UnitPatternOptions& options, const char* command);

// Checks the text of a numeric option before CLI11 converts it, so that a bad value is an
// InputError(source, element, reason) quoting the text as given: "'abc' is not an integer",
// "'99999999999999' is outside 1..64" (a value the type T cannot hold; `range` is the option's
// documented range), "'nan' is not a finite number". Integers are decimal: the text is
// rewritten to its value, so "010" is 10 (CLI11 alone would read it as octal).
template <class T>
CLI::Validator number_check(std::string source, std::string element, std::string range) {
  auto check = [source, element, range](std::string& text) -> std::string {
    std::string_view digits = text;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    T value{};
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    const bool whole = end == digits.data() + digits.size() && !digits.empty();
    if constexpr (std::is_floating_point_v<T>) {
      if (ec == std::errc::result_out_of_range && whole)
        throw InputError(source, element, "'" + text + "' is outside " + range);
      if (ec != std::errc() || !whole) throw InputError(source, element, "'" + text + "' is not a number");
      if (!std::isfinite(value)) throw InputError(source, element, "'" + text + "' is not a finite number");
    } else {
      // A negative number for an unsigned type parses as a number outside the range.
      bool negative_for_unsigned = false;
      if (std::is_unsigned_v<T> && ec != std::errc() && digits.size() > 1 && digits.front() == '-') {
        long long probe = 0;
        const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), probe);
        negative_for_unsigned = r.ptr == digits.data() + digits.size() && r.ec != std::errc::invalid_argument;
      }
      if ((ec == std::errc::result_out_of_range && whole) || negative_for_unsigned)
        throw InputError(source, element, "'" + text + "' is outside " + range);
      if (ec != std::errc() || !whole) throw InputError(source, element, "'" + text + "' is not an integer");
      text = std::to_string(value);
    }
    return {};
  };
  return CLI::Validator(check, "", "number");
}

// The workload both speed commands (bench, rtlbench) measure, and its options.
struct SpeedRunArgs {
  std::string mesh = "/usr/share/assimp/models/PLY/Wuson.ply";
  int tess_factor = 8;
  std::vector<int> int_blocks{1, 2, 4};
  std::vector<int> gpe_cycles{sim::EnvironmentConfig{}.gpe_cycles};
  int repeat = 5;
};
void add_speed_run_options(CLI::App& sub, SpeedRunArgs& args, const char* int_blocks_help);

// The range of T as text, for number_check where the option documents none.
template <class T>
std::string type_range() {
  return std::to_string(std::numeric_limits<T>::lowest()) + ".." + std::to_string(std::numeric_limits<T>::max());
}

// The outputs a command writes, checked together before any work: distinct paths (each has
// its own temporary beside it), none a directory or a loop of symbolic links, and none the same
// file as one of the command's `inputs` (an output may never overwrite what the run reads).
// Throws InputError naming the option. Empty paths are options not given.
struct OutputPath {
  const char* option;
  std::string path;
};
using InputPath = OutputPath;
void check_output_paths(const std::vector<OutputPath>& outputs, const std::vector<InputPath>& inputs = {});

// The cycle model and the RTL compute plain PN triangles: a scalar-tagged mesh's tags do not
// reach them. Prints a warning saying so when `mesh` has tags that change anything.
void warn_tags_ignored(const Mesh& mesh, const char* command);
// With --cpg-tags 1: a warning with the count of vertices whose tags vanish in the fixed-point
// input (sim::tags_lost_in_fixed_point).
void warn_tags_lost(const Mesh& mesh, const sim::NumberFormat& format);
// With a Nyquist rule: a warning with the count of edges whose displacement asks for more than
// the 64 segments a factor gives (model/factors.hpp, nyquist_shortfall).
void warn_nyquist_shortfall(const TessSettings& s, const Mesh& mesh);

void register_info(CLI::App& app);
void register_tessellate(CLI::App& app);
void register_render(CLI::App& app);
void register_sim(CLI::App& app);
// tessim sim SCENE.scene.json (app/cmd_sim_scene.cpp): whether the positional names a scene, and the run.
bool is_scene_file(const std::string& path);
void run_sim_scene(const std::string& path, const std::string& stats, const sim::UnitConfig& cfg, bool quiet);
void register_bench(CLI::App& app);
void register_schema(CLI::App& app);
void register_pattern(CLI::App& app);
void register_stpn_import(CLI::App& app);
void register_compare(CLI::App& app);
void register_report(CLI::App& app);
void register_power(CLI::App& app);
#ifdef TESSIM_HAVE_COSIM
void register_cosim(CLI::App& app);
void register_rtlbench(CLI::App& app);
#endif

}  // namespace tessim::app
