#include "app/report_html.hpp"

#include <cctype>
#include <string>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "app/report_page.hpp"
#include "model/base/error.hpp"
#include "render/raster.hpp"
#include "sim/report/report.hpp"
#include "sim/version.hpp"

// The page's skeleton, style and script, and the byte-level helpers of app/report_html.hpp; the
// sections come from app/report_page.hpp.
namespace tessim::app {

namespace {

using namespace report_page;

// No italic text: Debian's oblique sans face is in fonts-dejavu-extra, which the project does
// not install (scripts/check_packages.py reports a font read from it).
constexpr const char* kStyle = R"css(
:root{--fg:#1b1f24;--muted:#59626e;--line:#d8dde3;--bg:#f4f6f8;--accent:#1f5fa8}
*{box-sizing:border-box}
body{margin:0;font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;color:var(--fg);background:var(--bg)}
header{background:#14324f;color:#fff;padding:16px 28px}
header h1{margin:0;font-size:23px}
header p{margin:3px 0 0;color:#c9d6e3}
nav{position:sticky;top:0;z-index:1;background:#fff;border-bottom:1px solid var(--line);padding:6px 28px}
nav a{margin-right:16px;color:var(--accent);text-decoration:none;font-size:14px}
main{max-width:1140px;margin:0 auto;padding:6px 20px 20px}
section{background:#fff;border:1px solid var(--line);border-radius:6px;padding:12px 20px 16px;margin:14px 0}
h2{margin:0 0 8px;font-size:19px}
h3{margin:12px 0 4px;font-size:15px}
p{margin:6px 0}
table{border-collapse:collapse;font-size:14px;margin:6px 0}
th,td{padding:3px 10px;border-bottom:1px solid #eceff2;text-align:left;vertical-align:top}
th{font-weight:600}
.n{text-align:right;font-variant-numeric:tabular-nums}
tr.largest th,tr.largest td{background:#eef4fb}
.muted{color:var(--muted)}
.tiles{display:flex;flex-wrap:wrap;gap:10px;margin:4px 0 10px}
.tile{flex:1 1 150px;border:1px solid var(--line);border-radius:6px;padding:6px 14px}
.tile b{display:block;font-size:22px;font-variant-numeric:tabular-nums}
.tile span{color:var(--muted);font-size:13px}
.callout{border-left:4px solid #c2410c;background:#fff5eb;padding:8px 12px}
.bar{display:flex;position:relative;height:22px;border-radius:3px;overflow:hidden;background:#eceff2}
.bar span{display:block;height:100%;font-size:12px;line-height:22px;text-align:center;overflow:hidden;white-space:nowrap;color:#111}
.meter{width:320px}
.meter .label{position:absolute;left:8px;top:0;font-weight:normal;font-size:12px;line-height:22px}
.legend{display:flex;flex-wrap:wrap;gap:2px 14px;font-size:13px;color:var(--muted);margin:4px 0 8px}
.sw{display:inline-block;width:12px;height:12px;border-radius:2px;vertical-align:-1px;margin-right:4px}
svg{display:block;width:100%;height:auto;margin:6px 0}
svg text{font-size:12px;fill:#333}
svg .axis-title{font-size:13px;fill:#555}
svg .grid{stroke:#ffffff;stroke-opacity:.55;stroke-width:1}
#analytic-chart .grid{stroke:#e3e7ec;stroke-opacity:1}
svg .axis{stroke:#555}
svg .frame{fill:none;stroke:#888}
svg .line{fill:none;stroke-width:2.2}
svg .halo{fill:none;stroke:#fff;stroke-width:4.5;stroke-opacity:.85}
svg .bucket{fill:#000;fill-opacity:0}
svg .bucket:hover,svg .bucket.hot{fill-opacity:.14}
.readout{min-height:1.5em;font-size:13px}
figure{margin:10px 0}
figure img{max-width:100%;height:auto;border:1px solid var(--line)}
figcaption{color:var(--muted);font-size:13px}
code{font-size:13px;background:#f0f2f5;padding:0 3px;border-radius:3px}
footer{color:var(--muted);font-size:13px;text-align:center;padding:4px 0 24px}
)css";

// Progressive enhancement only: the page is complete without it. It repeats a hovered bucket's
// tooltip under the chart and marks the page as scripted (#report-scripted) for the browser test.
constexpr const char* kScript = R"js(
(function () {
  var out = document.getElementById('timeline-readout');
  var cells = document.querySelectorAll('#timeline-chart .bucket');
  for (var i = 0; i < cells.length; i++) {
    cells[i].addEventListener('mouseenter', function () {
      this.classList.add('hot');
      if (out) out.textContent = this.querySelector('title').textContent;
    });
    cells[i].addEventListener('mouseleave', function () { this.classList.remove('hot'); });
  }
  var mark = document.createElement('span');
  mark.id = 'report-scripted';
  mark.hidden = true;
  document.body.appendChild(mark);
})();
)js";

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string href_escape(std::string_view path) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16 |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8 |
                            static_cast<unsigned char>(bytes[i + 2]);
    out += alphabet[v >> 18];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += alphabet[v & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    out += alphabet[v >> 18];
    out += alphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

PngCheck png_size(std::string_view b) {
  static constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);
  PngCheck r;
  if (b.substr(0, 8) != kSignature) {
    r.error = "not a PNG file (no PNG signature)";
    return r;
  }
  auto u32 = [&](std::size_t at) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8 |
           static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3]));
  };
  // Chunks: length, type, data, CRC. The first is IHDR; the last IEND.
  std::size_t at = 8;
  bool first = true;
  while (true) {
    if (b.size() - at < 12) {
      r.error = "truncated PNG (no IEND chunk)";
      return r;
    }
    const std::uint32_t length = u32(at);
    const std::string_view type = b.substr(at + 4, 4);
    if (length > b.size() - at - 12) {
      r.error = "truncated PNG (chunk " + std::string(type) + " runs past the end)";
      return r;
    }
    if (first) {
      if (type != "IHDR" || length != 13) {
        r.error = "malformed PNG (no IHDR chunk first)";
        return r;
      }
      r.width = u32(at + 8);
      r.height = u32(at + 12);
      if (r.width == 0 || r.height == 0) {
        r.error = "malformed PNG (zero width or height)";
        return r;
      }
      // The page states the size it embeds: a header claiming more than any picture tessim
      // makes is refused rather than handed to the browser.
      if (r.width > static_cast<std::uint32_t>(render::kMaxImageSide) ||
          r.height > static_cast<std::uint32_t>(render::kMaxImageSide)) {
        r.error = "PNG of " + std::to_string(r.width) + "x" + std::to_string(r.height) + " pixels: larger than " +
                  std::to_string(render::kMaxImageSide) + " on a side";
        return r;
      }
      first = false;
    }
    // Every chunk's CRC-32 (over its type and data): a damaged file is refused, not embedded.
    const auto* bytes = reinterpret_cast<const Bytef*>(b.data() + at + 4);
    if (crc32(0L, bytes, static_cast<uInt>(length + 4)) != u32(at + 8 + length)) {
      r.error = "damaged PNG (chunk " + std::string(type) + " fails its CRC check)";
      return r;
    }
    at += 12 + length;
    if (type == "IEND") return r;
  }
}

std::string report_html(const json& stats, const ReportInput& in) {
  const Stats s(stats, in.stats_name);
  if (!stats.is_object()) s.fail("statistics", "not a JSON object (not the output of `tessim sim --stats`)");
  const json* version = s.find("schema_version");
  if (!version)
    s.fail("schema_version", "missing: not the statistics of `tessim sim --stats` (or written before schema 2)");
  if (!version->is_number_integer()) s.fail("schema_version", "not an integer");
  const auto schema = version->get<std::int64_t>();
  if (schema < kReportMinSchema || schema > sim::kStatsSchemaVersion)
    s.fail("schema_version", std::to_string(schema) + " is not supported (this tessim reads " +
                                 std::to_string(kReportMinSchema) + ".." + std::to_string(sim::kStatsSchemaVersion) + ")");

  const std::string mesh = s.text("mesh");
  std::string mesh_name = mesh.substr(mesh.find_last_of('/') == std::string::npos ? 0 : mesh.find_last_of('/') + 1);
  // Every section is built (and so checked) before anything is assembled.
  const std::string summary = summary_section(s);
  const std::string bottleneck = bottleneck_section(s);
  const std::string timeline = timeline_section(s, static_cast<int>(schema));
  const std::string classes = classes_section(s);
  const std::string analytic = analytic_section(s);
  const std::string ints = int_section(s);
  const std::string config = config_section(s);
  const std::string tool_version = s.text("tool.version");
  const json& cfg = s.object("config");
  auto cfg_text = [&](const char* k) { return cfg.contains(k) ? html_escape(value_text(cfg[k])) : std::string("?"); };
  const bool per_patch = s.find("workload.factors") && s.text("workload.factors") == "per patch";
  const std::string factors = per_patch ? "L per patch" : "L = " + cfg_text("tess_factor");

  std::string h;
  h.reserve(64 * 1024);
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  // Nothing may be fetched: no network, no other file; inline style and script, data: images.
  h += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
       "style-src 'unsafe-inline'; script-src 'unsafe-inline'; base-uri 'none'; form-action 'none'\">\n";
  h += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  h += "<meta name=\"generator\" content=\"tessim report " + html_escape(tessim::tool_version()) + "\">\n";
  h += "<title>tessim report: " + html_escape(mesh_name) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  h += "<header><h1>tessim run report: " + html_escape(mesh_name) + "</h1><p>cycle model, N = " +
       cfg_text("int_blocks") + " INT blocks, " + factors + ", K = " + cfg_text("gpe_cycles") +
       ", " + cfg_text("normals") + " normals, CPG " + cfg_text("cpg_mapping") + " &#183; " +
       grouped(s.count("cycles")) + " cycles, " + format("%.3f", s.number("cycles_per_vertex")) +
       " cycles/vertex</p></header>\n";
  h += "<nav><a href=\"#summary\">Summary</a><a href=\"#bottleneck\">Bottleneck</a><a href=\"#timeline\">Timeline</a>"
       "<a href=\"#classes\">Cycle classes</a><a href=\"#analytic\">Analytical bound</a><a href=\"#int\">INT "
       "blocks</a><a href=\"#configuration\">Configuration</a><a href=\"#images\">Images</a><a "
       "href=\"#files\">Files</a></nav>\n<main>\n";
  h += summary + bottleneck + timeline + classes + analytic + ints + config + images_section(in) + files_section(in);
  h += "</main>\n<footer id=\"footer\">statistics: <code>" + html_escape(in.stats_name) + "</code>, schema_version " +
       std::to_string(schema) + ", written by tessim " + html_escape(tool_version) + " &#183; report: tessim " +
       html_escape(tessim::tool_version()) + "</footer>\n";
  h += std::string("<script>") + kScript + "</script>\n</body>\n</html>\n";
  return h;
}

}  // namespace tessim::app
