// The fast TE (sim/blocks/te.hpp: age-ordered bit masks, values computed at retirement) against
// the reference TE written as rtl/tess_te.sv is (sim/blocks/te_reference.hpp: slots, bool flags,
// loops over candidates, values computed at issue), cycle for cycle. Each TE sits in a copy of
// the unit's wiring (TeBench, the decisions of Unit::tick); a real sim::Unit runs alongside and
// drives the testbench, so that both benches get the unit's inputs, and the bench around the
// fast TE must show the unit's own activity every cycle. Every cycle compares what the two TEs
// decide and hold: head done/waiting, allocation, retirement and the retired vertex, the issued
// ops (block, slot, op, vertex), the left-over flag, the statistics class, the queue (count,
// head slot) and the issued/done flags of every context. The same pattern as the datapath's
// check (sim/values/datapath.hpp): a plain version that the optimized one must equal exactly.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "model/d3d11_pattern.hpp"
#include "model/mesh_io.hpp"
#include "sim/blocks/te.hpp"
#include "sim/blocks/te_reference.hpp"
#include "sim/config/config.hpp"
#include "sim/run/testbench.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const Mesh& wuson() {
  static const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  return mesh;
}

// What a TE decided and holds in one cycle.
struct TeCycle {
  bool quiet = false;  // before the edge
  bool head_done = false, head_waiting = false, allocate = false, retire = false, left_over = false;
  int issued = 0;
  std::vector<IssuedOp> ops;
  TeClass cls = TeClass::Idle;
  std::uint64_t retired_seq = 0, allocated_seq = 0;
  VertexFx retired;
  // After the edge.
  int count = 0, head = 0;
  std::vector<std::uint32_t> issued_bits, done_bits;  // by age
};

constexpr std::uint32_t kOpBits = (std::uint32_t{1} << int_ops::kOpCount) - 1;

// The first field in which two cycles differ, "" if none.
std::string difference(const TeCycle& a, const TeCycle& b) {
  std::ostringstream s;
  auto field = [&](const char* name, auto x, auto y) {
    if (s.tellp() == 0 && x != y) s << name << ": fast " << x << ", reference " << y;
  };
  field("quiet", a.quiet, b.quiet);
  field("head_done", a.head_done, b.head_done);
  field("head_waiting", a.head_waiting, b.head_waiting);
  field("allocate", a.allocate, b.allocate);
  field("retire", a.retire, b.retire);
  field("issued", a.issued, b.issued);
  field("left_over", a.left_over, b.left_over);
  field("class", static_cast<int>(a.cls), static_cast<int>(b.cls));
  for (std::size_t i = 0; i < a.ops.size() && i < b.ops.size(); ++i) {
    field("op block", a.ops[i].block, b.ops[i].block);
    field("op context", a.ops[i].context, b.ops[i].context);
    field("op", a.ops[i].op, b.ops[i].op);
    field("op vertex", a.ops[i].vertex, b.ops[i].vertex);
  }
  if (a.retire && b.retire) {
    field("retired vertex", a.retired_seq, b.retired_seq);
    if (s.tellp() == 0 && !(a.retired == b.retired)) s << "retired values";
  }
  if (a.allocate && b.allocate) field("allocated vertex", a.allocated_seq, b.allocated_seq);
  field("contexts", a.count, b.count);
  if (a.count > 0) field("head slot", a.head, b.head);
  for (std::size_t age = 0; age < a.issued_bits.size() && age < b.issued_bits.size(); ++age) {
    field("issued bits", a.issued_bits[age] & kOpBits, b.issued_bits[age] & kOpBits);
    field("done bits", a.done_bits[age] & kOpBits, b.done_bits[age] & kOpBits);
  }
  return s.str();
}

// Unit::tick's wiring (sim/unit/unit.cpp) around a TE of type T: TRI FIFO, CPG, control-point
// buffers, VTX FIFO and the same decisions in the same order.
template <class T>
class TeBench {
 public:
  explicit TeBench(const UnitConfig& cfg)
      : tri_fifo_(cfg.tri_fifo_depth),
        cpg_(cfg.normals, cfg.format,
             cfg.cpg_mapping == CpgMapping::Gpe ? cfg.cpg_gpe_cycles : cpg_cycles(cfg.normals, cfg.format, cfg.cpg),
             cfg.cpg_mapping == CpgMapping::Gpe, cfg.cpg_tags != 0, cfg.cpg),
        buffers_(cfg.cp_buffers),
        te_(cfg.int_blocks, cfg.int_latency, cfg.te_contexts, cfg.normals, cfg.format),
        vtx_fifo_(cfg.vtx_fifo_depth) {
    buffers_.reset();
  }

  bool tri_ready() const { return !tri_fifo_.full(); }
  bool vtx_valid() const { return !vtx_fifo_.empty(); }
  const VertexFx& vtx() const { return vtx_fifo_.front(); }
  bool cpg_computing() const { return cpg_.computing(); }

  TeCycle tick(const UnitInputs& in) {
    TeCycle c;
    c.quiet = te_.quiet();
    const bool tri_push = in.tri_valid && !tri_fifo_.full();
    const bool vtx_pop = in.vtx_ready && !vtx_fifo_.empty();
    c.head_done = te_.head_done();
    c.retire = c.head_done && !vtx_fifo_.full();
    const bool point_available = buffers_.rd_full();
    c.allocate = te_.can_allocate(point_available);
    const CpgAction cpg = cpg_.decide(!tri_fifo_.empty(), buffers_.wr_empty(), in.cpg_step);
    c.head_waiting = te_.head_waiting();
    c.issued = te_.schedule();
    c.left_over = te_.left_over();
    c.cls = te_.classify(c.issued, c.head_waiting, c.head_done, vtx_fifo_.full(), point_available,
                         cpg_.busy() || !tri_fifo_.empty());
    const IssuedOp* ops = te_.issued_ops();
    c.ops.assign(ops, ops + c.issued);
    te_.commit(c.retire ? &vtx_fifo_.tail() : nullptr, c.allocate, buffers_, &c.retired_seq, &c.allocated_seq);
    if (c.retire) c.retired = vtx_fifo_.tail();
    vtx_fifo_.commit(c.retire, vtx_pop);
    cpg_.commit(cpg, tri_fifo_.front(), buffers_);
    if (tri_push) tri_fifo_.tail() = in.tri;
    tri_fifo_.commit(tri_push, cpg == CpgAction::Accept);
    c.count = te_.contexts_in_use();
    c.head = te_.head_slot();
    for (int age = 0; age < c.count; ++age) {
      c.issued_bits.push_back(te_.issued_bits(age));
      c.done_bits.push_back(te_.done_bits(age));
    }
    return c;
  }

 private:
  Fifo<TriangleFx> tri_fifo_;
  CpgBlock cpg_;
  ControlPointBuffer buffers_;
  T te_;
  Fifo<VertexFx> vtx_fifo_;
};

struct Coverage {
  std::uint64_t cycles = 0, ops = 0, vertices = 0, left_over = 0, blocked = 0, context_limited = 0;
};

// Runs `stream` through the unit and both benches in lock-step to the last accepted vertex.
void lockstep(const UnitConfig& cfg, const std::vector<TriangleFx>& stream, Coverage& cov, const std::string& what) {
  Unit unit(cfg);
  Testbench tb(stream, cfg);
  TeBench<Te> fast(cfg);
  TeBench<TeReference> ref(cfg);
  for (std::uint64_t cycle = 0; !tb.done(); ++cycle) {
    ASSERT_LT(cycle, 10'000'000u) << what << ": no progress";
    ASSERT_EQ(fast.tri_ready(), unit.tri_ready()) << what << " cycle " << cycle;
    ASSERT_EQ(fast.vtx_valid(), unit.vtx_valid()) << what << " cycle " << cycle;
    ASSERT_EQ(fast.cpg_computing(), unit.cpg_computing()) << what << " cycle " << cycle;
    ASSERT_EQ(ref.vtx_valid(), fast.vtx_valid()) << what << " cycle " << cycle;
    const UnitInputs& in = tb.inputs(unit);
    if (tb.gpe_cycle().accepted) {
      ASSERT_EQ(fast.vtx(), unit.vtx()) << what << " cycle " << cycle;
      ASSERT_EQ(ref.vtx(), unit.vtx()) << what << " cycle " << cycle;
      ++cov.vertices;
    }
    unit.tick(in);
    const TeCycle a = fast.tick(in);
    const TeCycle b = ref.tick(in);
    ASSERT_EQ(difference(a, b), "") << what << " cycle " << cycle;
    // The bench is the unit's wiring: the fast TE in it does what the unit's TE does.
    const CycleActivity& act = unit.activity();
    ASSERT_EQ(act.ops_issued, a.issued) << what << " cycle " << cycle;
    ASSERT_EQ(act.te, a.cls) << what << " cycle " << cycle;
    ASSERT_EQ(act.allocated, a.allocate) << what << " cycle " << cycle;
    ASSERT_EQ(act.retired, a.retire) << what << " cycle " << cycle;
    if (a.retire) {
      ASSERT_EQ(act.retired_vertex, a.retired_seq) << what << " cycle " << cycle;
    }
    for (int i = 0; i < a.issued; ++i) {
      ASSERT_EQ(unit.issued_ops()[i].context, a.ops[static_cast<std::size_t>(i)].context) << what << " cycle " << cycle;
      ASSERT_EQ(unit.issued_ops()[i].op, a.ops[static_cast<std::size_t>(i)].op) << what << " cycle " << cycle;
    }
    ++cov.cycles;
    cov.ops += static_cast<std::uint64_t>(a.issued);
    cov.left_over += a.left_over;
    cov.blocked += a.cls == TeClass::BlockedByGpe;
    cov.context_limited += a.cls == TeClass::ContextLimited;
  }
}

// A stream of uniform patches (L = 1..11) and D3D11 patches of every partitioning, interleaved.
std::vector<TriangleFx> mixed_stream(const NumberFormat& format, int count, unsigned salt) {
  const Mesh& mesh = wuson();
  const HostScaling scaling = host_scaling(mesh);
  std::vector<TriangleFx> stream;
  for (int i = 0; i < count; ++i) {
    const unsigned x = static_cast<unsigned>(i) * 7u + salt;
    TriangleFx tri = to_fixed(mesh, x % mesh.triangle_count(), scaling, format, 1 + static_cast<int>(x % 11));
    tri.id = static_cast<std::uint32_t>(i);
    if (i % 3 == 1) {
      const auto p = static_cast<Partitioning>(x % 4);
      const float f = 1.0f + 0.43f * static_cast<float>(x % 9);
      set_d3d11_pattern(tri, d3d11_tri_factors({f, f + 1.7f, 2.0f}, f + 0.6f, p), p);
    }
    stream.push_back(tri);
  }
  return stream;
}

UnitConfig config(NormalMode normals, int n, int latency, int v, int vtx_depth, int gpe_cycles, double stall,
                  bool gpe_cpg) {
  UnitConfig c;
  c.normals = normals;
  c.int_blocks = n;
  c.int_latency = latency;
  c.te_contexts = v;
  c.vtx_fifo_depth = vtx_depth;
  c.cp_buffers = 1 + (n + latency + v) % 4;  // a buffer index of 0..3 in the contexts
  c.gpe_cycles = gpe_cycles;
  c.gpe_stall_prob = stall;
  c.seed = static_cast<std::uint64_t>(n * 100 + latency * 10 + v);
  c.cpg_mapping = gpe_cpg ? CpgMapping::Gpe : CpgMapping::Dedicated;
  c.cpg_gpe_cycles = 9;
  // The fastest dedicated CPG (14 cycles a triangle): the TE, not the CPG, sets the pace.
  if (!gpe_cpg) c.cpg = CpgVariant{3, c.format.coord_width()};
  c.validate("test");
  return c;
}

constexpr std::array<NormalMode, 3> kModes{NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear};

// Every N of the issue (1, 2, 3, 4, 6) with every INT latency the configuration allows (1..8),
// each in three environments: a fast GPE with one-entry VTX FIFO, a slow stalling GPE (the
// FIFO fills, the head blocks), the CPG on the GPE's spare cycles; the contexts and the normal
// mode vary from run to run.
TEST(TeReference, FastTeEqualsItCycleForCycle) {
  constexpr std::array<int, 9> kContexts{1, 2, 3, 4, 5, 6, 8, 12, 16};
  Coverage cov;
  int run = 0;
  for (int n : {1, 2, 3, 4, 6}) {
    for (int latency = 1; latency <= IntBlocks::kMaxLatency; ++latency) {
      for (int env = 0; env < 3; ++env, ++run) {
        const NormalMode mode = kModes[static_cast<std::size_t>(run % 3)];
        const int v = kContexts[static_cast<std::size_t>((run * 5 + env) % kContexts.size())];
        const UnitConfig cfg = env == 0   ? config(mode, n, latency, v, 1, 1, 0.0, false)
                               : env == 1 ? config(mode, n, latency, v, 2, 8, 0.5, false)
                                          : config(mode, n, latency, v, 3, 1, 0.3, true);
        std::ostringstream what;
        what << "N=" << n << " latency=" << latency << " V=" << v << " mode=" << static_cast<int>(mode) << " env=" << env;
        lockstep(cfg, mixed_stream(cfg.format, 10, static_cast<unsigned>(run)), cov, what.str());
        if (HasFatalFailure()) return;
      }
    }
  }
  // The runs reach the TE's interesting states: ops left over after N issue slots, a head
  // blocked by the full VTX FIFO, a head waiting on results in flight.
  EXPECT_GT(cov.left_over, 1000u);
  EXPECT_GT(cov.blocked, 1000u);
  EXPECT_GT(cov.context_limited, 1000u);
  RecordProperty("cycles", std::to_string(cov.cycles));
  RecordProperty("ops", std::to_string(cov.ops));
  RecordProperty("vertices", std::to_string(cov.vertices));
}

// Every V the configuration allows (1..16: one to four mask words in the fast TE), each normal
// mode, with a latency long enough that many contexts are in flight.
TEST(TeReference, EveryContextCount) {
  Coverage cov;
  for (int v = 1; v <= Te::kMaxContexts; ++v) {
    for (NormalMode mode : kModes) {
      const UnitConfig cfg = config(mode, 1 + v % 4, 1 + v % 6, v, 1 + v % 3, v % 3 == 0 ? 6 : 1, 0.2, false);
      std::ostringstream what;
      what << "V=" << v << " mode=" << static_cast<int>(mode);
      lockstep(cfg, mixed_stream(cfg.format, 8, static_cast<unsigned>(v * 3)), cov, what.str());
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(cov.vertices, 3000u);
}

}  // namespace
}  // namespace tessim::sim
