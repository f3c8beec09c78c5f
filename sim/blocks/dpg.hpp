// Domain-point generator of rtl/tess_dpg.sv (docs/microarchitecture.md §7): walks the uniform
// pattern of the patch at the buffers' rd_ptr, j fastest: (0,0), (1,0), ..., (L,0), (0,1), ...,
// (0,L). A point is consumed when a TE context is allocated for it.
#pragma once

#include <array>
#include <cstdint>

#include "model/pattern.hpp"
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
  DpgPoint point(int L) {
    if (L != weights_L_) load_weights(L);
    DpgPoint p;
    p.j = j_;
    p.k = k_;
    p.u = weights_[static_cast<std::size_t>(j_)];
    p.v = weights_[static_cast<std::size_t>(k_)];
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
  // bary_weight(i, L) for i = 0..L, kept for the factor of the patches being walked (the
  // hardware's weights are a function of (i, L); the model saves two divisions per point).
  void load_weights(int L) {
    for (int i = 0; i <= L; ++i) weights_[static_cast<std::size_t>(i)] = bary_weight(i, L, format_.bary_bits);
    weights_L_ = L;
  }

  NumberFormat format_;
  int j_ = 0, k_ = 0;
  int weights_L_ = 0;
  std::array<std::int64_t, kMaxTessFactor + 1> weights_{};
};

}  // namespace tessim::sim
