// Cycle-level model of the PN tessellation unit: TRI FIFO, CPG (dedicated or on the geometry
// engine), two control-point buffers, DPG, TE with V contexts and N INT blocks, VTX FIFO.
// It implements docs/microarchitecture.md register for register; the co-simulation drives it
// next to the Verilated RTL with the same inputs every cycle and compares the outputs.
//
// Protocol of one cycle: read the outputs (tri_ready(), vtx_valid(), vtx(), cpg_computing()),
// which depend on registered state only; choose the inputs; call tick(), which is the clock
// edge. After tick() the observability accessors describe the cycle just simulated.
// The boundary types (VertexFx, UnitInputs) are shared with the RTL wrapper:
// sim/values/unit_io.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/base/fixed.hpp"
#include "sim/blocks/counters.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/blocks/cpg.hpp"
#include "sim/blocks/fifo.hpp"
#include "sim/blocks/te.hpp"
#include "sim/config/config.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// Everything a trace or a schedule printout needs about the cycle last simulated.
struct CycleActivity {
  std::uint64_t cycle = 0;  // index of the cycle (0 = first cycle after reset)
  int ops_issued = 0;       // entries valid in issued_ops()
  TeClass te = TeClass::Idle;
  CpgClass cpg = CpgClass::Idle;
  CpgAction cpg_action = CpgAction::Idle;
  std::uint32_t cpg_triangle = 0;  // the triangle the CPG accepts or works on (not while Idle)
  bool tri_pushed = false;
  bool vtx_popped = false;
  bool allocated = false;
  std::uint64_t allocated_vertex = 0;
  std::uint32_t allocated_patch = 0;  // the patch of the allocated vertex
  bool retired = false;
  std::uint64_t retired_vertex = 0;
};

class Unit {
 public:
  // The unit is built from its hardware parameters and its static mode input; the GPE mapping of
  // the CPG also needs the GPE cycles it takes per triangle. cfg must have passed validate().
  Unit(const HardwareConfig& hw, NormalMode normals, int cpg_gpe_cycles);
  explicit Unit(const UnitConfig& cfg) : Unit(cfg.hardware(), cfg.normals, cfg.cpg_gpe_cycles) {}

  // Asynchronous reset (doc §2): empties everything and clears every counter.
  void reset();

  // Outputs: functions of the registered state only.
  bool tri_ready() const { return !tri_fifo_.full(); }
  bool vtx_valid() const { return !vtx_fifo_.empty(); }
  const VertexFx& vtx() const { return vtx_fifo_.front(); }  // meaningful while vtx_valid()
  // gpe mapping only: the CPG is computing (busy, counter > 0) and wants a spare GPE cycle.
  // Always false in the dedicated mapping, so the GPE never counts a spare cycle as `cpg`.
  bool cpg_computing() const { return cpg_.computing(); }

  // The clock edge: one cycle with these inputs.
  void tick(const UnitInputs& in);

  // A triangle pushed into the TRI FIFO between clock edges, for a driver that runs the unit
  // ahead of the logic feeding it (sim/system/system_threads.hpp): the push of a cycle already
  // past, exact as long as the unit has not yet seen its TRI FIFO empty since that cycle. Counted
  // in TrianglesIn like a push by tick(). The FIFO must not be full.
  void inject(const TriangleFx& tri);

  // Fast-forward (docs/microarchitecture.md §11). quiet_cycles(in): how many cycles in a row,
  // from now, with these inputs held, would move no data between blocks (no push, pop,
  // allocation, retirement, CPG accept or write) and change only counters, the CPG's countdown
  // and the TE's op state; 0 if the next cycle moves data, kForever if nothing ends the stretch
  // but a change of inputs or the TE. skip(n, in, issuing_limit), n <= quiet_cycles(in): up to
  // n of those cycles at once — all n when the TE is quiet (nothing to issue, nothing in flight),
  // else cycle by cycle in the TE alone, at most issuing_limit, ending early where the head
  // context finishes with room in the VTX FIFO or the TE falls quiet. Returns how many; every
  // counter, the TE's state and the activity of the last one are exactly as that many tick(in)
  // calls would leave them.
  static constexpr std::uint64_t kForever = CpgBlock::kForever;
  std::uint64_t quiet_cycles(const UnitInputs& in) const;
  std::uint64_t skip(std::uint64_t n, const UnitInputs& in, std::uint64_t issuing_limit = kForever);
  // The TE has nothing to issue and nothing in flight: skip() takes all n cycles at once.
  bool te_quiet() const { return te_.quiet(); }

  const UnitCounters& stats() const { return counters_.stats(); }
  const ClassCounts<TeClass>& te_class_cycles() const { return counters_.te_class_cycles(); }
  const HardwareConfig& hardware() const { return hw_; }
  int cpg_cycles() const { return cpg_.cycles(); }  // C of doc §5 for this configuration
  std::uint64_t cpg_tag_cycles() const { return cpg_.tag_cycles(); }  // added by scalar tags

  // Observability of the cycle last simulated by tick().
  const CycleActivity& activity() const { return act_; }
  const IssuedOp* issued_ops() const { return te_.issued_ops(); }
  // Registered state after the last tick (counters for traces).
  int tri_fifo_count() const { return tri_fifo_.count(); }
  int vtx_fifo_count() const { return vtx_fifo_.count(); }
  int contexts_in_use() const { return te_.contexts_in_use(); }
  bool idle() const;  // nothing buffered or in flight anywhere in the unit

 private:
  void check_factors(const TriangleFx& tri) const;  // throws on a triangle outside the input contract

  // The blocks of rtl/tess_unit.sv, in data-flow order.
  HardwareConfig hw_;
  Fifo<TriangleFx> tri_fifo_;
  CpgArray cpg_;
  ControlPointBuffer buffers_;
  Te te_;
  Fifo<VertexFx> vtx_fifo_;
  Counters counters_;
  CycleActivity act_;
};

}  // namespace tessim::sim
