// `tessim pattern` as a user runs it (docs/patterns.md): JSON and text output, pictures,
// culled patches and bad input (docs/architecture.md, Bad input).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "model/d3d11_pattern.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using tessim::testing::run_tessim;
using tessim::testing::TempDir;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(PatternCli, JsonMatchesTheModelExactly) {
  TempDir scratch;
  const auto r = run_tessim({"pattern", "--outer", "3.5,2.2,7.9", "--inner", "4.4", "--partitioning", "fractional_odd",
                             "--json"},
                            scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // exactly one object: parse() rejects trailing data
  ASSERT_TRUE(j.is_object());
  EXPECT_FALSE(j.at("culled").get<bool>());
  const D3D11Pattern p = d3d11_tri_pattern({3.5f, 2.2f, 7.9f}, 4.4f, Partitioning::fractional_odd);
  ASSERT_EQ(j.at("points").size(), p.points.size());
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    EXPECT_EQ(j["points"][i][0].get<double>(), fixed16_to_double(p.points[i].u)) << i;
    EXPECT_EQ(j["points"][i][1].get<double>(), fixed16_to_double(p.points[i].v)) << i;
  }
  EXPECT_EQ(j.at("indices").get<std::vector<std::uint32_t>>(), p.indices);
}

TEST(PatternCli, EqualIntegerFactorsAndWinding) {
  TempDir scratch;
  for (const char* winding : {"ccw", "cw"}) {
    const auto r = run_tessim(
        {"pattern", "--outer", "4,4,4", "--inner", "4", "--partitioning", "integer", "--winding", winding, "--json"},
        scratch.path());
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["points"].size(), 19u);
    const auto idx = j["indices"].get<std::vector<std::uint32_t>>();
    ASSERT_EQ(idx.size(), 24u * 3);
    for (std::size_t t = 0; t < idx.size(); t += 3) {
      auto at = [&](std::size_t k, int c) { return j["points"][idx[t + k]][c].get<double>(); };
      const double area = (at(1, 0) - at(0, 0)) * (at(2, 1) - at(0, 1)) - (at(1, 1) - at(0, 1)) * (at(2, 0) - at(0, 0));
      if (std::string(winding) == "ccw") EXPECT_GT(area, 0.0) << t;
      else EXPECT_LT(area, 0.0) << t;
    }
  }
}

TEST(PatternCli, TextShowsEffectiveFactors) {
  TempDir scratch;
  const auto r = run_tessim({"pattern", "--outer", "100,3,5", "--inner", "9", "--partitioning", "pow2"}, scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("outer e0       64 "), std::string::npos) << r.out;  // clamped
  EXPECT_NE(r.out.find("outer e1       4 "), std::string::npos) << r.out;   // rounded up to a power of two
  EXPECT_NE(r.out.find("outer e2       8 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("inner          16 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("# triangle"), std::string::npos);
}

TEST(PatternCli, CulledPatch) {
  TempDir scratch;
  for (const char* outer : {"0,3,3", "3,-1,3", "3,3,nan"}) {
    std::string outer_option = "--outer=";
    outer_option += outer;
    const auto r = run_tessim({"pattern", outer_option, "--inner", "3", "--partitioning", "fractional_even", "--json"},
                              scratch.path());
    ASSERT_EQ(r.status, 0) << outer << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j.at("culled").get<bool>());
    EXPECT_TRUE(j.at("points").empty());
    EXPECT_TRUE(j.at("indices").empty());
    const auto text = run_tessim({"pattern", outer_option, "--inner", "3", "--partitioning", "integer"}, scratch.path());
    EXPECT_EQ(text.status, 0);
    EXPECT_NE(text.out.find("culled"), std::string::npos);
  }
}

TEST(PatternCli, WritesSvgAndPng) {
  TempDir scratch, work;
  const fs::path svg = work.path() / "p.svg", png = work.path() / "p.png";
  auto r = run_tessim({"pattern", "--outer", "2,5,3", "--inner", "4", "--partitioning", "integer", "-o", svg.string()},
                      scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = slurp(svg);
  EXPECT_EQ(text.rfind("<svg", 0), 0u);
  EXPECT_NE(text.find("</svg>"), std::string::npos);
  const D3D11Pattern p = d3d11_tri_pattern({2, 5, 3}, 4, Partitioning::integer);
  std::size_t polygons = 0, circles = 0;
  for (std::size_t at = 0; (at = text.find("<polygon", at)) != std::string::npos; ++at) ++polygons;
  for (std::size_t at = 0; (at = text.find("<circle", at)) != std::string::npos; ++at) ++circles;
  EXPECT_EQ(polygons, p.triangle_count() + 1);  // triangles and the domain outline
  EXPECT_EQ(circles, p.points.size());

  r = run_tessim({"pattern", "--outer", "2,5,3", "--inner", "4", "--partitioning", "integer", "-o", png.string(),
                  "--size", "200x180"},
                 scratch.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(png).substr(1, 3), "PNG");
  EXPECT_EQ(work.entries().size(), 2u);  // no temporary files left
}

TEST(PatternCli, BadInputIsAnError) {
  TempDir scratch, work;
  const fs::path svg = work.path() / "bad.svg";
  const std::vector<std::vector<std::string>> cases = {
      {"--outer", "1,2", "--inner", "3", "--partitioning", "integer"},
      {"--outer", "1,2,3,4", "--inner", "3", "--partitioning", "integer"},
      {"--outer", "1,two,3", "--inner", "3", "--partitioning", "integer"},
      {"--outer", "1,2,", "--inner", "3", "--partitioning", "integer"},
      {"--outer", "1,2,3", "--inner", "3x", "--partitioning", "integer"},
      {"--outer", "1,2,3", "--inner", "3", "--partitioning", "fractional"},
      {"--outer", "1,2,3", "--inner", "3", "--partitioning", "integer", "--winding", "left"},
      {"--outer", "1,2,3", "--inner", "3", "--partitioning", "integer", "-o", (work.path() / "p.txt").string()},
      {"--outer", "1,2,3", "--inner", "3", "--partitioning", "bogus", "-o", svg.string()},
  };
  for (const auto& args : cases) {
    std::vector<std::string> full = {"pattern"};
    full.insert(full.end(), args.begin(), args.end());
    const auto r = run_tessim(full, scratch.path());
    EXPECT_EQ(r.status, 2) << args[1] << " " << args[5];
    EXPECT_EQ(r.err.rfind("tessim: error: ", 0), 0u) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
  EXPECT_TRUE(work.empty());
}

}  // namespace
}  // namespace tessim
