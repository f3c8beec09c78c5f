// The TE's per-op state bits of all contexts, packed in age order (docs/microarchitecture.md
// §8): lane a (16 bits) belongs to the a-th oldest context (lane 0 = the head), bit o of a lane
// to op o. The scheduler's order — age first, then op — is then the order of the bits, so the
// first N ready ops are the N lowest set bits, and a retirement shifts every lane down by one.
#pragma once

#include <array>
#include <cstdint>

namespace tessim::sim {

struct OpMasks {
  static constexpr int kLaneBits = 16;  // ops per context (14) rounded up
  static constexpr int kLanesPerWord = 64 / kLaneBits;
  static constexpr int kMaxLanes = 16;  // V <= 16 (Te::kMaxContexts)
  static constexpr int kWords = kMaxLanes / kLanesPerWord;
  static constexpr std::uint64_t kLane = (std::uint64_t{1} << kLaneBits) - 1;

  std::array<std::uint64_t, kWords> word{};

  static constexpr int words_for(int lanes) { return (lanes + kLanesPerWord - 1) / kLanesPerWord; }
  static constexpr int shift_of(int lane) { return kLaneBits * (lane % kLanesPerWord); }

  std::uint32_t lane(int a) const {
    return static_cast<std::uint32_t>((word[static_cast<std::size_t>(a / kLanesPerWord)] >> shift_of(a)) & kLane);
  }
  void set_lane(int a, std::uint32_t bits) {
    std::uint64_t& w = word[static_cast<std::size_t>(a / kLanesPerWord)];
    w = (w & ~(kLane << shift_of(a))) | (std::uint64_t{bits} << shift_of(a));
  }

  // Lanes move down by `n` (the n oldest drop out) within the first `words` words; the lanes
  // freed at the top are zero.
  void shift_down(int n, int words) {
    if (n == 0) return;
    const int skip = n / kLanesPerWord;
    const int bits = shift_of(n);
    for (int w = 0; w < words; ++w) {
      const int from = w + skip;
      std::uint64_t lo = from < words ? word[static_cast<std::size_t>(from)] : 0;
      const std::uint64_t hi = from + 1 < words ? word[static_cast<std::size_t>(from + 1)] : 0;
      if (bits != 0) lo = (lo >> bits) | (hi << (64 - bits));
      word[static_cast<std::size_t>(w)] = lo;
    }
  }

  bool any(int words) const {
    std::uint64_t m = 0;
    for (int w = 0; w < words; ++w) m |= word[static_cast<std::size_t>(w)];
    return m != 0;
  }
};

}  // namespace tessim::sim
