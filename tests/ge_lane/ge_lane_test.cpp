// The geometry engine's ALU lanes (rtl/ge/) against C++ references, bit for bit:
//  - ge_fma_lane against std::fmaf with the lane's flush-to-zero rules: subnormal operands become
//    zeros of their sign before the fmaf; a subnormal result of the fmaf (that is, after IEEE
//    rounding at the subnormal quantum) becomes a zero of its sign; any NaN expects 0x7fc00000.
//  - ge_mac_lane (W = 1 + I + F, the unit's default format, and W = 32) against
//    sat(floor((a * b + 2^(F-1)) / 2^F) + c) in 128-bit integers.
// Random operands come from a fixed seed (GE_LANE_SEED overrides it; GE_LANE_CASES the count).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vge_fma_lane.h"
#include "Vge_mac_lane.h"
#include "Vge_mac_lane_w32.h"
#include "verilated.h"

namespace {

std::uint64_t env_or(const char* name, std::uint64_t fallback) {
  const char* v = std::getenv(name);
  return v ? std::strtoull(v, nullptr, 0) : fallback;
}

// One lane model: inputs set, one rising edge, the registered result read back.
template <class Model>
class Lane {
 public:
  Lane() : model_(std::make_unique<Model>(&context_, "lane")) {
    model_->clk_i = 0;
    model_->rst_ni = 0;
    model_->valid_i = 0;
    model_->eval();
    model_->rst_ni = 1;
    model_->eval();
  }
  ~Lane() { model_->final(); }
  std::uint64_t step(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    model_->a_i = a;
    model_->b_i = b;
    model_->c_i = c;
    model_->valid_i = 1;
    model_->clk_i = 0;
    model_->eval();
    model_->clk_i = 1;
    model_->eval();
    if (!model_->valid_o) ADD_FAILURE() << "valid_o low one cycle after valid_i";
    return model_->d_o;
  }

 private:
  VerilatedContext context_;
  std::unique_ptr<Model> model_;
};

// ---------------------------------------------------------------- FP32 reference
constexpr std::uint32_t kQuietNaN = 0x7fc00000u;

std::uint32_t ftz(std::uint32_t x) { return (x & 0x7f800000u) == 0 ? x & 0x80000000u : x; }

std::uint32_t ref_fma(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const float r = std::fmaf(std::bit_cast<float>(ftz(a)), std::bit_cast<float>(ftz(b)),
                            std::bit_cast<float>(ftz(c)));
  if (std::isnan(r)) return kQuietNaN;
  return ftz(std::bit_cast<std::uint32_t>(r));  // flush after the IEEE rounding
}

std::uint32_t fp(std::uint32_t sign, std::uint32_t exp, std::uint32_t frac) {
  return (sign & 1u) << 31 | (exp & 0xffu) << 23 | (frac & 0x7fffffu);
}
std::uint32_t fbits(float f) { return std::bit_cast<std::uint32_t>(f); }

// What kind of result a case produced, to show what the random mix reaches.
std::string result_class(std::uint32_t r, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (r == kQuietNaN) return "nan";
  if ((r & 0x7fffffffu) == 0x7f800000u) return "inf";
  if ((r & 0x7fffffffu) == 0) {
    // A zero with a nonzero, finite exact result was flushed (or underflowed).
    const double exact = static_cast<double>(std::bit_cast<float>(ftz(a))) *
                             static_cast<double>(std::bit_cast<float>(ftz(b))) +
                         static_cast<double>(std::bit_cast<float>(ftz(c)));
    return exact != 0.0 ? "zero_flushed" : "zero_exact";
  }
  if ((r & 0x7f800000u) == 0x00800000u) return "min_binade";
  return "normal";
}

class FmaCases {
 public:
  explicit FmaCases(std::uint64_t seed) : rng_(seed) {}

  static constexpr int kKinds = 10;
  // Random operands of one of ten kinds (the kind is returned for the statistics).
  int next(std::uint32_t& a, std::uint32_t& b, std::uint32_t& c) {
    const int kind = static_cast<int>(below(kKinds));
    switch (kind) {
      case 0:  // fully random bit patterns
        a = u32();
        b = u32();
        c = u32();
        break;
      case 1: {  // a * b close to -c: cancellation, c a few ulps from the rounded product
        a = fp(bit(), range(40, 214), u32());
        b = fp(bit(), range(40, 214), u32());
        const double p = static_cast<double>(std::bit_cast<float>(a)) * std::bit_cast<float>(b);
        std::uint32_t cb = fbits(static_cast<float>(-p));
        cb = static_cast<std::uint32_t>(static_cast<std::int64_t>(cb) + range(0, 16) - 8);
        if (below(8) == 0) cb ^= 0x80000000u;  // sometimes an addition instead
        c = cb;
        break;
      }
      case 2: {  // exponent differences from far below to far above the product
        const int ea = static_cast<int>(range(1, 254)), eb = static_cast<int>(range(1, 254));
        const int ec = ea + eb - 127 + static_cast<int>(range(0, 200)) - 100;
        a = fp(bit(), ea, u32());
        b = fp(bit(), eb, u32());
        c = fp(bit(), static_cast<std::uint32_t>(std::clamp(ec, 1, 254)), u32());
        break;
      }
      case 3: {  // exact zeros: short significands make a * b exact, c = -(a * b); zero operands
        if (below(2) == 0) {
          a = fp(bit(), range(64, 190), u32() & 0x7ff800u);
          b = fp(bit(), range(64, 190), u32() & 0x7ff800u);
          const float p = std::bit_cast<float>(a) * std::bit_cast<float>(b);  // exact
          c = fbits(-p);
        } else {
          a = below(2) ? fp(bit(), 0, below(2) ? 0 : u32()) : u32();
          b = below(2) ? fp(bit(), 0, below(2) ? 0 : u32()) : u32();
          c = below(2) ? fp(bit(), 0, below(2) ? 0 : u32()) : u32();
        }
        break;
      }
      case 4: {  // overflow: products and addends near the top of the range
        const int ea = static_cast<int>(range(127, 254));
        const int eb = std::clamp(static_cast<int>(range(0, 20)) + 244 - ea + 127, 1, 254);
        a = fp(bit(), static_cast<std::uint32_t>(ea), u32() | (below(2) ? 0x7fff00u : 0u));
        b = fp(bit(), static_cast<std::uint32_t>(eb), u32() | (below(2) ? 0x7fff00u : 0u));
        c = fp(bit(), range(230, 254), u32());
        break;
      }
      case 5: {  // results near 2^-126: products and addends around the subnormal boundary
        const int ea = static_cast<int>(range(1, 254));
        const int eb = std::clamp(127 - ea + static_cast<int>(range(0, 30)) - 26 + 1, 1, 254);
        a = fp(bit(), static_cast<std::uint32_t>(ea), below(2) ? u32() : 0x7fffffu - range(0, 3));
        b = fp(bit(), static_cast<std::uint32_t>(eb), below(2) ? u32() : range(0, 3));
        c = below(4) == 0 ? fp(bit(), 0, 0) : fp(bit(), range(1, 4), u32());
        break;
      }
      case 6: {  // special operands mixed with ordinary ones
        a = special();
        b = special();
        c = special();
        break;
      }
      case 7: {  // short significands, close exponents: exact results, ties and carries
        const int ea = static_cast<int>(range(100, 154)), eb = static_cast<int>(range(100, 154));
        const int ec = ea + eb - 127 + static_cast<int>(range(0, 60)) - 30;
        a = fp(bit(), ea, u32() & top_mask());
        b = fp(bit(), eb, u32() & top_mask());
        c = fp(bit(), static_cast<std::uint32_t>(std::clamp(ec, 1, 254)), u32() & top_mask());
        break;
      }
      case 8: {  // a tie in a short product, decided by an addend far below it (sticky bits)
        const int ea = static_cast<int>(range(64, 190)), eb = static_cast<int>(range(64, 190));
        const int ec = ea + eb - 127 - static_cast<int>(range(20, 90));
        a = fp(bit(), ea, u32() & 0x7ff800u);
        b = fp(bit(), eb, u32() & 0x7ff800u);
        c = fp(bit(), static_cast<std::uint32_t>(std::clamp(ec, 1, 254)), u32());
        break;
      }
      default: {  // c = -round(a * b) exactly: the result is the rounding error, often tiny
        a = fp(bit(), range(1, 254), u32());
        b = fp(bit(), std::clamp(static_cast<int>(range(0, 100)) + 127 - 50 + 127 -
                                     static_cast<int>((a >> 23) & 0xff),
                                 1, 254),
               u32());
        c = fbits(-(std::bit_cast<float>(a) * std::bit_cast<float>(b)));
        break;
      }
    }
    return kind;
  }

 private:
  std::uint64_t below(std::uint64_t n) { return rng_() % n; }
  std::uint32_t range(std::uint32_t lo, std::uint32_t hi) {
    return lo + static_cast<std::uint32_t>(below(hi - lo + 1));
  }
  std::uint32_t u32() { return static_cast<std::uint32_t>(rng_()); }
  std::uint32_t bit() { return static_cast<std::uint32_t>(rng_() & 1); }
  std::uint32_t top_mask() { return (0x7fffffu << range(0, 23)) & 0x7fffffu; }
  std::uint32_t special() {
    static const std::uint32_t pool[] = {0x00000000u, 0x80000000u, 0x00000001u, 0x807fffffu,
                                         0x7f800000u, 0xff800000u, 0x7fc00000u, 0xffc00001u,
                                         0x7f800001u, 0x7fbfffffu, 0x7f7fffffu, 0xff7fffffu,
                                         0x00800000u, 0x80800000u, 0x3f800000u, 0xbf800000u};
    return below(3) == 0 ? u32() : pool[below(std::size(pool))];
  }
  std::mt19937_64 rng_;
};

// Hand-picked operands: every special rule, the flush boundary, ties, overflow, signed zeros.
std::vector<std::array<std::uint32_t, 3>> directed_fma_cases() {
  const std::uint32_t pz = 0, nz = 0x80000000u, one = 0x3f800000u, mone = 0xbf800000u;
  const std::uint32_t inf = 0x7f800000u, ninf = 0xff800000u, qnan = 0x7fc00000u;
  const std::uint32_t snan = 0x7f800001u, nnan = 0xffffffffu, max = 0x7f7fffffu;
  const std::uint32_t min = 0x00800000u, sub = 0x00000001u, nsub = 0x807fffffu;
  const std::uint32_t below_one = 0x3f7fffffu;  // 1 - 2^-24
  std::vector<std::array<std::uint32_t, 3>> v = {
      // NaNs in any position, signalling or negative, and invalid operations
      {qnan, one, one}, {one, snan, one}, {one, one, nnan}, {snan, pz, inf}, {inf, pz, one},
      {pz, ninf, one}, {inf, sub, pz}, {inf, one, ninf}, {ninf, one, inf}, {inf, mone, inf},
      {inf, one, inf}, {inf, inf, inf}, {ninf, inf, ninf}, {max, max, ninf}, {one, one, inf},
      {pz, pz, ninf}, {sub, inf, qnan},
      // signed zeros: 0 * x + 0 in every sign combination, and flushed subnormal operands
      {pz, one, pz}, {pz, one, nz}, {nz, one, pz}, {nz, one, nz}, {pz, mone, nz}, {nz, mone, nz},
      {sub, one, nsub}, {nsub, one, nz}, {nsub, mone, nz}, {sub, sub, sub}, {one, nsub, one},
      {one, one, mone}, {mone, one, one}, {mone, mone, mone}, {one, mone, one},
      // the flush boundary: 2^-126 * (1 - 2^-24) = 2^-126 - 2^-150 rounds up to 2^-126 in IEEE
      {below_one, min, pz}, {below_one, min, nz}, {below_one, 0x80800000u, pz},
      {0x3f7ffffeu, min, pz}, {one, min, pz}, {one, min, 0x80800000u}, {min, one, 0x81000000u},
      {0x3f000000u, min, pz}, {0x3fc00000u, min, 0x80800000u}, {0x3f800001u, min, 0x80800000u},
      {0x40000000u, min, 0x81000000u}, {0x3fffffffu, min, 0x80800000u}, {min, min, pz},
      {0x3f7fffffu, 0x00ffffffu, pz}, {0x3f800001u, 0x00ffffffu, 0x80800000u},
      // ties at 1.0: 1 + 2^-24 (to even: 1), 1 + 3 * 2^-24 (up), 1 - 2^-25 (stays 1)
      {0x33800000u, one, one}, {0x34400000u, one, one}, {0x33000000u, mone, one},
      {0x33800001u, one, one}, {0x3f800001u, 0x33800000u, one}, {0xb3800000u, one, one},
      {0x3f800800u, 0x3f800800u, 0xbf800000u},  // (1 + 2^-12)^2 - 1 = 2^-11 + 2^-24: fused only
      // overflow and the largest finite
      {max, one, max}, {max, 0x40000000u, pz}, {max, one, 0x73800000u}, {max, one, 0x73000000u},
      {max, mone, 0xf3800000u}, {0x5f800000u, 0x5f800000u, pz}, {0x5f7fffffu, 0x5f7fffffu, pz},
      {max, 0x3f800001u, pz}, {max, mone, max},
      // addend far above and far below the product
      {min, min, one}, {min, min, mone}, {max, max, one}, {one, one, 0x4b800000u},
      {one, 0xbf800000u, 0x4b800000u}, {0x3f800001u, one, 0xcb800000u}, {one, min, one},
      {0x33800000u, 0x3f800001u, one}, {0x00800001u, 0x3f000000u, 0x80800000u}};
  return v;
}

// ---------------------------------------------------------------- fixed-point reference
using i128 = __int128;

std::int64_t sext(std::uint64_t x, int w) {
  const std::uint64_t m = std::uint64_t{1} << (w - 1);
  x &= (m << 1) - 1;
  return static_cast<std::int64_t>((x ^ m) - m);
}

std::int64_t ref_mac(std::int64_t a, std::int64_t b, std::int64_t c, int w, int f) {
  const i128 p = static_cast<i128>(a) * b;
  const i128 r = (p + (i128{1} << (f - 1))) >> f;  // arithmetic: floor, so round half up
  const i128 s = r + c;
  const i128 hi = (i128{1} << (w - 1)) - 1, lo = -(i128{1} << (w - 1));
  return static_cast<std::int64_t>(s > hi ? hi : (s < lo ? lo : s));
}

template <class Model>
void run_mac(int int_bits, int frac_bits, std::uint64_t cases, std::uint64_t seed) {
  const int w = 1 + int_bits + frac_bits;
  const std::uint64_t mask = (w == 64) ? ~std::uint64_t{0} : (std::uint64_t{1} << w) - 1;
  const std::int64_t max = (std::int64_t{1} << (w - 1)) - 1, min = -max - 1;
  Lane<Model> lane;
  std::mt19937_64 rng(seed);
  auto any = [&] { return sext(rng(), w); };
  auto small = [&] { return sext(rng(), static_cast<int>(1 + rng() % (w - 1))); };
  auto near = [&](std::int64_t v) { return std::clamp<std::int64_t>(v - 8 + static_cast<std::int64_t>(rng() % 17), min, max); };
  std::uint64_t failures = 0, checked = 0, saturated = 0, ties = 0;
  auto check = [&](std::int64_t a, std::int64_t b, std::int64_t c) {
    const std::int64_t want = ref_mac(a, b, c, w, frac_bits);
    const std::int64_t got = sext(lane.step(static_cast<std::uint64_t>(a) & mask,
                                            static_cast<std::uint64_t>(b) & mask,
                                            static_cast<std::uint64_t>(c) & mask),
                                  w);
    ++checked;
    if (want == max || want == min) ++saturated;
    if (((static_cast<i128>(a) * b) & ((i128{1} << frac_bits) - 1)) == (i128{1} << (frac_bits - 1))) ++ties;
    if (got != want && failures++ < 10)
      ADD_FAILURE() << "W=" << w << " a=" << a << " b=" << b << " c=" << c << ": lane " << got
                    << ", reference " << want;
  };
  // Directed: the extremes in every combination.
  const std::int64_t edges[] = {0, 1, -1, 2, -2, max, min, max - 1, min + 1,
                                std::int64_t{1} << frac_bits, -(std::int64_t{1} << frac_bits),
                                std::int64_t{1} << (frac_bits - 1), -(std::int64_t{1} << (frac_bits - 1))};
  for (auto a : edges)
    for (auto b : edges)
      for (auto c : edges) check(a, b, c);
  for (std::uint64_t i = 0; i < cases; ++i) {
    switch (rng() % 5) {
      case 0: check(any(), any(), any()); break;
      case 1: check(small(), small(), small()); break;
      case 2: {  // a * b with its dropped bits exactly one half: a tie, either sign
        const int j = static_cast<int>(rng() % frac_bits);
        const std::int64_t low = std::int64_t{1} << (frac_bits - 1 - j);
        std::int64_t a = (any() & ~((std::int64_t{1} << (frac_bits - j)) - 1)) | low;
        std::int64_t b = (rng() & 1) ? (std::int64_t{1} << j) : -(std::int64_t{1} << j);
        if (b < min) b = min;
        check(a, b, small());
        break;
      }
      case 3: check(any(), any(), near(rng() & 1 ? max : min)); break;  // saturation both ways
      default: {  // sums near the bounds: c = bound - round(a * b) + a few
        const std::int64_t a = small(), b = small();
        const i128 r = ((static_cast<i128>(a) * b) + (i128{1} << (frac_bits - 1))) >> frac_bits;
        const i128 bound = (rng() & 1) ? max : min;
        const i128 c = bound - r + static_cast<std::int64_t>(rng() % 9) - 4;
        check(a, b, static_cast<std::int64_t>(c > max ? max : (c < min ? min : c)));
        break;
      }
    }
  }
  std::printf("ge_mac_lane W=%d (I=%d, F=%d): %llu cases (%llu saturated, %llu ties), %llu mismatches\n",
              w, int_bits, frac_bits, static_cast<unsigned long long>(checked),
              static_cast<unsigned long long>(saturated), static_cast<unsigned long long>(ties),
              static_cast<unsigned long long>(failures));
  EXPECT_EQ(failures, 0u);
}

}  // namespace

// The reference itself on known values, so that a wrong libm or flag could not hide a lane bug.
TEST(GeFmaLane, ReferenceKnownValues) {
  EXPECT_EQ(ref_fma(0x3f800000u, 0x3f800000u, 0x3f800000u), 0x40000000u);           // 1 * 1 + 1
  EXPECT_EQ(ref_fma(0x33800000u, 0x3f800000u, 0x3f800000u), 0x3f800000u);           // tie to even
  EXPECT_EQ(ref_fma(0x3f800800u, 0x3f800800u, 0xbf800000u), 0x3a000400u);           // fused: 2^-11 + 2^-24
  EXPECT_EQ(ref_fma(0x3f7fffffu, 0x00800000u, 0u), 0x00800000u);                    // rounds up to 2^-126
  EXPECT_EQ(ref_fma(0x3f7ffffeu, 0x00800000u, 0u), 0u);                             // subnormal: flushed
  EXPECT_EQ(ref_fma(0x3f7ffffeu, 0x80800000u, 0u), 0x80000000u);                    // with its sign
  EXPECT_EQ(ref_fma(0x7f800000u, 0u, 0x3f800000u), kQuietNaN);                      // inf * 0
  EXPECT_EQ(ref_fma(0x00000001u, 0x7f800000u, 0x3f800000u), kQuietNaN);             // subnormal is 0
  EXPECT_EQ(ref_fma(0x80000000u, 0x3f800000u, 0x80000000u), 0x80000000u);           // -0 + -0
  EXPECT_EQ(ref_fma(0x3f800000u, 0x3f800000u, 0xbf800000u), 0u);                    // cancellation: +0
}

TEST(GeFmaLane, DirectedAndRandom) {
  const std::uint64_t seed = env_or("GE_LANE_SEED", 20240601);
  const std::uint64_t cases = env_or("GE_LANE_CASES", 4000000);
  Lane<Vge_fma_lane> lane;
  std::uint64_t failures = 0, checked = 0;
  std::map<std::string, std::uint64_t> classes;
  std::uint64_t per_kind[FmaCases::kKinds] = {};
  auto check = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const std::uint32_t want = ref_fma(a, b, c);
    const auto got = static_cast<std::uint32_t>(lane.step(a, b, c));
    ++checked;
    ++classes[result_class(want, a, b, c)];
    if (got != want && failures++ < 20) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "a=0x%08x b=0x%08x c=0x%08x: lane 0x%08x, reference 0x%08x",
                    a, b, c, got, want);
      ADD_FAILURE() << msg;
    }
  };
  const auto directed = directed_fma_cases();
  for (const auto& d : directed) {
    // Each directed case in all eight sign combinations, and with a and b swapped.
    for (std::uint32_t s = 0; s < 8; ++s) {
      const std::uint32_t a = d[0] ^ ((s & 1u) << 31), b = d[1] ^ ((s & 2u) << 30),
                          c = d[2] ^ ((s & 4u) << 29);
      check(a, b, c);
      check(b, a, c);
    }
  }
  const std::uint64_t directed_count = checked;
  FmaCases gen(seed);
  for (std::uint64_t i = 0; i < cases; ++i) {
    std::uint32_t a = 0, b = 0, c = 0;
    ++per_kind[gen.next(a, b, c)];
    check(a, b, c);
  }
  std::printf("ge_fma_lane: %llu directed + %llu random cases (seed %llu), %llu mismatches\n",
              static_cast<unsigned long long>(directed_count),
              static_cast<unsigned long long>(checked - directed_count),
              static_cast<unsigned long long>(seed), static_cast<unsigned long long>(failures));
  std::printf("  random kinds (random bits, cancel, exp diff, exact zero, overflow, near 2^-126, "
              "specials, short significands, tie + far addend, rounding error):");
  for (auto n : per_kind) std::printf(" %llu", static_cast<unsigned long long>(n));
  std::printf("\n  results:");
  for (const auto& [name, n] : classes) std::printf(" %s %llu", name.c_str(), static_cast<unsigned long long>(n));
  std::printf("\n");
  EXPECT_EQ(failures, 0u);
}

TEST(GeMacLane, DefaultFormat) {
  run_mac<Vge_mac_lane>(GE_INT_BITS, GE_FRAC_BITS, env_or("GE_LANE_CASES", 2000000) / 2,
                        env_or("GE_LANE_SEED", 20240601));
}

TEST(GeMacLane, Width32) {
  run_mac<Vge_mac_lane_w32>(11, GE_FRAC_BITS, env_or("GE_LANE_CASES", 2000000) / 2,
                            env_or("GE_LANE_SEED", 20240601) + 1);
}
