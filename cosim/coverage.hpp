// Functional coverage of a co-simulation (docs/verification.md, Coverage): which states and
// events of the unit the stimulus reached, sampled from the cycle model while it runs in
// lock-step with the RTL (they agree every cycle, so the bins hold for both). Bins are named
// "group/bin"; a report lists hit counts and the bins never hit. Coverage accumulates across
// runs (seeds, invocations: merge()).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "model/normal_mode.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::cosim {

class FunctionalCoverage {
 public:
  // Declares the bins of a run of this configuration (every bin starts at 0 hits if new).
  void declare(const sim::UnitConfig& cfg);
  // One cycle: the inputs and outputs before the clock edge, the unit after it.
  void sample_cycle(const sim::UnitInputs& in, bool vtx_valid, const sim::VertexFx& vtx_front,
                    const sim::GpeCycle& gpe, const sim::Unit& after);
  void sample_triangle(const sim::TriangleFx& tri, NormalMode mode);  // taken by the unit
  void sample_vertex(const sim::VertexFx& v);                         // accepted by the GPE
  void sample_reset(const sim::Unit& before);                         // a mid-stream reset

  void merge(const FunctionalCoverage& other);
  std::size_t bins() const { return hits_.size(); }
  std::size_t covered() const;
  std::vector<std::string> uncovered() const;
  nlohmann::json to_json() const;
  static FunctionalCoverage from_json(const nlohmann::json& j, const std::string& source);
  std::string summary() const;  // per group: covered / bins, and the bins never hit

 private:
  void hit(const std::string& bin, std::uint64_t n = 1) { hits_[bin] += n; }
  void declare_bin(const std::string& bin) { hits_.try_emplace(bin, 0); }
  std::map<std::string, std::uint64_t> hits_;
  int contexts_ = 0, blocks_ = 0, tri_depth_ = 0, vtx_depth_ = 0;
};

}  // namespace tessim::cosim
