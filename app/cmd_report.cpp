// tessim report STATS.json [--trace FILE] [--wave FILE] [--image PNG ...] -o REPORT.html: one
// self-contained HTML page describing a cycle-model run (app/report_html.*, docs/report.md).
// Every input is read and checked, and the whole page built in memory, before the output is
// opened: bad input leaves no file behind.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/report_html.hpp"
#include "model/base/error.hpp"
#include "model/base/input_file.hpp"
#include "model/base/output_file.hpp"
#include "sim/base/json_input.hpp"

namespace tessim::app {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ReportArgs {
  std::string stats;
  std::string output;
  std::string trace;
  std::string wave;
  std::vector<std::string> images;
};

// A file the page links to: it must exist; the link is relative to the page's directory, so
// the page and its files can move together.
ReportLink link_to(const std::string& path, const char* option, std::string what, const fs::path& page_dir) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(path, option, "not found");
  if (!fs::is_regular_file(st)) throw InputError(path, option, "not a regular file");
  const fs::path target = fs::weakly_canonical(fs::absolute(path));
  fs::path rel = target.lexically_relative(page_dir);
  if (rel.empty()) rel = target;
  return ReportLink{std::move(what), path, href_escape(rel.generic_string()), fs::file_size(path, ec)};
}

void run_report(const ReportArgs& a) {
  check_output_paths({{"-o", a.output}});
  std::vector<std::pair<const char*, std::string>> inputs{{"STATS", a.stats}};
  for (const std::string& img : a.images) inputs.emplace_back("--image", img);
  if (!a.trace.empty()) inputs.emplace_back("--trace", a.trace);
  if (!a.wave.empty()) inputs.emplace_back("--wave", a.wave);
  std::error_code ec;
  for (const auto& [option, path] : inputs)
    if (fs::exists(a.output, ec) && fs::equivalent(a.output, path, ec))
      throw InputError(a.output, "-o", std::string("is the input ") + option + " " + path + ": it would be overwritten");

  const std::string text = read_whole_file(a.stats, kDataFileLimit, "file");
  const json stats = sim::parse_json_text(text, a.stats);

  ReportInput in;
  in.stats_name = a.stats;
  for (const std::string& path : a.images) {
    ReportImage img{path, read_whole_file(path, kImageFileLimit, "--image")};
    const PngCheck png = png_size(img.bytes);
    if (!png.error.empty()) throw InputError(path, "--image", png.error);
    img.width = png.width;
    img.height = png.height;
    in.images.push_back(std::move(img));
  }
  // A page written to standard output, a device or a pipe links relative to the working directory.
  const bool to_file = output_kind(a.output) == OutputKind::File;
  const fs::path page_dir =
      to_file ? fs::weakly_canonical(fs::absolute(a.output)).parent_path() : fs::weakly_canonical(fs::current_path());
  if (!a.trace.empty()) in.links.push_back(link_to(a.trace, "--trace", "Perfetto trace", page_dir));
  if (!a.wave.empty()) {
    in.links.push_back(link_to(a.wave, "--wave", "waveform", page_dir));
    // tessim cosim --wave writes its gtkwave layout beside the waveform.
    const fs::path layout = fs::path(a.wave).replace_extension(".gtkw");
    if (fs::is_regular_file(layout, ec)) in.links.push_back(link_to(layout.string(), "--wave", "gtkwave layout", page_dir));
  }

  const std::string html = report_html(stats, in);
  AtomicOutput out(a.output);
  out.stream() << html;
  out.commit();
  // The page on standard output: the summary goes to stderr.
  std::FILE* summary = out.kind() == OutputKind::Stdout ? stderr : stdout;
  std::fprintf(summary, "wrote %s: %zu bytes, %zu image%s, %zu linked file%s\n", output_name(a.output).c_str(),
               html.size(), in.images.size(), in.images.size() == 1 ? "" : "s", in.links.size(),
               in.links.size() == 1 ? "" : "s");
}

}  // namespace

void register_report(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* sub = app.add_subcommand(
      "report", "One self-contained HTML page of a cycle-model run from its statistics (tessim sim --stats): "
                "configuration, summary, timeline, bottleneck, analytical bound, INT utilisation, images, links");
  sub->add_option("stats", args->stats, "statistics JSON of the run (tessim sim --stats)")->required();
  sub->add_option("-o,--output", args->output, "the HTML page to write")->required();
  sub->add_option("--image", args->images, "a PNG to embed in the page (tessim render); repeatable");
  sub->add_option("--trace", args->trace, "the run's Perfetto trace (tessim sim --trace), linked from the page");
  sub->add_option("--wave", args->wave, "a waveform (tessim cosim --wave), linked from the page with its .gtkw layout");
  sub->callback([args] { run_report(*args); });
}

}  // namespace tessim::app
