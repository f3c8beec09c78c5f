// Numbers as the report writes them, and the pieces every section is built from
// (app/report_page.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "app/report_page.hpp"

namespace tessim::app::report_page {

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

std::string section_open(const char* id, const char* title) {
  return std::string("<section id=\"") + id + "\">\n<h2>" + title + "</h2>\n";
}

std::string tile(const std::string& value, const std::string& label, const std::string& unit) {
  return "<div class=\"tile\"><b>" + value + "</b><span>" + html_escape(label) +
         (unit.empty() || unit == label ? "" : " (" + html_escape(unit) + ")") + "</span></div>";
}

std::vector<double> shares_of(const std::vector<std::uint64_t>& v) {
  const std::uint64_t whole = std::accumulate(v.begin(), v.end(), std::uint64_t{0});
  std::vector<double> out;
  for (std::uint64_t x : v) out.push_back(share(x, whole));
  return out;
}

}  // namespace tessim::app::report_page
