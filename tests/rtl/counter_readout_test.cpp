// The Verilated read-out of the counters (rtl/verilated/verilated_unit.hpp reads every row of
// sim/base/counter_registry.hpp that has an RTL counter from perf_ctr_o at its tess_pkg::ctr_e
// index): after co-simulated runs, every such row of the RTL equals the cycle model's, and each
// was counted (non-zero) in at least one run, so a row the read-out skipped (left 0) or read at
// another row's index could not pass. Rows without an RTL counter read 0 from the RTL.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::cosim {
namespace {

struct ReadoutRun {
  const char* build;
  int gpe_cycles;
  NormalMode mode;
  int max_L;
};

TEST(CounterReadout, EveryRowInTheRtlEqualsTheCycleModel) {
  // N = 1 and a fast GE: int_limited; latency 3 over 6 contexts: context_limited; a slow GE behind
  // a fast CPG (3 lanes, radix 2^8): blocked_by_gpe and a blocked CPG.
  const ReadoutRun runs[] = {{"n1", 1, NormalMode::Quadratic, 6},
                      {"n3_lat3", 1, NormalMode::Reflect, 6},
                      {"n2_l3r8", 16, NormalMode::Linear, 8}};
  std::vector<bool> counted(sim::kCounterRegistry.size(), false);
  std::uint64_t seed = 31;
  for (const ReadoutRun& run : runs) {
    SCOPED_TRACE(run.build);
    CosimOptions o;
    o.variant = run.build;
    static_cast<sim::HardwareConfig&>(o.unit) = rtl::make_rtl_unit(run.build)->config();
    o.unit.gpe_cycles = run.gpe_cycles;
    o.unit.normals = run.mode;
    o.seed = o.unit.seed = ++seed;
    const CosimReport r = run_cosim(random_triangles(12, o.seed, o.unit.format, run.max_L), o);
    EXPECT_TRUE(r.passed) << format_report(r, o);
    ASSERT_EQ(r.rtl_counters.int_blocks, o.unit.int_blocks);
    for (std::size_t row = 0; row < sim::kCounterRegistry.size(); ++row) {
      const sim::CounterRow& c = sim::kCounterRegistry[row];
      for (int i = 0; i < sim::counter_instances(r.model_counters, row); ++i) {
        const std::uint64_t model = sim::counter_value(r.model_counters, row, i);
        const std::uint64_t rtl = sim::counter_value(r.rtl_counters, row, i);
        if (c.has_rtl()) {
          EXPECT_EQ(rtl, model) << c.name << " [" << i << "] from perf_ctr_o at " << c.rtl;
          if (model > 0) counted[row] = true;
        } else if (sim::counter_slot(r.rtl_counters, row, i)) {
          EXPECT_EQ(rtl, 0u) << c.name << ": not in the RTL, nothing to read";
        }
      }
    }
  }
  for (std::size_t row = 0; row < sim::kCounterRegistry.size(); ++row) {
    const sim::CounterRow& c = sim::kCounterRegistry[row];
    if (c.has_rtl()) {
      EXPECT_TRUE(counted[row]) << c.name << " (" << c.rtl << ") was 0 in every run";
    }
  }
}

}  // namespace
}  // namespace tessim::cosim
