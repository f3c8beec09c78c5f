// The sections of the report page drawn as inline SVG (app/report_page.hpp): the analytical
// bounds against the measured cycles per vertex, and the timeline.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "app/report_page.hpp"

namespace tessim::app::report_page {

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

}  // namespace tessim::app::report_page
