// The system of units in RTL (rtl/tess_system.sv) and its cycle model (sim::UnitSystem) in
// lock-step: the same triangle stream (random triangles, uniform and D3D11 patterns of every
// partitioning mixed) and the same seeded, randomly stalling geometry-engine ports drive both;
// every cycle the triangle taken, each port's valid and vertex (every field) and the vertices the
// ports took are compared, and the first difference stops the run with its cycle, field,
// expected (cycle model) and actual (RTL) values. Built with TESSIM_BUILD_SYSTEM_RTL
// (rtl/system.cmake declares the Verilated builds).
//
// Port protocol. A port's ready is its GE's (sim::Gpe) ready of the cycle, remaining == 0 and no
// random stall, which Gpe::tick decides before it looks at the vertex offered: the testbench
// ticks a copy of each port's GE to learn it, drives ge_ready_i with it (0 for the RTL's ports
// beyond the model's P), evaluates, reads ge_valid_o[p] (which depends on the ready of the ports
// before p, never on its own) and ticks the model.
//
// The model exposes whether port p was offered a vertex only when the port is ready (it took one,
// or counted a starved cycle). The expected valid and vertex of every port, ready or not, come
// from a shadow of the reassembly buffer's queues kept from the model's observable decisions: the
// vertices each unit offered and the model admitted (SystemStats::unit_vertices), the unit each
// triangle went to (unit_triangles) and the vertices the ports took (emitted()). Port p expects
// the (number of ready ports before p)-th vertex of the shadow's stream order.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "rtl/verilated/verilated_unit.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/system/system.hpp"
#include "sim/values/cpg.hpp"

#include "Vtess_system_m2.h"
#include "Vtess_system_m2_fixed.h"
#include "Vtess_system_m4.h"

namespace tessim {
namespace {

using rtl::detail::get_bits;
using rtl::detail::put_bits;
using rtl::detail::sign_extend;

// ---------------------------------------------------------------- the RTL system

class RtlSystem {
 public:
  virtual ~RtlSystem() = default;
  virtual int ports() const = 0;  // the build's P
  virtual void reset() = 0;
  virtual void configure(const sim::UnitConfig& cfg) = 0;
  // Drives one cycle's inputs with the clock low and evaluates: the outputs then show the cycle.
  virtual void drive(bool tri_valid, const sim::TriangleFx& tri, const std::vector<bool>& ready) = 0;
  virtual bool tri_ready() const = 0;
  virtual bool port_valid(int p) const = 0;
  virtual sim::VertexFx port_vtx(int p) const = 0;
  virtual void clock() = 0;  // the rising edge
};

template <class Model>
class VerilatedSystem final : public RtlSystem {
 public:
  VerilatedSystem(int ports, const sim::NumberFormat& fmt, bool randomize_x, std::uint64_t seed)
      : ports_(ports), fmt_(fmt), context_(std::make_unique<VerilatedContext>()) {
    context_->fatalOnError(false);
    if (randomize_x) {
      context_->randReset(2);
      context_->randSeed(rtl::detail::verilator_seed(seed));
    }
    Verilated::threadContextp(context_.get());
    model_ = std::make_unique<Model>(context_.get(), "sys");
  }
  ~VerilatedSystem() override {
    Verilated::threadContextp(context_.get());
    model_->final();
  }

  int ports() const override { return ports_; }

  void reset() override {
    Verilated::threadContextp(context_.get());
    model_->tri_valid_i = 0;
    model_->ge_ready_i = 0;
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
    check();
  }

  void configure(const sim::UnitConfig& cfg) override {
    model_->mode_i = static_cast<CData>(sim::mode_code(cfg.normals));
    model_->cfg_distribution_i = static_cast<CData>(static_cast<int>(cfg.distribution));
    model_->cfg_batch_i = static_cast<CData>(cfg.dispatch_batch);
    model_->cfg_slots_i = static_cast<CData>(cfg.reorder_slots);
    const auto cpg_weight = (sim::cpg_cycles(cfg.normals, cfg.format, cfg.cpg) + 1) * cfg.int_blocks;
    const auto te_weight = sim::int_ops::ops_per_vertex(cfg.normals) * cfg.cpg.copies;
    model_->cpg_weight_i = static_cast<SData>(cpg_weight);
    model_->te_weight_i = static_cast<SData>(te_weight);
  }

  void drive(bool tri_valid, const sim::TriangleFx& tri, const std::vector<bool>& ready) override {
    Verilated::threadContextp(context_.get());
    const int w = fmt_.coord_width();
    model_->clk_i = 0;
    model_->tri_valid_i = tri_valid ? 1 : 0;
    for (int v = 0; v < 3; ++v) {
      for (int c = 0; c < 3; ++c) {
        put_bits(model_->tri_p_i, (3 * v + c) * w, w, static_cast<std::uint64_t>(tri.p[v][c]));
        put_bits(model_->tri_n_i, (3 * v + c) * w, w, static_cast<std::uint64_t>(tri.n[v][c]));
      }
    }
    model_->tri_l_i = static_cast<CData>(tri.L & 0x7f);
    model_->tri_pattern_i = static_cast<CData>(static_cast<unsigned>(tri.pattern) & 3);
    for (int e = 0; e < 4; ++e)
      put_bits(model_->tri_factors_i, 23 * e, 23, static_cast<std::uint64_t>(tri.factors[e]) & 0x7fffff);
    model_->tri_id_i = tri.id;
    std::uint64_t r = 0;
    for (int p = 0; p < ports_; ++p)
      if (ready[static_cast<std::size_t>(p)]) r |= std::uint64_t{1} << p;
    model_->ge_ready_i = static_cast<CData>(r);
    model_->eval();
  }

  bool tri_ready() const override { return model_->tri_ready_o != 0; }
  bool port_valid(int p) const override { return get_bits(model_->ge_valid_o, p, 1) != 0; }

  sim::VertexFx port_vtx(int p) const override {
    const int w = fmt_.coord_width();
    const int b = fmt_.bary_bits + 1;
    sim::VertexFx v;
    for (int c = 0; c < 3; ++c) {
      v.pos[c] = sign_extend(get_bits(model_->ge_pos_o, (3 * p + c) * w, w), w);
      v.nrm[c] = sign_extend(get_bits(model_->ge_nrm_o, (3 * p + c) * w, w), w);
    }
    v.u = static_cast<std::int64_t>(get_bits(model_->ge_u_o, p * b, b));
    v.v = static_cast<std::int64_t>(get_bits(model_->ge_v_o, p * b, b));
    v.j = static_cast<int>(get_bits(model_->ge_j_o, p * 7, 7));
    v.k = static_cast<int>(get_bits(model_->ge_k_o, p * 7, 7));
    v.L = static_cast<int>(get_bits(model_->ge_l_o, p * 7, 7));
    v.index = static_cast<int>(get_bits(model_->ge_index_o, p * 12, 12));
    v.id = static_cast<std::uint32_t>(get_bits(model_->ge_id_o, p * 32, 32));
    v.last = get_bits(model_->ge_last_o, p, 1) != 0;
    v.flags = static_cast<std::uint8_t>(get_bits(model_->ge_flags_o, p * 2, 2));
    return v;
  }

  void clock() override {
    Verilated::threadContextp(context_.get());
    model_->clk_i = 1;
    model_->eval();
    check();
  }

 private:
  void check() {
    if (context_->gotError()) {
      context_->gotError(false);
      context_->gotFinish(false);
      throw std::runtime_error("RTL assertion failed");
    }
  }

  int ports_;
  sim::NumberFormat fmt_;
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Model> model_;
};

enum class Build { M2, M4, M2Fixed };

std::unique_ptr<RtlSystem> make_system(Build b, const sim::NumberFormat& fmt, std::uint64_t seed) {
  switch (b) {
    case Build::M2: return std::make_unique<VerilatedSystem<Vtess_system_m2>>(2, fmt, false, seed);
    case Build::M4: return std::make_unique<VerilatedSystem<Vtess_system_m4>>(4, fmt, false, seed);
    case Build::M2Fixed: return std::make_unique<VerilatedSystem<Vtess_system_m2_fixed>>(1, fmt, true, seed);
  }
  return nullptr;
}

// ---------------------------------------------------------------- the shadow of the buffer

class Shadow {
 public:
  explicit Shadow(int units) : queues_(static_cast<std::size_t>(units)) {}
  // The next `n` vertices in stream order that the buffer holds (fewer if it has fewer).
  std::vector<sim::VertexFx> lanes(std::size_t n) const {
    std::vector<sim::VertexFx> out;
    std::vector<std::size_t> cursor(queues_.size(), 0);
    for (std::size_t o = 0; out.size() < n && o < order_.size();) {
      const auto u = static_cast<std::size_t>(order_[o]);
      if (cursor[u] >= queues_[u].size()) break;
      const sim::VertexFx& v = queues_[u][cursor[u]++];
      out.push_back(v);
      if (v.last) ++o;
    }
    return out;
  }
  void pop() {
    auto& q = queues_[static_cast<std::size_t>(order_.front())];
    const bool last = q.front().last;
    q.pop_front();
    if (last) order_.pop_front();
  }
  void push(int unit, const sim::VertexFx& v) { queues_[static_cast<std::size_t>(unit)].push_back(v); }
  void dispatch(int unit) { order_.push_back(unit); }
  std::size_t held() const {
    std::size_t n = 0;
    for (const auto& q : queues_) n += q.size();
    return n;
  }

 private:
  std::vector<std::deque<sim::VertexFx>> queues_;
  std::deque<int> order_;
};

// ---------------------------------------------------------------- lock-step

struct Outcome {
  bool passed = false;
  std::uint64_t cycles = 0, triangles = 0, vertices = 0;
  std::string failure;  // cycle, field, expected, actual
};

std::string show(const sim::VertexFx& v) {
  std::ostringstream os;
  os << "{id " << v.id << " index " << v.index << " last " << v.last << "}";
  return os.str();
}

// The first field in which `actual` differs from `expected`, "" when none.
std::string vertex_difference(const sim::VertexFx& expected, const sim::VertexFx& actual) {
  for (const sim::VertexField& f : sim::kVertexFields) {
    for (int c = 0; c < f.count; ++c) {
      const std::int64_t e = f.get(expected, c), a = f.get(actual, c);
      if (e != a) {
        std::ostringstream os;
        os << f.name;
        if (f.count > 1) os << "[" << c << "]";
        os << ": expected " << e << ", actual " << a;
        return os.str();
      }
    }
  }
  return {};
}

Outcome run_lockstep(const std::vector<sim::TriangleFx>& stream, const sim::UnitConfig& cfg, int gpe_cycles, Build build,
                     std::uint64_t max_cycles = 2'000'000) {
  Outcome out;
  sim::UnitSystem model(cfg, gpe_cycles);
  std::unique_ptr<RtlSystem> rtl = make_system(build, cfg.format, cfg.seed);
  rtl->configure(cfg);
  rtl->reset();
  Shadow shadow(cfg.units);
  const int m = cfg.units, p_model = cfg.ge_ports, p_rtl = rtl->ports();
  std::size_t next = 0;
  std::vector<bool> ready(static_cast<std::size_t>(p_rtl), false);
  std::vector<sim::VertexFx> offered(static_cast<std::size_t>(m));
  std::vector<bool> offering(static_cast<std::size_t>(m));
  auto fail = [&](const std::string& what) {
    std::ostringstream os;
    os << "cycle " << out.cycles << ": " << what;
    out.failure = os.str();
    return out;
  };
  for (; out.cycles < max_cycles; ++out.cycles) {
    if (next == stream.size() && model.idle() && shadow.held() == 0) break;
    const bool tri_valid = next < stream.size();
    const sim::TriangleFx tri = tri_valid ? stream[next] : sim::TriangleFx{};
    // The ports' ready of this cycle, from copies of their GE models.
    for (int p = 0; p < p_rtl; ++p) {
      bool r = false;
      if (p < p_model) {
        sim::Gpe probe = model.port(p);
        r = probe.tick(true, false).ready;
      }
      ready[static_cast<std::size_t>(p)] = r;
    }
    rtl->drive(tri_valid, tri, ready);

    // Every port's valid and vertex against the shadow's stream order.
    const std::vector<sim::VertexFx> lanes = shadow.lanes(static_cast<std::size_t>(p_rtl));
    std::vector<sim::VertexFx> rtl_taken;
    int ready_before = 0;
    for (int p = 0; p < p_rtl; ++p) {
      const auto k = static_cast<std::size_t>(ready_before);
      const bool exp_valid = k < lanes.size();
      const bool act_valid = rtl->port_valid(p);
      if (exp_valid != act_valid) {
        return fail("ge_valid[" + std::to_string(p) + "]: expected " + std::to_string(exp_valid) + ", actual " +
                    std::to_string(act_valid) + (exp_valid ? " (expected vertex " + show(lanes[k]) + ")" : ""));
      }
      if (act_valid) {
        const sim::VertexFx v = rtl->port_vtx(p);
        if (const std::string d = vertex_difference(lanes[k], v); !d.empty())
          return fail("port " + std::to_string(p) + " " + d + " (expected vertex " + show(lanes[k]) + ")");
        if (ready[static_cast<std::size_t>(p)]) rtl_taken.push_back(v);
      }
      if (ready[static_cast<std::size_t>(p)]) ++ready_before;
    }
    const bool rtl_take = tri_valid && rtl->tri_ready();

    // The cycle model's cycle, and what it decided.
    const sim::SystemStats before = model.stats();
    std::vector<std::uint64_t> port_vertices(static_cast<std::size_t>(p_model));
    for (int p = 0; p < p_model; ++p) port_vertices[static_cast<std::size_t>(p)] = model.port(p).stats().vertices;
    for (int u = 0; u < m; ++u) {
      offering[static_cast<std::size_t>(u)] = model.unit(u).vtx_valid();
      if (offering[static_cast<std::size_t>(u)]) offered[static_cast<std::size_t>(u)] = model.unit(u).vtx();
    }
    const bool take = model.tick(tri_valid, tri);
    if (take != rtl_take)
      return fail("triangle " + std::to_string(tri.id) + " taken: expected " + std::to_string(take) + ", actual " +
                  std::to_string(rtl_take));
    // Each ready port's transfer, and the vertices taken in order.
    for (int p = 0; p < p_model; ++p) {
      const bool model_took = model.port(p).stats().vertices != port_vertices[static_cast<std::size_t>(p)];
      const bool rtl_took = ready[static_cast<std::size_t>(p)] && rtl->port_valid(p);
      if (model_took != rtl_took)
        return fail("port " + std::to_string(p) + " transfer: expected " + std::to_string(model_took) + ", actual " +
                    std::to_string(rtl_took));
    }
    const std::vector<sim::VertexFx>& emitted = model.emitted();
    if (emitted.size() != rtl_taken.size())
      return fail("vertices taken: expected " + std::to_string(emitted.size()) + ", actual " +
                  std::to_string(rtl_taken.size()));
    for (std::size_t i = 0; i < emitted.size(); ++i) {
      if (const std::string d = vertex_difference(emitted[i], rtl_taken[i]); !d.empty())
        return fail("vertex taken " + std::to_string(i) + " " + d);
    }
    rtl->clock();

    // The shadow follows the model: pops, the admitted vertices, the dispatch.
    for (std::size_t i = 0; i < emitted.size(); ++i) shadow.pop();
    const sim::SystemStats& after = model.stats();
    for (int u = 0; u < m; ++u) {
      const auto i = static_cast<std::size_t>(u);
      if (after.unit_vertices[i] != before.unit_vertices[i]) {
        if (!offering[i]) return fail("shadow: unit " + std::to_string(u) + " admitted without a vertex");
        shadow.push(u, offered[i]);
      }
      if (after.unit_triangles[i] != before.unit_triangles[i]) shadow.dispatch(u);
    }
    if (take) ++next;
    out.triangles += take ? 1 : 0;
    out.vertices += emitted.size();
  }
  if (out.cycles >= max_cycles) return fail("no end after " + std::to_string(max_cycles) + " cycles");
  out.passed = true;
  return out;
}

// ---------------------------------------------------------------- the stream and the matrix

// Random triangles (cosim::random_triangles), about half of them with D3D11 factors of a
// partitioning drawn per triangle (cosim::assign_random_patterns), the rest uniform L = 1..6.
std::vector<sim::TriangleFx> mixed_stream(std::size_t count, std::uint64_t seed, const sim::NumberFormat& fmt) {
  std::vector<sim::TriangleFx> stream = cosim::random_triangles(count, seed, fmt, 6);
  std::vector<sim::TriangleFx> d3d11 = stream;
  cosim::assign_random_patterns(d3d11, seed, 6);
  sim::SplitMix64 pick(seed ^ 0x5157e35157e3ULL);
  for (std::size_t i = 0; i < stream.size(); ++i)
    if (pick.next() % 2 == 0) stream[i] = d3d11[i];
  return stream;
}

struct Case {
  Build build;
  int units, ports, slots;
  sim::Distribution distribution;
  int batch;
};

constexpr NormalMode kModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

sim::UnitConfig case_config(const Case& c, std::uint64_t seed) {
  sim::UnitConfig cfg;
  cfg.int_blocks = 1;  // the units of the Verilated builds (rtl/system.cmake)
  cfg.units = c.units;
  cfg.ge_ports = c.ports;
  cfg.reorder_slots = c.slots;
  cfg.distribution = c.distribution;
  cfg.dispatch_batch = c.batch;
  cfg.gpe_stall_prob = 0.3;
  cfg.seed = seed;
  cfg.normals = kModes[seed % 3];
  cfg.validate();
  return cfg;
}

std::string case_name(const Case& c) {
  static constexpr const char* kPolicy[] = {"rr", "ll", "ef"};
  std::string n = c.build == Build::M2Fixed ? "fixed_" : "";
  n += "M" + std::to_string(c.units) + "_P" + std::to_string(c.ports) + "_R" + std::to_string(c.slots) + "_" +
       kPolicy[static_cast<int>(c.distribution)] + "_B" + std::to_string(c.batch);
  return n;
}

std::vector<Case> matrix() {
  std::vector<Case> cases;
  for (int m : {2, 4})
    for (int p : {1, m})
      for (int r : {2, 4, 16, 64})
        for (sim::Distribution d : {sim::Distribution::RoundRobin, sim::Distribution::LeastLoaded,
                                    sim::Distribution::EarliestFinish})
          for (int b : {1, 3}) cases.push_back({m == 2 ? Build::M2 : Build::M4, m, p, r, d, b});
  cases.push_back({Build::M2Fixed, 2, 1, 4, sim::Distribution::EarliestFinish, 3});
  return cases;
}

class SystemRtl : public ::testing::TestWithParam<Case> {};

TEST_P(SystemRtl, AgreesWithUnitSystemOnEveryCycle) {
  const Case& c = GetParam();
  std::uint64_t total_cycles = 0, total_vertices = 0;
  // Two seeds, each with its own stream, normal mode and GE rate (K = 1 or 2).
  for (std::uint64_t seed : {std::uint64_t{3}, std::uint64_t{8}}) {
    const sim::UnitConfig cfg = case_config(c, seed + static_cast<std::uint64_t>(c.slots));
    const std::vector<sim::TriangleFx> stream = mixed_stream(48, seed * 7919 + static_cast<std::uint64_t>(c.units), cfg.format);
    const int k = 1 + static_cast<int>(seed % 2);
    const Outcome o = run_lockstep(stream, cfg, k, c.build);
    ASSERT_TRUE(o.passed) << case_name(c) << " seed " << cfg.seed << " K " << k << ": " << o.failure;
    EXPECT_EQ(o.triangles, stream.size());
    total_cycles += o.cycles;
    total_vertices += o.vertices;
  }
  RecordProperty("cycles", std::to_string(total_cycles));
  RecordProperty("vertices", std::to_string(total_vertices));
  std::printf("%s: %llu cycles, %llu vertices compared\n", case_name(c).c_str(),
              static_cast<unsigned long long>(total_cycles), static_cast<unsigned long long>(total_vertices));
}

INSTANTIATE_TEST_SUITE_P(Matrix, SystemRtl, ::testing::ValuesIn(matrix()),
                         [](const auto& info) { return case_name(info.param); });

}  // namespace
}  // namespace tessim
