// rtl/tess_te.sv section by section (contexts, DPG and allocation, scheduler, INT blocks,
// retirement, queue state, statistics). Names follow the RTL's: _q registered, _d next.
#include "sim/blocks/te_reference.hpp"

#include <stdexcept>

namespace tessim::sim {

namespace {

// tess_pkg::LinearSkipOps: ops 7, 8, 12 do not exist with linear normals.
bool linear_skip(int o) { return o == 7 || o == 8 || o == 12; }

}  // namespace

TeReference::TeReference(int int_blocks, int int_latency, int contexts, NormalMode normals,
                         const NumberFormat& format)
    : n_(int_blocks),
      latency_(int_latency),
      v_(contexts),
      bary_bits_(format.bary_bits),
      mode_linear_(normals == NormalMode::Linear),
      dpg_(format) {
  if (contexts < 1 || contexts > kMaxContexts || int_blocks < 1 || int_blocks > IntBlocks::kMaxBlocks ||
      int_latency < 1 || int_latency > IntBlocks::kMaxLatency)
    throw std::invalid_argument("TeReference: N, latency or V out of range");
  reset();
}

void TeReference::reset() {
  head_q_ = tail_q_ = count_q_ = 0;
  for (auto& block : stage_q_)
    for (Stage& s : block) s.valid = false;
  next_seq_ = 0;
  dpg_.reset();
  slot_valid_.fill(false);
  left_over_ = false;
}

// ------------------------------------------------------------------ scheduler

// age_ctx[a] = head_q + a, wrapped at V.
int TeReference::age_ctx(int a) const {
  const int sum = head_q_ + a;
  return sum >= v_ ? sum - v_ : sum;
}

// ready[a * 14 + o]: the context of age a exists, op o is not issued, its dependences are done.
bool TeReference::ready(int a, int o) const {
  if (a >= count_q_) return false;
  const std::array<bool, kNumOps>& dn = done_q_[static_cast<std::size_t>(age_ctx(a))];
  bool rdy = !issued_q_[static_cast<std::size_t>(age_ctx(a))][static_cast<std::size_t>(o)];
  switch (o) {  // the dependences of the L2 and L3 operations
    case 9: rdy = rdy && dn[0] && dn[1] && dn[3]; break;
    case 10: rdy = rdy && dn[1] && dn[2] && dn[4]; break;
    case 11: rdy = rdy && dn[3] && dn[4] && dn[5]; break;
    case 12: rdy = rdy && dn[6] && dn[7] && dn[8]; break;
    case 13: rdy = rdy && dn[9] && dn[10] && dn[11]; break;
    default: break;
  }
  return rdy;
}

int TeReference::schedule() {
  // remaining = ready; slot i takes the lowest remaining candidate and clears it.
  std::array<bool, kNumCand> remaining{};
  for (int a = 0; a < v_; ++a)
    for (int o = 0; o < kNumOps; ++o) remaining[static_cast<std::size_t>(a * kNumOps + o)] = ready(a, o);
  for (auto& row : selected_) row.fill(false);
  int issued = 0;
  for (int i = 0; i < n_; ++i) {
    slot_valid_[static_cast<std::size_t>(i)] = false;
    for (int c = 0; c < v_ * kNumOps; ++c) {
      if (remaining[static_cast<std::size_t>(c)]) {
        remaining[static_cast<std::size_t>(c)] = false;
        slot_valid_[static_cast<std::size_t>(i)] = true;
        slot_age_[static_cast<std::size_t>(i)] = c / kNumOps;
        slot_op_[static_cast<std::size_t>(i)] = c % kNumOps;
        selected_[static_cast<std::size_t>(c / kNumOps)][static_cast<std::size_t>(c % kNumOps)] = true;
        ++issued;
        break;
      }
    }
  }
  left_over_ = false;
  for (int c = 0; c < v_ * kNumOps; ++c) left_over_ = left_over_ || remaining[static_cast<std::size_t>(c)];
  return issued;
}

const IssuedOp* TeReference::issued_ops() const {
  for (int i = 0; i < n_; ++i) {
    if (!slot_valid_[static_cast<std::size_t>(i)]) continue;
    const int ctx = age_ctx(slot_age_[static_cast<std::size_t>(i)]);
    decoded_[static_cast<std::size_t>(i)] =
        IssuedOp{i, ctx, slot_op_[static_cast<std::size_t>(i)], ctx_q_[static_cast<std::size_t>(ctx)].seq};
  }
  return decoded_.data();
}

bool TeReference::quiet() const {
  for (int a = 0; a < v_; ++a)
    for (int o = 0; o < kNumOps; ++o)
      if (ready(a, o)) return false;
  for (int i = 0; i < n_; ++i)
    for (int s = 0; s + 1 < latency_; ++s)
      if (stage_q_[static_cast<std::size_t>(i)][static_cast<std::size_t>(s)].valid) return false;
  return true;
}

// ------------------------------------------------------------------ INT blocks

// The operands of the 14 operations (§8 table; linear op 6 combines N1, N2, N3), from the
// context's control-point buffer and temporaries, and tess_int's w A + u B + v C.
FxVec TeReference::int_result(int ctx, int op, const ControlPointBuffer& buffers) const {
  const Point& p = ctx_q_[static_cast<std::size_t>(ctx)];
  const ControlPointsFx& cp = buffers.entry(p.buf).cp;
  const auto& bsel = cp.b;
  const auto& nsel = cp.n;
  const auto& tsel = temp_q_[static_cast<std::size_t>(ctx)];
  const FxVec *opa = nullptr, *opb = nullptr, *opc = nullptr;
  switch (op) {
    case 0: opa = &bsel[0]; opb = &bsel[1]; opc = &bsel[4]; break;
    case 1: opa = &bsel[1]; opb = &bsel[2]; opc = &bsel[5]; break;
    case 2: opa = &bsel[2]; opb = &bsel[3]; opc = &bsel[6]; break;
    case 3: opa = &bsel[4]; opb = &bsel[5]; opc = &bsel[7]; break;
    case 4: opa = &bsel[5]; opb = &bsel[6]; opc = &bsel[8]; break;
    case 5: opa = &bsel[7]; opb = &bsel[8]; opc = &bsel[9]; break;
    case 6:
      opa = &nsel[0];
      opb = mode_linear_ ? &nsel[2] : &nsel[1];
      opc = mode_linear_ ? &nsel[5] : &nsel[3];
      break;
    case 7: opa = &nsel[1]; opb = &nsel[2]; opc = &nsel[4]; break;
    case 8: opa = &nsel[3]; opb = &nsel[4]; opc = &nsel[5]; break;
    case 9: opa = &tsel[0]; opb = &tsel[1]; opc = &tsel[3]; break;
    case 10: opa = &tsel[1]; opb = &tsel[2]; opc = &tsel[4]; break;
    case 11: opa = &tsel[3]; opb = &tsel[4]; opc = &tsel[5]; break;
    case 12: opa = &tsel[6]; opb = &tsel[7]; opc = &tsel[8]; break;
    default: opa = &tsel[9]; opb = &tsel[10]; opc = &tsel[11]; break;
  }
  return int_op(p.w, p.u, p.v, *opa, *opb, *opc, bary_bits_);
}

// ------------------------------------------------------------------ retirement

bool TeReference::head_done() const {
  if (count_q_ == 0) return false;
  for (int o = 0; o < kNumOps; ++o)
    if (!done_q_[static_cast<std::size_t>(head_q_)][static_cast<std::size_t>(o)]) return false;
  return true;
}

// ------------------------------------------------------------------ statistics

bool TeReference::head_waiting() const {
  bool head_ready = false;
  for (int o = 0; o < kNumOps; ++o) head_ready = head_ready || ready(0, o);
  return count_q_ != 0 && !head_done() && !head_ready;
}

TeClass TeReference::classify(int, bool, bool, bool vtx_full, bool point_available, bool upstream_busy) const {
  const bool head_waiting_now = head_waiting();
  bool any_issue = false;
  for (int i = 0; i < n_; ++i) any_issue = any_issue || slot_valid_[static_cast<std::size_t>(i)];
  const bool no_point = count_q_ == 0 && !point_available;
  const bool ctx_limited = head_waiting_now;
  const bool int_limited = !head_waiting_now && left_over_;
  const bool busy = !head_waiting_now && !left_over_ && any_issue;
  const bool blocked = !any_issue && head_done() && vtx_full;
  const bool starved = !any_issue && !blocked && no_point && upstream_busy;
  const bool idle = !any_issue && !blocked && no_point && !upstream_busy;
  const bool pipeline = !head_waiting_now && !any_issue && !blocked && !no_point;
  // Exactly one of the outputs is set (the RTL's classes are one-hot).
  const int set = ctx_limited + int_limited + busy + blocked + starved + idle + pipeline;
  if (set != 1) throw std::logic_error("TeReference: the TE classes are not one-hot");
  if (ctx_limited) return TeClass::ContextLimited;
  if (int_limited) return TeClass::IntLimited;
  if (busy) return TeClass::Busy;
  if (blocked) return TeClass::BlockedByGpe;
  if (starved) return TeClass::StarvedByCpg;
  if (idle) return TeClass::Idle;
  return TeClass::Pipeline;
}

std::uint32_t TeReference::issued_bits(int age) const {
  std::uint32_t m = 0;
  for (int o = 0; o < kNumOps; ++o)
    if (issued_q_[static_cast<std::size_t>(age_ctx(age))][static_cast<std::size_t>(o)]) m |= std::uint32_t{1} << o;
  return m;
}

std::uint32_t TeReference::done_bits(int age) const {
  std::uint32_t m = 0;
  for (int o = 0; o < kNumOps; ++o)
    if (done_q_[static_cast<std::size_t>(age_ctx(age))][static_cast<std::size_t>(o)]) m |= std::uint32_t{1} << o;
  return m;
}

// ------------------------------------------------------------------ the clock edge

void TeReference::commit(VertexFx* retire_into, bool allocate, ControlPointBuffer& buffers, std::uint64_t* retired_seq,
                         std::uint64_t* allocated_seq) {
  const bool retire = retire_into != nullptr;
  const bool alloc = allocate;

  // INT blocks: the issue slots' results (computed from the registered temporaries), and the
  // write-back of the cycle: the slot itself at latency 1, else the last pipeline register.
  std::array<Stage, IntBlocks::kMaxBlocks> issue{}, wb{};
  for (int i = 0; i < n_; ++i) {
    Stage& s = issue[static_cast<std::size_t>(i)];
    s.valid = slot_valid_[static_cast<std::size_t>(i)];
    if (s.valid) {
      s.ctx = age_ctx(slot_age_[static_cast<std::size_t>(i)]);
      s.op = slot_op_[static_cast<std::size_t>(i)];
      s.res = int_result(s.ctx, s.op, buffers);
    }
    wb[static_cast<std::size_t>(i)] =
        latency_ == 1 ? s : stage_q_[static_cast<std::size_t>(i)][static_cast<std::size_t>(latency_ - 2)];
  }

  // Retirement: the head's entry {flags, last, id, index, L, k, j, v, u, normal, position}.
  if (retire) {
    const Point& h = ctx_q_[static_cast<std::size_t>(head_q_)];
    const auto& t = temp_q_[static_cast<std::size_t>(head_q_)];
    VertexFx& out = *retire_into;
    out.pos = t[13];
    out.nrm = mode_linear_ ? t[6] : t[12];
    out.u = h.u;
    out.v = h.v;
    out.j = h.j;
    out.k = h.k;
    out.L = h.l;
    out.index = h.index;
    out.id = h.id;
    out.last = h.last;
    out.flags = h.flags;
    if (retired_seq) *retired_seq = h.seq;
  }
  const bool release = retire && ctx_q_[static_cast<std::size_t>(head_q_)].last;
  const int release_buf = ctx_q_[static_cast<std::size_t>(head_q_)].buf;

  // DPG and allocation: the point of the patch at rd_ptr.
  Point alloc_point;
  bool drain = false;
  const ControlPointBuffer::Entry& rd = buffers.rd();
  if (alloc) {
    const DpgPoint p = dpg_.point(rd);
    alloc_point.w = p.w;
    alloc_point.u = p.u;
    alloc_point.v = p.v;
    alloc_point.j = p.j;
    alloc_point.k = p.k;
    alloc_point.l = rd.pattern == TriPattern::uniform ? rd.L : 0;
    alloc_point.index = p.index;
    alloc_point.id = rd.id;
    alloc_point.flags = rd.cp.flags;
    alloc_point.last = p.last;
    alloc_point.buf = buffers.rd_ptr();
    alloc_point.seq = next_seq_;
    drain = p.last;
  }

  // Queue state.
  int head_d = head_q_, tail_d = tail_q_, count_d = count_q_;
  if (alloc) tail_d = tail_q_ == v_ - 1 ? 0 : tail_q_ + 1;
  if (retire) head_d = head_q_ == v_ - 1 ? 0 : head_q_ + 1;
  if (alloc && !retire) count_d = count_q_ + 1;
  else if (retire && !alloc) count_d = count_q_ - 1;

  // Per context x: fields taken at allocation, else issued |= issue_set, done |= done_set, and
  // the temporaries take the results written back for them.
  for (int x = 0; x < v_; ++x) {
    const auto xs = static_cast<std::size_t>(x);
    const bool alloc_here = alloc && tail_q_ == x;
    std::array<bool, kNumOps> issue_set{}, done_set{};
    for (int a = 0; a < v_; ++a)
      if (age_ctx(a) == x)
        for (int o = 0; o < kNumOps; ++o)
          issue_set[static_cast<std::size_t>(o)] =
              issue_set[static_cast<std::size_t>(o)] || selected_[static_cast<std::size_t>(a)][static_cast<std::size_t>(o)];
    for (int i = 0; i < n_; ++i) {
      const Stage& w = wb[static_cast<std::size_t>(i)];
      if (w.valid && w.ctx == x) {
        done_set[static_cast<std::size_t>(w.op)] = true;
        temp_q_[xs][static_cast<std::size_t>(w.op)] = w.res;
      }
    }
    if (alloc_here) {
      ctx_q_[xs] = alloc_point;
      for (int o = 0; o < kNumOps; ++o) {
        issued_q_[xs][static_cast<std::size_t>(o)] = mode_linear_ && linear_skip(o);
        done_q_[xs][static_cast<std::size_t>(o)] = mode_linear_ && linear_skip(o);
      }
    } else {
      for (int o = 0; o < kNumOps; ++o) {
        issued_q_[xs][static_cast<std::size_t>(o)] = issued_q_[xs][static_cast<std::size_t>(o)] || issue_set[static_cast<std::size_t>(o)];
        done_q_[xs][static_cast<std::size_t>(o)] = done_q_[xs][static_cast<std::size_t>(o)] || done_set[static_cast<std::size_t>(o)];
      }
    }
  }

  // The INT pipeline registers move on: stage 0 takes the issue slot.
  for (int i = 0; i < n_; ++i) {
    auto& st = stage_q_[static_cast<std::size_t>(i)];
    for (int s = latency_ - 2; s > 0; --s) st[static_cast<std::size_t>(s)] = st[static_cast<std::size_t>(s - 1)];
    if (latency_ >= 2) st[0] = issue[static_cast<std::size_t>(i)];
  }

  head_q_ = head_d;
  tail_q_ = tail_d;
  count_q_ = count_d;

  // The DPG and the control-point buffers at the same edge (tess_dpg consume_i, tess_cpbuf
  // drain_i and release_i).
  if (alloc) {
    if (allocated_seq) *allocated_seq = next_seq_;
    ++next_seq_;
    dpg_.consume(rd);
    if (drain) buffers.drain();
  }
  if (release) buffers.release(release_buf);
}

}  // namespace tessim::sim
