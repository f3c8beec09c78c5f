#include "cosim/cosim.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>

#include "model/error.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/error_bound.hpp"
#include "sim/host.hpp"
#include "sim/testbench.hpp"
#include "sim/unit.hpp"

namespace tessim::cosim {

namespace {

std::string vec_str(const sim::FxVec& v) {
  std::ostringstream os;
  os << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return os.str();
}

std::string vertex_str(const sim::VertexFx& x) {
  std::ostringstream os;
  os << "patch " << x.id << " (j,k)=(" << x.j << "," << x.k << ") L=" << x.L << " pos="
     << vec_str(x.pos) << " nrm=" << vec_str(x.nrm) << " u=" << x.u << " v=" << x.v
     << (x.last ? " last" : "") << (x.flags ? " flags=" + std::to_string(x.flags) : "");
  return os.str();
}

// First field in which two vertices differ, with both values; empty when equal.
struct FieldDiff {
  std::string field, expected, actual;
};
std::optional<FieldDiff> diff_vertex(const sim::VertexFx& e, const sim::VertexFx& a) {
  for (int c = 0; c < 3; ++c)
    if (e.pos[c] != a.pos[c])
      return FieldDiff{"vtx_pos[" + std::to_string(c) + "]", std::to_string(e.pos[c]), std::to_string(a.pos[c])};
  for (int c = 0; c < 3; ++c)
    if (e.nrm[c] != a.nrm[c])
      return FieldDiff{"vtx_nrm[" + std::to_string(c) + "]", std::to_string(e.nrm[c]), std::to_string(a.nrm[c])};
  auto num = [](const char* name, std::int64_t x, std::int64_t y) -> std::optional<FieldDiff> {
    if (x != y) return FieldDiff{name, std::to_string(x), std::to_string(y)};
    return std::nullopt;
  };
  if (auto d = num("vtx_u", e.u, a.u)) return d;
  if (auto d = num("vtx_v", e.v, a.v)) return d;
  if (auto d = num("vtx_j", e.j, a.j)) return d;
  if (auto d = num("vtx_k", e.k, a.k)) return d;
  if (auto d = num("vtx_l", e.L, a.L)) return d;
  if (auto d = num("vtx_id", e.id, a.id)) return d;
  if (auto d = num("vtx_last", e.last, a.last)) return d;
  if (auto d = num("vtx_flags", e.flags, a.flags)) return d;
  return std::nullopt;
}

std::optional<FieldDiff> diff_counters(const sim::UnitCounters& e, const sim::UnitCounters& a, int n) {
  // Called every cycle: names are built only for a difference.
  auto diff = [](const std::string& name, std::uint64_t x, std::uint64_t y) {
    return FieldDiff{"counters." + name, std::to_string(x), std::to_string(y)};
  };
  for (const sim::CounterField& f : sim::kRunCounters)
    if (e.*f.field != a.*f.field) return diff(f.name, e.*f.field, a.*f.field);
  for (int i = 0; i < n; ++i)
    if (e.int_busy[i] != a.int_busy[i]) return diff("int_busy[" + std::to_string(i) + "]", e.int_busy[i], a.int_busy[i]);
  for (const sim::CounterField& f : sim::kClassCounters)
    if (e.*f.field != a.*f.field) return diff(f.name, e.*f.field, a.*f.field);
  return std::nullopt;
}

// Float reference of each patch, built once per triangle of the stream from the quantized
// input (so the comparison measures the unit's arithmetic, not the input quantization).
class ReferenceChecker {
 public:
  ReferenceChecker(const std::vector<sim::TriangleFx>& stream, const sim::UnitConfig& cfg)
      : stream_(stream), cfg_(cfg), budget_(sim::position_error_budget(cfg.format)) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& t : stream)
      for (const auto& p : t.p) {
        const glm::dvec3 x = sim::dequantize(p, cfg.format);
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
      }
    diagonal_ = stream.empty() ? 1.0 : std::max(glm::length(hi - lo), 1e-12);
  }

  void check(const sim::VertexFx& v, std::size_t stream_index) {
    const sim::TriangleFx& tri = stream_[stream_index];
    if (stream_index != cached_index_) {
      PnInput in;
      for (int i = 0; i < 3; ++i) {
        in.p[i] = sim::dequantize(tri.p[i], cfg_.format);
        in.n[i] = sim::dequantize(tri.n[i], cfg_.format);
      }
      patch_ = make_patch(in, cfg_.normals);
      normal_bound_ = sim::normal_error_bound(tri, cfg_.normals, cfg_.format);
      cached_index_ = stream_index;
    }
    const double scale = static_cast<double>(cfg_.format.bary_one());
    const PnVertex ref = eval_bernstein(patch_, static_cast<double>(v.u) / scale, static_cast<double>(v.v) / scale);
    const glm::dvec3 pos = sim::dequantize(v.pos, cfg_.format);
    const glm::dvec3 nrm = sim::dequantize(v.nrm, cfg_.format);
    const double pos_err = glm::length(pos - ref.position);
    ++e_.vertices;
    e_.max_position = std::max(e_.max_position, pos_err / diagonal_);
    sum_pos2_ += (pos_err / diagonal_) * (pos_err / diagonal_);
    bool beyond = pos_err > budget_.position_units + 1e-12;
    std::string why = beyond ? "position error " + std::to_string(pos_err) + " > bound " +
                                   std::to_string(budget_.position_units)
                             : "";
    const double len = glm::length(nrm);
    const double angle_bound = sim::normal_angle_bound(normal_bound_, len);
    if (angle_bound >= 0) {
      const double c = std::clamp(glm::dot(nrm / len, glm::normalize(ref.normal)), -1.0, 1.0);
      const double angle = std::acos(c);
      e_.max_normal_angle = std::max(e_.max_normal_angle, angle);
      sum_ang2_ += angle * angle;
      ++normals_checked_;
      if (angle > angle_bound + 1e-9) {
        beyond = true;
        why = "normal angle " + std::to_string(angle) + " rad > bound " + std::to_string(angle_bound);
      }
    }
    if (beyond) {
      if (e_.beyond_bound == 0) e_.worst = vertex_str(v) + ": " + why;
      ++e_.beyond_bound;
    }
  }

  ReferenceErrors result() const {
    ReferenceErrors r = e_;
    if (r.vertices) r.rms_position = std::sqrt(sum_pos2_ / static_cast<double>(r.vertices));
    if (normals_checked_) r.rms_normal_angle = std::sqrt(sum_ang2_ / static_cast<double>(normals_checked_));
    return r;
  }

 private:
  const std::vector<sim::TriangleFx>& stream_;
  sim::UnitConfig cfg_;
  sim::ErrorBudget budget_;
  double diagonal_ = 1.0;
  std::size_t cached_index_ = static_cast<std::size_t>(-1);
  PnPatch patch_;
  double normal_bound_ = 0;
  ReferenceErrors e_;
  double sum_pos2_ = 0, sum_ang2_ = 0;
  std::uint64_t normals_checked_ = 0;
};

sim::UnitCounters model_counters(const sim::UnitStats& s) {
  sim::UnitCounters c;
  c.cycles = s.cycles;
  c.triangles_in = s.triangles_in;
  c.vertices_out = s.vertices_out;
  for (std::size_t i = 0; i < s.int_blocks.size() && i < c.int_busy.size(); ++i) c.int_busy[i] = s.int_blocks[i].busy;
  c.te_context_limited = s.te.context_limited;
  c.te_int_limited = s.te.int_limited;
  c.te_busy = s.te.busy;
  c.te_blocked_by_gpe = s.te.blocked_by_gpe;
  c.te_starved_by_cpg = s.te.starved_by_cpg;
  c.te_idle = s.te.idle;
  c.te_pipeline = s.te.pipeline;
  c.cpg_busy = s.cpg.busy;
  c.cpg_blocked = s.cpg.blocked;
  c.cpg_wait_gpe = s.cpg.wait_gpe;
  c.cpg_idle = s.cpg.idle;
  return c;
}

// The lock-step loop, ending at the end of the stream, at the first divergence or before cycle
// `stop_at`. With `wave_from` set it is the replay of a failing run: outputs are not compared
// and the RTL's waveform is recorded from that cycle on.
struct LockstepRun {
  CosimReport report;
  std::uint64_t expected_vertices = 0;
};

LockstepRun lockstep(const std::vector<sim::TriangleFx>& stream, const CosimOptions& opts,
                     rtl::RtlUnit& rtl, std::optional<std::uint64_t> wave_from,
                     std::uint64_t stop_at) {
  LockstepRun run;
  CosimReport& rep = run.report;
  rep.variant = opts.variant;
  rep.seed = opts.seed;
  for (const auto& t : stream) run.expected_vertices += static_cast<std::uint64_t>(pattern_vertex_count(t.L));

  sim::Unit model(opts.unit);
  sim::Testbench tb(stream, opts.unit);
  rtl.reset();
  rtl.set_mode(opts.unit.normals);
  std::unique_ptr<ReferenceChecker> ref;
  if (opts.check_reference && !wave_from) ref = std::make_unique<ReferenceChecker>(stream, opts.unit);

  std::deque<std::string> recent;
  auto note = [&](std::string s) {
    recent.push_back(std::move(s));
    while (recent.size() > static_cast<std::size_t>(std::max(opts.history, 0))) recent.pop_front();
  };
  std::uint64_t last_progress = 0;
  std::uint32_t last_patch = 0;
  std::vector<std::uint64_t> resets = opts.reset_at;
  std::sort(resets.begin(), resets.end());
  std::size_t next_reset = 0;
  std::uint64_t cycle = 0;
  bool stopped_early = false;  // at stop_at: the state of that cycle is outside the window

  auto diverge = [&](const std::string& field, const std::string& e, const std::string& a) {
    Divergence d;
    d.cycle = cycle;
    d.field = field;
    d.expected = e;
    d.actual = a;
    d.triangle = last_patch;
    d.recent.assign(recent.begin(), recent.end());
    rep.divergence = d;
  };

  for (;; ++cycle) {
    if (cycle >= stop_at) {
      stopped_early = true;
      break;
    }
    if (wave_from && cycle == *wave_from) rtl.set_wave_enabled(true);
    if (next_reset < resets.size() && cycle == resets[next_reset]) {
      // Mid-stream reset of both implementations: the stream starts again from the beginning.
      ++next_reset;
      model.reset();
      rtl.reset();
      tb.reset();
      note("cycle " + std::to_string(cycle) + ": reset");
      if (ref) ref = std::make_unique<ReferenceChecker>(stream, opts.unit);
    }

    // 1. Outputs of this cycle (registered state only) must agree.
    if (!wave_from) {
      if (model.tri_ready() != rtl.tri_ready()) {
        diverge("tri_ready", std::to_string(model.tri_ready()), std::to_string(rtl.tri_ready()));
        break;
      }
      if (model.vtx_valid() != rtl.vtx_valid()) {
        diverge("vtx_valid", std::to_string(model.vtx_valid()), std::to_string(rtl.vtx_valid()));
        if (model.vtx_valid()) last_patch = model.vtx().id;
        break;
      }
      // The performance counters are outputs too: comparing them every cycle finds a fault
      // that changes the unit's internal timing before it reaches the vertex stream.
      if (auto d = diff_counters(model_counters(model.stats()), rtl.counters(), opts.unit.int_blocks)) {
        diverge(d->field, d->expected, d->actual);
        break;
      }
      if (model.vtx_valid()) {
        const sim::VertexFx actual = rtl.vtx();
        if (auto d = diff_vertex(model.vtx(), actual)) {
          last_patch = model.vtx().id;
          diverge(d->field, d->expected + "  [" + vertex_str(model.vtx()) + "]",
                  d->actual + "  [" + vertex_str(actual) + "]");
          break;
        }
      }
    }

    // 2. The environment: source and geometry engine, driven by the (agreeing) outputs.
    const sim::UnitInputs& in = tb.inputs(model);
    if (tb.pushed()) {
      note("cycle " + std::to_string(cycle) + ": triangle " + std::to_string(in.tri.id) + " in (L=" +
           std::to_string(in.tri.L) + ")");
      last_progress = cycle;
    }
    if (tb.gpe_cycle().accepted) {
      const sim::VertexFx& v = model.vtx();
      last_patch = v.id;
      note("cycle " + std::to_string(cycle) + ": vertex out " + vertex_str(v));
      if (ref && v.id < stream.size()) ref->check(v, v.id);
      last_progress = cycle;
    }

    // 3. The clock edge, for both.
    model.tick(in);
    rtl.tick(in);

    if (!wave_from && tb.accepted() == run.expected_vertices) {
      ++cycle;
      break;
    }
    if (!wave_from && cycle - last_progress > opts.hang_cycles) {
      rep.hang = true;
      diverge("progress", "a transfer within " + std::to_string(opts.hang_cycles) + " cycles",
              "none (hang)");
      break;
    }
  }

  rep.cycles = cycle;
  rep.triangles = tb.triangles_taken();
  rep.vertices = tb.accepted();
  rep.gpe = tb.gpe().stats();
  rep.model_counters = model_counters(model.stats());
  rep.rtl_counters = rtl.counters();
  if (ref) rep.reference = ref->result();
  if (!rep.divergence && !wave_from && !stopped_early) {
    if (auto d = diff_counters(rep.model_counters, rep.rtl_counters, opts.unit.int_blocks)) {
      diverge(d->field, d->expected, d->actual);
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
  for (std::size_t i = 0; i < stream.size(); ++i) {
    if (stream[i].id != i)
      throw InputError("co-simulation stream", "triangle " + std::to_string(i),
                       "patch ids must be the stream positions");
    if (stream[i].L < 1 || stream[i].L > kMaxTessFactor)
      throw InputError("co-simulation stream", "triangle " + std::to_string(i),
                       "factor " + std::to_string(stream[i].L) + " outside 1.." + std::to_string(kMaxTessFactor));
  }
  auto rtl = rtl::make_rtl_unit(opts.variant, opts.seed);
  rtl::check_config(*rtl, opts.unit);  // throws InputError naming the first parameter that differs

  LockstepRun run = lockstep(stream, opts, *rtl, std::nullopt, stop_before);
  CosimReport rep = std::move(run.report);
  if (rep.divergence && !opts.wave.empty()) {
    // Replay from reset with the waveform recording the window before the divergence.
    auto replay = rtl::make_rtl_unit(opts.variant, opts.seed);
    replay->open_wave(opts.wave);
    replay->set_wave_enabled(false);
    const std::uint64_t c = rep.divergence->cycle;
    const std::uint64_t from = c > static_cast<std::uint64_t>(opts.wave_window) ? c - opts.wave_window : 0;
    lockstep(stream, opts, *replay, from, c + 2);
    replay->close_wave();
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
  if (r.divergence) {
    const Divergence& d = *r.divergence;
    os << "  FAIL: first divergence at cycle " << d.cycle << " in " << d.field << " (patch " << d.triangle << ")\n";
    os << "    expected (cycle model): " << d.expected << "\n";
    os << "    actual   (RTL):         " << d.actual << "\n";
    if (!d.recent.empty()) {
      os << "    last transactions before it:\n";
      for (const auto& s : d.recent) os << "      " << s << "\n";
    }
    if (!r.wave.empty()) os << "    waveform of the cycles before it: " << r.wave.string() << "\n";
  } else {
    os << "  outputs: bit- and cycle-identical on every cycle\n";
    os << "  counters: " << (r.counters_match ? "identical" : "DIFFER") << " (cycles " << r.rtl_counters.cycles
       << ", TE busy " << r.rtl_counters.te_busy << ", CPG busy " << r.rtl_counters.cpg_busy << ")\n";
  }
  if (r.reference.vertices) {
    os << "  vs float reference: max position error " << r.reference.max_position << " of the diagonal (rms "
       << r.reference.rms_position << "), max normal angle " << r.reference.max_normal_angle * 180.0 / M_PI
       << " deg (rms " << r.reference.rms_normal_angle * 180.0 / M_PI << ")";
    os << (r.reference.beyond_bound ? ", " + std::to_string(r.reference.beyond_bound) + " beyond bound: " + r.reference.worst
                                    : ", all within the derived bound")
       << "\n";
  }
  os << (r.passed ? "PASS" : "FAIL") << ": RTL " << r.variant << " seed " << r.seed << "\n";
  return os.str();
}

std::vector<sim::TriangleFx> random_triangles(std::size_t count, std::uint64_t seed, const sim::NumberFormat& fmt,
                                              int max_L, double degenerate_share) {
  sim::SplitMix64 rng(seed ^ 0x5eedc0de5eedc0deULL);
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
      t.p[v] = sim::quantize(p[v], fmt);
      t.n[v] = sim::quantize(n[v], fmt);
    }
    t.L = 1 + static_cast<int>(rng.next() % static_cast<std::uint64_t>(max_L));
    t.id = static_cast<std::uint32_t>(i);
    out.push_back(t);
  }
  return out;
}

}  // namespace tessim::cosim
