// The unit's environment, shared by the loops that drive a unit over a stream of triangles (the
// co-simulation, `tessim rtlbench`, the microbenchmark): the triangles offered in order on
// tri_valid/tri, and the geometry engine on vtx_ready/cpg_step. One cycle is
//     const UnitInputs& in = tb.inputs(dut);   // from the DUT's outputs (registered state)
//     dut.tick(in);                             // the clock edge
// for any DUT with tri_ready(), vtx_valid() and cpg_computing() (sim::Unit, rtl::RtlUnit).
// `tessim sim` streams from a mesh instead of a vector (sim/simulate.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/pattern.hpp"
#include "sim/gpe.hpp"
#include "sim/unit_io.hpp"

namespace tessim::sim {

class Testbench {
 public:
  Testbench(const std::vector<TriangleFx>& stream, const UnitConfig& cfg) : stream_(stream), gpe_(cfg) {
    for (const TriangleFx& t : stream) expected_ += static_cast<std::uint64_t>(pattern_vertex_count(t.L));
  }

  // Back to the start of the stream with a fresh geometry engine (a reset of the DUT).
  void reset() {
    gpe_.reset();
    next_ = 0;
    accepted_ = 0;
  }

  // The inputs of the cycle. The GPE steps on the DUT's outputs; a triangle offered while the
  // DUT is ready is taken this cycle, so the next one is offered from the next cycle on.
  template <class Dut>
  const UnitInputs& inputs(const Dut& dut) {
    cycle_ = gpe_.tick(dut.vtx_valid(), dut.cpg_computing());
    in_.tri_valid = next_ < stream_.size();
    if (in_.tri_valid) in_.tri = stream_[next_];
    in_.vtx_ready = cycle_.ready;
    in_.cpg_step = cycle_.spare;
    pushed_ = in_.tri_valid && dut.tri_ready();
    if (pushed_) ++next_;
    if (cycle_.accepted) ++accepted_;
    return in_;
  }

  const GpeCycle& gpe_cycle() const { return cycle_; }  // of the last inputs()
  bool pushed() const { return pushed_; }               // the last inputs() handed over a triangle
  const Gpe& gpe() const { return gpe_; }
  std::size_t triangles_taken() const { return next_; }  // triangles the DUT took since reset
  std::uint64_t accepted() const { return accepted_; }  // vertices the GPE took since reset
  std::uint64_t expected() const { return expected_; }  // vertices of the whole stream
  bool done() const { return accepted_ >= expected_; }

 private:
  const std::vector<TriangleFx>& stream_;
  Gpe gpe_;
  UnitInputs in_;
  GpeCycle cycle_;
  std::size_t next_ = 0;
  bool pushed_ = false;
  std::uint64_t accepted_ = 0;
  std::uint64_t expected_ = 0;
};

}  // namespace tessim::sim
