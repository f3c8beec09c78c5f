// FIFO of rtl/tess_fifo.sv, used for the TRI FIFO and the VTX FIFO: a ring of `depth` slots.
// A cycle decides from the registered head and count; the push writes tail() (the slot after
// the last entry at the start of the cycle) and commit() then moves head and count, so a push
// and a pop in the same cycle never touch the same slot.
#pragma once

#include <cstddef>
#include <vector>

namespace tessim::sim {

template <class T>
class Fifo {
 public:
  explicit Fifo(int depth) : slots_(static_cast<std::size_t>(depth)), depth_(depth) {}

  void reset() { head_ = count_ = 0; }

  int depth() const { return depth_; }
  int count() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == depth_; }
  const T& front() const { return slots_[static_cast<std::size_t>(head_)]; }  // while !empty()

  // The slot a push in this cycle writes (meaningful while !full()).
  T& tail() {
    int pos = head_ + count_;
    if (pos >= depth_) pos -= depth_;
    return slots_[static_cast<std::size_t>(pos)];
  }

  // The clock edge: a push (tail() already written) and/or a pop of front().
  void commit(bool push, bool pop) {
    if (pop) head_ = head_ + 1 == depth_ ? 0 : head_ + 1;
    count_ += (push ? 1 : 0) - (pop ? 1 : 0);
  }

 private:
  std::vector<T> slots_;
  int depth_;
  int head_ = 0;
  int count_ = 0;
};

}  // namespace tessim::sim
