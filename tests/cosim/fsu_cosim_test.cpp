// The factor setup unit on raw factors (docs/rtl.md, FSU): the host sends factors processed by
// sim::d3d11_host_factors, which never produces some of what the unit's interface admitted — a
// fractional_odd inner factor of exactly 1 beside larger outer factors (the host raises it to
// 1 + 2^-16). Driven with it, RTL and cycle model parted at its first inner-ring point (the model
// placed it outside the domain): the interface now refuses it. Everything else the interface
// admits (sim::tri_pattern_problem: each factor in its partitioning's range, integers for
// integer) the RTL must treat as the cycle model does, so this drives it in lock-step with every
// admitted integer, and fractional factors at and next to every integer and at every half, in
// each factor slot.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "model/base/error.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::cosim {
namespace {

// Every factor value the interface admits at the integers, and the fractional ones around them:
// k, k + 2^-16, k + 1/2 and k + 1 - 2^-16 (integer partitioning: the integers alone).
std::vector<Fixed16> admitted_values(sim::TriPattern p) {
  const int lo = p == sim::TriPattern::fractional_even ? 2 : 1;
  const int hi = p == sim::TriPattern::fractional_odd ? 63 : 64;
  std::vector<Fixed16> v;
  for (int k = lo; k <= hi; ++k) {
    const Fixed16 f = k * kFixed16One;
    v.push_back(f);
    if (p == sim::TriPattern::integer || k == hi) continue;
    v.push_back(f + 1);
    v.push_back(f + kFixed16One / 2);
    v.push_back(f + kFixed16One - 1);
  }
  return v;
}

sim::TriangleFx with_factors(sim::TriangleFx t, sim::TriPattern p, Fixed16 o0, Fixed16 o1, Fixed16 o2, Fixed16 inner) {
  t.pattern = p;
  t.factors = {o0, o1, o2, inner};
  return t;
}

class FsuRawFactors : public ::testing::TestWithParam<sim::TriPattern> {};

TEST_P(FsuRawFactors, EveryAdmittedFactorAgrees) {
  const sim::TriPattern p = GetParam();
  const std::vector<Fixed16> values = admitted_values(p);
  const std::size_t n = values.size();
  CosimOptions o;
  o.variant = "n3_lat3";  // three CPG lanes: a short CPG (and a build the mutation campaign has)
  static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(o.variant)->config();
  o.unit.normals = NormalMode::Linear;  // the shortest CPG pass: the patterns are the subject
  o.unit.gpe_cycles = 1;
  o.seed = 3;
  const std::vector<sim::TriangleFx> shapes = random_triangles(16, o.seed, o.unit.format, 1, 0.0);
  std::vector<sim::TriangleFx> stream;
  int refused = 0;  // fractional_odd, inner exactly 1 beside a larger outer factor
  auto add = [&](Fixed16 o0, Fixed16 o1, Fixed16 o2, Fixed16 inner) {
    sim::TriangleFx t = with_factors(shapes[stream.size() % shapes.size()], p, o0, o1, o2, inner);
    t.id = static_cast<std::uint32_t>(stream.size());
    if (p == sim::TriPattern::fractional_odd && inner == kFixed16One && (o0 > inner || o1 > inner || o2 > inner)) {
      EXPECT_NE(sim::tri_pattern_problem(t).find("inner factor 0x10000 (16.16) is 1 beside an outer factor above 1"),
                std::string::npos)
          << "the interface refuses it";
      ++refused;
      return;
    }
    ASSERT_EQ(sim::tri_pattern_problem(t), "") << "the interface admits it";
    stream.push_back(t);
  };
  // Each value as the inner factor, beside outer factors drawn across the range; each value in
  // each outer slot beside the smallest inner factor (small patches, mostly the outer ring).
  for (std::size_t i = 0; i < n; ++i)
    add(values[(i * 7) % n], values[(i * 13 + 5) % n], values[(i * 29 + 11) % n], values[i]);
  // (fractional_odd: inner factor 1 is refused beside larger outer ones, so the sweep runs again
  // with the smallest inner factor it admits there, 1 + 2^-16.)
  for (const std::size_t small : {std::size_t{0}, std::size_t{1}}) {
    if (small == 1 && p != sim::TriPattern::fractional_odd) break;
    for (std::size_t i = 0; i < n; ++i)
      add(i % 3 == 0 ? values[i] : values[(i * 11) % n], i % 3 == 1 ? values[i] : values[(i * 5 + 3) % n],
          i % 3 == 2 ? values[i] : values[(i * 17 + 1) % n], values[small]);
  }
  // The smallest inner factor beside the largest and the smallest outer ones, and all at the bottom.
  add(values[n - 1], values[n - 1], values[n - 1], values[0]);
  add(values[0], values[0], values[n - 1], values[0]);
  add(values[0], values[0], values[0], values[0]);
  if (p == sim::TriPattern::fractional_odd) EXPECT_GT(refused, 100);
  else EXPECT_EQ(refused, 0);
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
  std::uint64_t vertices = 0;
  for (const sim::TriangleFx& t : stream) vertices += static_cast<std::uint64_t>(sim::patch_vertex_count(t));
  EXPECT_EQ(r.vertices, vertices);
  EXPECT_EQ(r.triangles, stream.size());
  RecordProperty("patches", static_cast<int>(stream.size()));
  RecordProperty("points", static_cast<int>(vertices));
  RecordProperty("refused", refused);
}

// The descriptor the contract excludes is bad input to the co-simulation and to the cycle model,
// refused before the run; the single triangle (all four factors 1) stays.
TEST(FsuRawFactorsContract, OddInnerOneBesideLargerOuterIsRefused) {
  CosimOptions o;
  o.variant = "n3_lat3";
  static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(o.variant)->config();
  std::vector<sim::TriangleFx> stream = random_triangles(2, 1, o.unit.format, 1, 0.0);
  stream[0] = with_factors(stream[0], sim::TriPattern::fractional_odd, kFixed16One, kFixed16One, kFixed16One, kFixed16One);
  stream[1] = with_factors(stream[1], sim::TriPattern::fractional_odd, kFixed16One, 3 * kFixed16One + 1, kFixed16One,
                           kFixed16One);
  try {
    run_cosim(stream, o);
    ADD_FAILURE() << "the stream must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos) << e.what();
  }
  stream.pop_back();
  EXPECT_TRUE(run_cosim(stream, o).passed) << "the single triangle is admitted";
  sim::Unit unit(o.unit);
  sim::UnitInputs in;
  in.tri_valid = true;
  in.tri = with_factors(stream[0], sim::TriPattern::fractional_odd, 2 * kFixed16One, kFixed16One, kFixed16One,
                        kFixed16One);
  EXPECT_THROW(unit.tick(in), std::invalid_argument);
}

// The pattern's structural corners, enumerated rather than drawn: every factor 1 on the outer edges
// with inner factors 2..8 (the first step into an inner ring comes straight off an outer ring of
// single segments), a factor just below, at and just above every integer 2..16 where a ring
// appears or a transition point splits, each alone in one slot beside 1s and all four together,
// in each partitioning the unit takes (pow2 reaches it as integer). Winding is the host's (the
// unit places points; the index list's order is made from them), so the unit's corners do not
// depend on it.
std::vector<std::array<Fixed16, 4>> d3d11_corners(sim::TriPattern p) {
  const Fixed16 one = kFixed16One, eps = p == sim::TriPattern::integer ? 0 : 1;
  const Fixed16 lo = p == sim::TriPattern::fractional_even ? 2 * one : one;  // the smallest factor
  const Fixed16 hi = p == sim::TriPattern::fractional_odd ? 63 * one : 64 * one;
  auto near = [&](int k) {  // k - 2^-16, k, k + 2^-16 within the partitioning's range
    std::vector<Fixed16> v;
    for (const Fixed16 f : {k * one - eps, k * one, k * one + eps})
      if (f >= lo && f <= hi && (v.empty() || v.back() != f)) v.push_back(f);
    return v;
  };
  std::vector<std::array<Fixed16, 4>> out;
  // Outer factors at the bottom (1, and 1 + 2^-16 where fractional), inner 2..8 and next to them.
  for (const Fixed16 outer : {lo, lo + eps})
    for (int k = 2; k <= 8; ++k)
      for (const Fixed16 inner : near(k)) out.push_back({outer, outer, outer, inner});
  // Next to every integer 2..16: alone in each slot beside the smallest factor, and in all four.
  for (int k = 2; k <= 16; ++k)
    for (const Fixed16 f : near(k)) {
      for (int slot = 0; slot < 4; ++slot) {
        // (fractional_odd refuses inner 1 beside a larger outer factor: its inner is 1 + 2^-16 there.)
        const Fixed16 inner = p == sim::TriPattern::fractional_odd && slot < 3 ? lo + eps : lo;
        std::array<Fixed16, 4> fs{lo, lo, lo, inner};
        fs[static_cast<std::size_t>(slot)] = f;
        out.push_back(fs);
      }
      out.push_back({f, f, f, f});
    }
  // Drop what the interface refuses (fractional_odd: inner 1 beside larger outer factors) and
  // repeats (integer partitioning: no neighbours).
  std::vector<std::array<Fixed16, 4>> admitted;
  for (const auto& fs : out) {
    sim::TriangleFx t;
    t.pattern = p;
    t.factors = fs;
    if (sim::tri_pattern_problem(t).empty() && std::find(admitted.begin(), admitted.end(), fs) == admitted.end())
      admitted.push_back(fs);
  }
  return admitted;
}

TEST(D3d11Corners, EveryBuildAgreesOnTheEnumeratedCorners) {
  std::size_t builds = 0;
  for (const std::string& name : rtl::rtl_variants()) {
    if (rtl::make_rtl_unit(name)->inject_bug() != 0) continue;  // the checker's own faults
    ++builds;
    CosimOptions o;
    o.variant = name;
    static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(name)->config();
    o.unit.normals = NormalMode::Linear;  // the shortest CPG pass: the patterns are the subject
    o.unit.gpe_cycles = 1;
    o.unit.gpe_stall_prob = 0.1;
    o.seed = o.unit.seed = 11;
    const std::vector<sim::TriangleFx> shapes = random_triangles(16, o.seed, o.unit.format, 1, 0.0);
    for (const sim::TriPattern p : {sim::TriPattern::integer, sim::TriPattern::fractional_odd,
                                    sim::TriPattern::fractional_even}) {
      const std::vector<std::array<Fixed16, 4>> corners = d3d11_corners(p);
      std::vector<sim::TriangleFx> stream;
      std::uint64_t vertices = 0;
      for (const auto& fs : corners) {
        sim::TriangleFx t = with_factors(shapes[stream.size() % shapes.size()], p, fs[0], fs[1], fs[2], fs[3]);
        t.id = static_cast<std::uint32_t>(stream.size());
        vertices += static_cast<std::uint64_t>(sim::patch_vertex_count(t));
        stream.push_back(t);
      }
      // integer: 7 + 15 * 5 less the 7 repeats; fractional: 2 * 7 * 3 + 15 * 3 * 5 less the neighbours
      // outside the range (fractional_even: 2 - 2^-16) and the repeats.
      RecordProperty(std::string(partitioning_name(sim::tri_partitioning(p))) + "_patches", static_cast<int>(stream.size()));
      EXPECT_GE(stream.size(), p == sim::TriPattern::integer ? 75u : 230u);  // 75, 246, 235
      const CosimReport r = run_cosim(stream, o);
      SCOPED_TRACE(name + " " + std::string(partitioning_name(sim::tri_partitioning(p))));
      ASSERT_TRUE(r.passed) << format_report(r, o);
      EXPECT_EQ(r.vertices, vertices);
    }
  }
  EXPECT_GE(builds, 1u);
}

// The enumeration holds the corners it names: inner 2..8 beside outer 1 in each partitioning that
// admits outer 1, and the neighbours of the integers where the partitioning has them.
TEST(D3d11Corners, TheEnumerationHasTheNamedCorners) {
  const Fixed16 one = kFixed16One;
  for (const sim::TriPattern p : {sim::TriPattern::integer, sim::TriPattern::fractional_odd}) {
    const auto c = d3d11_corners(p);
    for (int k = 2; k <= 8; ++k)
      EXPECT_NE(std::find(c.begin(), c.end(), std::array<Fixed16, 4>{one, one, one, k * one}), c.end()) << k;
  }
  const auto odd = d3d11_corners(sim::TriPattern::fractional_odd);
  for (int k = 2; k <= 16; ++k)
    for (const Fixed16 f : {k * one - 1, k * one + 1})
      EXPECT_NE(std::find(odd.begin(), odd.end(), std::array<Fixed16, 4>{f, f, f, f}), odd.end()) << f;
  const auto even = d3d11_corners(sim::TriPattern::fractional_even);
  EXPECT_NE(std::find(even.begin(), even.end(), std::array<Fixed16, 4>{2 * one, 2 * one, 2 * one, 3 * one}),
            even.end());
}

INSTANTIATE_TEST_SUITE_P(Partitionings, FsuRawFactors,
                         ::testing::Values(sim::TriPattern::integer, sim::TriPattern::fractional_odd,
                                           sim::TriPattern::fractional_even),
                         [](const auto& info) {
                           return std::string(partitioning_name(sim::tri_partitioning(info.param)));
                         });

}  // namespace
}  // namespace tessim::cosim
