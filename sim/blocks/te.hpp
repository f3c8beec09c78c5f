// Tessellation engine of rtl/tess_te.sv (docs/microarchitecture.md §8): V vertex contexts in a
// circular queue, the scheduler that issues the first N ready operations (oldest context first,
// lowest op first) onto the N INT blocks, the DPG that supplies domain points, and in-order
// retirement of the head context into the VTX FIFO. sim/blocks/te_reference.hpp is the same TE
// written as the RTL is; tests/sim/te_reference_test.cpp checks the two cycle for cycle.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/base/counter_registry.hpp"
#include "sim/base/fixed.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/blocks/dpg.hpp"
#include "sim/blocks/int_blocks.hpp"
#include "sim/blocks/op_masks.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// One operation issued to an INT block.
struct IssuedOp {
  int block = 0;            // INT block (the i-th issued op of a cycle goes to block i)
  int context = 0;          // context slot 0..V-1
  int op = 0;               // 0..13, sim/base/int_ops.hpp
  std::uint64_t vertex = 0; // sequence number of the vertex (allocation order since reset)
};

class Te {
 public:
  static constexpr int kMaxContexts = OpMasks::kMaxLanes;  // V: the configuration limit (sim/config/params.cpp)

  Te(int int_blocks, int int_latency, int contexts, NormalMode normals, const NumberFormat& format);

  void reset();

  int contexts_in_use() const { return count_; }
  int int_blocks() const { return ints_.blocks(); }
  // The head context has every result: it retires unless the VTX FIFO is full.
  bool head_done() const { return count_ > 0 && done_.lane(0) == all_ops_; }
  // The head context waits on results: not all done and no op ready (the registered state: call
  // before schedule(), which takes the issued ops out of the ready masks).
  bool head_waiting() const { return count_ > 0 && done_.lane(0) != all_ops_ && ready_.lane(0) == 0; }
  bool can_allocate(bool point_available) const { return count_ < n_contexts_ && point_available; }
  // Nothing to issue and no result in flight: without a retirement or an allocation the TE's
  // state stays as it is.
  bool quiet() const { return !any(ready_) && ints_.empty(); }
  void skip(std::uint64_t cycles) { ints_.skip(cycles); }  // `cycles` quiet clock edges

  // Scheduler of the cycle: issues up to N ready ops — the N lowest set bits of the age-ordered
  // ready masks — and returns how many (the i-th went to INT block i, issued_ops()[i]).
  int schedule() {
    int issued = 0;
    const int n_blocks = ints_.blocks();
    issued_head_ = head_;
    for_words([&](std::size_t w) {
      std::uint64_t ready = ready_.word[w];
      std::uint64_t take = 0;
      while (ready != 0 && issued < n_blocks) {
        const std::uint64_t lowest = ready & (~ready + 1);
        take |= lowest;
        ready ^= lowest;
        ++issued;
      }
      ready_.word[w] = ready;
      issued_now_.word[w] = take;
      issued_.word[w] |= take;
    });
    // All N blocks taken and a context still has a ready op: it waits for an INT block.
    left_over_ = any(ready_);
    if (issued > 0 && ints_.latency() > 1) ints_.issue(issued_now_, retired_);
    return issued;
  }
  // Of the last schedule(): a ready op was left unissued because all N INT blocks were taken.
  bool left_over() const { return left_over_; }
  // The ops the last schedule() issued, in issue order (decoded on demand: traces and tests).
  const IssuedOp* issued_ops() const;
  // Registered state, for the cycle-for-cycle check against TeReference (tests): the head's
  // physical slot and the issued/done bits of the context of age `age` (< contexts_in_use()).
  int head_slot() const { return head_; }
  std::uint32_t issued_bits(int age) const { return issued_.lane(age); }
  std::uint32_t done_bits(int age) const { return done_.lane(age); }

  // The class of the cycle whose schedule() issued `issued` ops; head_waiting() as it was before
  // schedule(), the other flags from the registered state (doc §10).
  TeClass classify(int issued, bool head_waiting, bool head_done, bool vtx_full, bool point_available,
                   bool upstream_busy) const {
    if (head_waiting) return TeClass::ContextLimited;
    if (left_over_) return TeClass::IntLimited;
    if (issued > 0) return TeClass::Busy;
    if (head_done && vtx_full) return TeClass::BlockedByGpe;
    if (count_ == 0 && !point_available) return upstream_busy ? TeClass::StarvedByCpg : TeClass::Idle;
    return TeClass::Pipeline;
  }

  // The clock edge. `retire_into`: the VTX FIFO slot the head vertex retires into (null: no
  // retirement); `allocate`: the DPG's current point goes into the tail context. Returns the
  // sequence numbers of the retired and allocated vertices through the pointers when non-null.
  [[gnu::always_inline]] void commit(VertexFx* retire_into, bool allocate, ControlPointBuffer& buffers, std::uint64_t* retired_seq,
              std::uint64_t* allocated_seq);
  // The clock edge of a cycle without retirement or allocation: only INT results arrive.
  void advance() {
    complete_due();
    update_ready();
  }

 private:
  // The values of a context, in its physical slot (the circular queue of the RTL). Its op state
  // lives in the age-ordered masks below.
  struct Context {
    // The vertex as it will leave the TE, but for pos and nrm (written at retirement from T13
    // and the mode's normal op): weights, lattice point, factor, patch id, last, flags.
    VertexFx tag;
    std::int64_t w = 0;  // third weight, 1 - u - v, used by every INT op
    std::uint8_t buffer = 0;
    std::uint64_t seq = 0;
  };

  // Ops whose dependences are all done (issued or not), for every done mask of one context: a
  // lane's ready bits after a completion are one load. Only the ops some op depends on (0..11)
  // index the table (2^12 entries of 16 bits, built at compile time within clang's constexpr
  // step limit).
  static constexpr std::uint32_t kDependedOn = [] {
    std::uint32_t m = 0;
    for (const int_ops::IntOp& o : int_ops::kIntOps) m |= o.depends;
    return m;
  }();
  static_assert(int_ops::kOpCount <= OpMasks::kLaneBits && (kDependedOn & (kDependedOn + 1)) == 0,
                "kDependencesMet holds 16-bit masks indexed by the low, contiguous depended-on ops");
  static constexpr std::array<std::uint16_t, std::size_t{kDependedOn} + 1> kDependencesMet = [] {
    std::array<std::uint16_t, std::size_t{kDependedOn} + 1> met{};
    for (std::uint32_t done = 0; done < met.size(); ++done)
      for (const int_ops::IntOp& o : int_ops::kIntOps)
        if ((done & o.depends) == o.depends) met[done] = static_cast<std::uint16_t>(met[done] | (1u << o.op));
    return met;
  }();
  // The same for the four lanes of a mask word.
  static std::uint64_t dependences_met(std::uint64_t done) {
    std::uint64_t met = 0;
    for (int lane = 0; lane < OpMasks::kLanesPerWord; ++lane)
      met |= std::uint64_t{kDependencesMet[(done >> OpMasks::shift_of(lane)) & kDependedOn]} << OpMasks::shift_of(lane);
    return met;
  }

  // The values of a vertex's ops. An op's result depends only on its operands, which are the
  // control points (unchanged until the patch's last vertex retires) and earlier results, never
  // on when it was issued: computing them all at retirement, in op order (a topological order of
  // the table), gives the results the INT blocks produce at issue, bit for bit.
  using Temporaries = std::array<FxVec, int_ops::kOpCount>;
  template <int_ops::Operand O>
  static const FxVec& operand(const ControlPointsFx& cp, const Temporaries& t) {
    if constexpr (O.net == int_ops::Net::B) return cp.b[O.index];
    else if constexpr (O.net == int_ops::Net::N) return cp.n[O.index];
    else return t[O.index];
  }
  template <std::array<int_ops::Operand, 3> Src>
  void compute_from(const ControlPointsFx& cp, const Context& ctx, Temporaries& t, int op) const {
    t[static_cast<std::size_t>(op)] = int_op(ctx.w, ctx.tag.u, ctx.tag.v, operand<Src[0]>(cp, t),
                                             operand<Src[1]>(cp, t), operand<Src[2]>(cp, t), bary_bits_);
  }
  template <int Op>
  void compute(const ControlPointsFx& cp, const Context& ctx, Temporaries& t) const {
    if constexpr (Op == int_ops::kLinearNormalOp) {
      if (linear_normals_) return compute_from<int_ops::operands(Op, NormalMode::Linear)>(cp, ctx, t, Op);
    }
    if (absent_ops_ & (std::uint32_t{1} << Op)) return;
    compute_from<int_ops::kIntOps[Op].operands>(cp, ctx, t, Op);
  }
  template <std::size_t... Op>
  void compute_all(const ControlPointsFx& cp, const Context& ctx, Temporaries& t, std::index_sequence<Op...>) const {
    (compute<static_cast<int>(Op)>(cp, ctx, t), ...);
  }
  // The retiring vertex, values computed. Once per vertex, out of line: commit(), which runs
  // every cycle, stays small enough to be inlined into the unit's tick.
  [[gnu::noinline]] void write_vertex(const ControlPointsFx& cp, const Context& ctx, VertexFx& out) const {
    Temporaries t;
    compute_all(cp, ctx, t, std::make_index_sequence<int_ops::kOpCount>{});
    out = ctx.tag;
    out.pos = t[int_ops::kPositionOp];
    out.nrm = t[static_cast<std::size_t>(normal_op_)];
  }
  // INT results due at the end of this cycle, on the ages as registered: for Λ = 1 the ops this
  // cycle issued, otherwise those issued Λ - 1 cycles ago (their ages moved down by one per
  // retirement since; a context with an op in flight cannot retire, so none drops out).
  void complete_due() {
    if (ints_.latency() == 1) {
      for_words([this](std::size_t w) { done_.word[w] |= issued_now_.word[w]; });
    } else {
      ints_.complete_due([this](OpMasks ops, std::uint64_t retired_at_issue) {
        ops.shift_down(static_cast<int>(retired_ - retired_at_issue), words_);
        for_words([&](std::size_t w) { done_.word[w] |= ops.word[w]; });
      });
    }
  }
  // f(w) for every mask word in use; one word (V <= 4, the usual case) without a loop.
  template <class F>
  [[gnu::always_inline]] void for_words(F&& f) const {
    if (words_ == 1) {
      f(std::size_t{0});
    } else {
      for (int w = 0; w < words_; ++w) f(static_cast<std::size_t>(w));
    }
  }
  bool any(const OpMasks& m) const {
    if (words_ == 1) return m.word[0] != 0;
    return m.any(words_);
  }
  // Ready: not issued and every dependence done.
  void update_ready() {
    for_words([this](std::size_t w) { ready_.word[w] = dependences_met(done_.word[w]) & ~issued_.word[w]; });
  }
  // The DPG's current point into the context of age `age` (allocation, once per vertex).
  [[gnu::noinline]] void allocate_into(int age, ControlPointBuffer& buffers, std::uint64_t* allocated_seq);

  int n_contexts_;
  int words_;  // mask words in use: ceil(V / 4)
  int bary_bits_;
  bool linear_normals_;       // op kLinearNormalOp reads the linear operands
  std::uint32_t all_ops_;     // done mask of a finished vertex
  std::uint32_t absent_ops_;  // ops that do not exist in this mode (linear: 7, 8, 12)
  int normal_op_;             // temporary holding the output normal
  std::array<Context, kMaxContexts> contexts_{};
  int head_ = 0, count_ = 0;
  // Op state in age order. A lane without a context has every issued bit set, so it is never
  // ready; the lanes beyond V stay that way.
  OpMasks issued_, done_;
  OpMasks ready_;  // not issued, every dependence done: done_ and issued_ derive it
  OpMasks empty_lanes_from_last_;  // all ones in lane V-1 and above: the lane a retirement frees
  std::uint64_t retired_ = 0;  // retirements since reset (ages of ops in flight move with them)
  std::uint64_t next_seq_ = 0;
  Dpg dpg_;
  IntBlocks ints_;
  OpMasks issued_now_;  // the ops the last schedule() issued
  int issued_head_ = 0;  // head_ at that schedule()
  bool left_over_ = false;
  mutable std::array<IssuedOp, IntBlocks::kMaxBlocks> decoded_{};  // issued_ops()
};

// Inline: called every cycle from Unit::tick.
inline void Te::commit(VertexFx* retire_into, bool allocate, ControlPointBuffer& buffers, std::uint64_t* retired_seq,
                std::uint64_t* allocated_seq) {
  const int count_start = count_;

  complete_due();

  if (retire_into) {
    const Context& h = contexts_[static_cast<std::size_t>(head_)];
    write_vertex(buffers.entry(h.buffer).cp, h, *retire_into);
    if (h.tag.last) buffers.release(h.buffer);
    if (retired_seq) *retired_seq = h.seq;
    head_ = head_ + 1 == n_contexts_ ? 0 : head_ + 1;
    done_.shift_down(1, words_);
    issued_.shift_down(1, words_);
    for_words([this](std::size_t w) { issued_.word[w] |= empty_lanes_from_last_.word[w]; });
    ++retired_;
  }

  if (allocate) allocate_into(count_start - (retire_into ? 1 : 0), buffers, allocated_seq);

  update_ready();
  count_ = count_start + (allocate ? 1 : 0) - (retire_into ? 1 : 0);
}

}  // namespace tessim::sim
