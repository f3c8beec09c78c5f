// Control-point buffers of rtl/tess_cpbuf.sv (docs/microarchitecture.md §6): a ring of
// cp_buffers entries, so that the CPG fills one while the TE reads the others. The CPG writes at
// wr_ptr, the DPG hands out the points of the patch at rd_ptr; an entry is EMPTY -> FULL (CPG
// write) -> DRAINING (last domain point handed out) -> EMPTY (last vertex of the patch retired).
// Both pointers step round the ring, so patches are written, drained and released in order.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "sim/values/cpg.hpp"

namespace tessim::sim {

class ControlPointBuffer {
 public:
  static constexpr int kMaxBuffers = 8;
  enum class State : std::uint8_t { Empty, Full, Draining };
  struct Entry {
    ControlPointsFx cp;
    State state = State::Empty;
    int L = 1;
    TriPattern pattern = TriPattern::uniform;
    D3D11Setup d3d11;  // D3D11 patterns: the walk set up from the factors while the CPG ran
    std::uint32_t id = 0;
  };

  // buffers: HardwareConfig::cp_buffers, validated by the parameter table (sim/config/params.cpp).
  explicit ControlPointBuffer(int buffers) : count_(buffers) {
    if (buffers < 1 || buffers > kMaxBuffers)
      throw std::invalid_argument("ControlPointBuffer: 1.." + std::to_string(kMaxBuffers) + " buffers");
  }

  void reset() {
    for (Entry& e : entries_) e.state = State::Empty;
    wr_ptr_ = rd_ptr_ = 0;
  }

  bool wr_empty() const { return entries_[static_cast<std::size_t>(wr_ptr_)].state == State::Empty; }
  bool rd_full() const { return entries_[static_cast<std::size_t>(rd_ptr_)].state == State::Full; }
  int rd_ptr() const { return rd_ptr_; }
  const Entry& rd() const { return entries_[static_cast<std::size_t>(rd_ptr_)]; }
  const Entry& entry(int index) const { return entries_[static_cast<std::size_t>(index)]; }
  bool empty() const {
    for (int b = 0; b < count_; ++b)
      if (entries_[static_cast<std::size_t>(b)].state != State::Empty) return false;
    return true;
  }

  // CPG write (while wr_empty()): fill the entry, then it is FULL and wr_ptr moves on.
  Entry& write_slot() { return entries_[static_cast<std::size_t>(wr_ptr_)]; }
  void commit_write() {
    entries_[static_cast<std::size_t>(wr_ptr_)].state = State::Full;
    wr_ptr_ = next(wr_ptr_);
  }
  // DPG handed out the patch's last point: DRAINING, rd_ptr moves on.
  void drain() {
    entries_[static_cast<std::size_t>(rd_ptr_)].state = State::Draining;
    rd_ptr_ = next(rd_ptr_);
  }
  // The patch's last vertex retired.
  void release(int index) { entries_[static_cast<std::size_t>(index)].state = State::Empty; }

 private:
  int next(int ptr) const { return ptr + 1 == count_ ? 0 : ptr + 1; }

  std::array<Entry, kMaxBuffers> entries_;
  int count_;
  int wr_ptr_ = 0, rd_ptr_ = 0;
};

}  // namespace tessim::sim
