#include "app/report_html.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/config/params.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/version.hpp"

namespace tessim::app {

namespace {

using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Checked reads: the page is built only from values that passed these, so a file that is JSON
// but not the expected statistics ends in an InputError naming the key instead of a JSON
// exception (an internal error) or a page with holes.

class Stats {
 public:
  Stats(const json& root, std::string file) : root_(root), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
    throw InputError(file_, path, reason);
  }
  const json* find(const std::string& path) const {
    const json* j = &root_;
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = path.find('.', start);
      const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (!j->is_object()) return nullptr;
      const auto it = j->find(key);
      if (it == j->end()) return nullptr;
      j = &*it;
      if (dot == std::string::npos) return j;
      start = dot + 1;
    }
  }
  const json& node(const std::string& path) const {
    const json* j = find(path);
    if (!j) fail(path, "missing");
    return *j;
  }
  const json& object(const std::string& path) const {
    const json& j = node(path);
    if (!j.is_object()) fail(path, "not an object");
    return j;
  }
  const json& array(const std::string& path) const {
    const json& j = node(path);
    if (!j.is_array()) fail(path, "not an array");
    return j;
  }
  std::uint64_t count_of(const json& j, const std::string& path) const {
    if (j.is_number_unsigned()) return j.get<std::uint64_t>();
    if (j.is_number_integer() && j.get<std::int64_t>() >= 0) return j.get<std::uint64_t>();
    fail(path, "not a non-negative integer");
  }
  double number_of(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "not a number");
    return j.get<double>();
  }
  std::uint64_t count(const std::string& path) const { return count_of(node(path), path); }
  double number(const std::string& path) const { return number_of(node(path), path); }
  std::string text(const std::string& path) const {
    const json& j = node(path);
    if (!j.is_string()) fail(path, "not a string");
    return j.get<std::string>();
  }
  // `n` non-negative integers.
  std::vector<std::uint64_t> counts(const std::string& path, std::size_t n) const {
    const json& a = array(path);
    if (a.size() != n) fail(path, std::to_string(a.size()) + " entries, not " + std::to_string(n));
    std::vector<std::uint64_t> v;
    v.reserve(n);
    for (std::size_t i = 0; i < n; ++i) v.push_back(count_of(a[i], path + "[" + std::to_string(i) + "]"));
    return v;
  }
  // The unit of a figure from the file's own table ("int.blocks[].busy"); "" when none.
  std::string unit(const std::string& key) const {
    const json* u = find("units");
    if (!u || !u->is_object()) return "";
    const auto it = u->find(key);
    return it != u->end() && it->is_string() ? it->get<std::string>() : "";
  }

 private:
  const json& root_;
  std::string file_;
};

// ---------------------------------------------------------------------------------------------
// Text.

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}
std::string pct(double fraction) { return format("%.1f%%", 100.0 * fraction); }
std::string sig(double v) { return format("%.4g", v); }
std::string coord(double v) { return format("%.1f", v); }
// One SVG path command with its coordinate ("H123.4"), appended in place.
void path_to(std::string& d, char command, double v) {
  d += command;
  d += coord(v);
}
double share(std::uint64_t part, std::uint64_t whole) { return whole == 0 ? 0.0 : static_cast<double>(part) / whole; }

// 1340000 as "1 340 000" (narrow no-break spaces, as the docs write large counts).
std::string grouped(std::uint64_t v) {
  std::string digits = std::to_string(v), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += "\u202f";
    out += digits[i];
  }
  return out;
}

// Axis labels: 0, 500, 25k, 1.2M.
std::string compact(double v) {
  if (v >= 1e9) return format("%.4gG", v / 1e9);
  if (v >= 1e6) return format("%.4gM", v / 1e6);
  if (v >= 1e3) return format("%.4gk", v / 1e3);
  return format("%.4g", v);
}

// A step of 1, 2 or 5 times a power of ten giving about `target` intervals up to `range`.
double nice_step(double range, int target) {
  if (range <= 0) return 1;
  const double raw = range / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm <= 1 ? 1 : norm <= 2 ? 2 : norm <= 5 ? 5 : 10) * mag;
  return std::max(step, 1.0);
}

std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return sig(v.get<double>());
  return v.dump();
}

// ---------------------------------------------------------------------------------------------
// The classes of the blocks from the counter registry (sim/base/counter_registry.hpp): in the
// order they stack (useful work at the bottom), with their colours and meanings.

struct ClassStyle {
  const char* key;
  const char* colour;
  const char* meaning;
};

template <sim::CounterBlock Block>
constexpr std::array<ClassStyle, sim::row_count(Block)> class_styles() {
  std::array<ClassStyle, sim::row_count(Block)> styles{};
  for (const sim::CounterRow& r : sim::kCounterRegistry)
    if (r.block == Block) styles[static_cast<std::size_t>(r.stack)] = {r.key, r.colour, r.meaning};
  return styles;
}
constexpr auto kTeStyles = class_styles<sim::CounterBlock::Te>();
constexpr auto kCpgStyles = class_styles<sim::CounterBlock::Cpg>();
constexpr auto kGpeStyles = class_styles<sim::CounterBlock::Gpe>();
constexpr const char* kIntLine = "#000000";
constexpr const char* kGpeLine = "#0072B2";

template <std::size_t N>
std::string legend(const std::array<ClassStyle, N>& styles, const std::vector<double>& shares) {
  std::string s = "<div class=\"legend\">";
  for (std::size_t i = 0; i < N; ++i)
    s += std::string("<span title=\"") + styles[i].meaning + "\"><span class=\"sw\" style=\"background:" +
         styles[i].colour + "\"></span>" + styles[i].key + " " + pct(shares[i]) + "</span>";
  return s + "</div>";
}

// A horizontal bar of shares (CSS: drawn without SVG or script); labels on the wide parts.
template <std::size_t N>
std::string stacked_bar(const std::array<ClassStyle, N>& styles, const std::vector<double>& shares, const std::string& label) {
  std::string s = "<div class=\"bar\" role=\"img\" aria-label=\"" + html_escape(label) + "\">";
  for (std::size_t i = 0; i < N; ++i) {
    if (shares[i] <= 0) continue;
    s += std::string("<span style=\"width:") + format("%.3f", 100 * shares[i]) + "%;background:" + styles[i].colour +
         "\" title=\"" + styles[i].key + " " + pct(shares[i]) + "\">" +
         (shares[i] >= 0.09 ? std::string(styles[i].key) + " " + pct(shares[i]) : std::string()) + "</span>";
  }
  return s + "</div>";
}

// ---------------------------------------------------------------------------------------------
// Sections.

std::string section_open(const char* id, const char* title) {
  return std::string("<section id=\"") + id + "\">\n<h2>" + title + "</h2>\n";
}

std::string tile(const std::string& value, const std::string& label, const std::string& unit) {
  return "<div class=\"tile\"><b>" + value + "</b><span>" + html_escape(label) +
         (unit.empty() || unit == label ? "" : " (" + html_escape(unit) + ")") + "</span></div>";
}

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

template <std::size_t N>
std::vector<std::uint64_t> class_counts(const Stats& s, const std::string& block, const std::array<ClassStyle, N>& styles,
                                        std::uint64_t cycles, bool must_sum) {
  std::vector<std::uint64_t> v;
  std::uint64_t sum = 0;
  for (const ClassStyle& c : styles) {
    v.push_back(s.count(block + "." + c.key));
    sum += v.back();
  }
  if (must_sum && sum != cycles)
    s.fail(block, "classes sum to " + std::to_string(sum) + " cycles, not the run's " + std::to_string(cycles));
  return v;
}

std::vector<double> shares_of(const std::vector<std::uint64_t>& v) {
  const std::uint64_t whole = std::accumulate(v.begin(), v.end(), std::uint64_t{0});
  std::vector<double> out;
  for (std::uint64_t x : v) out.push_back(share(x, whole));
  return out;
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

std::string analytic_section(const Stats& s) {
  const double measured = s.number("cycles_per_vertex");
  const double predicted = s.number("analytic.cycles_per_vertex");
  const std::string largest = s.text("analytic.bottleneck");
  const json& bounds = s.object("analytic.bounds");
  std::vector<std::pair<std::string, double>> rows;
  for (const char* k : {"int_issue", "te_chain", "cpg", "gpe", "dpg"})
    rows.emplace_back(k, s.number(std::string("analytic.bounds.") + k));
  for (const auto& [k, v] : bounds.items())  // bounds a newer tessim may add
    if (std::none_of(rows.begin(), rows.end(), [&](const auto& r) { return r.first == k; }))
      rows.emplace_back(k, s.number_of(v, "analytic.bounds." + k));
  const char* meaning[] = {"INT issue: operations per vertex / N blocks",
                           "TE contexts: one vertex's dependence chain over V contexts",
                           "CPG: cycles per triangle / vertices per patch",
                           "GPE: K cycles per vertex (plus CPG steps in the gpe mapping)",
                           "DPG: one domain point per cycle"};

  std::string h = section_open("analytic", "Analytical bound");
  h += "<p>Each block on its own needs at least this many cycles per vertex; the largest bound, <b>" +
       html_escape(largest) + "</b> at " + format("%.3f", predicted) +
       " cycles/vertex, is the analytical model's prediction of the steady state (docs/results/load-balancing.md). "
       "The cycle model measured <b>" + format("%.3f", measured) + "</b> cycles/vertex (" +
       format("%.1f%%", predicted > 0 ? 100 * std::abs(measured / predicted - 1) : 0.0) +
       (measured >= predicted ? " above" : " below") + " the prediction; the measured figure includes the fill and drain of the run).</p>\n";

  // Bars on a common scale, the measured figure as a dashed line.
  const double top = std::max(measured, std::max_element(rows.begin(), rows.end(), [](auto& a, auto& b) {
                                          return a.second < b.second;
                                        })->second) * 1.08;
  const double x0 = 180, x1 = 900, row_h = 30, y0 = 26;
  const double height = y0 + row_h * static_cast<double>(rows.size()) + 30, title_h = 22;
  auto X = [&](double v) { return x0 + (top > 0 ? v / top : 0) * (x1 - x0); };
  h += "<svg id=\"analytic-chart\" viewBox=\"0 0 1000 " + coord(height + title_h) +
       "\" role=\"img\" aria-label=\"analytical bounds per block against the measured cycles per vertex\">\n";
  const double step = nice_step(top, 6);
  for (double t = 0; t <= top + 1e-9; t += step) {
    h += "<line x1=\"" + coord(X(t)) + "\" y1=\"" + coord(y0 - 6) + "\" x2=\"" + coord(X(t)) + "\" y2=\"" +
         coord(height - 24) + "\" class=\"grid\"/><text x=\"" + coord(X(t)) + "\" y=\"" + coord(height - 8) +
         "\" text-anchor=\"middle\">" + sig(t) + "</text>\n";
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& [name, v] = rows[i];
    const double y = y0 + row_h * static_cast<double>(i);
    const bool is_largest = name == largest;
    h += "<text x=\"" + coord(x0 - 8) + "\" y=\"" + coord(y + 17) + "\" text-anchor=\"end\"" +
         (is_largest ? " font-weight=\"bold\"" : "") + ">" + html_escape(name) + "</text>";
    h += "<rect x=\"" + coord(x0) + "\" y=\"" + coord(y + 4) + "\" width=\"" + coord(X(v) - x0) +
         "\" height=\"" + coord(row_h - 8) + "\" fill=\"" + (is_largest ? "#1f5fa8" : "#9fb3c8") + "\"><title>" +
         html_escape(name) + ": " + format("%.4g", v) + " cycles/vertex</title></rect>";
    h += "<text x=\"" + coord(X(v) + 6) + "\" y=\"" + coord(y + 17) + "\">" + format("%.3f", v) + "</text>\n";
  }
  h += "<line x1=\"" + coord(X(measured)) + "\" y1=\"" + coord(y0 - 8) + "\" x2=\"" + coord(X(measured)) +
       "\" y2=\"" + coord(height - 24) + "\" stroke=\"#c2410c\" stroke-width=\"2\" stroke-dasharray=\"6 4\"/>";
  h += "<text x=\"" + coord(X(measured)) + "\" y=\"" + coord(y0 - 12) +
       "\" text-anchor=\"middle\" fill=\"#c2410c\">measured " + format("%.3f", measured) + "</text>\n";
  h += "<text x=\"" + coord((x0 + x1) / 2) + "\" y=\"" + coord(height + title_h - 4) +
       "\" text-anchor=\"middle\" class=\"axis-title\">cycles per vertex</text></svg>\n";

  h += "<table>\n<tr><th>bound</th><th class=\"n\">cycles/vertex</th><th class=\"n\">of the measured</th><th>what "
       "it counts</th></tr>\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& [name, v] = rows[i];
    h += "<tr" + std::string(name == largest ? " class=\"largest\"" : "") + "><th>" + html_escape(name) +
         "</th><td class=\"n\">" + format("%.4g", v) + "</td><td class=\"n\">" +
         pct(measured > 0 ? v / measured : 0) + "</td><td class=\"muted\">" + (i < 5 ? meaning[i] : "") +
         "</td></tr>\n";
  }
  h += "</table>\n<table class=\"kv\">\n";
  auto row = [&](const std::string& label, const std::string& a, const std::string& b) {
    h += "<tr><th>" + label + "</th><td class=\"n\">" + a + "</td><td class=\"n\">" + b + "</td></tr>\n";
  };
  h += "<tr><th></th><th class=\"n\">predicted</th><th class=\"n\">measured</th></tr>\n";
  row("cycles of the run",
      grouped(static_cast<std::uint64_t>(std::llround(std::max(0.0, s.number("analytic.run_cycles"))))),
      grouped(s.count("cycles")));
  row("throughput (vertices/cycle)", format("%.4f", s.number("analytic.throughput")),
      format("%.4f", s.number("throughput")));
  row("INT utilisation", pct(s.number("analytic.int_utilisation")), pct(s.number("int.utilisation")));
  row("GPE busy", pct(s.number("analytic.gpe_busy")), pct(share(s.count("gpe.busy"), s.count("cycles"))));
  if (s.find("analytic.varying")) {
    row("per-patch factors: no buffering (cycles/vertex)",
        format("%.3f", s.number("analytic.varying.no_buffer_cycles_per_vertex")), "");
    row("per-patch factors: full buffering (cycles/vertex)",
        format("%.3f", s.number("analytic.varying.full_buffer_cycles_per_vertex")), "");
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

// The statistics over time: TE classes stacked as shares of each bucket, INT utilisation and GPE
// busy as lines, one transparent cell per bucket carrying its figures as a tooltip.
std::string timeline_section(const Stats& s, int schema) {
  std::string h = section_open("timeline", "Timeline");
  if (schema < 3) {
    return h + "<p class=\"muted\" id=\"timeline-missing\">These statistics (schema version " +
           std::to_string(schema) + ") have no timeline; rerun <code>tessim sim --stats</code>.</p>\n</section>\n";
  }
  s.object("timeline");
  const std::uint64_t total = s.count("cycles");
  const std::uint64_t n64 = s.count("timeline.buckets");
  if (n64 > 65536) s.fail("timeline.buckets", std::to_string(n64) + " is more than a run records");
  const auto n = static_cast<std::size_t>(n64);
  const std::uint64_t width = s.count("timeline.bucket_cycles");
  if (width == 0) s.fail("timeline.bucket_cycles", "zero");
  const std::vector<std::uint64_t> cycles = s.counts("timeline.cycles", n);
  std::vector<std::vector<std::uint64_t>> te;
  for (const ClassStyle& c : kTeStyles) te.push_back(s.counts(std::string("timeline.te.") + c.key, n));
  std::vector<std::vector<std::uint64_t>> gpe;
  for (const ClassStyle& c : kGpeStyles) gpe.push_back(s.counts(std::string("timeline.gpe.") + c.key, n));
  const std::vector<std::uint64_t> int_busy = s.counts("timeline.int_busy", n);
  const std::vector<std::uint64_t> cpg_busy = s.counts("timeline.cpg_busy", n);
  const std::vector<std::uint64_t> vertices = s.counts("timeline.vertices_out", n);
  const std::uint64_t blocks = s.array("int.blocks").size();

  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    if (cycles[i] == 0 || cycles[i] > width) s.fail("timeline.cycles" + at, "outside 1..bucket_cycles");
    std::uint64_t te_sum = 0, gpe_sum = 0;
    for (const auto& v : te) te_sum += v[i];
    for (const auto& v : gpe) gpe_sum += v[i];
    if (te_sum != cycles[i]) s.fail("timeline.te" + at, "classes do not sum to the bucket's cycles");
    if (gpe_sum != cycles[i]) s.fail("timeline.gpe" + at, "classes do not sum to the bucket's cycles");
    if (int_busy[i] > blocks * cycles[i]) s.fail("timeline.int_busy" + at, "more than N block-cycles");
    sum += cycles[i];
  }
  if (sum != total)
    s.fail("timeline.cycles", "buckets sum to " + std::to_string(sum) + " cycles, not the run's " + std::to_string(total));
  if (n == 0) return h + "<p class=\"muted\">An empty run: no cycles.</p>\n</section>\n";

  // Plot area in SVG user units; the legend to its right.
  const double L = 64, R = 770, T = 16, B = 336, W = 1000, H = 384;
  std::vector<double> xs(n + 1);
  {
    std::uint64_t c = 0;
    for (std::size_t i = 0; i <= n; ++i) {
      xs[i] = L + (R - L) * static_cast<double>(c) / static_cast<double>(total);
      if (i < n) c += cycles[i];
    }
  }
  auto Y = [&](double f) { return T + (1.0 - f) * (B - T); };
  auto frac = [&](std::uint64_t part, std::size_t i) { return static_cast<double>(part) / static_cast<double>(cycles[i]); };

  std::uint64_t last_cycles = cycles.back();
  h += "<p>" + std::to_string(n) + " buckets of " + grouped(width) + " cycles" +
       (last_cycles != width ? " (the last " + grouped(last_cycles) + ")" : std::string()) +
       ". In each, the TE's classes as shares of the bucket's cycles (stacked), the INT utilisation (busy "
       "block-cycles / N cycles) and the share of cycles the GPE was busy. Point at a bucket for its figures.</p>\n";
  h += "<svg id=\"timeline-chart\" viewBox=\"0 0 " + coord(W) + " " + coord(H) +
       "\" role=\"img\" aria-label=\"TE classes, INT utilisation and GPE busy over the run, per bucket of cycles\">\n";

  // Stacked areas, as steps: each bucket is an interval of cycles.
  std::vector<double> lower(n, 0.0), upper(n);
  for (std::size_t k = 0; k < te.size(); ++k) {
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      upper[i] = lower[i] + frac(te[k][i], i);
      any = any || te[k][i] > 0;
    }
    if (any) {
      std::string d = "M" + coord(xs[0]) + "," + coord(Y(upper[0]));
      for (std::size_t i = 0; i < n; ++i) {
        if (i > 0) path_to(d, 'V', Y(upper[i]));
        path_to(d, 'H', xs[i + 1]);
      }
      path_to(d, 'V', Y(lower[n - 1]));
      for (std::size_t i = n; i-- > 0;) {
        path_to(d, 'H', xs[i]);
        if (i > 0) path_to(d, 'V', Y(lower[i - 1]));
      }
      h += std::string("<path class=\"area\" d=\"") + d + "Z\" fill=\"" + kTeStyles[k].colour + "\"><title>TE " +
           kTeStyles[k].key + "</title></path>\n";
    }
    lower = upper;
  }

  // Grid and axes over the areas.
  for (int p = 0; p <= 4; ++p) {
    const double y = Y(p / 4.0);
    h += "<line x1=\"" + coord(L) + "\" y1=\"" + coord(y) + "\" x2=\"" + coord(R) + "\" y2=\"" + coord(y) +
         "\" class=\"grid\"/><text x=\"" + coord(L - 6) + "\" y=\"" + coord(y + 4) + "\" text-anchor=\"end\">" +
         std::to_string(25 * p) + "%</text>\n";
  }
  const double step = nice_step(static_cast<double>(total), 8);
  for (double c = 0; c <= static_cast<double>(total) + 0.5; c += step) {
    const double x = L + (R - L) * c / static_cast<double>(total);
    h += "<line x1=\"" + coord(x) + "\" y1=\"" + coord(B) + "\" x2=\"" + coord(x) + "\" y2=\"" + coord(B + 5) +
         "\" class=\"axis\"/><text x=\"" + coord(x) + "\" y=\"" + coord(B + 19) + "\" text-anchor=\"middle\">" +
         compact(c) + "</text>\n";
  }
  h += "<rect x=\"" + coord(L) + "\" y=\"" + coord(T) + "\" width=\"" + coord(R - L) + "\" height=\"" + coord(B - T) +
       "\" class=\"frame\"/>\n";
  h += "<text x=\"" + coord((L + R) / 2) + "\" y=\"" + coord(B + 40) +
       "\" text-anchor=\"middle\" class=\"axis-title\">cycle</text>\n";
  h += "<text transform=\"translate(16 " + coord((T + B) / 2) +
       ") rotate(-90)\" text-anchor=\"middle\" class=\"axis-title\">share of the bucket's cycles</text>\n";

  // Lines: a white halo under each keeps them readable on every area colour.
  auto step_line = [&](auto value) {
    std::string d = "M" + coord(xs[0]) + "," + coord(Y(value(0)));
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) path_to(d, 'V', Y(value(i)));
      path_to(d, 'H', xs[i + 1]);
    }
    return d;
  };
  const std::string int_d = step_line([&](std::size_t i) {
    return static_cast<double>(int_busy[i]) / (static_cast<double>(blocks) * static_cast<double>(cycles[i]));
  });
  const std::string gpe_d = step_line([&](std::size_t i) { return frac(gpe[0][i], i); });
  h += "<path d=\"" + int_d + "\" class=\"halo\"/><path id=\"timeline-int\" d=\"" + int_d + "\" stroke=\"" + kIntLine +
       "\" class=\"line\"/>\n";
  h += "<path d=\"" + gpe_d + "\" class=\"halo\"/><path id=\"timeline-gpe\" d=\"" + gpe_d + "\" stroke=\"" + kGpeLine +
       "\" class=\"line\" stroke-dasharray=\"7 4\"/>\n";

  // One cell per bucket with its figures (a tooltip without script; the script shows the same
  // text under the chart).
  h += "<g class=\"cells\">\n";
  std::uint64_t first = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::string t = "cycles " + grouped(first) + "–" + grouped(first + cycles[i] - 1) + ": TE";
    for (std::size_t k = 0; k < te.size(); ++k)
      if (te[k][i] > 0) t += std::string(" ") + kTeStyles[k].key + " " + pct(frac(te[k][i], i));
    t += "; INT " + pct(static_cast<double>(int_busy[i]) / (static_cast<double>(blocks) * static_cast<double>(cycles[i]))) +
         "; GPE busy " + pct(frac(gpe[0][i], i)) + "; CPG busy " + pct(frac(cpg_busy[i], i)) + "; " +
         grouped(vertices[i]) + " vertices (" + format("%.4f", frac(vertices[i], i)) + "/cycle)";
    h += "<rect class=\"bucket\" x=\"" + coord(xs[i]) + "\" y=\"" + coord(T) + "\" width=\"" +
         coord(std::max(xs[i + 1] - xs[i], 0.1)) + "\" height=\"" + coord(B - T) + "\"><title>" + t +
         "</title></rect>\n";
    first += cycles[i];
  }
  h += "</g>\n";

  // Legend: the run's share of each class beside its colour.
  std::vector<double> run_share;
  for (const auto& v : te) run_share.push_back(share(std::accumulate(v.begin(), v.end(), std::uint64_t{0}), total));
  double y = T + 8;
  h += "<g class=\"legend-svg\">\n<text x=\"790\" y=\"" + coord(y) + "\" font-weight=\"bold\">TE class (run)</text>\n";
  for (std::size_t k = te.size(); k-- > 0;) {  // top of the stack first
    y += 22;
    h += "<rect x=\"790\" y=\"" + coord(y - 11) + "\" width=\"14\" height=\"14\" fill=\"" + kTeStyles[k].colour +
         "\"/><text x=\"811\" y=\"" + coord(y) + "\">" + kTeStyles[k].key + " " + pct(run_share[k]) + "</text>\n";
  }
  y += 32;
  h += "<line x1=\"790\" y1=\"" + coord(y - 4) + "\" x2=\"806\" y2=\"" + coord(y - 4) + "\" stroke=\"" + kIntLine +
       "\" stroke-width=\"2.5\"/><text x=\"811\" y=\"" + coord(y) + "\">INT utilisation</text>\n";
  y += 22;
  h += "<line x1=\"790\" y1=\"" + coord(y - 4) + "\" x2=\"806\" y2=\"" + coord(y - 4) + "\" stroke=\"" + kGpeLine +
       "\" stroke-width=\"2.5\" stroke-dasharray=\"5 3\"/><text x=\"811\" y=\"" + coord(y) + "\">GPE busy</text>\n";
  h += "</g>\n</svg>\n<p id=\"timeline-readout\" class=\"readout muted\">&#160;</p>\n";
  return h + "</section>\n";
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
      first = false;
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
