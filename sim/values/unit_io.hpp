// The unit's boundary, shared by every implementation that runs in lock-step: the cycle
// model (sim/unit/unit.hpp) and the Verilated RTL (rtl/verilated/). Field meanings and bit widths:
// docs/microarchitecture.md §3; counter definitions: §10.
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <type_traits>

#include "sim/base/counter_registry.hpp"
#include "sim/base/fixed.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

constexpr int kMaxIntBlocks = 32;

// One output vertex as it leaves the VTX FIFO.
struct VertexFx {
  FxVec pos{};
  FxVec nrm{};            // unnormalized (2 n(u,v) for quadratic/reflect, linear field otherwise)
  std::int64_t u = 0;     // barycentric weights, B fraction bits
  std::int64_t v = 0;
  int j = 0, k = 0, L = 0;  // uniform pattern: lattice point and factor; D3D11: ring, edge, 0
  int index = 0;            // position in the patch's pattern order
  std::uint32_t id = 0;   // patch id from the input triangle
  bool last = false;      // last vertex of its patch
  std::uint8_t flags = 0; // FxFlag bits of the patch's control points
  bool operator==(const VertexFx&) const = default;
};

// The output vertex's fields as the RTL names its ports (vtx_<name>_o), each read as integers
// (`count` components): the co-simulation compares them in this order and `tessim schema`
// lists them.
struct VertexField {
  const char* name;
  int count;
  std::int64_t (*get)(const VertexFx&, int component);
};
inline constexpr std::array<VertexField, 11> kVertexFields{{
    {"vtx_pos", 3, [](const VertexFx& x, int c) -> std::int64_t { return x.pos[static_cast<std::size_t>(c)]; }},
    {"vtx_nrm", 3, [](const VertexFx& x, int c) -> std::int64_t { return x.nrm[static_cast<std::size_t>(c)]; }},
    {"vtx_u", 1, [](const VertexFx& x, int) -> std::int64_t { return x.u; }},
    {"vtx_v", 1, [](const VertexFx& x, int) -> std::int64_t { return x.v; }},
    {"vtx_j", 1, [](const VertexFx& x, int) -> std::int64_t { return x.j; }},
    {"vtx_k", 1, [](const VertexFx& x, int) -> std::int64_t { return x.k; }},
    {"vtx_l", 1, [](const VertexFx& x, int) -> std::int64_t { return x.L; }},
    {"vtx_index", 1, [](const VertexFx& x, int) -> std::int64_t { return x.index; }},
    {"vtx_id", 1, [](const VertexFx& x, int) -> std::int64_t { return x.id; }},
    {"vtx_last", 1, [](const VertexFx& x, int) -> std::int64_t { return x.last; }},
    {"vtx_flags", 1, [](const VertexFx& x, int) -> std::int64_t { return x.flags; }},
}};

// Inputs of one cycle.
struct UnitInputs {
  bool tri_valid = false;
  TriangleFx tri{};
  bool vtx_ready = false;
  bool cpg_step = false;  // gpe mapping only: the GPE has a spare cycle for CPG this cycle
};

// The counters both implementations keep (docs/microarchitecture.md §10): the cycle model's
// statistics and the RTL's perf_*_o outputs, compared every cycle and at the end of a
// co-simulation. One field per registry row (sim/base/counter_registry.hpp) that the unit
// counts: the run counts by their keys, INT busy per block, the TE's and the CPG's classes.
struct UnitCounters {
#define TESSIM_RUN_FIELD(BLOCK, ID, KEY, ...) std::uint64_t KEY = 0;
  TESSIM_RUN_COUNTERS(TESSIM_RUN_FIELD)  // cycles, triangles_in, vertices_out
#undef TESSIM_RUN_FIELD
  int int_blocks = 0;  // N: the entries of int_busy in use (the others stay 0)
  std::array<std::uint64_t, kMaxIntBlocks> int_busy{};
  ClassCounts<TeClass> te;
  ClassCounts<CpgClass> cpg;

  std::uint64_t int_idle(int block) const { return cycles - int_busy[static_cast<std::size_t>(block)]; }
  std::span<const std::uint64_t> int_busy_used() const {
    return {int_busy.data(), static_cast<std::size_t>(int_blocks)};
  }
  bool operator==(const UnitCounters&) const = default;
};

// Registry row `row` of k: how many instances it has (N for an INT block's row, else 1), where
// it is stored (nullptr when derived, an INT block's idle, or not the unit's, the GPE's), and
// its value.
constexpr int counter_instances(const UnitCounters& k, std::size_t row) {
  return kCounterRegistry[row].block == CounterBlock::Int ? k.int_blocks : 1;
}
template <class Counters>
  requires std::same_as<std::remove_const_t<Counters>, UnitCounters>
constexpr auto counter_slot(Counters& k, std::size_t row, int instance = 0)
    -> std::conditional_t<std::is_const_v<Counters>, const std::uint64_t*, std::uint64_t*> {
  const CounterRow& r = kCounterRegistry[row];
  switch (r.block) {
    case CounterBlock::Run:
      switch (static_cast<RunCounter>(r.index)) {
#define TESSIM_RUN_SLOT(BLOCK, ID, KEY, ...) \
  case RunCounter::ID:                      \
    return &k.KEY;
        TESSIM_RUN_COUNTERS(TESSIM_RUN_SLOT)
#undef TESSIM_RUN_SLOT
      }
      return nullptr;
    case CounterBlock::Int:
      return static_cast<IntClass>(r.index) == IntClass::Busy ? &k.int_busy[static_cast<std::size_t>(instance)] : nullptr;
    case CounterBlock::Te: return &k.te.n[r.index];
    case CounterBlock::Cpg: return &k.cpg.n[r.index];
    case CounterBlock::Gpe: return nullptr;
  }
  return nullptr;
}
constexpr std::uint64_t counter_value(const UnitCounters& k, std::size_t row, int instance = 0) {
  const CounterRow& r = kCounterRegistry[row];
  if (r.block == CounterBlock::Int && static_cast<IntClass>(r.index) == IntClass::Idle) return k.int_idle(instance);
  const std::uint64_t* slot = counter_slot(k, row, instance);
  return slot ? *slot : 0;
}
// The sum of a block's classes (of INT block `instance`): the cycles, for every block of classes.
constexpr std::uint64_t class_total(const UnitCounters& k, CounterBlock b, int instance = 0) {
  std::uint64_t s = 0;
  for (std::size_t row = first_row(b); row < first_row(b) + row_count(b); ++row) s += counter_value(k, row, instance);
  return s;
}
// a += b, every stored counter (the chunks of a chunked run).
constexpr void add(UnitCounters& a, const UnitCounters& b) {
  for (std::size_t row = 0; row < kCounterRegistry.size(); ++row)
    for (int i = 0; i < counter_instances(b, row); ++i)
      if (std::uint64_t* slot = counter_slot(a, row, i)) *slot += counter_value(b, row, i);
}

// The unit's counters by name, for `tessim schema`: the run counts, then the TE's and the CPG's
// classes (INT busy per block, int_busy[0..N-1], comes between them when they are compared).
struct CounterField {
  const char* name;
  std::size_t row;  // in kCounterRegistry
};
template <std::size_t N>
constexpr std::array<CounterField, N> counter_fields(std::initializer_list<CounterBlock> blocks) {
  std::array<CounterField, N> a{};
  std::size_t i = 0;
  for (CounterBlock b : blocks)
    for (std::size_t row = first_row(b); row < first_row(b) + row_count(b); ++row)
      a[i++] = {kCounterRegistry[row].name, row};
  return a;
}
inline constexpr auto kRunCounters = counter_fields<row_count(CounterBlock::Run)>({CounterBlock::Run});
inline constexpr auto kClassCounters =
    counter_fields<row_count(CounterBlock::Te) + row_count(CounterBlock::Cpg)>({CounterBlock::Te, CounterBlock::Cpg});

}  // namespace tessim::sim
