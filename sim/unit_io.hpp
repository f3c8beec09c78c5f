// The unit's boundary, shared by every implementation that runs in lock-step: the cycle
// model (sim/unit.hpp) and the Verilated RTL (rtl/verilated/). Field meanings and bit widths:
// docs/microarchitecture.md §3; counter definitions: §10.
#pragma once

#include <array>
#include <cstdint>

#include "sim/cpg.hpp"
#include "sim/fixed.hpp"

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

// The counters both implementations keep (docs/microarchitecture.md §10), compared exactly
// at the end of a co-simulation.
struct UnitCounters {
  std::uint64_t cycles = 0;
  std::uint64_t triangles_in = 0;
  std::uint64_t vertices_out = 0;
  std::array<std::uint64_t, kMaxIntBlocks> int_busy{};
  std::uint64_t te_context_limited = 0, te_int_limited = 0, te_busy = 0, te_blocked_by_gpe = 0,
                te_starved_by_cpg = 0, te_idle = 0, te_pipeline = 0;
  std::uint64_t cpg_busy = 0, cpg_blocked = 0, cpg_wait_gpe = 0, cpg_idle = 0;
  bool operator==(const UnitCounters&) const = default;
};

// The scalar counters once, by name (the RTL's perf_<name>_o outputs, co-simulation reports),
// in the order the co-simulation compares them; int_busy[0..N-1] comes after `vertices_out`.
struct CounterField {
  const char* name;
  std::uint64_t UnitCounters::*field;
};
inline constexpr std::array<CounterField, 3> kRunCounters{{
    {"cycles", &UnitCounters::cycles},
    {"triangles_in", &UnitCounters::triangles_in},
    {"vertices_out", &UnitCounters::vertices_out},
}};
inline constexpr std::array<CounterField, 11> kClassCounters{{
    {"te_context_limited", &UnitCounters::te_context_limited},
    {"te_int_limited", &UnitCounters::te_int_limited},
    {"te_busy", &UnitCounters::te_busy},
    {"te_blocked_by_gpe", &UnitCounters::te_blocked_by_gpe},
    {"te_starved_by_cpg", &UnitCounters::te_starved_by_cpg},
    {"te_idle", &UnitCounters::te_idle},
    {"te_pipeline", &UnitCounters::te_pipeline},
    {"cpg_busy", &UnitCounters::cpg_busy},
    {"cpg_blocked", &UnitCounters::cpg_blocked},
    {"cpg_wait_gpe", &UnitCounters::cpg_wait_gpe},
    {"cpg_idle", &UnitCounters::cpg_idle},
}};

}  // namespace tessim::sim
