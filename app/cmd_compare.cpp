// tessim compare A.json B.json [--csv] [--changed] [--key PREFIX]: two runs' statistics (tessim
// sim --stats) side by side, every configuration key that differs first, then every number with
// the ratio B/A and its unit, keys in natural order (histogram bins 0, 1, 2, 10).
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "model/base/input_file.hpp"
#include "sim/base/json_input.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::app {

namespace {

using nlohmann::json;

struct CompareArgs {
  std::string a, b;
  bool csv = false;
  bool changed = false;              // only the figures that differ
  std::vector<std::string> prefixes;  // only the keys that start with one of these
};

// Every field the comparison reads beyond the numbers is checked here, before anything is
// printed: a statistics file is refused whole or compared whole.
json read_stats(const std::string& path) {
  const json j = sim::parse_json_text(read_whole_file(path, kDataFileLimit, "file"), path);
  if (!j.is_object() || !j.contains("cycles") || !j.contains("config"))
    throw InputError(path, "statistics", "not the statistics of `tessim sim --stats` (no cycles or config)");
  if (j.contains("schema_version") && !j["schema_version"].is_number_unsigned())
    throw InputError(path, "schema_version", j["schema_version"].dump() + " is not a non-negative integer");
  // A newer schema may mean other things by the same keys: refused, as `report` refuses it.
  if (j.contains("schema_version") && j["schema_version"].get<std::uint64_t>() > static_cast<std::uint64_t>(sim::kStatsSchemaVersion))
    throw InputError(path, "schema_version",
                     j["schema_version"].dump() + " is newer than this tessim's " +
                         std::to_string(sim::kStatsSchemaVersion) + " (compare with the tessim that wrote it)");
  if (j.contains("tool")) {
    const json& tool = j["tool"];
    if (!tool.is_object()) throw InputError(path, "tool", tool.dump() + " is not an object");
    if (tool.contains("version") && !tool["version"].is_string())
      throw InputError(path, "tool.version", tool["version"].dump() + " is not a string");
  }
  return j;
}

// Keys compared as text, except that runs of digits compare as numbers: "bins.2" < "bins.10".
struct NaturalLess {
  bool operator()(const std::string& a, const std::string& b) const {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
      const bool da = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
      const bool db = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
      if (da && db) {
        std::size_t ei = i, ej = j;
        while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
        while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
        // Without leading zeros the longer run is the larger number.
        std::size_t si = i, sj = j;
        while (si + 1 < ei && a[si] == '0') ++si;
        while (sj + 1 < ej && b[sj] == '0') ++sj;
        if (ei - si != ej - sj) return ei - si < ej - sj;
        if (const int c = a.compare(si, ei - si, b, sj, ej - sj); c != 0) return c < 0;
        if (ei - i != ej - j) return ei - i < ej - j;
        i = ei;
        j = ej;
        continue;
      }
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
    return a.size() - i < b.size() - j;
  }
};
using FlatStats = std::map<std::string, json, NaturalLess>;

// Every number and string of `j` by its path; array elements are numbered ("int.blocks.1.busy")
// and looked up in the units table as "[]".
void flatten(const json& j, const std::string& path, FlatStats& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten(v, path.empty() ? k : path + "." + k, out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) flatten(j[i], path + "." + std::to_string(i), out);
  } else {
    out[path] = j;
  }
}

std::string unit_key(const std::string& path) {
  std::string key;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    const std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    if (index) key += "[]";
    else key += (key.empty() ? "" : ".") + part;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return key;
}

std::string text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) {
    // A count stored as a double (analytic.run_cycles) prints exactly, as the integer it is.
    const double x = v.get<double>();
    char buf[400];
    if (std::isfinite(x) && x == std::nearbyint(x) && std::abs(x) < 0x1p53)
      std::snprintf(buf, sizeof buf, "%.0f", x);
    else
      std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
  }
  return v.dump();
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void run(const CompareArgs& args) {
  const json a = read_stats(args.a), b = read_stats(args.b);
  FlatStats fa, fb;
  flatten(a, "", fa);
  flatten(b, "", fb);
  const json units = sim::stats_units();
  std::set<std::string, NaturalLess> keys;
  for (const auto& [k, v] : fa) keys.insert(k);
  for (const auto& [k, v] : fb) keys.insert(k);
  auto selected = [&args](const std::string& key) {
    if (args.prefixes.empty()) return true;
    for (const std::string& p : args.prefixes)
      if (key.rfind(p, 0) == 0) return true;
    return false;
  };

  struct Row {
    std::string key, va, vb, ratio, unit;
  };
  std::vector<Row> config, stats;
  for (const std::string& k : keys) {
    // The timeline's buckets are a time series, not figures of the run (and two runs' buckets
    // differ in width): left out.
    if (k.rfind("units.", 0) == 0 || k.rfind("tool.", 0) == 0 || k.rfind("timeline.", 0) == 0) continue;
    const json* x = fa.contains(k) ? &fa.at(k) : nullptr;
    const json* y = fb.contains(k) ? &fb.at(k) : nullptr;
    Row r{k, x ? text(*x) : "-", y ? text(*y) : "-", "", ""};
    // The configuration keys that differ say what the two runs are: shown whatever --key selects.
    if (k.rfind("config.", 0) == 0 || k == "mesh") {
      if (r.va != r.vb) config.push_back(r);
      continue;
    }
    if (!selected(k)) continue;
    if (args.changed && x && y && *x == *y) continue;
    if (x && y && x->is_number() && y->is_number()) {
      const double p = x->get<double>(), q = y->get<double>();
      if (p != 0) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.4f", q / p);
        r.ratio = buf;
      } else {
        r.ratio = q == 0 ? "=" : "-";
      }
    }
    const std::string uk = unit_key(k);
    if (units.contains(uk)) r.unit = units[uk].get<std::string>();
    stats.push_back(r);
  }

  if (args.csv) {
    std::cout << "key,a,b,ratio_b_over_a,unit\n";
    for (const auto* rows : {&config, &stats})
      for (const Row& r : *rows)
        std::cout << csv_field(r.key) << "," << csv_field(r.va) << "," << csv_field(r.vb) << "," << r.ratio << ","
                  << csv_field(r.unit) << "\n";
    return;
  }
  auto tool = [](const json& j) {
    return j.contains("tool") ? j["tool"].value("version", std::string("?")) : std::string("before schema 2");
  };
  std::printf("A  %s  (tessim %s)\nB  %s  (tessim %s)\n", args.a.c_str(), tool(a).c_str(), args.b.c_str(),
              tool(b).c_str());
  if (a.value("schema_version", 1) != b.value("schema_version", 1))
    std::printf("note: statistics schema versions differ (%d and %d)\n", a.value("schema_version", 1),
                b.value("schema_version", 1));
  std::size_t width = 10;
  for (const auto* rows : {&config, &stats})
    for (const Row& r : *rows) width = std::max(width, r.key.size());
  std::printf("\n%-*s  %16s  %16s  %8s\n", static_cast<int>(width), config.empty() ? "configuration: the same" : "configuration",
              "A", "B", "");
  for (const Row& r : config)
    std::printf("%-*s  %16s  %16s\n", static_cast<int>(width), r.key.c_str(), r.va.c_str(), r.vb.c_str());
  std::printf("\n%-*s  %16s  %16s  %8s  %s\n", static_cast<int>(width), "statistic", "A", "B", "B/A", "unit");
  for (const Row& r : stats) {
    if (r.va.size() > 16 || r.vb.size() > 16) {  // text (the bottleneck line): on lines of their own
      std::printf("%-*s  A: %s\n%-*s  B: %s\n", static_cast<int>(width), r.key.c_str(), r.va.c_str(),
                  static_cast<int>(width), "", r.vb.c_str());
      continue;
    }
    std::printf("%-*s  %16s  %16s  %8s  %s\n", static_cast<int>(width), r.key.c_str(), r.va.c_str(), r.vb.c_str(),
                r.ratio.c_str(), r.unit.c_str());
  }
}

}  // namespace

void register_compare(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* sub = app.add_subcommand(
      "compare", "Two runs' statistics (tessim sim --stats) side by side: differing configuration, every figure "
                 "with the ratio B/A and its unit");
  sub->add_option("a", args->a, "statistics JSON of run A")->required();
  sub->add_option("b", args->b, "statistics JSON of run B")->required();
  sub->add_flag("--csv", args->csv, "print CSV (key, a, b, ratio_b_over_a, unit) instead of a table");
  sub->add_flag("--changed", args->changed, "only the figures that differ between A and B");
  sub->add_option("--key", args->prefixes,
                  "only the figures whose keys start with this prefix (e.g. analytic., int.blocks; the "
                  "configuration keys that differ are always shown); repeatable");
  sub->callback([args]() { run(*args); });
}

}  // namespace tessim::app
