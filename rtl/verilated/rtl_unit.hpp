// One C++ interface over every Verilated configuration of the unit (rtl/CMakeLists.txt), with
// the same lock-step boundary as the cycle model (sim/values/unit_io.hpp): drive one cycle's inputs,
// clock, read the registered outputs. docs/rtl.md lists the variants.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/normal_mode.hpp"
#include "sim/config/config.hpp"
#include "sim/values/dut.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::rtl {

// Raised by tick() when an RTL assertion fired (only builds verilated with --assert check).
class RtlAssertionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RtlUnit : public sim::Dut {
 public:
  ~RtlUnit() override;
  RtlUnit(const RtlUnit&) = delete;
  RtlUnit& operator=(const RtlUnit&) = delete;

  // Asserts rst_ni (asynchronous) and releases it; the cycle count restarts at 0.
  void reset() override = 0;
  // mode_i; static during a run (throws std::invalid_argument for a mode the unit lacks).
  virtual void set_mode(NormalMode mode) = 0;

  // Outputs: functions of registered state, valid between ticks.
  bool tri_ready() const override = 0;
  bool vtx_valid() const override = 0;
  sim::VertexFx vtx() const override = 0;  // meaningful only while vtx_valid()
  // The RTL's CPG is dedicated: it never asks the geometry engine for spare cycles.
  bool cpg_computing() const final { return false; }
  sim::UnitCounters counters() const override = 0;

  // One clock cycle: drive the inputs, evaluate, rising edge, evaluate. UnitInputs::cpg_step
  // is ignored (the RTL implements the dedicated CPG). Throws RtlAssertionError when an
  // assertion of a --assert build fails during the cycle.
  void tick(const sim::UnitInputs& in) override = 0;

  // FST waveform: open a file, dump only while enabled (enabled by open_wave), close. Each
  // tick dumps at time 2 x cycle (inputs applied, clock low) and 2 x cycle + 1 (after the
  // rising edge); after a second reset the time continues where the file left off.
  virtual void open_wave(const std::filesystem::path& path) = 0;
  virtual void close_wave() = 0;
  virtual void set_wave_enabled(bool enabled) = 0;

  const std::string& variant() const { return variant_; }
  int int_blocks() const { return config_.int_blocks; }
  int int_latency() const { return config_.int_latency; }
  int contexts() const { return config_.te_contexts; }
  int inject_bug() const { return inject_bug_; }
  const sim::NumberFormat& format() const { return config_.format; }
  // The hardware this variant implements (dedicated CPG); mode, factors and the geometry engine
  // belong to the run.
  const sim::HardwareConfig& config() const { return config_; }
  std::uint64_t cycle() const { return cycle_; }  // ticks since the last reset

 protected:
  RtlUnit(std::string variant, const sim::HardwareConfig& config, int inject_bug)
      : variant_(std::move(variant)), config_(config), inject_bug_(inject_bug) {}
  std::uint64_t cycle_ = 0;

 private:
  std::string variant_;
  sim::HardwareConfig config_;
  int inject_bug_ = 0;
};

// "n1".."n4" (N INT blocks, V = 4, latency 1, default widths), "n2_verif" (N = 2, X values
// randomised from `seed`, assertions on), "n2_bug1", "n2_bug2" (N = 2 with an injected
// fault). Throws std::invalid_argument for an unknown name.
std::unique_ptr<RtlUnit> make_rtl_unit(const std::string& variant, std::uint64_t seed = 1);
std::vector<std::string> rtl_variants();
// The first fault-free build (a VERIF build if `verif`) that implements exactly `hw` (its CPG
// mapping aside), if there is one.
std::optional<std::string> find_rtl_variant(const sim::HardwareConfig& hw, bool verif);

// Throws InputError naming the first parameter of `cfg` that the variant was not built with
// (widths, N, latency, contexts, FIFO depths; also a CPG mapping or normal mode the RTL lacks).
void check_config(const RtlUnit& unit, const sim::UnitConfig& cfg);

}  // namespace tessim::rtl
