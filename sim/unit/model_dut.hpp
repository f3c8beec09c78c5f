// The cycle model behind the Dut boundary (sim/values/dut.hpp): what the co-simulation runs in
// lock-step with the RTL.
#pragma once

#include "sim/config/config.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/dut.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

class ModelDut final : public Dut {
 public:
  explicit ModelDut(const UnitConfig& cfg) : unit_(cfg) {}
  void reset() override { unit_.reset(); }
  bool tri_ready() const override { return unit_.tri_ready(); }
  bool vtx_valid() const override { return unit_.vtx_valid(); }
  VertexFx vtx() const override { return unit_.vtx(); }
  bool cpg_computing() const override { return unit_.cpg_computing(); }
  UnitCounters counters() const override { return unit_.stats(); }
  void tick(const UnitInputs& in) override { unit_.tick(in); }
  const Unit& unit() const { return unit_; }

 private:
  Unit unit_;
};

}  // namespace tessim::sim
