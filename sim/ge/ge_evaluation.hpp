// Evaluation on the geometry engine (evaluation gpe; docs/microarchitecture.md §12): the unit
// without its TE and INT blocks, in the manner of Boubekeur & Schlick and of Direct3D 11's
// fixed-function tessellator feeding a domain shader. TRI FIFO, CPG (dedicated, on the GE's spare
// cycles, or the host's control points latched), control-point buffers and DPG as in sim::Unit;
// the DPG's points go into the VTX FIFO, and the GE evaluates each one as a shader (its cycles per
// vertex: sim/ge/ge_cost.hpp). A patch's buffer is released when the GE accepts its last point (the
// GE reads the control points as the shader's constants until then).
//
// Protocol as sim::Unit: read the outputs, choose the inputs, tick().
#pragma once

#include <cstdint>

#include "sim/blocks/counters.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/blocks/cpg.hpp"
#include "sim/blocks/dpg.hpp"
#include "sim/blocks/fifo.hpp"
#include "sim/config/config.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// A domain point on its way to the GE, with the buffer that holds its patch's control points.
struct GePoint {
  DpgPoint point;
  int buffer = 0;
  std::uint32_t id = 0;  // the patch's triangle
};

class GeEvaluationUnit {
 public:
  // cfg must have passed validate() with evaluation gpe.
  explicit GeEvaluationUnit(const UnitConfig& cfg);

  void reset();

  bool tri_ready() const { return !tri_fifo_.full(); }
  bool vtx_valid() const { return !vtx_fifo_.empty(); }
  const GePoint& vtx() const { return vtx_fifo_.front(); }  // while vtx_valid()
  bool cpg_computing() const { return cpg_.computing(); }
  // The buffer entry a point names: valid from the DPG's hand-out until the GE accepts the
  // patch's last point.
  const ControlPointBuffer::Entry& entry(int buffer) const { return buffers_.entry(buffer); }

  void tick(const UnitInputs& in);

  // The run counters, the CPG's classes, and the DPG's in the TE's classes (busy: a point handed
  // out; blocked_by_gpe: the VTX FIFO full; starved_by_cpg: no point, the CPG busy or a triangle
  // waiting; idle). No INT blocks.
  const UnitCounters& stats() const { return counters_.stats(); }
  int cpg_cycles() const { return cpg_.cycles(); }
  std::uint64_t cpg_tag_cycles() const { return cpg_.tag_cycles(); }

 private:
  Fifo<TriangleFx> tri_fifo_;
  CpgArray cpg_;
  ControlPointBuffer buffers_;
  Dpg dpg_;
  Fifo<GePoint> vtx_fifo_;
  Counters counters_;
};

}  // namespace tessim::sim
