// The C++ description of the RTL's boundary and tables (sim/config/ports.hpp, sim/base/int_ops.hpp,
// sim/config/rtl_builds.hpp) against the SystemVerilog itself: tess_pkg.sv's widths, codes and
// INT-op constants, tess_te.sv's operand and dependence table, tess_unit.sv's port list. Every
// difference fails. (tests/rtl/rtl_ports_test.cpp checks the widths on the Verilated models.)
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/base/int_ops.hpp"
#include "sim/config/params.hpp"
#include "sim/config/ports.hpp"
#include "sim/config/rtl_builds.hpp"
#include "sim/report/schema.hpp"
#include "sim/values/unit_io.hpp"

namespace {

using namespace tessim;
using namespace tessim::sim;
using nlohmann::json;

std::string read_rtl(const std::string& name) {
  std::ifstream f(std::string(TESSIM_SOURCE_DIR) + "/rtl/" + name);
  EXPECT_TRUE(f) << "rtl/" << name;
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    if (i == s.size() || s[i] == sep) {
      parts.push_back(trim(s.substr(start, i - start)));
      start = i + 1;
    }
  }
  return parts;
}

// tess_pkg's `localparam int unsigned NAME = EXPR;`, EXPR a sum of products of integers and
// earlier names (all tess_pkg uses), and the enumerators of its `typedef enum int unsigned`s
// (0, 1, ... in order: tess_pkg gives none a value).
std::map<std::string, long long> pkg_ints(const std::string& pkg_text) {
  std::map<std::string, long long> values;
  const std::string pkg = std::regex_replace(pkg_text, std::regex("//[^\n]*"), "");
  const std::regex enum_body(R"(typedef\s+enum\s+int\s+unsigned\s*\{([^}]*)\})");
  for (auto it = std::sregex_iterator(pkg.begin(), pkg.end(), enum_body); it != std::sregex_iterator(); ++it) {
    long long k = 0;
    for (const std::string& name : split((*it)[1].str(), ',')) {
      const std::string n = std::regex_replace(name, std::regex("\\s+"), "");
      if (!n.empty()) values[n] = k++;
    }
  }
  const std::regex line(R"(localparam\s+int\s+unsigned\s+(\w+)\s*=\s*([^;]+);)");
  for (auto it = std::sregex_iterator(pkg.begin(), pkg.end(), line); it != std::sregex_iterator(); ++it) {
    long long sum = 0;
    for (const std::string& term : split((*it)[2].str(), '+')) {
      long long product = 1;
      for (const std::string& factor : split(term, '*')) {
        if (!factor.empty() && std::all_of(factor.begin(), factor.end(), ::isdigit)) {
          product *= std::stoll(factor);
        } else {
          const auto known = values.find(factor);
          if (known == values.end()) {
            ADD_FAILURE() << "tess_pkg.sv: cannot evaluate '" << (*it)[2].str() << "' of " << (*it)[1];
            return values;
          }
          product *= known->second;
        }
      }
      sum += product;
    }
    values[(*it)[1].str()] = sum;
  }
  return values;
}

// tess_pkg's `localparam logic [M:0] NAME = N'bBITS;` (also 'd, 'h), underscores allowed.
std::map<std::string, long long> pkg_logic(const std::string& pkg) {
  std::map<std::string, long long> values;
  const std::regex line(R"(localparam\s+logic\s*\[\d+:0\]\s*(\w+)\s*=\s*\d+'([bdh])([0-9a-fA-F_]+);)");
  for (auto it = std::sregex_iterator(pkg.begin(), pkg.end(), line); it != std::sregex_iterator(); ++it) {
    std::string digits = (*it)[3].str();
    digits.erase(std::remove(digits.begin(), digits.end(), '_'), digits.end());
    const char base = (*it)[2].str()[0];
    values[(*it)[1].str()] = std::stoll(digits, nullptr, base == 'b' ? 2 : base == 'h' ? 16 : 10);
  }
  return values;
}

TEST(RtlPackage, FieldWidthsAreTessPkgs) {
  const auto ints = pkg_ints(read_rtl("tess_pkg.sv"));
  for (const pkg::Constant& c : pkg::kWidths) {
    ASSERT_TRUE(ints.count(c.name)) << c.name << " not in tess_pkg.sv";
    EXPECT_EQ(ints.at(c.name), c.value) << c.name;
  }
}

// Every code tess_pkg defines for a port (Mode*, Pat*, Flag*) is one of port_codes(), with the
// same value, and the other way round.
TEST(RtlPackage, PortCodesAreTessPkgs) {
  const auto logic = pkg_logic(read_rtl("tess_pkg.sv"));
  std::set<std::string> rtl_codes, cpp_codes;
  for (const auto& [name, value] : logic) {
    if (name.rfind("Mode", 0) == 0 || name.rfind("Pat", 0) == 0 || name.rfind("Flag", 0) == 0) rtl_codes.insert(name);
  }
  for (const PortCode& c : port_codes()) {
    ASSERT_NE(c.pkg, nullptr) << c.port << " " << c.name;
    cpp_codes.insert(c.pkg);
    ASSERT_TRUE(logic.count(c.pkg)) << c.pkg << " not in tess_pkg.sv";
    EXPECT_EQ(logic.at(c.pkg), c.value) << c.pkg << " (" << c.port << " " << c.name << ")";
  }
  EXPECT_EQ(rtl_codes, cpp_codes);
  EXPECT_EQ(rtl_codes.size(), 9u);  // 3 modes, 4 patterns, 2 flags
}

// tess_pkg's INT-op constants and tess_te.sv's operand and dependence table against
// sim/base/int_ops.hpp.
TEST(RtlPackage, IntOpTableIsTheRtls) {
  const std::string pkg = read_rtl("tess_pkg.sv");
  const auto ints = pkg_ints(pkg);
  const auto logic = pkg_logic(pkg);
  EXPECT_EQ(ints.at("NumOps"), int_ops::kOpCount);
  EXPECT_EQ(logic.at("LinearSkipOps"), int_ops::kLinearAbsent);
  EXPECT_EQ(ints.at("OpNormalL2"), int_ops::normal_op(NormalMode::Quadratic));
  EXPECT_EQ(ints.at("OpNormalL2"), int_ops::normal_op(NormalMode::Reflect));
  EXPECT_EQ(ints.at("OpNormalL1"), int_ops::normal_op(NormalMode::Linear));
  EXPECT_EQ(ints.at("OpGeomL3"), int_ops::kPositionOp);

  const std::string te = read_rtl("tess_te.sv");
  // Dependences: `rdy[o] = rdy[o] & dn[a] & dn[b] ...;` (ops without such a line have none).
  std::map<int, std::uint32_t> depends;
  const std::regex dep(R"(rdy\[(\d+)\]\s*=\s*rdy\[\1\]((?:\s*&\s*dn\[\d+\])+)\s*;)");
  const std::regex dn(R"(dn\[(\d+)\])");
  for (auto it = std::sregex_iterator(te.begin(), te.end(), dep); it != std::sregex_iterator(); ++it) {
    const std::string rhs = (*it)[2].str();
    std::uint32_t bits = 0;
    for (auto d = std::sregex_iterator(rhs.begin(), rhs.end(), dn); d != std::sregex_iterator(); ++d)
      bits |= int_ops::bit(std::stoi((*d)[1].str()));
    depends[std::stoi((*it)[1].str())] = bits;
  }
  EXPECT_EQ(depends.size(), 5u);  // ops 9..13
  for (const int_ops::IntOp& op : int_ops::kIntOps) {
    const auto d = depends.find(op.op);
    EXPECT_EQ(d == depends.end() ? 0u : d->second, op.depends) << "dependences of op " << op.op;
  }

  // Operands: `op_a[O] = Xsel[i];`, `op_b[O] = ...;`, `op_c[O] = ...;` for every op O; op 6
  // has `mode_linear ? nsel[i] : nsel[j]` for the linear normal.
  const std::regex operand(
      R"(op_([abc])\[(\d+)\]\s*=\s*(?:mode_linear\s*\?\s*([bnt])sel\[(\d+)\]\s*:\s*)?([bnt])sel\[(\d+)\]\s*;)");
  auto to_operand = [](const std::string& net, const std::string& index) {
    const int i = std::stoi(index);
    return net == "b" ? int_ops::b(i) : net == "n" ? int_ops::n(i) : int_ops::t(i);
  };
  auto same = [](const int_ops::Operand& x, const int_ops::Operand& y) { return x.net == y.net && x.index == y.index; };
  std::map<int, std::array<int_ops::Operand, 3>> normal, linear;
  std::map<int, int> found;
  for (auto m = std::sregex_iterator(te.begin(), te.end(), operand); m != std::sregex_iterator(); ++m) {
    const int op = std::stoi((*m)[2].str());
    const std::size_t slot = static_cast<std::size_t>((*m)[1].str()[0] - 'a');
    normal[op][slot] = to_operand((*m)[5].str(), (*m)[6].str());
    linear[op][slot] = (*m)[3].matched ? to_operand((*m)[3].str(), (*m)[4].str()) : normal[op][slot];
    ++found[op];
  }
  ASSERT_EQ(found.size(), static_cast<std::size_t>(int_ops::kOpCount));
  for (int op = 0; op < int_ops::kOpCount; ++op) {
    ASSERT_EQ(found[op], 3) << "operands of op " << op;
    for (std::size_t s = 0; s < 3; ++s) {
      const int_ops::Operand want = int_ops::operands(op, NormalMode::Quadratic)[s];
      const int_ops::Operand want_linear = int_ops::operands(op, NormalMode::Linear)[s];
      EXPECT_TRUE(same(normal[op][s], want)) << "op " << op << " operand " << s;
      EXPECT_TRUE(same(linear[op][s], want_linear)) << "op " << op << " operand " << s << " (linear)";
    }
  }
}

// The port list of tess_unit.sv, in order, with directions; the vertex item is the vertex
// fields the co-simulation compares (sim/values/unit_io.hpp).
TEST(RtlPackage, PortsAreTessUnits) {
  const std::string unit = read_rtl("tess_unit.sv");
  const std::regex decl(R"(\b(input|output)\s+logic\s*(?:\[[^\]]*\])?\s*(\w+)\s*[,)\n])");
  std::vector<std::pair<std::string, PortDir>> rtl;
  for (auto it = std::sregex_iterator(unit.begin(), unit.end(), decl); it != std::sregex_iterator(); ++it)
    rtl.emplace_back((*it)[2].str(), (*it)[1].str() == "input" ? PortDir::In : PortDir::Out);
  ASSERT_EQ(rtl.size(), unit_ports().size());
  for (std::size_t i = 0; i < rtl.size(); ++i) {
    EXPECT_EQ(rtl[i].first, unit_ports()[i].name);
    EXPECT_EQ(rtl[i].second, unit_ports()[i].dir) << rtl[i].first;
  }
  std::vector<std::string> vertex_ports, fields;
  for (const Port& p : unit_ports())
    if (p.item == PortItem::Vertex) vertex_ports.emplace_back(p.name);
  for (const VertexField& f : kVertexFields) fields.push_back(std::string(f.name) + "_o");
  EXPECT_EQ(vertex_ports, fields);
}

TEST(RtlPackage, ItemWidthsAtTheDefaults) {
  // W = 24, B = 16: tess_unit's TriW = 18W + DescBits + IdBits (+ 18W with tags), VtxW = 6W +
  // 2(B + 1) + 3 FactorBits + IndexBits + IdBits + 1 + FlagBits.
  HardwareConfig hw = UnitConfig{}.hardware();
  EXPECT_EQ(item_bits(PortItem::Triangle, hw), 18 * 24 + 101 + 32);
  EXPECT_EQ(item_bits(PortItem::Vertex, hw), 6 * 24 + 2 * 17 + 21 + 12 + 32 + 1 + 2);
  hw.cpg_tags = 1;
  EXPECT_EQ(item_bits(PortItem::Triangle, hw), 36 * 24 + 101 + 32);
  EXPECT_EQ(width_text(find_port("vtx_u_o")->width), "bary_bits + 1");
  EXPECT_EQ(width_text(find_port("perf_ctr_o")->width), "64*int_blocks + " + std::to_string(64 * kRtlScalarCounters));
}

// The schema's RTL builds: rtl/builds.json as embedded. (Each build's flags through the
// command-line parser of `tessim sim` / `tessim cosim`: tests/cli/config_cli_test.cpp.)
TEST(RtlBuilds, EmbeddedListAndFlags) {
  std::ifstream f(std::string(TESSIM_SOURCE_DIR) + "/rtl/builds.json");
  const json file = json::parse(f);
  ASSERT_EQ(rtl_builds().size(), file["builds"].size());
  const json schema = schema_json();
  ASSERT_EQ(schema["rtl_builds"].size(), rtl_builds().size());
  for (std::size_t i = 0; i < rtl_builds().size(); ++i) {
    const RtlBuild& b = rtl_builds()[i];
    EXPECT_EQ(b.name, file["builds"][i]["name"]);
    EXPECT_EQ(schema["rtl_builds"][i]["name"], b.name);
    EXPECT_EQ(schema["rtl_builds"][i]["triangle_bits"], item_bits(PortItem::Triangle, b.hardware()));
    for (const auto& [name, value] : b.parameters) {
      if (name == "InjectBug") continue;
      EXPECT_EQ(find_rtl_param(name)->get(with_hardware(b.hardware())), value) << b.name << " " << name;
    }
  }
  const RtlBuild* lat3 = find_rtl_build("n3_lat3");
  ASSERT_NE(lat3, nullptr);
  EXPECT_EQ(lat3->flags(), (std::vector<std::string>{"--int-blocks", "3", "--int-latency", "3", "--te-contexts", "6",
                                                      "--cpg-lanes", "3", "--cpg-digit-bits", "5", "--cpg-tags", "1",
                                                      "--cpg-copies", "2", "--cpg-product-reg", "1", "--alpha-bits", "8"}));
  EXPECT_EQ(find_rtl_build("n2_bug2")->inject_bug(), 2);
  EXPECT_TRUE(find_rtl_build("n2_verif")->verif);
}

}  // namespace
