// The N INT blocks of rtl/tess_int.sv (docs/microarchitecture.md §8): each takes one operation
// per cycle and delivers it Λ cycles later. The cycle model keeps only the done bits in flight:
// the ops one cycle issued, as age-ordered masks (sim/blocks/op_masks.hpp) with the number of
// retirements before their issue, wait in slot (issue + Λ - 1) mod Λ. The values are computed
// when the vertex retires (sim/blocks/te.hpp): a result depends on its operands alone, never on
// when it was issued.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>

#include "sim/blocks/op_masks.hpp"

namespace tessim::sim {

class IntBlocks {
 public:
  // The configuration limits: N <= 32, Λ <= 8 (sim/config/params.cpp).
  static constexpr int kMaxBlocks = 32;
  static constexpr int kMaxLatency = 8;

  IntBlocks(int blocks, int latency) : blocks_(blocks), latency_(latency) {
    if (blocks < 1 || blocks > kMaxBlocks || latency < 1 || latency > kMaxLatency)
      throw std::invalid_argument("IntBlocks: N or latency out of range");
    reset();
  }

  void reset() {
    for (InFlight& f : slots_) f.pending = false;
    pending_count_ = 0;
    due_slot_ = 0;
  }

  int blocks() const { return blocks_; }
  int latency() const { return latency_; }
  bool empty() const { return pending_count_ == 0; }  // no completion pending

  // The ops issued in this cycle (Λ > 1), in age order as of `retired` retirements since reset:
  // their done bits are due at the end of cycle t + Λ - 1, whose slot is (t - 1) mod Λ.
  void issue(const OpMasks& ops, std::uint64_t retired) {
    InFlight& f = slots_[static_cast<std::size_t>(due_slot_ == 0 ? latency_ - 1 : due_slot_ - 1)];
    f.ops = ops;
    f.retired = retired;
    f.pending = true;
    ++pending_count_;
  }

  // `cycles` clock edges with nothing pending (empty()).
  void skip(std::uint64_t cycles) {
    due_slot_ = static_cast<int>((static_cast<std::uint64_t>(due_slot_) + cycles) % static_cast<std::uint64_t>(latency_));
  }

  // The clock edge: hands the ops due in this cycle to `apply(ops, retired)`.
  template <class Apply>
  void complete_due(Apply&& apply) {
    InFlight& f = slots_[static_cast<std::size_t>(due_slot_)];
    if (f.pending) {
      apply(f.ops, f.retired);
      f.pending = false;
      --pending_count_;
    }
    due_slot_ = due_slot_ + 1 == latency_ ? 0 : due_slot_ + 1;
  }

 private:
  struct InFlight {
    OpMasks ops;
    std::uint64_t retired = 0;
    bool pending = false;
  };
  int blocks_;
  int latency_;
  std::array<InFlight, kMaxLatency> slots_{};  // by due slot
  int pending_count_ = 0;
  int due_slot_ = 0;  // slot of the current cycle: cycle mod latency
};

}  // namespace tessim::sim
