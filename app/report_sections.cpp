// The sections of the report page that are tables and bars (app/report_page.hpp): summary,
// where the cycles went, bottleneck, INT blocks, configuration, images and files.
#include <algorithm>
#include <numeric>

#include "app/report_page.hpp"
#include "sim/config/params.hpp"

namespace tessim::app::report_page {

std::string summary_section(const Stats& s) {
  const std::uint64_t cycles = s.count("cycles"), vertices = s.count("vertices_out");
  std::string h = section_open("summary", "Summary");
  h += "<div class=\"tiles\">";
  h += tile(grouped(cycles), "cycles", s.unit("cycles"));
  h += tile(grouped(vertices), "vertices out", s.unit("vertices_out"));
  h += tile(format("%.3f", s.number("cycles_per_vertex")), "cycles per vertex", s.unit("cycles_per_vertex"));
  h += tile(format("%.4f", s.number("throughput")), "throughput", s.unit("throughput"));
  h += tile(pct(s.number("int.utilisation")), "INT utilisation", s.unit("int.utilisation"));
  h += "</div>\n<table class=\"kv\">\n";
  auto row = [&](const std::string& label, const std::string& value, const std::string& unit_key) {
    h += "<tr><th>" + html_escape(label) + "</th><td class=\"n\">" + value + "</td><td class=\"muted\">" +
         html_escape(s.unit(unit_key)) + "</td></tr>\n";
  };
  h += "<tr><th>mesh</th><td colspan=\"2\"><code>" + html_escape(s.text("mesh")) + "</code></td></tr>\n";
  row("triangles", grouped(s.count("triangles")), "triangles");
  // The unit's other run counters, as the registry has them (sim/base/counter_registry.hpp).
  for (const sim::CounterRow& r : sim::kCounterRegistry) {
    const std::string key = r.key;
    if (r.block != sim::CounterBlock::Run || key == "cycles" || key == "vertices_out" || !s.find(key)) continue;
    row(key + " (unit counter)", grouped(s.count(key)), key);
  }
  row("CPG cycles per triangle", grouped(s.count("cpg_cycles_per_triangle")), "cpg_cycles_per_triangle");
  row("INT operations per vertex", format("%.3f", s.number("int.ops_per_vertex")), "int.ops_per_vertex");
  if (s.find("workload")) {
    h += "<tr><th>factors</th><td colspan=\"2\">" + html_escape(s.text("workload.factors")) + "</td></tr>\n";
    row("vertices per patch (min / mean / max)",
        grouped(s.count("workload.vertices_per_patch.min")) + " / " +
            format("%.1f", s.number("workload.vertices_per_patch.mean")) + " / " +
            grouped(s.count("workload.vertices_per_patch.max")),
        "workload.vertices_per_patch.mean");
  }
  if (s.find("warnings")) {
    row("degenerate patches", grouped(s.count("warnings.degenerate_patches")), "warnings.degenerate_patches");
    row("zero normals", grouped(s.count("warnings.zero_normals")), "warnings.zero_normals");
  }
  if (s.find("wall_seconds")) row("simulation time", format("%.3f", s.number("wall_seconds")), "wall_seconds");
  h += "</table>\n";
  if (const json* e = s.find("errors"); e && e->is_object()) {
    h += "<h3>Errors against the float reference</h3>\n<table>\n<tr><th></th><th class=\"n\">value</th><th>unit</th></tr>\n";
    for (const std::string prefix : {"errors.", "errors.arithmetic."})
      for (const char* k : {"position_max", "position_rms", "normal_angle_max", "normal_angle_rms"})
        if (s.find(prefix + k))
          h += "<tr><th>" + prefix.substr(7) + k + "</th><td class=\"n\">" + sig(s.number(prefix + k)) +
               "</td><td class=\"muted\">" + html_escape(s.unit(prefix + k)) + "</td></tr>\n";
    if (s.find("errors.arithmetic.beyond_bound"))
      h += "<tr><th>vertices beyond the arithmetic bound</th><td class=\"n\">" +
           grouped(s.count("errors.arithmetic.beyond_bound")) + "</td><td></td></tr>\n";
    h += "</table>\n";
  }
  return h + "</section>\n";
}

std::string classes_section(const Stats& s) {
  const std::uint64_t cycles = s.count("cycles");
  std::string h = section_open("classes", "Where the cycles went");
  h += "<p class=\"muted\">Every cycle of each block in exactly one class (docs/microarchitecture.md §10), as a "
       "share of the run's " + grouped(cycles) + " cycles.</p>\n";
  auto block = [&](const char* title, const std::string& key, const auto& styles) {
    const std::vector<double> sh = shares_of(class_counts(s, key, styles, cycles, true));
    h += std::string("<h3>") + title + "</h3>\n" + stacked_bar(styles, sh, title) + legend(styles, sh) + "\n";
  };
  block("TE", "te", kTeStyles);
  block("CPG", "cpg", kCpgStyles);
  block("GPE", "gpe", kGpeStyles);
  return h + "</section>\n";
}

std::string bottleneck_section(const Stats& s) {
  const std::uint64_t cycles = s.count("cycles");
  std::string h = section_open("bottleneck", "Bottleneck");
  h += "<p class=\"callout\" id=\"bottleneck-line\">" + html_escape(s.text("bottleneck")) + "</p>\n";
  const std::uint64_t waited = s.count("limit.gpe_waited");
  h += "<p>The geometry engine waited for a vertex in " + grouped(waited) + " cycles (" + pct(share(waited, cycles)) +
       " of the run) after its first one. A <b>late vertex interval</b> runs from one accepted vertex to the "
       "next when the GPE waited in it; the TE's classes over those intervals say what held the vertex up, and "
       "the largest stall class names the limit (GPE when it waited no more than the TE was blocked by it; "
       "docs/statistics.md).</p>\n";
  const std::vector<std::uint64_t> late = class_counts(s, "limit.te_late", kTeStyles, cycles, false);
  const std::uint64_t late_total = std::accumulate(late.begin(), late.end(), std::uint64_t{0});
  if (late_total > 0) {
    const std::vector<double> sh = shares_of(late);
    h += "<h3>TE in the late vertex intervals (" + grouped(late_total) + " cycles)</h3>\n" +
         stacked_bar(kTeStyles, sh, "TE classes in the late vertex intervals") + legend(kTeStyles, sh) + "\n";
  } else {
    h += "<p class=\"muted\">No late vertex intervals: the unit always had a vertex ready when the GPE was.</p>\n";
  }
  h += "<table>\n<tr><th>stall</th><th class=\"n\">cycles</th><th class=\"n\">share</th></tr>\n";
  for (const char* k : {"te_starved_by_cpg", "te_blocked_by_gpe", "gpe_starved_by_te"}) {
    const std::uint64_t n = s.count(std::string("stalls.") + k);
    h += std::string("<tr><th>") + k + "</th><td class=\"n\">" + grouped(n) + "</td><td class=\"n\">" +
         pct(share(n, cycles)) + "</td></tr>\n";
  }
  return h + "</table>\n</section>\n";
}

std::string int_section(const Stats& s) {
  const json& blocks = s.array("int.blocks");
  if (blocks.empty()) s.fail("int.blocks", "no blocks");
  std::string h = section_open("int", "INT blocks");
  h += "<p>Utilisation " + pct(s.number("int.utilisation")) + " over " + std::to_string(blocks.size()) +
       " blocks, " + format("%.3f", s.number("int.ops_per_vertex")) +
       " operations per vertex. The scheduler gives the i-th ready operation of a cycle to block i, so the "
       "later blocks fill up last.</p>\n<table class=\"int\">\n<tr><th>block</th><th class=\"n\">busy</th><th "
       "class=\"n\">idle</th><th>utilisation</th></tr>\n";
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::string p = "int.blocks[" + std::to_string(i) + "]";
    if (!blocks[i].is_object()) s.fail(p, "not an object");
    auto field = [&](const char* k) -> const json& {
      if (!blocks[i].contains(k)) s.fail(p + "." + k, "missing");
      return blocks[i][k];
    };
    const std::uint64_t busy = s.count_of(field("busy"), p + ".busy");
    const std::uint64_t idle = s.count_of(field("idle"), p + ".idle");
    const double u = std::clamp(s.number_of(field("utilisation"), p + ".utilisation"), 0.0, 1.0);
    h += "<tr><th>INT " + std::to_string(i) + "</th><td class=\"n\">" + grouped(busy) + "</td><td class=\"n\">" +
         grouped(idle) + "</td><td><div class=\"bar meter\" role=\"img\" aria-label=\"INT " + std::to_string(i) +
         " " + pct(u) + "\"><span style=\"width:" + format("%.3f", 100 * u) + "%;background:#009E73\"></span><b class=\"label\">" +
         pct(u) + "</b></div></td></tr>\n";
  }
  return h + "</table>\n</section>\n";
}

std::string config_section(const Stats& s) {
  const json& cfg = s.object("config");
  std::string h = section_open("configuration", "Configuration");
  h += "<table>\n<tr><th>key</th><th class=\"n\">value</th><th>unit</th><th>kind</th><th>meaning</th></tr>\n";
  auto row = [&](const std::string& key, const json& v, const sim::ParamSpec* p) {
    h += "<tr><th><code>" + html_escape(key) + "</code></th><td class=\"n\">" + html_escape(value_text(v)) +
         "</td><td class=\"muted\">" + (p ? p->unit : "") + "</td><td class=\"muted\">" +
         (p ? sim::to_string(p->kind) : "") + "</td><td class=\"muted\">" +
         (p ? html_escape(p->description) : "not a parameter of this tessim") + "</td></tr>\n";
  };
  for (const sim::ParamSpec& p : sim::unit_params())
    if (const auto it = cfg.find(p.key); it != cfg.end()) row(p.key, *it, &p);
  for (const auto& [k, v] : cfg.items())
    if (!sim::find_param(k)) row(k, v, nullptr);
  return h + "</table>\n</section>\n";
}

std::string images_section(const ReportInput& in) {
  std::string h = section_open("images", "Images");
  if (in.images.empty()) return h + "<p class=\"muted\">None given (<code>--image</code>).</p>\n</section>\n";
  for (const ReportImage& img : in.images) {
    h += "<figure><img src=\"data:image/png;base64," + base64(img.bytes) + "\" width=\"" + std::to_string(img.width) +
         "\" height=\"" + std::to_string(img.height) + "\" alt=\"" + html_escape(img.name) + "\"><figcaption><code>" +
         html_escape(img.name) + "</code>, " + std::to_string(img.width) + "×" + std::to_string(img.height) +
         "</figcaption></figure>\n";
  }
  return h + "</section>\n";
}

std::string files_section(const ReportInput& in) {
  std::string h = section_open("files", "Files");
  if (in.links.empty())
    return h + "<p class=\"muted\">None given (<code>--trace</code>, <code>--wave</code>).</p>\n</section>\n";
  h += "<ul>\n";
  for (const ReportLink& l : in.links)
    h += "<li>" + html_escape(l.what) + ": <a href=\"" + l.href + "\">" + html_escape(l.name) + "</a> <span class=\"muted\">(" +
         grouped(static_cast<std::uint64_t>(l.bytes)) + " bytes)</span></li>\n";
  h += "</ul>\n<p class=\"muted\">Open a trace in the Perfetto UI (ui.perfetto.dev, &#8220;Open trace file&#8221;; it "
       "stays on this machine) and a waveform with <code>gtkwave FILE LAYOUT.gtkw</code> "
       "(docs/verification.md).</p>\n";
  return h + "</section>\n";
}

}  // namespace tessim::app::report_page
