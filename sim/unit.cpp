#include "sim/unit.hpp"

#include <bit>
#include <stdexcept>
#include <string>

#include "model/pattern.hpp"

namespace tessim::sim {

namespace {

constexpr std::uint32_t bit(int op) { return std::uint32_t{1} << op; }

// Dependences of doc §8's table: the level-2 and level-3 ops wait for three results each.
constexpr std::uint32_t kDeps9 = bit(0) | bit(1) | bit(3);
constexpr std::uint32_t kDeps10 = bit(1) | bit(2) | bit(4);
constexpr std::uint32_t kDeps11 = bit(3) | bit(4) | bit(5);
constexpr std::uint32_t kDeps12 = bit(6) | bit(7) | bit(8);
constexpr std::uint32_t kDeps13 = bit(9) | bit(10) | bit(11);
constexpr std::uint32_t kLevel1 = 0x1FF;  // ops 0..8 have no dependences

// Ops whose dependences are all done (issued or not).
inline std::uint32_t dependences_met(std::uint32_t done) {
  std::uint32_t r = kLevel1;
  r |= std::uint32_t{(done & kDeps9) == kDeps9} << 9;
  r |= std::uint32_t{(done & kDeps10) == kDeps10} << 10;
  r |= std::uint32_t{(done & kDeps11) == kDeps11} << 11;
  r |= std::uint32_t{(done & kDeps12) == kDeps12} << 12;
  r |= std::uint32_t{(done & kDeps13) == kDeps13} << 13;
  return r;
}

// The input stream carries L in 7 bits, 1..64; anything else is a caller bug.
[[noreturn, gnu::cold, gnu::noinline]] void throw_bad_factor(const TriangleFx& tri) {
  std::string msg = "Unit: triangle ";
  msg += std::to_string(tri.id);
  msg += " has tessellation factor ";
  msg += std::to_string(tri.L);
  throw std::invalid_argument(msg);
}

}  // namespace

const char* to_string(TeClass c) {
  switch (c) {
    case TeClass::Busy: return "busy";
    case TeClass::BlockedByGpe: return "blocked_by_gpe";
    case TeClass::StarvedByCpg: return "starved_by_cpg";
    case TeClass::Idle: return "idle";
    case TeClass::Pipeline: return "pipeline";
  }
  return "?";
}

const char* to_string(CpgClass c) {
  switch (c) {
    case CpgClass::Busy: return "busy";
    case CpgClass::Blocked: return "blocked";
    case CpgClass::WaitGpe: return "wait_gpe";
    case CpgClass::Idle: return "idle";
  }
  return "?";
}

const char* to_string(CpgAction a) {
  switch (a) {
    case CpgAction::Idle: return "idle";
    case CpgAction::Accept: return "accept";
    case CpgAction::Compute: return "compute";
    case CpgAction::WaitGpe: return "wait_gpe";
    case CpgAction::Write: return "write";
    case CpgAction::Blocked: return "blocked";
  }
  return "?";
}

Unit::Unit(const UnitConfig& cfg)
    : cfg_(cfg),
      n_blocks_(cfg.int_blocks),
      latency_(cfg.int_latency),
      n_contexts_(cfg.te_contexts),
      gpe_mapping_(cfg.cpg_mapping == CpgMapping::Gpe) {
  if (!hardware_supports(cfg.normals))
    throw std::invalid_argument("Unit: normal mode not implemented by the unit");
  if (n_blocks_ < 1 || latency_ < 1 || n_contexts_ < 1 || cfg.tri_fifo_depth < 1 ||
      cfg.vtx_fifo_depth < 1 || n_contexts_ > 255)
    throw std::invalid_argument("Unit: configuration not validated");

  // Dedicated: accept, C - 1 compute cycles, write (doc §5). GPE mapping: the counter is
  // loaded with C so that the CPG consumes exactly C spare GPE cycles per triangle.
  cpg_c_ = gpe_mapping_ ? cfg.cpg_gpe_cycles : sim::cpg_cycles(cfg.normals, cfg.format);

  auto b = [](int i) { return Operand{kNetB, static_cast<std::uint8_t>(i)}; };
  auto n = [](int i) { return Operand{kNetN, static_cast<std::uint8_t>(i)}; };
  auto t = [](int i) { return Operand{kTemp, static_cast<std::uint8_t>(i)}; };
  operands_ = {{
      {b(0), b(1), b(4)}, {b(1), b(2), b(5)}, {b(2), b(3), b(6)},
      {b(4), b(5), b(7)}, {b(5), b(6), b(8)}, {b(7), b(8), b(9)},
      {n(0), n(1), n(3)}, {n(1), n(2), n(4)}, {n(3), n(4), n(5)},
      {t(0), t(1), t(3)}, {t(1), t(2), t(4)}, {t(3), t(4), t(5)},
      {t(6), t(7), t(8)}, {t(9), t(10), t(11)},
  }};
  all_ops_ = (std::uint32_t{1} << 14) - 1;
  if (cfg.normals == NormalMode::Linear) {
    operands_[6] = {n(0), n(2), n(5)};  // w N1 + u N2 + v N3
    preset_ops_ = bit(7) | bit(8) | bit(12);
    normal_op_ = 6;
  } else {
    preset_ops_ = 0;
    normal_op_ = 12;
  }

  tri_fifo_.resize(static_cast<std::size_t>(cfg.tri_fifo_depth));
  vtx_fifo_.resize(static_cast<std::size_t>(cfg.vtx_fifo_depth));
  contexts_.resize(static_cast<std::size_t>(n_contexts_));
  pending_.assign(static_cast<std::size_t>(latency_),
                  std::vector<Completion>(static_cast<std::size_t>(n_blocks_)));
  pending_count_.assign(static_cast<std::size_t>(latency_), 0);
  issued_.resize(static_cast<std::size_t>(n_blocks_));
  reset();
}

void Unit::reset() {
  tri_head_ = tri_count_ = 0;
  cpg_busy_ = false;
  cpg_counter_ = 0;
  for (Buffer& buf : buffers_) buf.state = BufferState::Empty;
  wr_ptr_ = rd_ptr_ = 0;
  dpg_j_ = dpg_k_ = 0;
  for (Context& c : contexts_) c.issued = c.done = 0;
  ctx_head_ = ctx_count_ = 0;
  next_seq_ = 0;
  for (int& count : pending_count_) count = 0;
  due_slot_ = 0;
  vtx_head_ = vtx_count_ = 0;
  stats_ = UnitStats{};
  stats_.int_blocks.assign(static_cast<std::size_t>(n_blocks_), IntBlockStats{});
  act_ = CycleActivity{};
}

bool Unit::idle() const {
  return tri_count_ == 0 && !cpg_busy_ && buffers_[0].state == BufferState::Empty &&
         buffers_[1].state == BufferState::Empty && ctx_count_ == 0 && vtx_count_ == 0;
}

void Unit::issue(Context& ctx, int context_slot, int op, int block) {
  const Buffer& buf = buffers_[ctx.buffer];
  const FxVec* base[3] = {buf.cp.b.data(), buf.cp.n.data(), ctx.t.data()};
  const auto& src = operands_[static_cast<std::size_t>(op)];
  // The result is stored at issue although done[op] is set only Λ cycles later: nothing reads
  // T[op] before done[op] (dependent ops wait for it, retirement waits for all), so the early
  // write is invisible and the pipeline registers need only carry the done bit.
  ctx.t[static_cast<std::size_t>(op)] =
      int_op(ctx.w, ctx.u, ctx.v, base[src[0].space][src[0].index], base[src[1].space][src[1].index],
             base[src[2].space][src[2].index], cfg_.format.bary_bits);
  ctx.issued |= bit(op);
  // Due at the end of cycle t + Λ - 1, whose slot is (t + Λ - 1) mod Λ = (t - 1) mod Λ.
  const int slot = due_slot_ == 0 ? latency_ - 1 : due_slot_ - 1;
  pending_[static_cast<std::size_t>(slot)][static_cast<std::size_t>(pending_count_[static_cast<std::size_t>(slot)]++)] =
      Completion{static_cast<std::uint8_t>(context_slot), bit(op)};
  issued_[static_cast<std::size_t>(block)] = IssuedOp{block, context_slot, op, ctx.seq};
}

void Unit::tick(const UnitInputs& in) {
  const int tri_depth = cfg_.tri_fifo_depth;
  const int vtx_depth = cfg_.vtx_fifo_depth;
  const std::uint64_t cycle = stats_.cycles;

  // ---- Every decision of the cycle, from the registered state and the inputs (doc §2).
  const bool tri_push = in.tri_valid && tri_count_ < tri_depth;
  if (tri_push && (in.tri.L < 1 || in.tri.L > kMaxTessFactor)) throw_bad_factor(in.tri);
  int tri_push_pos = tri_head_ + tri_count_;
  if (tri_push_pos >= tri_depth) tri_push_pos -= tri_depth;
  const bool vtx_pop = in.vtx_ready && vtx_count_ > 0;
  const bool head_done = ctx_count_ > 0 && contexts_[static_cast<std::size_t>(ctx_head_)].done == all_ops_;
  const bool retire = head_done && vtx_count_ < vtx_depth;
  const bool point_available = buffers_[static_cast<std::size_t>(rd_ptr_)].state == BufferState::Full;
  const bool allocate = ctx_count_ < n_contexts_ && point_available;

  CpgAction cpg;
  if (!cpg_busy_) {
    cpg = tri_count_ > 0 ? CpgAction::Accept : CpgAction::Idle;
  } else if (cpg_counter_ > 0) {
    cpg = (!gpe_mapping_ || in.cpg_step) ? CpgAction::Compute : CpgAction::WaitGpe;
  } else {
    cpg = buffers_[static_cast<std::size_t>(wr_ptr_)].state == BufferState::Empty ? CpgAction::Write
                                                                                  : CpgAction::Blocked;
  }

  // ---- Scheduler: the first N ready (age, op) candidates, the i-th to INT block i.
  int issued = 0;
  for (int age = 0; age < ctx_count_ && issued < n_blocks_; ++age) {
    int slot = ctx_head_ + age;
    if (slot >= n_contexts_) slot -= n_contexts_;
    Context& ctx = contexts_[static_cast<std::size_t>(slot)];
    std::uint32_t ready = dependences_met(ctx.done) & ~ctx.issued;
    while (ready != 0 && issued < n_blocks_) {
      const int op = std::countr_zero(ready);
      ready &= ready - 1;
      issue(ctx, slot, op, issued);
      ++issued;
    }
  }

  // ---- Statistics of the cycle (doc §10), from the same registered state.
  TeClass te;
  if (issued > 0) te = TeClass::Busy;
  else if (head_done && vtx_count_ == vtx_depth) te = TeClass::BlockedByGpe;
  else if (ctx_count_ == 0 && !point_available)
    te = (cpg_busy_ || tri_count_ > 0) ? TeClass::StarvedByCpg : TeClass::Idle;
  else te = TeClass::Pipeline;

  CpgClass cpg_class;
  switch (cpg) {
    case CpgAction::Accept:
    case CpgAction::Compute:
    case CpgAction::Write: cpg_class = CpgClass::Busy; break;
    case CpgAction::Blocked: cpg_class = CpgClass::Blocked; break;
    case CpgAction::WaitGpe: cpg_class = CpgClass::WaitGpe; break;
    default: cpg_class = CpgClass::Idle; break;
  }

  ++stats_.cycles;
  for (int i = 0; i < n_blocks_; ++i) {
    IntBlockStats& s = stats_.int_blocks[static_cast<std::size_t>(i)];
    if (i < issued) ++s.busy;
    else ++s.idle;
  }
  switch (te) {
    case TeClass::Busy: ++stats_.te.busy; break;
    case TeClass::BlockedByGpe: ++stats_.te.blocked_by_gpe; break;
    case TeClass::StarvedByCpg: ++stats_.te.starved_by_cpg; break;
    case TeClass::Idle: ++stats_.te.idle; break;
    case TeClass::Pipeline: ++stats_.te.pipeline; break;
  }
  switch (cpg_class) {
    case CpgClass::Busy: ++stats_.cpg.busy; break;
    case CpgClass::Blocked: ++stats_.cpg.blocked; break;
    case CpgClass::WaitGpe: ++stats_.cpg.wait_gpe; break;
    case CpgClass::Idle: ++stats_.cpg.idle; break;
  }
  if (tri_push) ++stats_.triangles_in;
  if (vtx_pop) ++stats_.vertices_out;

  act_.cycle = cycle;
  act_.ops_issued = issued;
  act_.te = te;
  act_.cpg = cpg_class;
  act_.cpg_action = cpg;
  act_.tri_pushed = tri_push;
  act_.vtx_popped = vtx_pop;
  act_.allocated = allocate;
  act_.retired = retire;

  // ---- State updates: the clock edge at the end of the cycle.

  // Retirement of the head context into the VTX FIFO (slot computed from the start-of-cycle
  // head and count, so a simultaneous pop cannot collide with it).
  const int ctx_head_start = ctx_head_;
  const int ctx_count_start = ctx_count_;
  if (retire) {
    const Context& head = contexts_[static_cast<std::size_t>(ctx_head_)];
    int pos = vtx_head_ + vtx_count_;
    if (pos >= vtx_depth) pos -= vtx_depth;
    VertexFx& out = vtx_fifo_[static_cast<std::size_t>(pos)];
    out.pos = head.t[13];
    out.nrm = head.t[static_cast<std::size_t>(normal_op_)];
    out.u = head.u;
    out.v = head.v;
    out.j = head.j;
    out.k = head.k;
    out.L = head.L;
    out.id = head.id;
    out.last = head.last;
    out.flags = head.flags;
    if (head.last) buffers_[head.buffer].state = BufferState::Empty;
    act_.retired_vertex = head.seq;
    ctx_head_ = ctx_head_ + 1 == n_contexts_ ? 0 : ctx_head_ + 1;
  }
  const int vtx_count_start = vtx_count_;
  if (vtx_pop) vtx_head_ = vtx_head_ + 1 == vtx_depth ? 0 : vtx_head_ + 1;
  vtx_count_ = vtx_count_start + (retire ? 1 : 0) - (vtx_pop ? 1 : 0);

  // INT results due at the end of this cycle (issued Λ - 1 cycles ago, or just now for Λ = 1).
  {
    const std::size_t slot = static_cast<std::size_t>(due_slot_);
    std::vector<Completion>& due = pending_[slot];
    for (int i = 0; i < pending_count_[slot]; ++i)
      contexts_[due[static_cast<std::size_t>(i)].context].done |= due[static_cast<std::size_t>(i)].bit;
    pending_count_[slot] = 0;
    due_slot_ = due_slot_ + 1 == latency_ ? 0 : due_slot_ + 1;
  }

  // Allocation of the next domain point into the tail context.
  if (allocate) {
    Buffer& buf = buffers_[static_cast<std::size_t>(rd_ptr_)];
    int tail = ctx_head_start + ctx_count_start;
    if (tail >= n_contexts_) tail -= n_contexts_;
    Context& ctx = contexts_[static_cast<std::size_t>(tail)];
    const int L = buf.L;
    const int bary_bits = cfg_.format.bary_bits;
    ctx.j = dpg_j_;
    ctx.k = dpg_k_;
    ctx.L = L;
    ctx.u = bary_weight(dpg_j_, L, bary_bits);
    ctx.v = bary_weight(dpg_k_, L, bary_bits);
    ctx.w = cfg_.format.bary_one() - ctx.u - ctx.v;
    ctx.id = buf.id;
    ctx.flags = buf.cp.flags;
    ctx.buffer = static_cast<std::uint8_t>(rd_ptr_);
    ctx.last = dpg_k_ == L;
    ctx.issued = preset_ops_;
    ctx.done = preset_ops_;
    ctx.seq = next_seq_++;
    act_.allocated_vertex = ctx.seq;
    if (ctx.last) {
      dpg_j_ = dpg_k_ = 0;
      buf.state = BufferState::Draining;
      rd_ptr_ ^= 1;
    } else if (dpg_j_ + 1 + dpg_k_ <= L) {
      ++dpg_j_;
    } else {
      dpg_j_ = 0;
      ++dpg_k_;
    }
  }
  ctx_count_ = ctx_count_start + (allocate ? 1 : 0) - (retire ? 1 : 0);

  // CPG.
  const int tri_count_start = tri_count_;
  switch (cpg) {
    case CpgAction::Accept:
      cpg_latch_ = tri_fifo_[static_cast<std::size_t>(tri_head_)];
      tri_head_ = tri_head_ + 1 == tri_depth ? 0 : tri_head_ + 1;
      cpg_busy_ = true;
      cpg_counter_ = gpe_mapping_ ? cpg_c_ : cpg_c_ - 1;
      break;
    case CpgAction::Compute: --cpg_counter_; break;
    case CpgAction::Write: {
      Buffer& buf = buffers_[static_cast<std::size_t>(wr_ptr_)];
      buf.cp = compute_control_points(cpg_latch_, cfg_.normals, cfg_.format);
      buf.L = cpg_latch_.L;
      buf.id = cpg_latch_.id;
      buf.state = BufferState::Full;
      wr_ptr_ ^= 1;
      cpg_busy_ = false;
      break;
    }
    default: break;
  }

  // TRI FIFO push (slot from the start-of-cycle head and count).
  if (tri_push) tri_fifo_[static_cast<std::size_t>(tri_push_pos)] = in.tri;
  tri_count_ = tri_count_start + (tri_push ? 1 : 0) - (cpg == CpgAction::Accept ? 1 : 0);
}

}  // namespace tessim::sim
