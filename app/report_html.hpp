// The page of `tessim report` (docs/report.md): one self-contained HTML file built from the
// statistics of one cycle-model run. Nothing on it is fetched: styles, the script and the charts
// (SVG) are inline, images are data: URIs, and a Content-Security-Policy forbids any request.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace tessim::app {

// Statistics schema versions the report reads: 2 (before the timeline) and 3.
inline constexpr int kReportMinSchema = 2;

struct ReportImage {
  std::string name;   // as given on the command line (caption)
  std::string bytes;  // the PNG file, checked by png_size()
  std::uint32_t width = 0, height = 0;
};

struct ReportLink {
  std::string what;  // "Perfetto trace", "waveform", ...
  std::string name;  // as given on the command line
  std::string href;  // relative to the page, percent-encoded
  std::uintmax_t bytes = 0;
};

struct ReportInput {
  std::string stats_name;  // for messages
  std::vector<ReportImage> images;
  std::vector<ReportLink> links;
};

// The page. Every figure is read through checks: a statistics file that lacks one, or holds the
// wrong type, is an InputError(stats_name, "PATH.TO.KEY", reason); so is a schema_version
// outside kReportMinSchema..kStatsSchemaVersion.
std::string report_html(const nlohmann::json& stats, const ReportInput& in);

// Width and height from a PNG's header, after walking its chunks to IEND; a reason when the
// bytes are not a whole PNG file.
struct PngCheck {
  std::uint32_t width = 0, height = 0;
  std::string error;  // empty: a PNG
};
PngCheck png_size(std::string_view bytes);

std::string base64(std::string_view bytes);
std::string html_escape(std::string_view text);
// A relative path as an href: every byte but unreserved characters and '/' percent-encoded.
std::string href_escape(std::string_view path);

}  // namespace tessim::app
