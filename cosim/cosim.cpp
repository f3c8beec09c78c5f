#include "cosim/cosim.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>

#include "cosim/checkers.hpp"
#include "cosim/wave.hpp"
#include "model/base/error.hpp"
#include "model/pattern.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/run/testbench.hpp"
#include "sim/unit/model_dut.hpp"
#include "sim/values/host.hpp"

namespace tessim::cosim {

namespace {

// The lock-step loop, ending at the end of the stream, at the first divergence or before cycle
// `stop_at`. Without `checking` it is the replay of a failing run: outputs are not compared.
// With `record` the RTL's waveform (opened by the caller) records those cycles.
struct LockstepRun {
  CosimReport report;
  std::uint64_t expected_vertices = 0;
};

LockstepRun lockstep(const std::vector<sim::TriangleFx>& stream, const CosimOptions& opts,
                     rtl::RtlUnit& rtl, bool checking, std::optional<WaveWindow> record,
                     std::uint64_t stop_at) {
  LockstepRun run;
  CosimReport& rep = run.report;
  rep.variant = opts.variant;
  rep.seed = opts.seed;
  for (const auto& t : stream) run.expected_vertices += static_cast<std::uint64_t>(sim::patch_vertex_count(t));

  sim::ModelDut model(opts.unit);
  sim::Dut& expected = model;  // the reference implementation
  sim::Dut& actual = rtl;      // the implementation under test
  sim::Testbench tb(stream, opts.unit);
  actual.reset();
  rtl.set_mode(opts.unit.normals);

  // The checkers (cosim/checkers.hpp). A replay of a failing run only records the waveform.
  const OutputChecker outputs;
  const CounterChecker counters(opts.unit.int_blocks);
  ProgressChecker progress(opts.hang_cycles);
  const double diagonal = sim::ArithmeticCheck::diagonal_of(stream, opts.unit.format);
  auto make_reference = [&] {
    return std::make_unique<sim::ArithmeticCheck>([&stream](std::uint32_t id) { return stream[id]; }, diagonal,
                                                  opts.unit);
  };
  std::unique_ptr<sim::ArithmeticCheck> reference;
  if (opts.check_reference && checking) reference = make_reference();
  FunctionalCoverage* coverage = checking ? opts.coverage : nullptr;
  if (coverage) coverage->declare(opts.unit);

  std::deque<std::string> recent;
  auto note = [&](std::string s) {
    recent.push_back(std::move(s));
    while (recent.size() > static_cast<std::size_t>(std::max(opts.history, 0))) recent.pop_front();
  };
  std::uint32_t last_patch = 0;
  std::vector<std::uint64_t> resets = opts.reset_at;
  std::sort(resets.begin(), resets.end());
  std::size_t next_reset = 0;
  std::uint64_t cycle = 0;

  // The DPG's place in its patch, followed from the cycle model's allocations (each takes one
  // point of the patch): where a reset lands, and where a random one is aimed.
  std::uint32_t walk_patch = 0;
  int walk_taken = 0, walk_points = 0, walk_outer_ring = 0;  // taken 0: between patches
  auto follow_walk = [&](const sim::CycleActivity& act) {
    if (!act.allocated) return;
    if (walk_taken == 0) {
      walk_patch = act.allocated_patch;
      const sim::TriangleFx& t = stream[walk_patch];
      walk_points = sim::patch_vertex_count(t);
      walk_outer_ring = walk_points;
      if (t.pattern != sim::TriPattern::uniform) {
        const auto& outer = sim::tri_setup(t).factors.outer_points;
        walk_outer_ring = outer[0] + outer[1] + outer[2] - 3;
      }
    }
    if (++walk_taken == walk_points) walk_taken = 0;
  };
  auto dpg_in_d3d11 = [&] { return walk_taken > 0 && stream[walk_patch].pattern != sim::TriPattern::uniform; };
  auto dpg_in_inner_ring = [&] { return dpg_in_d3d11() && walk_taken >= walk_outer_ring; };
  auto cpg_computing = [&] { return model.unit().activity().cpg_action == sim::CpgAction::Compute; };

  // Random resets (RandomResets): the next one's due cycle and its target.
  const RandomResets& random = opts.random_resets;
  sim::SplitMix64 reset_rng(opts.seed ^ 0x4e5e7a7a4e5e7a7aULL);
  const std::uint64_t span = std::max<std::uint64_t>(random.span, 1);
  int random_fired = 0;
  std::uint64_t reset_due = 1 + reset_rng.next() % span;
  auto random_reset_now = [&] {
    if (random_fired >= random.count || cycle < reset_due) return false;
    switch (random_fired % 3) {
      case 1: return dpg_in_inner_ring() || cycle >= reset_due + 8 * span;
      case 2: return cpg_computing() || cycle >= reset_due + 8 * span;
      default: return true;
    }
  };
  bool stopped_early = false;  // at stop_at: the state of that cycle is outside the window

  auto diverge = [&](const Mismatch& m) {
    Divergence d;
    d.cycle = cycle;
    d.field = m.field;
    d.expected = m.expected;
    d.actual = m.actual;
    d.triangle = last_patch;
    d.recent.assign(recent.begin(), recent.end());
    rep.divergence = d;
  };

  for (;; ++cycle) {
    if (cycle >= stop_at) {
      stopped_early = true;
      break;
    }
    if (record && cycle == record->from) rtl.set_wave_enabled(true);
    if (record && record->to != std::numeric_limits<std::uint64_t>::max() && cycle == record->to + 1)
      rtl.set_wave_enabled(false);
    const bool listed_reset = next_reset < resets.size() && cycle == resets[next_reset];
    const bool random_reset = random_reset_now();
    if (listed_reset || random_reset) {
      // Mid-stream reset of both implementations: the stream starts again from the beginning.
      if (listed_reset) ++next_reset;
      if (random_reset) {
        ++random_fired;
        reset_due = cycle + 1 + reset_rng.next() % span;
      }
      ++rep.resets.total;
      rep.resets.dpg_d3d11 += dpg_in_d3d11();
      rep.resets.dpg_inner_ring += dpg_in_inner_ring();
      rep.resets.cpg_compute += cpg_computing();
      walk_taken = 0;
      if (coverage) coverage->sample_reset(model.unit());
      expected.reset();
      actual.reset();
      tb.reset();
      note("cycle " + std::to_string(cycle) + ": reset");
      if (reference) reference = make_reference();
    }

    // 1. Outputs of this cycle (registered state only) must agree. The performance counters are
    // outputs too: comparing them every cycle finds a fault that changes the unit's internal
    // timing before it reaches the vertex stream.
    if (checking) {
      std::optional<Mismatch> m = outputs.check(expected, actual);
      if (!m) m = counters.check(expected.counters(), actual.counters());
      if (m) {
        if (expected.vtx_valid()) last_patch = expected.vtx().id;
        diverge(*m);
        break;
      }
    }

    // 2. The environment: source and geometry engine, driven by the (agreeing) outputs.
    const sim::UnitInputs& in = tb.inputs(expected);
    const bool vtx_valid = expected.vtx_valid();
    const sim::VertexFx vtx_front = vtx_valid ? expected.vtx() : sim::VertexFx{};
    if (coverage && tb.pushed()) coverage->sample_triangle(in.tri, opts.unit.normals);
    if (tb.pushed()) {
      note("cycle " + std::to_string(cycle) + ": triangle " + std::to_string(in.tri.id) + " in (" + sim::describe_pattern(in.tri) +
           ")");
      progress.transfer(cycle);
    }
    if (tb.gpe_cycle().accepted) {
      const sim::VertexFx v = expected.vtx();
      last_patch = v.id;
      note("cycle " + std::to_string(cycle) + ": vertex out " + sim::describe(v));
      if (reference && v.id < stream.size()) reference->check(v);
      if (coverage) coverage->sample_vertex(v);
      progress.transfer(cycle);
      if (checking && opts.vertices_done) opts.vertices_done->fetch_add(1, std::memory_order_relaxed);
    }

    // 3. The clock edge, for both.
    expected.tick(in);
    actual.tick(in);
    follow_walk(model.unit().activity());
    if (coverage) coverage->sample_cycle(in, vtx_valid, vtx_front, tb.gpe_cycle(), model.unit());

    if (checking && tb.accepted() == run.expected_vertices) {
      ++cycle;
      break;
    }
    if (checking && progress.hung(cycle)) {
      rep.hang = true;
      diverge({"progress", "a transfer within " + std::to_string(progress.limit()) + " cycles", "none (hang)"});
      break;
    }
  }

  rep.cycles = cycle;
  rep.triangles = tb.triangles_taken();
  rep.vertices = tb.accepted();
  rep.gpe = tb.gpe().stats();
  rep.model_counters = expected.counters();
  rep.rtl_counters = actual.counters();
  if (reference) rep.reference = reference->result();
  if (!rep.divergence && checking && !stopped_early) {
    if (auto m = counters.check(rep.model_counters, rep.rtl_counters)) {
      diverge(*m);
    } else {
      rep.counters_match = true;
    }
  }
  if (stopped_early && !rep.divergence) rep.counters_match = true;  // compared every cycle so far
  rep.passed = !rep.divergence && rep.counters_match && rep.reference.beyond_bound == 0;
  return run;
}

}  // namespace

CosimReport run_cosim(const std::vector<sim::TriangleFx>& stream, const CosimOptions& opts) {
  return run_cosim_until(stream, opts, std::numeric_limits<std::uint64_t>::max());
}

CosimReport run_cosim_until(const std::vector<sim::TriangleFx>& stream, const CosimOptions& opts,
                            std::uint64_t stop_before) {
  opts.unit.validate("co-simulation configuration");
  if (opts.unit.cpg_mapping != sim::CpgMapping::Dedicated)
    throw InputError("co-simulation configuration", "cpg_mapping",
                     "the RTL implements the dedicated CPG only");
  if (opts.unit.units != 1)
    throw InputError("co-simulation configuration", "units", "the co-simulation runs one unit");
  if (opts.unit.evaluation != sim::Evaluation::Unit)
    throw InputError("co-simulation configuration", "evaluation", "the RTL evaluates on its TE (evaluation unit) only");
  for (std::size_t i = 0; i < stream.size(); ++i) {
    if (stream[i].id != i)
      throw InputError("co-simulation stream", "triangle " + std::to_string(i),
                       "patch ids must be the stream positions");
    std::string problem = sim::tri_pattern_problem(stream[i]);
    if (problem.empty()) problem = sim::tri_alpha_problem(stream[i], opts.unit.format);
    if (!problem.empty()) throw InputError("co-simulation stream", "triangle " + std::to_string(i), problem);
    if (stream[i].pattern != sim::TriPattern::uniform && opts.unit.format.bary_bits < 16)
      throw InputError("co-simulation configuration", "bary_bits",
                       "the D3D11 pattern's points are 16.16: it needs bary_bits >= 16, not " +
                           std::to_string(opts.unit.format.bary_bits));
  }
  auto rtl = rtl::make_rtl_unit(opts.variant, opts.seed);
  rtl::check_config(*rtl, opts.unit);  // throws InputError naming the first parameter that differs

  // An explicit window is recorded in the run itself, passing or not.
  const bool record = !opts.wave.empty() && opts.wave_cycles.has_value();
  const WaveWindow window = record ? *opts.wave_cycles : WaveWindow{};
  if (record) {
    rtl->open_wave(wave_recording_path(opts.wave));
    rtl->set_wave_enabled(false);
  }
  LockstepRun run = lockstep(stream, opts, *rtl, true, record ? std::optional<WaveWindow>(window) : std::nullopt,
                             stop_before);
  CosimReport rep = std::move(run.report);
  if (record) {
    rtl->close_wave();
    finish_wave(opts.wave, rtl->config(), window.from,
                rep.divergence ? std::optional<std::uint64_t>(rep.divergence->cycle) : std::nullopt);
    rep.wave = opts.wave;
  } else if (rep.divergence && !opts.wave.empty()) {
    // Replay from reset with the waveform recording the window before the divergence.
    auto replay = rtl::make_rtl_unit(opts.variant, opts.seed);
    replay->open_wave(wave_recording_path(opts.wave));
    replay->set_wave_enabled(false);
    const std::uint64_t c = rep.divergence->cycle;
    const std::uint64_t from = c > static_cast<std::uint64_t>(opts.wave_window) ? c - opts.wave_window : 0;
    // A few cycles after it too, so that the divergent value shows in the viewer.
    lockstep(stream, opts, *replay, false, WaveWindow{from, c + 5}, c + 6);
    replay->close_wave();
    finish_wave(opts.wave, replay->config(), from, c);
    rep.wave = opts.wave;
  }
  return rep;
}

std::string format_report(const CosimReport& r, const CosimOptions& o) {
  std::ostringstream os;
  const auto& u = o.unit;
  os << "co-simulation  RTL " << r.variant << "  vs  cycle model   seed " << r.seed << "\n";
  os << "  config: N=" << u.int_blocks << " latency=" << u.int_latency << " contexts=" << u.te_contexts
     << " normals=" << to_string(u.normals) << " W=" << u.format.coord_width() << " (I=" << u.format.coord_int_bits
     << ",F=" << u.format.coord_frac_bits << ") B=" << u.format.bary_bits << "  GPE K=" << u.gpe_cycles
     << " stall=" << u.gpe_stall_prob << "\n";
  os << "  ran " << r.cycles << " cycles, " << r.triangles << " triangles in, " << r.vertices << " vertices out\n";
  if (r.resets.total)
    os << "  resets: " << r.resets.total << " (" << r.resets.dpg_d3d11 << " with the DPG inside a D3D11 patch, "
       << r.resets.dpg_inner_ring << " of them past its outer ring; " << r.resets.cpg_compute
       << " with the CPG mid-triangle)\n";
  if (r.divergence) {
    const Divergence& d = *r.divergence;
    os << "  FAIL: first divergence at cycle " << d.cycle << " in " << d.field << " (patch " << d.triangle << ")\n";
    os << "    expected (cycle model): " << d.expected << "\n";
    os << "    actual   (RTL):         " << d.actual << "\n";
    if (!d.recent.empty()) {
      os << "    last transactions before it:\n";
      for (const auto& s : d.recent) os << "      " << s << "\n";
    }
    if (!r.wave.empty())
      os << "    waveform of " << (o.wave_cycles ? "the requested cycles" : "the cycles before it") << ": "
         << r.wave.string() << " (gtkwave " << gtkw_path(r.wave).string() << ")\n";
  } else {
    os << "  outputs: bit- and cycle-identical on every cycle\n";
    if (!r.wave.empty() && o.wave_cycles)
      os << "  waveform of cycles " << o.wave_cycles->from << ".." << std::min(o.wave_cycles->to, r.cycles) << ": "
         << r.wave.string() << " (gtkwave " << gtkw_path(r.wave).string() << ")\n";
    os << "  counters: " << (r.counters_match ? "identical" : "DIFFER") << " (cycles " << r.rtl_counters.cycles
       << ", TE busy " << r.rtl_counters.te[sim::TeClass::Busy] << ", CPG busy "
       << r.rtl_counters.cpg[sim::CpgClass::Busy] << ")\n";
  }
  if (r.reference.stats.vertices) {
    const sim::ErrorStats& e = r.reference.stats;
    os << "  vs float reference: max position error " << e.position_max << " of the diagonal (rms "
       << e.position_rms << "), max normal angle " << e.normal_angle_max << " rad (rms " << e.normal_angle_rms
       << " rad)";  // radians, as in the statistics and the study (docs/statistics.md)
    // After a divergence the run stopped early: say how far the check went, not that all is well.
    os << (r.reference.beyond_bound ? ", " + std::to_string(r.reference.beyond_bound) + " beyond bound: " + r.reference.worst
           : r.divergence ? ", the " + std::to_string(e.vertices) + (e.vertices == 1 ? " vertex" : " vertices") +
                                " before the divergence within the derived bound"
                          : ", all within the derived bound")
       << "\n";
    if (r.reference.saturated) os << "  saturated: " << r.reference.saturated << " vertices of clamped patches (outside the bound's premise, not compared)\n";
  }
  os << (r.passed ? "PASS" : "FAIL") << ": RTL " << r.variant << " seed " << r.seed << "\n";
  return os.str();
}

std::vector<sim::TriangleFx> random_triangles(std::size_t count, std::uint64_t seed, const sim::NumberFormat& fmt,
                                              int max_L, double degenerate_share, double extent, bool with_tags) {
  const double limit = std::ldexp(static_cast<double>(fmt.coord_max()), -fmt.coord_frac_bits);
  sim::SplitMix64 rng(seed ^ 0x5eedc0de5eedc0deULL);
  sim::SplitMix64 tag_rng(seed ^ 0x7a9575a97a9575a9ULL);
  auto tag_uni = [&](double lo, double hi) { return lo + (hi - lo) * tag_rng.uniform(); };
  // A tag scalar: often exactly 0 or 1 (the ends of σ's range), else uniform in [lo, hi].
  auto tag_scalar = [&](double lo, double hi) {
    const std::uint64_t pick = tag_rng.next() % 4;
    return pick == 0 ? 0.0 : pick == 1 ? 1.0 : tag_uni(lo, hi);
  };
  auto uni = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
  std::vector<sim::TriangleFx> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    glm::dvec3 p[3];
    const glm::dvec3 c(uni(-0.6, 0.6), uni(-0.6, 0.6), uni(-0.6, 0.6));
    const double size = std::exp(uni(std::log(0.002), std::log(0.5)));
    for (auto& x : p) x = c + size * glm::dvec3(uni(-1, 1), uni(-1, 1), uni(-1, 1));
    glm::dvec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
    face = glm::length(face) > 0 ? glm::normalize(face) : glm::dvec3(0, 0, 1);
    glm::dvec3 n[3];
    for (auto& x : n) x = glm::normalize(face + 0.6 * glm::dvec3(uni(-1, 1), uni(-1, 1), uni(-1, 1)));
    if (rng.uniform() < degenerate_share) {
      switch (rng.next() % 4) {
        case 0: p[1] = p[0]; break;                        // zero-length edge
        case 1: p[2] = 0.5 * (p[0] + p[1]); break;         // collinear, zero area
        case 2: n[1] = -n[0]; break;                       // opposite normals on an edge
        default: p[1] = p[0]; p[2] = p[0]; break;          // a point
      }
    }
    sim::TriangleFx t;
    for (int v = 0; v < 3; ++v) {
      if (extent != 1.0) p[v] = glm::clamp(extent * p[v], glm::dvec3(-limit), glm::dvec3(limit));
      t.p[v] = sim::quantize(p[v], fmt);
      t.n[v] = sim::quantize(n[v], fmt);
    }
    t.L = 1 + static_cast<int>(rng.next() % static_cast<std::uint64_t>(max_L));
    t.id = static_cast<std::uint32_t>(i);
    for (int v = 0; with_tags && v < 3; ++v) {
      sim::TagsFx& tags = t.tags[v];
      const std::uint64_t kind = tag_rng.next() % 8;  // 0..3 crease, 4..5 θ only, 6..7 neutral
      if (kind < 4) {
        const glm::dvec3 delta(tag_uni(-1, 1), tag_uni(-1, 1), tag_uni(-1, 1));
        tags.delta = sim::quantize(delta, fmt);
        tags.sigma = sim::quantize(tag_scalar(0, 1), fmt);
        tags.beta = sim::quantize(tag_uni(-1, 1), fmt);
      }
      if (kind < 4) tags.theta = sim::quantize(kind % 2 ? tag_scalar(-1, 1) : 0.0, fmt);
      else if (kind < 6) tags.theta = sim::quantize(kind == 4 ? 1.0 : tag_uni(-1, 1), fmt);
    }
    out.push_back(t);
  }
  return out;
}

std::array<std::size_t, 4> assign_random_alpha(std::vector<sim::TriangleFx>& stream, std::uint64_t seed,
                                               int alpha_bits) {
  sim::SplitMix64 rng(seed ^ 0xa1fa0a1fa0a1fa0aULL);
  const std::uint32_t step = std::uint32_t{1} << (sim::kAlphaFracBits - alpha_bits);
  const std::array<std::uint32_t, 4> special{0, sim::kAlphaOne, step, sim::kAlphaOne - step};
  std::array<std::size_t, 4> seen{};
  for (sim::TriangleFx& t : stream) {
    for (std::uint32_t& a : t.alpha) {
      const std::uint64_t pick = rng.next() % 8;
      a = pick < 4 ? special[pick] : sim::quantize_alpha(rng.uniform(), alpha_bits);
      for (std::size_t i = 0; i < special.size(); ++i) seen[i] += a == special[i];
    }
  }
  return seen;
}

void assign_random_patterns(std::vector<sim::TriangleFx>& stream, std::uint64_t seed, int max_factor,
                            std::optional<Partitioning> partitioning) {
  sim::SplitMix64 rng(seed ^ 0xd3d11d3d11d3d11dULL);
  auto uni = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
  const double top = static_cast<double>(max_factor);
  // A factor: mostly uniform in [0.5, top], often right next to an integer (the rounding
  // boundaries of the fractional partitionings), sometimes exactly 1 or beyond the range.
  auto factor = [&]() -> float {
    switch (rng.next() % 8) {
      case 0: return 1.0f;
      case 1:
      case 2: {
        const double k = std::floor(uni(1.0, top + 1.0));
        const double eps = std::ldexp(1.0, -static_cast<int>(rng.next() % 20));
        return static_cast<float>(rng.next() % 2 ? k + eps : k - eps);
      }
      case 3: return static_cast<float>(uni(top, 70.0));
      default: return static_cast<float>(uni(0.5, top));
    }
  };
  constexpr Partitioning kAll[] = {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                                   Partitioning::fractional_even};
  for (sim::TriangleFx& t : stream) {
    const Partitioning p = partitioning ? *partitioning : kAll[rng.next() % 4];
    // A culled patch is not sent to the unit: draw again (a factor 1 - 1 = 0 culls).
    D3D11Factors f;
    do {
      const std::array<float, 3> outer{factor(), factor(), factor()};
      const float inner = rng.next() % 4 == 0 ? 1.0f : factor();
      f = sim::d3d11_host_factors(outer, inner, p);
    } while (f.culled);
    sim::set_d3d11_pattern(t, f, p);
  }
}

}  // namespace tessim::cosim
