// The parts of the page of `tessim report` (app/report_html.hpp): checked reads of the
// statistics, numbers as text, the blocks' classes with their colours, and the sections.
// report_html.cpp assembles the page (its skeleton, style and script) from the sections of
// report_sections.cpp (tables and bars) and report_charts.cpp (the SVG charts); report_text.cpp
// writes the numbers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/report_html.hpp"
#include "model/base/error.hpp"
#include "sim/base/counter_registry.hpp"

namespace tessim::app::report_page {

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
// Text (report_text.cpp).

std::string format(const char* fmt, double v);
std::string pct(double fraction);
std::string sig(double v);
std::string coord(double v);
// One SVG path command with its coordinate ("H123.4"), appended in place.
void path_to(std::string& d, char command, double v);
double share(std::uint64_t part, std::uint64_t whole);
// 1340000 as "1 340 000" (narrow no-break spaces, as the docs write large counts).
std::string grouped(std::uint64_t v);
// Axis labels: 0, 500, 25k, 1.2M.
std::string compact(double v);
// A step of 1, 2 or 5 times a power of ten giving about `target` intervals up to `range`.
double nice_step(double range, int target);
std::string value_text(const json& v);

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
inline constexpr auto kTeStyles = class_styles<sim::CounterBlock::Te>();
inline constexpr auto kCpgStyles = class_styles<sim::CounterBlock::Cpg>();
inline constexpr auto kGpeStyles = class_styles<sim::CounterBlock::Gpe>();
inline constexpr const char* kIntLine = "#000000";
inline constexpr const char* kGpeLine = "#0072B2";

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
// Sections: the pieces (report_text.cpp) and the sections themselves, each built (and so
// checked) before the page is assembled.

std::string section_open(const char* id, const char* title);
std::string tile(const std::string& value, const std::string& label, const std::string& unit);

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

std::vector<double> shares_of(const std::vector<std::uint64_t>& v);

// report_sections.cpp
std::string summary_section(const Stats& s);
std::string classes_section(const Stats& s);
std::string bottleneck_section(const Stats& s);
std::string int_section(const Stats& s);
std::string config_section(const Stats& s);
std::string images_section(const ReportInput& in);
std::string files_section(const ReportInput& in);

// report_charts.cpp: the analytical bounds against the measured figure, and the timeline.
std::string analytic_section(const Stats& s);
std::string timeline_section(const Stats& s, int schema);

}  // namespace tessim::app::report_page
