// Domain-point generator of rtl/tess_dpg.sv (docs/microarchitecture.md §7): walks the uniform
// pattern of the patch at the buffers' rd_ptr, j fastest: (0,0), (1,0), ..., (L,0), (0,1), ...,
// (0,L). A point is consumed when a TE context is allocated for it.
#pragma once

#include <cstdint>

#include "sim/fixed.hpp"

namespace tessim::sim {

struct DpgPoint {
  int j = 0, k = 0;
  std::int64_t w = 0, u = 0, v = 0;  // barycentric weights, B fraction bits, w + u + v = 2^B
  bool last = false;                 // (0, L): the patch's last point
};

class Dpg {
 public:
  explicit Dpg(const NumberFormat& format) : format_(format) {}

  void reset() { j_ = k_ = 0; }

  // The current point of a patch with factor L.
  DpgPoint point(int L) const {
    DpgPoint p;
    p.j = j_;
    p.k = k_;
    p.u = bary_weight(j_, L, format_.bary_bits);
    p.v = bary_weight(k_, L, format_.bary_bits);
    p.w = format_.bary_one() - p.u - p.v;
    p.last = k_ == L;
    return p;
  }

  // The clock edge after the current point was consumed.
  void consume(int L) {
    if (k_ == L) {
      j_ = k_ = 0;
    } else if (j_ + 1 + k_ <= L) {
      ++j_;
    } else {
      j_ = 0;
      ++k_;
    }
  }

 private:
  NumberFormat format_;
  int j_ = 0, k_ = 0;
};

}  // namespace tessim::sim
