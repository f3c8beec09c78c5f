// The narrow boundary every implementation of the unit offers to a testbench and to the
// co-simulation's checkers: outputs that are functions of registered state, one clock edge,
// the performance counters. The cycle model (ModelDut over sim::Unit, sim/unit/model_dut.hpp) and
// the Verilated RTL (rtl::RtlUnit) implement it; docs/verification.md describes the checkers
// built on it. Loops that run one implementation at full speed (tessim sim, benchmarks) drive
// sim::Unit directly: the testbench is a template over any type with these members. Only the
// unit's I/O types are needed here, so the RTL adapter does not pull in the cycle model.
#pragma once

#include "sim/values/unit_io.hpp"

namespace tessim::sim {

class Dut {
 public:
  virtual ~Dut() = default;
  virtual void reset() = 0;                    // asynchronous reset; counters cleared
  virtual bool tri_ready() const = 0;
  virtual bool vtx_valid() const = 0;
  virtual VertexFx vtx() const = 0;            // meaningful only while vtx_valid()
  virtual bool cpg_computing() const = 0;      // gpe mapping: wants the GPE's spare cycle
  virtual UnitCounters counters() const = 0;   // docs/microarchitecture.md §10
  virtual void tick(const UnitInputs& in) = 0; // the clock edge
};

}  // namespace tessim::sim
