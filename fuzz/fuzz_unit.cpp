// The cycle model under libFuzzer: a configuration (N, Λ, V, K, FIFO depths, CPG mapping, normal
// mode, stall probability) and a stream of triangles with arbitrary in-range coordinates and
// factors, all from the input bytes. Invariants checked on every input:
// - every vertex leaves once, in patch order and pattern order, the last one flagged last;
// - the run ends (no hang) and every triangle is taken;
// - the statistics add up: each block's classes sum to the cycles (every block of classes of the
//   counter registry, each INT block on its own), the GPE's classes to the cycles, vertices out
//   to the stream's vertex count;
// - fast-forward (docs/microarchitecture.md §11) gives the same counters as plain clocking.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "model/pattern.hpp"
#include "sim/config/config.hpp"
#include "sim/run/testbench.hpp"
#include "sim/unit/unit.hpp"

namespace {

using namespace tessim;
using namespace tessim::sim;

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz_unit: invariant violated: %s\n", what);
  std::abort();
}

struct Outcome {
  UnitCounters unit;
  GpeStats gpe;
};

Outcome run(const UnitConfig& cfg, const std::vector<TriangleFx>& stream, bool fast_forward) {
  Unit unit(cfg);
  Testbench tb(stream, cfg);
  std::uint32_t expect_id = 0;
  int expect_index = 0;
  std::uint64_t cycles = 0;
  const std::uint64_t limit = 4'000'000;
  while (!tb.done()) {
    if (fast_forward) {
      const std::uint64_t n = tb.fast_forward(unit, limit - cycles);
      cycles += n;
      if (n > 0) continue;
    }
    const UnitInputs& in = tb.inputs(unit);
    if (tb.gpe_cycle().accepted) {
      const VertexFx& v = unit.vtx();
      if (expect_id >= stream.size() || v.id != expect_id) fail("vertex of an unexpected patch");
      const int L = stream[expect_id].L;
      if (v.L != L || pattern_index(v.j, v.k, L) != expect_index) fail("vertex out of pattern order");
      const bool last = expect_index == pattern_vertex_count(L) - 1;
      if (v.last != last) fail("last flag");
      if (last) {
        ++expect_id;
        expect_index = 0;
      } else {
        ++expect_index;
      }
    }
    unit.tick(in);
    if (++cycles >= limit) fail("no end within the cycle limit");
  }
  if (expect_id != stream.size()) fail("vertices missing");
  return {unit.stats(), tb.gpe().stats()};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  UnitConfig cfg;
  cfg.int_blocks = in.ConsumeIntegralInRange(1, 6);
  cfg.int_latency = in.ConsumeIntegralInRange(1, 4);
  cfg.te_contexts = in.ConsumeIntegralInRange(1, 8);
  cfg.gpe_cycles = in.ConsumeIntegralInRange(1, 12);
  cfg.tri_fifo_depth = in.ConsumeIntegralInRange(1, 4);
  cfg.vtx_fifo_depth = in.ConsumeIntegralInRange(1, 4);
  cfg.cp_buffers = in.ConsumeIntegralInRange(1, 4);
  cfg.cpg_mapping = in.ConsumeBool() ? CpgMapping::Gpe : CpgMapping::Dedicated;
  cfg.cpg_gpe_cycles = in.ConsumeIntegralInRange(1, 80);
  const int copies = in.ConsumeIntegralInRange(1, 4);  // the GE mapping has one CPG
  cfg.cpg.copies = cfg.cpg_mapping == CpgMapping::Dedicated ? copies : 1;
  const bool product_reg = in.ConsumeBool();  // registered products: a dedicated CPG's timing
  cfg.cpg.product_reg = cfg.cpg_mapping == CpgMapping::Dedicated && product_reg ? 1 : 0;
  static constexpr NormalMode kModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};
  cfg.normals = kModes[in.ConsumeIntegralInRange(0, 2)];
  cfg.gpe_stall_prob = in.ConsumeIntegralInRange(0, 4) * 0.15;
  cfg.seed = in.ConsumeIntegral<std::uint8_t>();
  cfg.validate("fuzz");

  const NumberFormat& f = cfg.format;
  std::vector<TriangleFx> stream;
  const std::size_t count = in.ConsumeIntegralInRange<std::size_t>(1, 12);
  for (std::size_t t = 0; t < count && in.remaining_bytes() > 0; ++t) {
    TriangleFx tri;
    for (auto& p : tri.p)
      for (auto& c : p) c = in.ConsumeIntegralInRange<std::int64_t>(f.coord_min(), f.coord_max());
    for (auto& n : tri.n)
      for (auto& c : n) c = in.ConsumeIntegralInRange<std::int64_t>(f.coord_min(), f.coord_max());
    tri.L = in.ConsumeIntegralInRange(1, 10);
    tri.id = static_cast<std::uint32_t>(t);
    stream.push_back(tri);
  }
  if (stream.empty()) return 0;

  const Outcome plain = run(cfg, stream, false);
  const UnitCounters& u = plain.unit;
  std::uint64_t vertices = 0;
  for (const TriangleFx& t : stream) vertices += static_cast<std::uint64_t>(pattern_vertex_count(t.L));
  if (u.vertices_out != vertices) fail("vertices_out");
  if (u.triangles_in != stream.size()) fail("triangles_in");
  // A cycle takes a triangle, refuses one, or has none offered.
  if (u.tri_stalls + u.triangles_in > u.cycles) fail("tri_stalls");
  // Every block of classes of the registry (sim/base/counter_registry.hpp): its classes sum to
  // the cycles, per INT block for the INT blocks, whose busy cannot exceed the cycles.
  for (const CounterBlockInfo& b : kCounterBlocks) {
    if (!b.classes || !b.in_unit) continue;
    const int instances = b.block == CounterBlock::Int ? u.int_blocks : 1;
    for (int i = 0; i < instances; ++i)
      if (class_total(u, b.block, i) != u.cycles) {
        std::fprintf(stderr, "fuzz_unit: %s block %d\n", b.label, i);
        fail("a block's classes do not sum to the cycles");
      }
  }
  for (std::uint64_t busy : u.int_busy_used())
    if (busy > u.cycles) fail("INT block busy beyond the cycles");
  const GpeStats& g = plain.gpe;
  if (g.cycles != u.cycles || g.total() != g.cycles) fail("GPE classes");
  if (g.vertices != vertices) fail("GPE vertices");

  const Outcome ff = run(cfg, stream, true);
  if (!(ff.unit == plain.unit) || !(ff.gpe == plain.gpe)) fail("fast-forward changed the counters");
  return 0;
}
