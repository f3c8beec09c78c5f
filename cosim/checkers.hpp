// The co-simulation's checkers, each watching one property of two implementations of the unit
// (sim::Dut) that run in lock-step on the same inputs (compare lowRISC Ibex's cosim and
// XiangShan's difftest: one testbench, independent checkers):
//  - OutputChecker: every output port, every cycle, bit for bit (sim/values/unit_io.hpp
//    kVertexFields);
//  - CounterChecker: every performance counter, every cycle and at the end;
//  - sim::ArithmeticCheck (sim/run/reference_check.hpp): every accepted vertex against the float
//    reference within the derived error bound;
//  - ProgressChecker: some transfer within a number of cycles (a hang is a failure).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sim/values/dut.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::cosim {

struct Mismatch {
  std::string field;     // the port or counter, e.g. "vtx_pos[1]", "tri_ready", "counters.te_busy"
  std::string expected;  // reference implementation (the cycle model)
  std::string actual;    // implementation under test (the RTL)
};

class OutputChecker {
 public:
  // The first output that differs this cycle: tri_ready, vtx_valid, then (while valid) the
  // vertex fields in port order.
  std::optional<Mismatch> check(const sim::Dut& expected, const sim::Dut& actual) const;
  // The first vertex field that differs.
  static std::optional<Mismatch> diff(const sim::VertexFx& expected, const sim::VertexFx& actual);
};

class CounterChecker {
 public:
  explicit CounterChecker(int int_blocks) : int_blocks_(int_blocks) {}
  // The first counter that differs, in the order of sim/values/unit_io.hpp.
  std::optional<Mismatch> check(const sim::UnitCounters& expected, const sim::UnitCounters& actual) const;

 private:
  int int_blocks_;
};

class ProgressChecker {
 public:
  explicit ProgressChecker(std::uint64_t limit) : limit_(limit) {}
  void transfer(std::uint64_t cycle) { last_ = cycle; }
  bool hung(std::uint64_t cycle) const { return cycle - last_ > limit_; }
  std::uint64_t limit() const { return limit_; }

 private:
  std::uint64_t limit_;
  std::uint64_t last_ = 0;
};

}  // namespace tessim::cosim
