// Chunked runs (sim/run/chunked.hpp, docs/statistics.md "Chunked runs"): against a single run of
// the same stream, the same vertices bit for bit and the same timing-independent counts, the
// statistics merged consistently (timeline included), and the cycles within the documented
// bound per chunk boundary. `tessim sim --chunks`: tests/cli/chunked_cli_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "sim/config/config.hpp"
#include "sim/run/chunked.hpp"
#include "sim/run/simulate.hpp"

namespace tessim::sim {
namespace {

const char* const kSphere = "/usr/share/assimp/models/STL/sphereWithHole.stl";

const Mesh& sphere() {
  static const Mesh m = load_mesh(kSphere);
  return m;
}

// A per-triangle factor stream that mixes small patches with large ones (the CPG far ahead of
// the TE, then behind it).
std::vector<std::uint8_t> mixed_factors(std::size_t n) {
  std::vector<std::uint8_t> f(n);
  std::uint64_t x = 12345;
  for (auto& L : f) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    L = static_cast<std::uint8_t>((x >> 60) < 3 ? 16 + (x >> 33) % 33 : 1 + (x >> 33) % 4);
  }
  return f;
}

std::string describe(const UnitConfig& c, bool adaptive) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "N=%d %s L=%s K=%d V=%d lat=%d cpg=%s stall=%.2f", c.int_blocks,
                std::string(to_string(c.normals)).c_str(), adaptive ? "mixed" : std::to_string(c.tess_factor).c_str(),
                c.gpe_cycles, c.te_contexts, c.int_latency, to_string(c.cpg_mapping).c_str(), c.gpe_stall_prob);
  return buf;
}

// The timeline of a merged run: at most 256 buckets, none wider than bucket_cycles(), classes
// summing to each bucket's cycles, every series to the run's totals.
void expect_timeline_consistent(const SimResult& r) {
  const Timeline& t = r.timeline;
  ASSERT_GT(t.size(), 0u);
  ASSERT_LE(t.size(), Timeline::kBuckets);
  std::uint64_t cycles = 0, int_busy = 0, vertices = 0, te_busy = 0, gpe_busy = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::uint64_t n = t.cycles(i);
    EXPECT_GE(n, 1u);
    EXPECT_LE(n, t.bucket_cycles()) << "bucket " << i;
    EXPECT_EQ(t.bucket(i).te.total(), n) << "bucket " << i;
    EXPECT_EQ(t.bucket(i).gpe.total(), n) << "bucket " << i;
    cycles += n;
    int_busy += t.bucket(i).int_busy;
    vertices += t.bucket(i).vertices;
    te_busy += t.bucket(i).te[TeClass::Busy];
    gpe_busy += t.bucket(i).gpe[GpeClass::Busy];
  }
  std::uint64_t busy = 0;
  for (std::uint64_t b : r.unit.int_busy_used()) busy += b;
  EXPECT_EQ(cycles, r.unit.cycles);
  EXPECT_EQ(int_busy, busy);
  EXPECT_EQ(vertices, r.unit.vertices_out);
  EXPECT_EQ(te_busy, r.unit.te[TeClass::Busy]);
  EXPECT_EQ(gpe_busy, r.gpe[GpeClass::Busy]);
}

// One configuration, single and chunked in 2, 3 and 4 chunks.
void check(const UnitConfig& cfg, const std::vector<std::uint8_t>& factors = {}, bool errors = false) {
  const Mesh& mesh = sphere();
  const std::string what = describe(cfg, !factors.empty());
  SCOPED_TRACE(what);
  std::vector<VertexFx> single_vertices;
  SimHooks hooks;
  hooks.measure_errors = errors;
  hooks.on_vertex = [&](const VertexFx& v) { single_vertices.push_back(v); };
  const SimResult single = simulate(mesh, cfg, hooks, factors);
  std::uint64_t single_busy = 0;
  for (std::uint64_t b : single.unit.int_busy_used()) single_busy += b;

  for (int k : {2, 3, 4}) {
    SCOPED_TRACE(std::to_string(k) + " chunks");
    std::vector<std::vector<VertexFx>> chunk_vertices(static_cast<std::size_t>(k));
    ChunkCallbacks callbacks;
    callbacks.hooks = [&](int chunk) {
      SimHooks h;
      h.measure_errors = errors;
      auto* out = &chunk_vertices[static_cast<std::size_t>(chunk)];
      h.on_vertex = [out](const VertexFx& v) { out->push_back(v); };
      return h;
    };
    int next_done = 0;
    callbacks.done = [&](int chunk) { EXPECT_EQ(chunk, next_done++) << "chunks done out of order"; };
    const SimResult chunked = simulate_chunked(mesh, cfg, k, callbacks, factors);
    EXPECT_EQ(next_done, k);

    // Every vertex, bit for bit, in the same order.
    std::vector<VertexFx> vertices;
    for (const auto& c : chunk_vertices) vertices.insert(vertices.end(), c.begin(), c.end());
    ASSERT_EQ(vertices.size(), single_vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
      ASSERT_EQ(vertices[i], single_vertices[i]) << "vertex " << i << ": " << sim::describe(vertices[i]);

    // What does not depend on timing.
    EXPECT_EQ(chunked.triangles, single.triangles);
    EXPECT_EQ(chunked.unit.triangles_in, single.unit.triangles_in);
    EXPECT_EQ(chunked.unit.vertices_out, single.unit.vertices_out);
    EXPECT_EQ(chunked.gpe.vertices, single.gpe.vertices);
    std::uint64_t busy = 0;
    for (std::uint64_t b : chunked.unit.int_busy_used()) busy += b;
    EXPECT_EQ(busy, single_busy) << "operations issued";
    EXPECT_EQ(chunked.degenerate_patches, single.degenerate_patches);
    EXPECT_EQ(chunked.zero_normals, single.zero_normals);
    EXPECT_EQ(chunked.cpg_tag_cycles, single.cpg_tag_cycles);
    EXPECT_EQ(chunked.factors.uniform, single.factors.uniform);
    EXPECT_EQ(chunked.factors.vertices, single.factors.vertices);
    EXPECT_EQ(chunked.factors.patches_with_factor, single.factors.patches_with_factor);
    EXPECT_EQ(chunked.cpg_cycles, single.cpg_cycles);
    EXPECT_EQ(chunked.config, cfg);
    if (cfg.cpg_mapping == CpgMapping::Dedicated) {
      EXPECT_EQ(chunked.unit.cpg[CpgClass::Busy], single.unit.cpg[CpgClass::Busy]) << "C + 1 per triangle";
    }
    // The classes of every block still sum to the cycles.
    for (const CounterBlockInfo& b : kCounterBlocks) {
      if (b.classes && b.in_unit && b.block != CounterBlock::Int) {
        EXPECT_EQ(class_total(chunked.unit, b.block), chunked.unit.cycles) << b.label;
      }
    }
    EXPECT_EQ(chunked.gpe.total(), chunked.unit.cycles);
    EXPECT_EQ(chunked.gpe.cycles, chunked.unit.cycles);
    for (std::uint64_t b : chunked.unit.int_busy_used()) EXPECT_LE(b, chunked.unit.cycles);
    std::uint64_t chunk_sum = 0;
    for (std::uint64_t c : chunked.chunk_cycles) chunk_sum += c;
    EXPECT_EQ(chunked.chunk_cycles.size(), static_cast<std::size_t>(k));
    EXPECT_EQ(chunk_sum, chunked.unit.cycles);
    expect_timeline_consistent(chunked);

    if (errors) {
      ASSERT_TRUE(chunked.errors && single.errors);
      const ErrorStats &a = chunked.errors->mesh, &b = single.errors->mesh;
      EXPECT_EQ(a.vertices, b.vertices);
      EXPECT_EQ(a.normals_compared, b.normals_compared);
      EXPECT_EQ(a.position_max, b.position_max);
      EXPECT_EQ(a.normal_angle_max, b.normal_angle_max);
      EXPECT_NEAR(a.position_rms, b.position_rms, 1e-12 * b.position_rms);
      EXPECT_NEAR(a.normal_angle_rms, b.normal_angle_rms, 1e-12 * b.normal_angle_rms);
      EXPECT_EQ(chunked.errors->arithmetic.beyond_bound, single.errors->arithmetic.beyond_bound);
      EXPECT_EQ(chunked.errors->arithmetic.stats.position_max, single.errors->arithmetic.stats.position_max);
      EXPECT_EQ(chunked.errors->arithmetic.worst, single.errors->arithmetic.worst);
    }

    // Cycles: within the bound per boundary.
    const ChunkBoundaryBound bound = chunk_boundary_bound(cfg, single.factors.uniform);
    const auto boundaries = static_cast<std::int64_t>(k - 1);
    const std::int64_t diff =
        static_cast<std::int64_t>(chunked.unit.cycles) - static_cast<std::int64_t>(single.unit.cycles);
    double slack = 0;  // random stalls: chunks after the first draw others than the single run
    if (cfg.gpe_stall_prob > 0) {
      const double p = cfg.gpe_stall_prob;
      slack = 6 * std::sqrt(static_cast<double>(chunked.unit.cycles - chunked.chunk_cycles[0]) * p) / (1 - p);
    }
    std::printf("[chunked] %-62s chunks %d: single %9llu chunked %9llu diff %+6lld (%+.1f per boundary; bound -%llu..+%llu)\n",
                what.c_str(), k, static_cast<unsigned long long>(single.unit.cycles),
                static_cast<unsigned long long>(chunked.unit.cycles), static_cast<long long>(diff),
                static_cast<double>(diff) / static_cast<double>(boundaries), static_cast<unsigned long long>(bound.shorter),
                static_cast<unsigned long long>(bound.longer));
    EXPECT_LE(static_cast<double>(diff), static_cast<double>(boundaries * static_cast<std::int64_t>(bound.longer)) + slack);
    EXPECT_GE(static_cast<double>(diff), -static_cast<double>(boundaries * static_cast<std::int64_t>(bound.shorter)) - slack);
    if (cfg.gpe_stall_prob == 0 && bound.shorter == 0) {
      EXPECT_GE(chunked.unit.cycles, single.unit.cycles) << "a chunk never overlaps its fill with the drain before it";
    }
  }
}

UnitConfig config(int N, NormalMode mode, int L, int K = 1) {
  UnitConfig c;
  c.int_blocks = N;
  c.normals = mode;
  c.tess_factor = L;
  c.gpe_cycles = K;
  return c;
}

TEST(Chunked, SameVerticesAndCountsCyclesWithinTheBound) {
  for (int N : {1, 2, 4})
    for (NormalMode mode : {NormalMode::Linear, NormalMode::Reflect, NormalMode::Quadratic})
      for (int L : {2, 12}) check(config(N, mode, L));
}

TEST(Chunked, PerTriangleFactors) {
  const std::vector<std::uint8_t> factors = mixed_factors(sphere().triangle_count());
  for (int N : {1, 4})
    for (NormalMode mode : {NormalMode::Linear, NormalMode::Quadratic}) check(config(N, mode, 4), factors);
}

TEST(Chunked, GeometryEngineBoundAndGpeMapping) {
  check(config(2, NormalMode::Quadratic, 6, 40));   // the GPE's countdown outlasts a chunk's fill
  check(config(8, NormalMode::Reflect, 3, 300));
  UnitConfig gpe = config(4, NormalMode::Quadratic, 8, 4);
  gpe.cpg_mapping = CpgMapping::Gpe;
  check(gpe);
  UnitConfig slow = config(2, NormalMode::Quadratic, 16);
  slow.te_contexts = 1;
  slow.int_latency = 3;
  check(slow);
}

TEST(Chunked, RandomStalls) {
  UnitConfig c = config(2, NormalMode::Quadratic, 8, 2);
  c.gpe_stall_prob = 0.3;
  check(c);
}

TEST(Chunked, ErrorsMerged) { check(config(2, NormalMode::Quadratic, 5), {}, true); }

// The first chunk is the single run's beginning, cycle for cycle: nothing after it in the stream
// can delay it (in-order FIFOs and CPG, the oldest context first, the GPE's draws per cycle).
TEST(Chunked, FirstChunkIsTheSingleRunsPrefix) {
  struct LastAcceptance : CycleObserver {
    std::uint64_t vertices = 0, target = 0, cycles = 0;
    bool on_cycle(const Unit& unit, const GpeCycle& g) override {
      if (g.accepted && ++vertices == target) cycles = unit.activity().cycle + 1;
      return vertices < target;
    }
  } watch;
  UnitConfig c = config(2, NormalMode::Quadratic, 6, 3);
  c.gpe_stall_prob = 0.1;
  const std::vector<std::uint64_t> starts = chunk_starts(sphere().triangle_count(), 3);
  watch.target = starts[1] * static_cast<std::uint64_t>(pattern_vertex_count(6));
  SimHooks hooks;
  hooks.observers.push_back(&watch);
  simulate(sphere(), c, hooks);
  const SimResult chunked = simulate_chunked(sphere(), c, 3);
  EXPECT_EQ(chunked.chunk_cycles[0], watch.cycles);
}

TEST(Chunked, ChunkStartsAreContiguousAndBalanced) {
  EXPECT_EQ(chunk_starts(10, 3), (std::vector<std::uint64_t>{0, 4, 7, 10}));
  EXPECT_EQ(chunk_starts(4, 4), (std::vector<std::uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(chunk_starts(7, 1), (std::vector<std::uint64_t>{0, 7}));
  EXPECT_THROW(chunk_starts(3, 4), std::logic_error);
}

TEST(Chunked, BadInputOfALaterChunkIsReportedAsBySingleRun) {
  // Widths too narrow for the mesh: a single run throws at the first saturated patch; a chunked
  // run reports the same one, whichever chunk finishes first.
  UnitConfig c = config(2, NormalMode::Quadratic, 2);
  c.format.coord_int_bits = 1;
  std::string single, chunked;
  try {
    simulate(sphere(), c);
  } catch (const std::exception& e) {
    single = e.what();
  }
  try {
    simulate_chunked(sphere(), c, 4);
  } catch (const std::exception& e) {
    chunked = e.what();
  }
  EXPECT_EQ(chunked, single);
}

}  // namespace
}  // namespace tessim::sim
