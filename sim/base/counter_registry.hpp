// The counter registry: one row per performance counter of the unit and per cycle class of its
// blocks (definitions: docs/microarchitecture.md §10; how they are reported: docs/statistics.md).
// Everything else is derived from these rows: the class enums and their names, the
// class-indexed counts (ClassCounts, UnitCounters in sim/values/unit_io.hpp), the statistics JSON keys
// and units and the summary lines (sim/run/simulate.cpp), the report's legend and colours
// (app/report_html.cpp), the read-out of the Verilated RTL's counter bus (rtl/verilated/
// verilated_unit.hpp, at rtl_counter_index), the co-simulation's comparison (cosim/checkers.cpp),
// `tessim schema`, and the invariant that each block's classes sum to the cycles
// (fuzz/fuzz_unit.cpp, the tests).
//
// Adding a class or a counter: its row here, the block that decides it (e.g. Te::classify in
// sim/blocks/te.hpp; a run counter's RunEvents bit in Unit::tick and Unit::skip), and in the RTL
// its enumerator in tess_pkg::ctr_e (rtl/tess_pkg.sv, at the same place in the order) and its
// increment in rtl/tess_unit.sv; docs/statistics.md has the list.
// tests/sim/counter_registry_test.cpp checks the rows against tess_pkg's enumerators.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

// One row: X(BLOCK, ID, KEY, UNIT, RTL, STACK, COLOUR, MEANING)
//   BLOCK   Run: one count per run · Int: one count per INT block · Te, Cpg, Gpe: the block's
//           class of each cycle (exactly one per cycle, so a block's classes sum to the cycles)
//   ID      the enumerator (RunCounter, IntClass, TeClass, CpgClass, GpeClass); a block's rows
//           are in the enum's order, for classes the priority order of §10 (first that applies)
//   KEY     the statistics JSON key (te.KEY, cpg.KEY, ...), the word of the summary and traces
//   UNIT    its unit in the statistics' "units" table
//   RTL     its enumerator in tess_pkg::ctr_e (rtl/tess_pkg.sv): where tess_unit's perf_ctr_o
//           carries it; or no_rtl: the GPE is not in the RTL, the RTL has only the dedicated
//           CPG (no wait_gpe), an INT block's idle is cycles - busy
//   STACK   its place in the report's stacked bars, from the bottom (useful work first)
//   COLOUR  its colour in the report (Okabe-Ito, distinguishable with the common colour-vision
//           deficiencies); "" for rows the report does not draw as classes
//   MEANING one line: the report's legend
#define TESSIM_RUN_COUNTERS(X)                                                                              \
  X(Run, Cycles, cycles, "cycles", CtrCycles, 0, "", "clock edges since reset")                         \
  X(Run, TrianglesIn, triangles_in, "triangles (the unit's input counter; equal to triangles after a whole run)", \
    CtrTriIn, 1, "", "triangles taken from the input stream (tri_valid and tri_ready)")                 \
  X(Run, VerticesOut, vertices_out, "vertices", CtrVtxOut, 2, "",                                      \
    "vertices the GPE accepted (vtx_valid and vtx_ready)")                                                 \
  X(Run, TriStalls, tri_stalls, "cycles", CtrTriStalls, 3, "",                                         \
    "cycles a triangle was offered and refused (tri_valid, TRI FIFO full): the unit's back-pressure on its input") \
  X(Run, VtxStalls, vtx_stalls, "cycles", CtrVtxStalls, 4, "",                                         \
    "cycles a vertex was offered and refused (vtx_valid, vtx_ready low): the geometry engine's back-pressure on the unit")

#define TESSIM_INT_CLASSES(X)                                                           \
  X(Int, Busy, busy, "cycles", CtrIntBusy, 0, "", "issued an op this cycle")       \
  X(Int, Idle, idle, "cycles", no_rtl, 1, "", "issued nothing")

#define TESSIM_TE_CLASSES(X)                                                                                   \
  X(Te, ContextLimited, context_limited, "cycles", CtrTeContextLimited, 2, "#D55E00",                    \
    "the oldest vertex waits on its dependence chain")                                                         \
  X(Te, IntLimited, int_limited, "cycles", CtrTeIntLimited, 1, "#E69F00",                                \
    "all INT blocks taken, a ready op waits")                                                                  \
  X(Te, Busy, busy, "cycles", CtrTeBusy, 0, "#009E73", "issued ops, no ready op left over")               \
  X(Te, BlockedByGpe, blocked_by_gpe, "cycles", CtrTeBlockedByGpe, 4, "#CC79A7",                        \
    "finished vertex, VTX FIFO full")                                                                          \
  X(Te, StarvedByCpg, starved_by_cpg, "cycles", CtrTeStarvedByCpg, 5, "#56B4E9",                        \
    "no vertex, CPG or TRI FIFO busy")                                                                         \
  X(Te, Idle, idle, "cycles", CtrTeIdle, 6, "#C8C8C8", "nothing to do")                                   \
  X(Te, Pipeline, pipeline, "cycles", CtrTePipeline, 3, "#F0E442", "results in flight, nothing ready")

#define TESSIM_CPG_CLASSES(X)                                                                          \
  X(Cpg, Busy, busy, "cycles", CtrCpgBusy, 0, "#009E73", "accept, compute, write")                \
  X(Cpg, Blocked, blocked, "cycles", CtrCpgBlocked, 1, "#CC79A7", "control points ready, buffer full") \
  X(Cpg, WaitGpe, wait_gpe, "cycles", no_rtl, 2, "#56B4E9", "waiting for a spare GPE cycle (gpe mapping)") \
  X(Cpg, Idle, idle, "cycles", CtrCpgIdle, 3, "#C8C8C8", "no triangle")

#define TESSIM_GPE_CLASSES(X)                                                                       \
  X(Gpe, Busy, busy, "cycles", no_rtl, 0, "#009E73", "accepting or processing a vertex")           \
  X(Gpe, Stalled, stalled, "cycles", no_rtl, 1, "#E69F00", "random stall")                         \
  X(Gpe, Cpg, cpg, "cycles", no_rtl, 2, "#0072B2", "spare cycle given to the CPG (gpe mapping)")   \
  X(Gpe, Starved, starved, "cycles", no_rtl, 3, "#D55E00", "ready, no vertex offered")

// Every row, block by block (a block's rows are contiguous).
#define TESSIM_COUNTER_REGISTRY(X) \
  TESSIM_RUN_COUNTERS(X) TESSIM_INT_CLASSES(X) TESSIM_TE_CLASSES(X) TESSIM_CPG_CLASSES(X) TESSIM_GPE_CLASSES(X)

namespace tessim::sim {

#define TESSIM_REGISTRY_ENUMERATOR(BLOCK, ID, ...) ID,
// The unit's counts per run, and the classes of each block (doc §10), in priority order.
enum class RunCounter : std::uint8_t { TESSIM_RUN_COUNTERS(TESSIM_REGISTRY_ENUMERATOR) };
enum class IntClass : std::uint8_t { TESSIM_INT_CLASSES(TESSIM_REGISTRY_ENUMERATOR) };
enum class TeClass : std::uint8_t { TESSIM_TE_CLASSES(TESSIM_REGISTRY_ENUMERATOR) };
enum class CpgClass : std::uint8_t { TESSIM_CPG_CLASSES(TESSIM_REGISTRY_ENUMERATOR) };
enum class GpeClass : std::uint8_t { TESSIM_GPE_CLASSES(TESSIM_REGISTRY_ENUMERATOR) };
#undef TESSIM_REGISTRY_ENUMERATOR

enum class CounterBlock : std::uint8_t { Run, Int, Te, Cpg, Gpe };

// What a block is: its label (summary, messages), the JSON object of its classes, whether the
// unit (and so the RTL) keeps its counts, and how many cycle classes it has.
struct CounterBlockInfo {
  CounterBlock block;
  const char* label;  // "TE"
  const char* key;    // "te": statistics JSON object and co-simulation prefix (te_busy)
  bool classes;       // its rows are cycle classes, summing to the cycles
  bool in_unit;       // counted by the unit (UnitCounters), not by the testbench's GPE model
};
inline constexpr std::array<CounterBlockInfo, 5> kCounterBlocks{{
    {CounterBlock::Run, "run", "", false, true},
    {CounterBlock::Int, "INT", "int", true, true},
    {CounterBlock::Te, "TE", "te", true, true},
    {CounterBlock::Cpg, "CPG", "cpg", true, true},
    {CounterBlock::Gpe, "GPE", "gpe", true, false},
}};
constexpr const CounterBlockInfo& block_info(CounterBlock b) { return kCounterBlocks[static_cast<std::size_t>(b)]; }

struct CounterRow {
  CounterBlock block;
  std::uint8_t index;     // the enumerator's value
  const char* key;        // statistics JSON key within its block
  const char* name;       // qualified by its block (te_busy; cycles): co-simulation, `tessim schema`
  const char* unit;
  std::string_view rtl;   // its tess_pkg::ctr_e enumerator; empty: the RTL does not count it
  int stack;
  const char* colour;
  const char* meaning;
  constexpr bool has_rtl() const { return !rtl.empty(); }
};

// RTL as a string: "no_rtl" is none.
constexpr std::string_view registry_rtl(std::string_view p) { return p == "no_rtl" ? std::string_view{} : p; }

#define TESSIM_REGISTRY_ENUM_Run RunCounter
#define TESSIM_REGISTRY_ENUM_Int IntClass
#define TESSIM_REGISTRY_ENUM_Te TeClass
#define TESSIM_REGISTRY_ENUM_Cpg CpgClass
#define TESSIM_REGISTRY_ENUM_Gpe GpeClass
#define TESSIM_REGISTRY_NAME_Run(KEY) #KEY
#define TESSIM_REGISTRY_NAME_Int(KEY) "int_" #KEY
#define TESSIM_REGISTRY_NAME_Te(KEY) "te_" #KEY
#define TESSIM_REGISTRY_NAME_Cpg(KEY) "cpg_" #KEY
#define TESSIM_REGISTRY_NAME_Gpe(KEY) "gpe_" #KEY
#define TESSIM_REGISTRY_ROW(BLOCK, ID, KEY, UNIT, RTL, STACK, COLOUR, MEANING)                         \
  CounterRow{CounterBlock::BLOCK, static_cast<std::uint8_t>(TESSIM_REGISTRY_ENUM_##BLOCK::ID), #KEY,     \
             TESSIM_REGISTRY_NAME_##BLOCK(KEY), UNIT, registry_rtl(#RTL), STACK, COLOUR, MEANING},
inline constexpr std::array kCounterRegistry{TESSIM_COUNTER_REGISTRY(TESSIM_REGISTRY_ROW)};
#undef TESSIM_REGISTRY_ROW

// ---- derived: rows of a block, enums, names

constexpr std::size_t row_count(CounterBlock b) {
  std::size_t n = 0;
  for (const CounterRow& r : kCounterRegistry) n += r.block == b;
  return n;
}
constexpr std::size_t first_row(CounterBlock b) {
  for (std::size_t i = 0; i < kCounterRegistry.size(); ++i)
    if (kCounterRegistry[i].block == b) return i;
  return kCounterRegistry.size();
}
// The row of a tess_pkg::ctr_e enumerator (kCounterRegistry.size() when none has it).
constexpr std::size_t row_of_rtl(std::string_view rtl) {
  for (std::size_t i = 0; i < kCounterRegistry.size(); ++i)
    if (kCounterRegistry[i].rtl == rtl) return i;
  return kCounterRegistry.size();
}

// ---- derived: the RTL's counter bus (tess_unit's perf_ctr_o, tess_pkg::ctr_e)

// The rows with an RTL counter in registry order, the INT block row (N counters) last: the order
// of tess_pkg::ctr_e, so the counters a row has do not move with N.
constexpr bool per_int_block(const CounterRow& r) { return r.block == CounterBlock::Int; }
// Counters before the INT block's (tess_pkg::NumScalarCtrs).
inline constexpr std::size_t kRtlScalarCounters = [] {
  std::size_t n = 0;
  for (const CounterRow& r : kCounterRegistry) n += r.has_rtl() && !per_int_block(r);
  return n;
}();
// Index in the bus of row `row`'s (first) counter; INT block i's at that + i.
constexpr std::size_t rtl_counter_index(std::size_t row) {
  if (per_int_block(kCounterRegistry[row])) return kRtlScalarCounters;
  std::size_t k = 0;
  for (std::size_t i = 0; i < row; ++i) k += kCounterRegistry[i].has_rtl() && !per_int_block(kCounterRegistry[i]);
  return k;
}

// The block of each enum.
template <class E>
struct CounterEnum;
template <>
struct CounterEnum<RunCounter> { static constexpr CounterBlock block = CounterBlock::Run; };
template <>
struct CounterEnum<IntClass> { static constexpr CounterBlock block = CounterBlock::Int; };
template <>
struct CounterEnum<TeClass> { static constexpr CounterBlock block = CounterBlock::Te; };
template <>
struct CounterEnum<CpgClass> { static constexpr CounterBlock block = CounterBlock::Cpg; };
template <>
struct CounterEnum<GpeClass> { static constexpr CounterBlock block = CounterBlock::Gpe; };

template <class E>
constexpr std::size_t kEnumSize = row_count(CounterEnum<E>::block);

// Every enumerator of E, in order.
template <class E>
constexpr std::array<E, kEnumSize<E>> all_of() {
  std::array<E, kEnumSize<E>> a{};
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = static_cast<E>(i);
  return a;
}
inline constexpr auto kTeClasses = all_of<TeClass>();
inline constexpr auto kCpgClasses = all_of<CpgClass>();
inline constexpr auto kGpeClasses = all_of<GpeClass>();

template <class E>
constexpr const CounterRow& row_of(E e) {
  return kCounterRegistry[first_row(CounterEnum<E>::block) + static_cast<std::size_t>(e)];
}
constexpr const char* to_string(TeClass c) { return row_of(c).key; }
constexpr const char* to_string(CpgClass c) { return row_of(c).key; }
constexpr const char* to_string(GpeClass c) { return row_of(c).key; }

// ---- derived: counts indexed by class

// Cycles per class of one block, indexed by its enum (or by position). Counting a cycle is one
// array increment.
template <class E>
struct ClassCounts {
  std::array<std::uint64_t, kEnumSize<E>> n{};

  static constexpr std::size_t size() { return kEnumSize<E>; }
  constexpr std::uint64_t& operator[](E c) { return n[static_cast<std::size_t>(c)]; }
  constexpr std::uint64_t operator[](E c) const { return n[static_cast<std::size_t>(c)]; }
  constexpr std::uint64_t& operator[](std::size_t i) { return n[i]; }
  constexpr std::uint64_t operator[](std::size_t i) const { return n[i]; }
  constexpr auto begin() const { return n.begin(); }
  constexpr auto end() const { return n.end(); }

  constexpr std::uint64_t total() const {
    std::uint64_t s = 0;
    for (std::uint64_t x : n) s += x;
    return s;
  }
  constexpr ClassCounts& operator+=(const ClassCounts& o) {
    for (std::size_t i = 0; i < n.size(); ++i) n[i] += o.n[i];
    return *this;
  }
  friend constexpr ClassCounts operator-(ClassCounts a, const ClassCounts& b) {
    for (std::size_t i = 0; i < a.n.size(); ++i) a.n[i] -= b.n[i];
    return a;
  }
  bool operator==(const ClassCounts&) const = default;
};

// ---- checks of the table itself

namespace registry_check {
constexpr bool same(const char* a, const char* b) { return std::string_view(a) == std::string_view(b); }
constexpr bool blocks_in_order() {
  for (std::size_t i = 0; i < kCounterBlocks.size(); ++i)
    if (static_cast<std::size_t>(kCounterBlocks[i].block) != i) return false;
  return true;
}
// Rows of a block contiguous, its indices 0..n-1 in order, its STACK a permutation of 0..n-1,
// keys and RTL enumerators unique.
constexpr bool rows_well_formed() {
  for (std::size_t i = 0; i < kCounterRegistry.size(); ++i) {
    const CounterRow& r = kCounterRegistry[i];
    if (static_cast<std::size_t>(r.index) != i - first_row(r.block)) return false;
    const auto n = static_cast<int>(row_count(r.block));
    if (r.stack < 0 || r.stack >= n) return false;
    for (std::size_t j = 0; j < i; ++j) {
      const CounterRow& o = kCounterRegistry[j];
      if (o.block == r.block && (same(o.key, r.key) || o.stack == r.stack)) return false;
      if (same(o.name, r.name)) return false;
      if (r.has_rtl() && o.rtl == r.rtl) return false;
    }
  }
  return true;
}
// One INT row in the RTL (busy; idle is cycles - busy): the bus has one counter per block after
// the scalar ones.
constexpr bool one_int_row_in_rtl() {
  std::size_t n = 0;
  for (const CounterRow& r : kCounterRegistry) n += r.has_rtl() && per_int_block(r);
  return n == 1;
}
static_assert(blocks_in_order());
static_assert(one_int_row_in_rtl(), "the RTL's counter bus has room for one per-INT-block counter (tess_pkg::CtrIntBusy)");
static_assert(rows_well_formed(), "counter registry: a block's rows must be contiguous, with unique keys, "
                                  "names, RTL enumerators and a STACK that is a permutation of 0..n-1");
}  // namespace registry_check

}  // namespace tessim::sim
