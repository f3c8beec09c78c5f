// The default co-simulation matrix (docs/verification.md, What CI runs): every fault-free RTL
// build, each with the parameters it was verilated with, under every stimulus that some class of
// bug needs to show — a fast and a slow geometry engine (blocked-by-GE accounting, full VTX FIFOs),
// random stalls, a saturating stream (the clamps), scalar tags (builds that take them) and D3D11
// patterns (builds with B >= 16). Streams are short: the matrix is about reaching each build in
// each state, the long runs are scripts/soak.py's.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::cosim {
namespace {

// Every fault-free build of rtl/CMakeLists.txt; MatrixCoversEveryBuild keeps the list complete.
const char* const kBuilds[] = {"n1",     "n2",      "n3",       "n4",       "n2_verif", "n3_lat3",
                               "n1_r4",  "n2_l3r8", "n4_l3r24", "n2_w28b20", "n1_w20b18"};

enum class Stimulus { FastGe, SlowGe, Stalls, Saturating, Tagged, D3D11 };
constexpr Stimulus kStimuli[] = {Stimulus::FastGe,     Stimulus::SlowGe, Stimulus::Stalls,
                                 Stimulus::Saturating, Stimulus::Tagged, Stimulus::D3D11};

const char* name_of(Stimulus s) {
  switch (s) {
    case Stimulus::FastGe: return "fast_ge";
    case Stimulus::SlowGe: return "slow_ge";
    case Stimulus::Stalls: return "stalls";
    case Stimulus::Saturating: return "saturating";
    case Stimulus::Tagged: return "tagged";
    default: return "d3d11";
  }
}

// One run of `build` under `stimulus`.
void run_stimulus(const char* build, Stimulus stimulus) {
  SCOPED_TRACE(std::string(build) + " " + name_of(stimulus));
  CosimOptions o;
  o.variant = build;
  static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(build)->config();
  o.seed = 7000 + static_cast<std::uint64_t>(stimulus);
  o.unit.seed = o.seed;
  // The geometry engine: K = 1 keeps up with any TE; K = 16 is slower than every build's TE
  // (N = 1 takes 11 cycles a linear vertex), so the VTX FIFO fills and the TE is blocked by it.
  o.unit.gpe_cycles = stimulus == Stimulus::SlowGe ? 16 : stimulus == Stimulus::FastGe ? 1 : 2;
  o.unit.gpe_stall_prob = stimulus == Stimulus::Stalls || stimulus == Stimulus::Tagged ? 0.3 : 0.0;
  constexpr NormalMode kModeOf[] = {NormalMode::Quadratic, NormalMode::Linear,    NormalMode::Reflect,
                                    NormalMode::Quadratic, NormalMode::Quadratic, NormalMode::Linear};
  o.unit.normals = kModeOf[static_cast<int>(stimulus)];
  const double extent = stimulus == Stimulus::Saturating ? 30.0 : 1.0;
  const int max_L = stimulus == Stimulus::Saturating ? 3 : 6;
  const std::size_t count = stimulus == Stimulus::Saturating ? 40 : 20;
  std::vector<sim::TriangleFx> stream = random_triangles(count, o.seed, o.unit.format, max_L, 0.1, extent,
                                                         stimulus == Stimulus::Tagged);
  if (stimulus == Stimulus::D3D11) assign_random_patterns(stream, o.seed, 10);
  const CosimReport r = run_cosim(stream, o);
  EXPECT_TRUE(r.passed) << format_report(r, o);
  std::uint64_t vertices = 0;
  for (const sim::TriangleFx& t : stream) vertices += static_cast<std::uint64_t>(sim::patch_vertex_count(t));
  EXPECT_EQ(r.vertices, vertices);
  // Each stimulus reached the state it is there for.
  if (stimulus == Stimulus::SlowGe) {
    EXPECT_GT(r.model_counters.te[sim::TeClass::BlockedByGpe], 0u) << "the TE must wait for the GE";
  }
  if (stimulus == Stimulus::Saturating) {
    EXPECT_GT(r.reference.saturated, 0u) << "the stream must saturate";
  }
  if (stimulus == Stimulus::Tagged) {
    EXPECT_GT(r.model_counters.cpg[sim::CpgClass::Busy],
              count * static_cast<std::uint64_t>(sim::cpg_cycles(o.unit.normals, o.unit.format, o.unit.cpg)))
        << "the tag pass must run";
  }
}

class CosimMatrix : public ::testing::TestWithParam<const char*> {};

// Every stimulus the build can take: tags only where the CPG takes them, D3D11 patterns only
// with B >= 16 (their points are 16.16).
TEST_P(CosimMatrix, AgreesUnderEveryStimulus) {
  const sim::HardwareConfig hw = rtl::make_rtl_unit(GetParam())->config();
  int runs = 0;
  for (const Stimulus s : kStimuli) {
    if (s == Stimulus::Tagged && hw.cpg_tags == 0) continue;
    if (s == Stimulus::D3D11 && hw.format.bary_bits < 16) continue;
    run_stimulus(GetParam(), s);
    ++runs;
  }
  EXPECT_GE(runs, 4);
}

INSTANTIATE_TEST_SUITE_P(EveryBuild, CosimMatrix, ::testing::ValuesIn(kBuilds),
                         [](const auto& info) { return std::string(info.param); });

// A build added to rtl/CMakeLists.txt joins the matrix: the list above must name every
// fault-free build there is.
TEST(CosimMatrixBuilds, MatrixCoversEveryBuild) {
  for (const std::string& v : rtl::rtl_variants()) {
    if (rtl::make_rtl_unit(v)->inject_bug() != 0) continue;
    EXPECT_TRUE(std::find(std::begin(kBuilds), std::end(kBuilds), v) != std::end(kBuilds))
        << v << " is not in the co-simulation matrix";
  }
}

}  // namespace
}  // namespace tessim::cosim
