// Domain-point generator of rtl/tess_dpg.sv (docs/microarchitecture.md §7): walks the pattern
// of the patch at the buffers' rd_ptr. Uniform pattern: j fastest, (0,0), (1,0), ..., (L,0),
// (0,1), ..., (0,L). D3D11 pattern: the tessellator's order (sim/values/d3d11_walk.hpp,
// D3D11PointWalker) from the walk set up while the CPG ran. A point is consumed when a TE
// context is allocated for it.
#pragma once

#include <array>
#include <cstdint>

#include "model/pattern.hpp"
#include "sim/base/fixed.hpp"
#include "sim/blocks/cp_buffer.hpp"

namespace tessim::sim {

struct DpgPoint {
  int j = 0, k = 0;  // uniform: the lattice point; D3D11: ring and edge (3: the centre)
  int index = 0;     // in the patch's pattern order
  std::int64_t w = 0, u = 0, v = 0;  // barycentric weights, B fraction bits, w + u + v = 2^B
  bool last = false;                 // the patch's last point
};

class Dpg {
 public:
  explicit Dpg(const NumberFormat& format) : format_(format) {}

  void reset() {
    j_ = k_ = index_ = 0;
    walking_ = false;
  }

  // The current point of the patch in `entry`.
  DpgPoint point(const ControlPointBuffer::Entry& entry) {
    DpgPoint p;
    p.index = index_;
    if (entry.pattern != TriPattern::uniform) {
      if (!walking_) start(entry);
      const FixedUV uv = walker_.point(entry.d3d11);
      p.j = walker_.ring();
      p.k = walker_.edge();
      // 16.16 to B >= 16 fraction bits: exact (validate() refuses D3D11 patterns below 16).
      const int shift = format_.bary_bits - 16;
      p.u = std::int64_t{uv.u} << shift;
      p.v = std::int64_t{uv.v} << shift;
      p.w = format_.bary_one() - p.u - p.v;
      p.last = walker_.last();
      return p;
    }
    const int L = entry.L;
    if (L != weights_L_) load_weights(L);
    p.j = j_;
    p.k = k_;
    p.u = weights_[static_cast<std::size_t>(j_)];
    p.v = weights_[static_cast<std::size_t>(k_)];
    p.w = format_.bary_one() - p.u - p.v;
    p.last = k_ == L;
    return p;
  }

  // The clock edge after the current point was consumed.
  void consume(const ControlPointBuffer::Entry& entry) {
    if (entry.pattern != TriPattern::uniform) {
      if (!walking_) start(entry);
      if (walker_.last()) {
        walking_ = false;
        index_ = 0;
      } else {
        walker_.next(entry.d3d11);
        ++index_;
      }
      return;
    }
    const int L = entry.L;
    if (k_ == L) {
      j_ = k_ = index_ = 0;
      return;
    }
    ++index_;
    if (j_ + 1 + k_ <= L) {
      ++j_;
    } else {
      j_ = 0;
      ++k_;
    }
  }

 private:
  void start(const ControlPointBuffer::Entry& entry) {
    walker_.start(entry.d3d11);
    walking_ = true;
  }

  // bary_weight(i, L) for i = 0..L, kept for the factor of the patches being walked (the
  // hardware's weights are a function of (i, L); the model saves two divisions per point).
  void load_weights(int L) {
    for (int i = 0; i <= L; ++i) weights_[static_cast<std::size_t>(i)] = bary_weight(i, L, format_.bary_bits);
    weights_L_ = L;
  }

  NumberFormat format_;
  int j_ = 0, k_ = 0;
  int index_ = 0;
  int weights_L_ = 0;
  std::array<std::int64_t, kMaxTessFactor + 1> weights_{};
  D3D11PointWalker walker_;
  bool walking_ = false;  // walker_ is on the patch at rd_ptr (started at its first point)
};

}  // namespace tessim::sim
