// The Verilated-model side of tessim::rtl::RtlUnit, as a template over the model class that
// Verilator generates for one configuration (rtl/CMakeLists.txt). Only translation units that
// include the generated headers need this file; everything else uses rtl_unit.hpp.
#pragma once

#include <unistd.h>


#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <verilated.h>
#include <verilated_fst_c.h>
#ifdef TESSIM_RTL_COVERAGE
#include <verilated_cov.h>
#endif

#include "rtl/verilated/rtl_unit.hpp"

namespace tessim::rtl {

namespace detail {

// ---- bit fields of Verilator port types (CData..QData, or VlWide for > 64 bits) ----

template <class T>
struct IsWide : std::false_type {};
template <std::size_t N>
struct IsWide<VlWide<N>> : std::true_type {};

constexpr std::uint64_t low_mask(int width) {
  return width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
}

template <class T>
std::uint64_t get_bits(const T& sig, int lsb, int width) {
  if constexpr (IsWide<T>::value) {
    std::uint64_t r = 0;
    for (int done = 0; done < width;) {
      const int bit = lsb + done;
      const int off = bit % 32;
      const int take = std::min(32 - off, width - done);
      const std::uint64_t chunk = (static_cast<std::uint64_t>(sig[bit / 32]) >> off) & low_mask(take);
      r |= chunk << done;
      done += take;
    }
    return r;
  } else {
    return (static_cast<std::uint64_t>(sig) >> lsb) & low_mask(width);
  }
}

template <class T>
void put_bits(T& sig, int lsb, int width, std::uint64_t value) {
  value &= low_mask(width);
  if constexpr (IsWide<T>::value) {
    for (int done = 0; done < width;) {
      const int bit = lsb + done;
      const int off = bit % 32;
      const int take = std::min(32 - off, width - done);
      const std::uint32_t field = static_cast<std::uint32_t>(low_mask(take) << off);
      const std::uint32_t chunk = static_cast<std::uint32_t>(((value >> done) & low_mask(take)) << off);
      sig[bit / 32] = (sig[bit / 32] & ~field) | chunk;
      done += take;
    }
  } else {
    using U = std::remove_reference_t<T>;
    const std::uint64_t field = low_mask(width) << lsb;
    sig = static_cast<U>((static_cast<std::uint64_t>(sig) & ~field) | (value << lsb));
  }
}

inline std::int64_t sign_extend(std::uint64_t v, int width) {
  const std::uint64_t sign = std::uint64_t{1} << (width - 1);
  return static_cast<std::int64_t>((v ^ sign) - sign);
}

// Verilator's random reset takes a non-zero int seed (0 would mean "seed from the clock").
inline int verilator_seed(std::uint64_t seed) {
  const auto folded = static_cast<std::uint32_t>((seed ^ (seed >> 31)) & 0x7fffffffu);
  return folded == 0 ? 1 : static_cast<int>(folded);
}

}  // namespace detail

// A Verilated configuration as rtl/CMakeLists.txt declares it (tessim_rtl_variant): its name,
// whether it is a verification build, and the tess_unit parameters given on top of tess_pkg's
// defaults (which are sim::UnitConfig's).
struct RtlParameter {
  const char* name;  // tess_unit parameter, e.g. "IntBlocks"
  int value;
};

struct VariantSpec {
  const char* name;
  bool randomize_x = false;  // VERIF build: seed the random initial values, assertions on
  std::vector<RtlParameter> parameters;

  int inject_bug() const;                 // InjectBug, 0 when not given
  sim::HardwareConfig config() const;     // the hardware it implements (dedicated CPG)
};

template <class Model>
class VerilatedUnit final : public RtlUnit {
 public:
  VerilatedUnit(const VariantSpec& spec, std::uint64_t seed)
      : RtlUnit(spec.name, spec.config(), spec.inject_bug()),
        context_(std::make_unique<VerilatedContext>()) {
    context_->fatalOnError(false);  // a failed assertion becomes an RtlAssertionError
    context_->traceEverOn(true);
    if (spec.randomize_x) {
      context_->randReset(2);
      context_->randSeed(detail::verilator_seed(seed));
    }
    Verilated::threadContextp(context_.get());
    model_ = std::make_unique<Model>(context_.get(), "tess");
    // perf_ctr_o is 64 (NumScalarCtrs + N) bits: tess_pkg::ctr_e has as many counters as the
    // registry has rows in the RTL.
    static_assert(detail::IsWide<std::remove_cvref_t<decltype(model_->perf_ctr_o)>>::value);
    if (sizeof(model_->perf_ctr_o) != 8 * (sim::kRtlScalarCounters + static_cast<std::size_t>(int_blocks())))
      throw std::logic_error(std::string(spec.name) + ": perf_ctr_o is " + std::to_string(8 * sizeof(model_->perf_ctr_o)) +
                             " bits, the counter registry reads " +
                             std::to_string(64 * (sim::kRtlScalarCounters + static_cast<std::size_t>(int_blocks()))));
    set_mode(NormalMode::Quadratic);
    reset();
  }

  ~VerilatedUnit() override {
    Verilated::threadContextp(context_.get());
    close_wave();
    model_->final();
#ifdef TESSIM_RTL_COVERAGE
    // Coverage builds: this unit's counts, one file per unit (verilator_coverage merges them).
    if (const char* base = std::getenv("TESSIM_RTL_COVERAGE_FILE")) {
      static int written = 0;
      const std::string path = std::string(base) + "." + std::to_string(getpid()) + "." + std::to_string(written++);
      context_->coveragep()->write(path.c_str());
    }
#endif
  }

  void reset() override {
    Verilated::threadContextp(context_.get());
    drive_idle();
    // A falling rst_ni edge whatever its initial value, then one clock edge under reset.
    // These evaluations are not cycles and are not dumped.
    model_->clk_i = 0;
    model_->rst_ni = 1;
    model_->eval();
    model_->rst_ni = 0;
    model_->eval();
    model_->clk_i = 1;
    model_->eval();
    model_->clk_i = 0;
    model_->eval();
    model_->rst_ni = 1;
    model_->eval();
    cycle_ = 0;
    // Waveform time is 2 x cycle (+1 at the rising edge) from the first reset on; after a
    // later reset it continues past what was already dumped.
    if (dumped_) time_base_ = last_dump_ + 2 - (last_dump_ % 2);
    check_errors();
  }

  void set_mode(NormalMode mode) override {
    if (!sim::hardware_supports(mode)) {
      throw std::invalid_argument("normal mode " + std::string(to_string(mode)) +
                                  " is not implemented by the unit");
    }
    model_->mode_i = static_cast<CData>(sim::mode_code(mode));
  }

  bool tri_ready() const override { return model_->tri_ready_o != 0; }
  bool vtx_valid() const override { return model_->vtx_valid_o != 0; }

  sim::VertexFx vtx() const override {
    const int w = format().coord_width();
    const int b = format().bary_bits;
    sim::VertexFx v;
    for (int c = 0; c < 3; ++c) {
      v.pos[c] = detail::sign_extend(detail::get_bits(model_->vtx_pos_o, c * w, w), w);
      v.nrm[c] = detail::sign_extend(detail::get_bits(model_->vtx_nrm_o, c * w, w), w);
    }
    v.u = static_cast<std::int64_t>(detail::get_bits(model_->vtx_u_o, 0, b + 1));
    v.v = static_cast<std::int64_t>(detail::get_bits(model_->vtx_v_o, 0, b + 1));
    v.j = static_cast<int>(model_->vtx_j_o);
    v.k = static_cast<int>(model_->vtx_k_o);
    v.L = static_cast<int>(model_->vtx_l_o);
    v.index = static_cast<int>(model_->vtx_index_o);
    v.id = static_cast<std::uint32_t>(model_->vtx_id_o);
    v.last = model_->vtx_last_o != 0;
    v.flags = static_cast<std::uint8_t>(model_->vtx_flags_o);
    return v;
  }

  // Every registry row with an RTL counter (sim/base/counter_registry.hpp), read from the
  // counter bus perf_ctr_o at its rtl_counter_index (tess_pkg::ctr_e); rows without one stay 0
  // (the GPE's classes, cpg wait_gpe: the RTL's CPG is dedicated).
  sim::UnitCounters counters() const override {
    sim::UnitCounters k;
    k.int_blocks = int_blocks();
    for (std::size_t row = 0; row < sim::kCounterRegistry.size(); ++row) {
      if (!sim::kCounterRegistry[row].has_rtl()) continue;
      const auto first = static_cast<int>(sim::rtl_counter_index(row));
      for (int i = 0; i < sim::counter_instances(k, row); ++i)
        *sim::counter_slot(k, row, i) = detail::get_bits(model_->perf_ctr_o, 64 * (first + i), 64);
    }
    return k;
  }

  void tick(const sim::UnitInputs& in) override {
    Verilated::threadContextp(context_.get());
    const int w = format().coord_width();
    model_->clk_i = 0;
    model_->tri_valid_i = in.tri_valid ? 1 : 0;
    for (int v = 0; v < 3; ++v) {
      for (int c = 0; c < 3; ++c) {
        detail::put_bits(model_->tri_p_i, (3 * v + c) * w, w, static_cast<std::uint64_t>(in.tri.p[v][c]));
        detail::put_bits(model_->tri_n_i, (3 * v + c) * w, w, static_cast<std::uint64_t>(in.tri.n[v][c]));
      }
    }
    // Scalar tags (read by CpgTags builds only): vertex v's Δ, σ, θ, β at [6vW +: 6W].
    for (int v = 0; v < 3; ++v) {
      const sim::TagsFx& t = in.tri.tags[v];
      for (int c = 0; c < 3; ++c)
        detail::put_bits(model_->tri_tags_i, (6 * v + c) * w, w, static_cast<std::uint64_t>(t.delta[c]));
      detail::put_bits(model_->tri_tags_i, (6 * v + 3) * w, w, static_cast<std::uint64_t>(t.sigma));
      detail::put_bits(model_->tri_tags_i, (6 * v + 4) * w, w, static_cast<std::uint64_t>(t.theta));
      detail::put_bits(model_->tri_tags_i, (6 * v + 5) * w, w, static_cast<std::uint64_t>(t.beta));
    }
    // Silhouette weights (read by AlphaBits builds only): edge e's alpha at [e(A + 1) +: A + 1].
    if (const int a = format().alpha_bits; a > 0) {
      for (int e = 0; e < 3; ++e)
        detail::put_bits(model_->tri_alpha_i, e * (a + 1), a + 1, sim::alpha_port_value(in.tri.alpha[e], a));
    }
    model_->tri_l_i = static_cast<CData>(in.tri.L & 0x7f);
    model_->tri_pattern_i = static_cast<CData>(static_cast<unsigned>(in.tri.pattern) & 3);
    for (int e = 0; e < 4; ++e)
      detail::put_bits(model_->tri_factors_i, 23 * e, 23, static_cast<std::uint64_t>(in.tri.factors[e]) & 0x7fffff);
    model_->tri_id_i = in.tri.id;
    model_->vtx_ready_i = in.vtx_ready ? 1 : 0;
    model_->eval();
    dump(time_base_ + 2 * cycle_);
    model_->clk_i = 1;
    model_->eval();
    dump(time_base_ + 2 * cycle_ + 1);
    ++cycle_;
    check_errors();
  }

  void open_wave(const std::filesystem::path& path) override {
    close_wave();
    fst_ = std::make_unique<VerilatedFstC>();
    model_->trace(fst_.get(), 99);
    fst_->open(path.string().c_str());
    if (!fst_->isOpen()) {
      fst_.reset();
      throw std::runtime_error("cannot open waveform file " + path.string());
    }
    wave_enabled_ = true;
  }

  void close_wave() override {
    if (fst_) {
      fst_->close();
      fst_.reset();
    }
    wave_enabled_ = false;
  }

  void set_wave_enabled(bool enabled) override { wave_enabled_ = enabled && fst_ != nullptr; }

 private:
  void drive_idle() {
    model_->tri_valid_i = 0;
    model_->vtx_ready_i = 0;
  }

  void dump(std::uint64_t time) {
    if (!wave_enabled_) return;
    fst_->dump(time);
    last_dump_ = time;
    dumped_ = true;
  }

  void check_errors() {
    if (context_->gotError()) {
      context_->gotError(false);
      context_->gotFinish(false);
      throw RtlAssertionError("RTL assertion failed in variant " + variant() + " at cycle " +
                              std::to_string(cycle_));
    }
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<VerilatedFstC> fst_;
  bool wave_enabled_ = false;
  bool dumped_ = false;
  std::uint64_t last_dump_ = 0;
  std::uint64_t time_base_ = 0;
};

// The factory entry of a variant: make_variant<Vtess_xyz>.
template <class Model>
std::unique_ptr<RtlUnit> make_variant(const VariantSpec& spec, std::uint64_t seed) {
  return std::make_unique<VerilatedUnit<Model>>(spec, seed);
}

}  // namespace tessim::rtl
