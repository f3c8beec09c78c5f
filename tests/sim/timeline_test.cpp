// The statistics over time (sim/values/timeline.hpp, docs/statistics.md "timeline"): the buckets
// add up to the run's totals exactly, whether the run is shorter than the bucket table or long
// enough to merge it many times, with and without fast-forward; the bucket rule itself on a bare
// Timeline.
#include <gtest/gtest.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "sim/config/config.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/timeline.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
const char* const kSphere = "/usr/share/assimp/models/STL/sphereWithHole.stl";

const Mesh& mesh_at(const char* path) {
  static std::vector<std::pair<std::string, Mesh>> cache;
  for (const auto& [p, m] : cache)
    if (p == path) return m;
  cache.emplace_back(path, load_mesh(path));
  return cache.back().second;
}

Mesh one_triangle() {
  Mesh m;
  m.source = "one triangle";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.2}};
  m.normals = {{0, 0, 1}, {0.3, 0, 0.954}, {0, 0.3, 0.954}};
  for (auto& n : m.normals) n = glm::normalize(n);
  m.triangles = {{0, 1, 2}};
  return m;
}

// Every counter summed over the buckets equals the run's total, and every bucket but the last
// holds bucket_cycles() cycles, each counted once per block.
void expect_sums(const SimResult& r) {
  const Timeline& t = r.timeline;
  ASSERT_LE(t.size(), Timeline::kBuckets);
  ASSERT_GT(t.size(), 0u);
  std::uint64_t cycles = 0, int_busy = 0, cpg_busy = 0, vertices = 0;
  ClassCounts<TeClass> te;
  ClassCounts<GpeClass> gpe;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Timeline::Bucket& b = t.bucket(i);
    const std::uint64_t n = t.cycles(i);
    if (i + 1 < t.size()) {
      EXPECT_EQ(n, t.bucket_cycles()) << "bucket " << i;
    }
    EXPECT_GE(n, 1u);
    EXPECT_LE(n, t.bucket_cycles());
    EXPECT_EQ(b.te.total(), n) << "bucket " << i;
    EXPECT_EQ(b.gpe.total(), n) << "bucket " << i;
    te += b.te;
    gpe += b.gpe;
    EXPECT_LE(b.int_busy, n * static_cast<std::uint64_t>(r.unit.int_blocks));
    EXPECT_LE(b.cpg_busy, n);
    EXPECT_LE(b.vertices, n);
    cycles += n;
    int_busy += b.int_busy;
    cpg_busy += b.cpg_busy;
    vertices += b.vertices;
  }
  std::uint64_t int_total = 0;
  for (std::uint64_t busy : r.unit.int_busy_used()) int_total += busy;
  EXPECT_EQ(cycles, r.unit.cycles);
  EXPECT_EQ(te, r.unit.te);
  EXPECT_EQ(int_busy, int_total);
  EXPECT_EQ(cpg_busy, r.unit.cpg[CpgClass::Busy]);
  EXPECT_EQ(vertices, r.unit.vertices_out);
  EXPECT_EQ(gpe, static_cast<const ClassCounts<GpeClass>&>(r.gpe));
  // The width is the smallest power of two that fits the run into the table.
  std::uint64_t width = 1;
  while (width * Timeline::kBuckets < r.unit.cycles) width *= 2;
  EXPECT_EQ(t.bucket_cycles(), width);
}

// The same sums on the JSON as `tessim sim --stats` writes it.
void expect_json_sums(const SimResult& r) {
  const nlohmann::json j = stats_json(r);
  const nlohmann::json& tl = j["timeline"];
  auto sum = [](const nlohmann::json& a) {
    std::uint64_t s = 0;
    for (const auto& v : a) s += v.get<std::uint64_t>();
    return s;
  };
  EXPECT_EQ(tl["buckets"].get<std::size_t>(), tl["cycles"].size());
  EXPECT_EQ(sum(tl["cycles"]), j["cycles"].get<std::uint64_t>());
  for (const auto& [k, v] : j["te"].items()) EXPECT_EQ(sum(tl["te"][k]), v.get<std::uint64_t>()) << k;
  for (GpeClass c : kGpeClasses)
    EXPECT_EQ(sum(tl["gpe"][to_string(c)]), j["gpe"][to_string(c)].get<std::uint64_t>()) << to_string(c);
  EXPECT_EQ(sum(tl["int_busy"]), j["int"]["busy"].get<std::uint64_t>());
  EXPECT_EQ(sum(tl["cpg_busy"]), j["cpg"]["busy"].get<std::uint64_t>());
  EXPECT_EQ(sum(tl["vertices_out"]), j["vertices_out"].get<std::uint64_t>());
}

struct Case {
  const char* name;
  const char* mesh;  // nullptr: one_triangle()
  int n = 2, L = 4, k = 8;
  CpgMapping mapping = CpgMapping::Dedicated;
  double stall = 0.0;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

UnitConfig config_of(const Case& c) {
  UnitConfig cfg;
  cfg.int_blocks = c.n;
  cfg.tess_factor = c.L;
  cfg.gpe_cycles = c.k;
  cfg.cpg_mapping = c.mapping;
  cfg.cpg_gpe_cycles = 1;
  cfg.gpe_stall_prob = c.stall;
  cfg.validate("timeline_test");
  return cfg;
}

class TimelineSums : public ::testing::TestWithParam<Case> {};

TEST_P(TimelineSums, BucketsAddUpToTheRunTotals) {
  const Case& c = GetParam();
  const UnitConfig cfg = config_of(c);
  const Mesh single = one_triangle();
  const Mesh& mesh = c.mesh ? mesh_at(c.mesh) : single;
  const SimResult r = simulate(mesh, cfg);
  expect_sums(r);
  expect_json_sums(r);
  if (!c.mesh) {
    // Shorter than the table: one cycle per bucket.
    ASSERT_LT(r.unit.cycles, Timeline::kBuckets);
    EXPECT_EQ(r.timeline.bucket_cycles(), 1u);
    EXPECT_EQ(r.timeline.size(), r.unit.cycles);
  } else {
    EXPECT_GT(r.timeline.size(), Timeline::kBuckets / 2);  // merged tables are at least half full
  }
  // Fast-forward takes quiet cycles in one step: the buckets are the same as cycle by cycle.
  SimHooks slow;
  slow.fast_forward = false;
  const SimResult s = simulate(mesh, cfg, slow);
  ASSERT_EQ(s.unit, r.unit);
  ASSERT_EQ(s.timeline.size(), r.timeline.size());
  EXPECT_EQ(s.timeline.bucket_cycles(), r.timeline.bucket_cycles());
  for (std::size_t i = 0; i < r.timeline.size(); ++i) {
    EXPECT_EQ(r.timeline.cycles(i), s.timeline.cycles(i)) << "bucket " << i;
    EXPECT_EQ(r.timeline.bucket(i), s.timeline.bucket(i)) << "bucket " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Runs, TimelineSums,
    ::testing::Values(
        // 1 triangle, L = 1, CPG on the GPE at 1 cycle: a few dozen cycles, fewer than the buckets.
        Case{"short_one_triangle", nullptr, 2, 1, 1, CpgMapping::Gpe},
        // sphereWithHole at L = 4: CPG-bound, long quiet stretches taken by fast-forward.
        Case{"sphere_L4_k1", kSphere, 2, 4, 1},
        // GPE-bound with a slow GPE: quiet stretches of many cycles crossing bucket boundaries.
        Case{"sphere_L8_k40", kSphere, 2, 8, 40},
        // Random GPE stalls (nothing fast-forwarded), the CPG on the GPE.
        Case{"sphere_gpe_mapping_stalls", kSphere, 4, 6, 4, CpgMapping::Gpe, 0.3},
        // Wuson at L = 8: about 1.3 M cycles, the table merged 13 times.
        Case{"wuson_L8_long", kWuson, 2, 8, 8}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

// A synthetic run: totals advanced cycle by cycle or a stretch at once, the buckets closed where
// simulate() closes them.
struct Feeder {
  Timeline t;
  Timeline::Bucket totals;
  std::uint64_t cycles = 0;

  static void add(Timeline::Bucket& to, const Timeline::Bucket& one, std::uint64_t n) {
    for (std::size_t c = 0; c < to.te.size(); ++c) to.te[c] += n * one.te[c];
    for (std::size_t c = 0; c < to.gpe.size(); ++c) to.gpe[c] += n * one.gpe[c];
    to.int_busy += n * one.int_busy;
    to.cpg_busy += n * one.cpg_busy;
    to.vertices += n * one.vertices;
  }
  void cycle(const Timeline::Bucket& one) {
    add(totals, one, 1);
    if (++cycles == t.next_boundary()) t.close(totals);
  }
  void stretch(const Timeline::Bucket& one, std::uint64_t n) {
    add(totals, one, n);
    cycles += n;
    if (cycles >= t.next_boundary()) t.close_within(totals, cycles, one);
  }
};

// Cycle c of a synthetic run: its classes and counts vary with c.
Timeline::Bucket cycle_of(std::uint64_t c) {
  Timeline::Bucket b;
  b.te[c % kTeClasses.size()] = 1;
  b.gpe[c % kGpeClasses.size()] = 1;
  b.int_busy = c % 3;
  b.cpg_busy = c % 2;
  b.vertices = c % 5 == 0;
  return b;
}

// The bucket rule: width 1 up to kBuckets cycles; a cycle past the last bucket merges pairs.
TEST(TimelineBuckets, MergePairsAndDoubleTheWidth) {
  Feeder empty;
  empty.t.finish(empty.totals, 0);
  EXPECT_EQ(empty.t.size(), 0u);

  Feeder f;
  for (std::uint64_t c = 0; c < Timeline::kBuckets; ++c) f.cycle(cycle_of(c));
  Feeder full = f;
  full.t.finish(full.totals, full.cycles);
  EXPECT_EQ(full.t.size(), Timeline::kBuckets);
  EXPECT_EQ(full.t.bucket_cycles(), 1u);
  EXPECT_EQ(full.t.cycles(Timeline::kBuckets - 1), 1u);
  EXPECT_EQ(full.t.bucket(7), cycle_of(7));

  f.cycle(cycle_of(Timeline::kBuckets));  // cycle 256: the first merge
  Feeder merged = f;
  merged.t.finish(merged.totals, merged.cycles);
  EXPECT_EQ(merged.t.bucket_cycles(), 2u);
  EXPECT_EQ(merged.t.size(), Timeline::kBuckets / 2 + 1);
  EXPECT_EQ(merged.t.cycles(0), 2u);
  EXPECT_EQ(merged.t.cycles(Timeline::kBuckets / 2), 1u);
  Timeline::Bucket first_two = cycle_of(0);
  Feeder::add(first_two, cycle_of(1), 1);
  EXPECT_EQ(merged.t.bucket(0), first_two);
  EXPECT_EQ(merged.t.bucket(Timeline::kBuckets / 2), cycle_of(Timeline::kBuckets));

  // 512 cycles fill 256 buckets of 2: no further merge until a cycle falls past them.
  while (f.cycles < 2 * Timeline::kBuckets) f.cycle(cycle_of(f.cycles));
  Feeder exact = f;
  exact.t.finish(exact.totals, exact.cycles);
  EXPECT_EQ(exact.t.size(), Timeline::kBuckets);
  EXPECT_EQ(exact.t.bucket_cycles(), 2u);
  EXPECT_EQ(exact.t.cycles(Timeline::kBuckets - 1), 2u);

  // A stretch of identical cycles taken at once fills the buckets as cycle by cycle.
  Feeder once, each;
  once.cycle(cycle_of(0));
  each.cycle(cycle_of(0));
  const Timeline::Bucket quiet = Timeline::quiet_cycle(TeClass::StarvedByCpg, CpgClass::Busy, GpeClass::Starved);
  const std::uint64_t n = 100000;
  once.stretch(quiet, n - 7);
  once.stretch(quiet, 7);
  for (std::uint64_t i = 0; i < n; ++i) each.cycle(quiet);
  once.t.finish(once.totals, once.cycles);
  each.t.finish(each.totals, each.cycles);
  EXPECT_EQ(once.t.bucket_cycles(), 512u);  // 100001 cycles: 196 buckets of 512
  ASSERT_EQ(once.t.size(), 196u);
  ASSERT_EQ(each.t.size(), once.t.size());
  for (std::size_t i = 0; i < once.t.size(); ++i) {
    EXPECT_EQ(once.t.cycles(i), each.t.cycles(i));
    EXPECT_EQ(once.t.bucket(i), each.t.bucket(i)) << "bucket " << i;
  }
}

}  // namespace
}  // namespace tessim::sim
