// The N INT blocks of rtl/tess_int.sv (docs/microarchitecture.md §8): each takes one operation
// per cycle and delivers it Λ cycles later. The cycle model keeps only the done bits in flight
// (completions due at the end of cycle c wait in slot c mod Λ); the values are computed when
// the vertex retires (sim/blocks/te.hpp): a result depends on its operands alone, never on
// when it was issued.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>

namespace tessim::sim {

class IntBlocks {
 public:
  struct Completion {
    std::uint8_t context;
    std::uint32_t bit;  // done bit of the op
  };

  // The configuration limits: N <= 32, Λ <= 8 (sim/params.cpp).
  static constexpr int kMaxBlocks = 32;
  static constexpr int kMaxLatency = 8;

  IntBlocks(int blocks, int latency) : blocks_(blocks), latency_(latency) {
    if (blocks < 1 || blocks > kMaxBlocks || latency < 1 || latency > kMaxLatency)
      throw std::invalid_argument("IntBlocks: N or latency out of range");
    reset();
  }

  void reset() {
    pending_count_.fill(0);
    due_slot_ = 0;
  }

  int blocks() const { return blocks_; }
  bool empty() const {  // no completion pending
    for (int i = 0; i < latency_; ++i)
      if (pending_count_[static_cast<std::size_t>(i)] != 0) return false;
    return true;
  }
  int latency() const { return latency_; }

  // An op issued in this cycle: its done bit is due at the end of cycle t + Λ - 1, whose slot
  // is (t + Λ - 1) mod Λ = (t - 1) mod Λ.
  void issue(int context, std::uint32_t done_bit) {
    const int slot = due_slot_ == 0 ? latency_ - 1 : due_slot_ - 1;
    int& count = pending_count_[static_cast<std::size_t>(slot)];
    pending_[static_cast<std::size_t>(slot)][static_cast<std::size_t>(count++)] =
        Completion{static_cast<std::uint8_t>(context), done_bit};
  }

  // `cycles` clock edges with nothing pending (empty()).
  void skip(std::uint64_t cycles) {
    due_slot_ = static_cast<int>((static_cast<std::uint64_t>(due_slot_) + cycles) % static_cast<std::uint64_t>(latency_));
  }

  // The clock edge: hands the completions due in this cycle to `apply(context, bit)`.
  template <class Apply>
  void complete_due(Apply&& apply) {
    const std::size_t slot = static_cast<std::size_t>(due_slot_);
    const Completion* due = pending_[slot].data();
    for (int i = 0; i < pending_count_[slot]; ++i) apply(due[i].context, due[i].bit);
    pending_count_[slot] = 0;
    due_slot_ = due_slot_ + 1 == latency_ ? 0 : due_slot_ + 1;
  }

 private:
  int blocks_;
  int latency_;
  std::array<std::array<Completion, kMaxBlocks>, kMaxLatency> pending_{};  // by due slot
  std::array<int, kMaxLatency> pending_count_{};
  int due_slot_ = 0;  // slot of the current cycle: cycle mod latency
};

}  // namespace tessim::sim
