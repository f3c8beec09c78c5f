// Cycle-level model of the PN tessellation unit: TRI FIFO, CPG (dedicated or on the geometry
// engine), two control-point buffers, DPG, TE with V contexts and N INT blocks, VTX FIFO.
// It implements docs/microarchitecture.md register for register; the co-simulation drives it
// next to the Verilated RTL with the same inputs every cycle and compares the outputs.
//
// Protocol of one cycle: read the outputs (tri_ready(), vtx_valid(), vtx(), cpg_computing()),
// which depend on registered state only; choose the inputs; call tick(), which is the clock
// edge. After tick() the observability accessors describe the cycle just simulated.
// The boundary types (VertexFx, UnitInputs) are shared with the RTL wrapper: sim/unit_io.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/config.hpp"
#include "sim/cpg.hpp"
#include "sim/fixed.hpp"
#include "sim/unit_io.hpp"

namespace tessim::sim {

// Statistics of doc §10. Every cycle is counted in exactly one class per block.
struct IntBlockStats {
  std::uint64_t busy = 0;
  std::uint64_t idle = 0;
  bool operator==(const IntBlockStats&) const = default;
};
struct TeStats {
  std::uint64_t busy = 0;
  std::uint64_t blocked_by_gpe = 0;
  std::uint64_t starved_by_cpg = 0;
  std::uint64_t idle = 0;
  std::uint64_t pipeline = 0;
  bool operator==(const TeStats&) const = default;
};
struct CpgStats {
  std::uint64_t busy = 0;
  std::uint64_t blocked = 0;
  std::uint64_t wait_gpe = 0;
  std::uint64_t idle = 0;
  bool operator==(const CpgStats&) const = default;
};
struct UnitStats {
  std::uint64_t cycles = 0;
  std::uint64_t triangles_in = 0;   // triangles pushed into the TRI FIFO
  std::uint64_t vertices_out = 0;   // vertices popped from the VTX FIFO (accepted by the GPE)
  std::vector<IntBlockStats> int_blocks;  // N entries, sized once by the constructor
  TeStats te;
  CpgStats cpg;
  bool operator==(const UnitStats&) const = default;
};

// Per-cycle classes, in the order of doc §10's tables.
enum class TeClass : std::uint8_t { Busy, BlockedByGpe, StarvedByCpg, Idle, Pipeline };
enum class CpgClass : std::uint8_t { Busy, Blocked, WaitGpe, Idle };
// What the CPG did in the cycle (finer than its class, for traces).
enum class CpgAction : std::uint8_t { Idle, Accept, Compute, WaitGpe, Write, Blocked };

const char* to_string(TeClass c);
const char* to_string(CpgClass c);
const char* to_string(CpgAction a);

// One operation issued to an INT block.
struct IssuedOp {
  int block = 0;            // INT block (the i-th issued op of a cycle goes to block i)
  int context = 0;          // context slot 0..V-1
  int op = 0;               // 0..13, doc §8 table
  std::uint64_t vertex = 0; // sequence number of the vertex (allocation order since reset)
};

// Everything a trace or a schedule printout needs about the cycle last simulated.
struct CycleActivity {
  std::uint64_t cycle = 0;  // index of the cycle (0 = first cycle after reset)
  int ops_issued = 0;       // entries valid in issued_ops()
  TeClass te = TeClass::Idle;
  CpgClass cpg = CpgClass::Idle;
  CpgAction cpg_action = CpgAction::Idle;
  bool tri_pushed = false;
  bool vtx_popped = false;
  bool allocated = false;
  std::uint64_t allocated_vertex = 0;
  bool retired = false;
  std::uint64_t retired_vertex = 0;
};

class Unit {
 public:
  explicit Unit(const UnitConfig& cfg);  // cfg must have passed validate()

  // Asynchronous reset (doc §2): empties everything and clears every counter.
  void reset();

  // Outputs: functions of the registered state only.
  bool tri_ready() const { return tri_count_ < cfg_.tri_fifo_depth; }
  bool vtx_valid() const { return vtx_count_ > 0; }
  const VertexFx& vtx() const { return vtx_fifo_[vtx_head_]; }  // meaningful while vtx_valid()
  // gpe mapping only: the CPG is computing (busy, counter > 0) and wants a spare GPE cycle.
  // Always false in the dedicated mapping, so the GPE never counts a spare cycle as `cpg`.
  bool cpg_computing() const { return gpe_mapping_ && cpg_busy_ && cpg_counter_ > 0; }

  // The clock edge: one cycle with these inputs.
  void tick(const UnitInputs& in);

  const UnitStats& stats() const { return stats_; }
  const UnitConfig& config() const { return cfg_; }
  int cpg_cycles() const { return cpg_c_; }  // C of doc §5 for this configuration

  // Observability of the cycle last simulated by tick().
  const CycleActivity& activity() const { return act_; }
  const IssuedOp* issued_ops() const { return issued_.data(); }
  // Registered state after the last tick (counters for traces).
  int tri_fifo_count() const { return tri_count_; }
  int vtx_fifo_count() const { return vtx_count_; }
  int contexts_in_use() const { return ctx_count_; }
  bool idle() const;  // nothing buffered or in flight anywhere in the unit

 private:
  enum class BufferState : std::uint8_t { Empty, Full, Draining };
  struct Buffer {
    ControlPointsFx cp;
    BufferState state = BufferState::Empty;
    int L = 1;
    std::uint32_t id = 0;
  };
  struct Context {
    std::array<FxVec, 14> t{};  // temporaries T0..T13
    std::int64_t w = 0, u = 0, v = 0;
    std::uint32_t issued = 0, done = 0;  // bit o: op o issued / result written
    int j = 0, k = 0, L = 1;
    std::uint32_t id = 0;
    bool last = false;
    std::uint8_t flags = 0;
    std::uint8_t buffer = 0;
    std::uint64_t seq = 0;
  };
  // Operand source of an INT op: a slot of the geometry net, the normal net or the temporaries.
  enum Space : std::uint8_t { kNetB, kNetN, kTemp };
  struct Operand {
    Space space;
    std::uint8_t index;
  };
  struct Completion {
    std::uint8_t context;
    std::uint32_t bit;
  };

  void issue(Context& ctx, int context_slot, int op, int block);

  UnitConfig cfg_;
  int n_blocks_;
  int latency_;
  int n_contexts_;
  int cpg_c_;            // counter load value at accept (doc §5)
  bool gpe_mapping_;
  std::uint32_t all_ops_;        // done mask of a finished vertex
  std::uint32_t preset_ops_;     // ops that do not exist in this mode (linear: 7, 8, 12)
  std::array<std::array<Operand, 3>, 14> operands_{};
  int normal_op_;                // temporary holding the output normal

  // TRI FIFO
  std::vector<TriangleFx> tri_fifo_;
  int tri_head_ = 0, tri_count_ = 0;
  // CPG
  bool cpg_busy_ = false;
  int cpg_counter_ = 0;
  TriangleFx cpg_latch_;
  // Control-point buffers
  std::array<Buffer, 2> buffers_;
  int wr_ptr_ = 0, rd_ptr_ = 0;
  // DPG
  int dpg_j_ = 0, dpg_k_ = 0;
  // TE contexts (circular queue)
  std::vector<Context> contexts_;
  int ctx_head_ = 0, ctx_count_ = 0;
  std::uint64_t next_seq_ = 0;
  // INT pipelines: completions due at the end of cycle c live in slot c mod latency.
  std::vector<std::vector<Completion>> pending_;
  std::vector<int> pending_count_;
  int due_slot_ = 0;  // slot of the current cycle: cycles mod latency
  // VTX FIFO
  std::vector<VertexFx> vtx_fifo_;
  int vtx_head_ = 0, vtx_count_ = 0;

  UnitStats stats_;
  CycleActivity act_;
  std::vector<IssuedOp> issued_;
};

}  // namespace tessim::sim
