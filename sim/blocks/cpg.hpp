// Control-point generation as a timed block, rtl/tess_cpg.sv (docs/microarchitecture.md §5):
// accepts a triangle from the TRI FIFO, computes for C cycles, writes the control points into
// the buffer at wr_ptr when that one is EMPTY. The values come from the untimed fixed-point
// CPG (sim/values/cpg.hpp, compute_control_points); this block only decides when.
//
// Mappings: dedicated (own datapath: accept, C - 1 compute cycles, write) or on the geometry
// engine (the counter is loaded with C and counts only cycles the GPE grants, cpg_step).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/base/counter_registry.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

// What the CPG does in a cycle (finer than its statistics class, for traces).
enum class CpgAction : std::uint8_t { Idle, Accept, Compute, WaitGpe, Write, Blocked };
// Its statistics class is a CpgClass (sim/base/counter_registry.hpp).

const char* to_string(CpgAction a);

class CpgBlock {
 public:
  // cycles: C, the counter load value at accept (sim::cpg_cycles or the GPE-mapped C).
  // tags: the CPG takes scalar tags (HardwareConfig::cpg_tags); a tagged triangle then computes
  // for cpg_tag_cycles more (on the GPE mapping too: the same operations on the GPE).
  CpgBlock(NormalMode normals, const NumberFormat& format, int cycles, bool gpe_mapping, bool tags = false,
           const CpgVariant& variant = {})
      : normals_(normals), format_(format), cycles_(cycles), gpe_mapping_(gpe_mapping), tags_(tags),
        variant_(variant) {}

  void reset() {
    busy_ = false;
    counter_ = 0;
    tag_cycles_ = 0;
  }
  // CPG cycles (spare GPE cycles on the GPE mapping) the tagged triangles added so far.
  std::uint64_t tag_cycles() const { return tag_cycles_; }

  bool busy() const { return busy_; }
  int cycles() const { return cycles_; }
  std::uint32_t triangle_id() const { return latch_.id; }  // the latched triangle (while busy)
  // GPE mapping only: computing and asking for a spare GPE cycle (always false when dedicated).
  bool computing() const { return gpe_mapping_ && busy_ && counter_ > 0; }

  // The cycle's action from the registered state: a triangle waiting in the TRI FIFO, the
  // buffer at wr_ptr EMPTY, the GPE granting a spare cycle.
  CpgAction decide(bool tri_available, bool wr_empty, bool cpg_step) const {
    if (!busy_) return tri_available ? CpgAction::Accept : CpgAction::Idle;
    if (counter_ > 0) return (!gpe_mapping_ || cpg_step) ? CpgAction::Compute : CpgAction::WaitGpe;
    return wr_empty ? CpgAction::Write : CpgAction::Blocked;
  }

  // Cycles in a row the action `a` (from decide()) repeats with unchanged inputs while only the
  // counter moves: a countdown lasts `counter` cycles; Idle, WaitGpe and Blocked last as long as
  // their inputs do (kForever); Accept and Write change the state at once (0).
  static constexpr std::uint64_t kForever = ~std::uint64_t{0};
  std::uint64_t repeats(CpgAction a) const {
    switch (a) {
      case CpgAction::Compute: return static_cast<std::uint64_t>(counter_);
      case CpgAction::Idle:
      case CpgAction::WaitGpe:
      case CpgAction::Blocked: return kForever;
      default: return 0;
    }
  }
  // `n` cycles of action `a` at once (n <= repeats(a)), as n commit() calls would.
  void commit_repeated(CpgAction a, std::uint64_t n) {
    if (a == CpgAction::Compute) counter_ -= static_cast<int>(n);
  }

  static CpgClass classify(CpgAction a) {
    switch (a) {
      case CpgAction::Accept:
      case CpgAction::Compute:
      case CpgAction::Write: return CpgClass::Busy;
      case CpgAction::Blocked: return CpgClass::Blocked;
      case CpgAction::WaitGpe: return CpgClass::WaitGpe;
      default: return CpgClass::Idle;
    }
  }

  // The clock edge. Accept latches `tri_front`; Write fills the buffer at wr_ptr. Both happen
  // once per triangle, out of line: the countdown, every other cycle, stays inlined in the tick.
  void commit(CpgAction a, const TriangleFx& tri_front, ControlPointBuffer& buffers) {
    switch (a) {
      case CpgAction::Accept: accept(tri_front); break;
      case CpgAction::Compute: --counter_; break;
      case CpgAction::Write: write(buffers); break;
      default: break;
    }
  }

 private:
  [[gnu::noinline]] void accept(const TriangleFx& tri) {
    latch_ = tri;
    busy_ = true;
    counter_ = gpe_mapping_ ? cycles_ : cycles_ - 1;
    if (tags_) {
      const int extra = cpg_tag_cycles(latch_, format_, variant_);
      counter_ += extra;
      tag_cycles_ += static_cast<std::uint64_t>(extra);
    }
  }
  [[gnu::noinline]] void write(ControlPointBuffer& buffers) {
    ControlPointBuffer::Entry& e = buffers.write_slot();
    e.cp = compute_control_points(latch_, normals_, format_);
    e.L = latch_.L;
    e.pattern = latch_.pattern;
    if (latch_.pattern != TriPattern::uniform) e.d3d11 = tri_setup(latch_);
    e.id = latch_.id;
    buffers.commit_write();
    busy_ = false;
  }

  NormalMode normals_;
  NumberFormat format_;
  int cycles_;
  bool gpe_mapping_;
  bool tags_;
  CpgVariant variant_;
  std::uint64_t tag_cycles_ = 0;  // cycles added by tags since reset
  bool busy_ = false;
  int counter_ = 0;
  TriangleFx latch_;
};

// cpg_copies CPGs behind one TRI FIFO and one buffer write port (docs/microarchitecture.md §5,
// "Several triangles in flight"): triangles go to the copies round robin (accept pointer), and
// the copies write their control points in the same order (write pointer), so that patches
// reach the buffers in input order. One copy computes a triangle in C + 1 cycles; M copies
// start one every ceil((C + 1) / M) cycles. With one copy this is exactly CpgBlock.
class CpgArray {
 public:
  static constexpr int kMaxCopies = 16;
  // copies: HardwareConfig::cpg.copies, validated by the parameter table (sim/config/params.cpp);
  // more than one needs the dedicated mapping (the GE-mapped CPG is one program on the GE).
  CpgArray(int copies, NormalMode normals, const NumberFormat& format, int cycles, bool gpe_mapping, bool tags,
           const CpgVariant& variant)
      : first_(normals, format, cycles, gpe_mapping, tags, variant), count_(copies) {
    if (copies < 1 || copies > kMaxCopies || (gpe_mapping && copies > 1))
      throw std::invalid_argument("CpgArray: 1.." + std::to_string(kMaxCopies) + " copies, one on the GE mapping");
    rest_.reserve(static_cast<std::size_t>(copies - 1));  // once: no allocation per cycle
    for (int i = 1; i < copies; ++i) rest_.emplace_back(normals, format, cycles, gpe_mapping, tags, variant);
  }

  void reset() {
    first_.reset();
    for (CpgBlock& c : rest_) c.reset();
    accept_ = write_ = 0;
  }

  // Every copy's action this cycle: only the copy at the accept pointer sees the TRI FIFO's
  // head, only the copy at the write pointer sees buffer[wr_ptr] EMPTY. Packed four bits a copy
  // into one word, so that the actions stay in a register (an array in memory, written a byte
  // at a time and read back whole, stalled the store forwarding in every cycle).
  class Actions {
   public:
    CpgAction of(int copy) const { return static_cast<CpgAction>((bits_ >> (4 * copy)) & 0xF); }
    void set(int copy, CpgAction a) { bits_ |= static_cast<std::uint64_t>(a) << (4 * copy); }

   private:
    std::uint64_t bits_ = 0;
  };
  static_assert(kMaxCopies * 4 <= 64, "four bits per copy in one word");
  Actions decide(bool tri_available, bool wr_empty, bool cpg_step) const {
    Actions a;
    if (single()) {
      a.set(0, first_.decide(tri_available, wr_empty, cpg_step));
      return a;
    }
    for (int i = 0; i < count(); ++i)
      a.set(i, copy(i).decide(tri_available && i == accept_, wr_empty && i == write_, cpg_step));
    return a;
  }
  bool accepts(const Actions& a) const { return a.of(accept_) == CpgAction::Accept; }

  // The class of the cycle for the statistics: busy if any copy accepts, computes or writes,
  // else blocked if any holds finished control points, else waiting for the GE, else idle.
  CpgClass classify(const Actions& a) const {
    if (single()) return CpgBlock::classify(a.of(0));
    bool blocked = false, wait = false;
    for (int i = 0; i < count(); ++i) {
      const CpgClass c = CpgBlock::classify(a.of(i));
      if (c == CpgClass::Busy) return CpgClass::Busy;
      blocked |= c == CpgClass::Blocked;
      wait |= c == CpgClass::WaitGpe;
    }
    return blocked ? CpgClass::Blocked : wait ? CpgClass::WaitGpe : CpgClass::Idle;
  }
  // One action and triangle for traces, as the statistics class ranks them: a write, else an
  // accept, else a computing copy, else one waiting for the GE, blocked, idle; among copies
  // with the same action the oldest triangle's (from the write pointer on). With one copy, that
  // copy's action.
  int summary_copy(const Actions& a) const {
    if (single()) return 0;
    static constexpr auto rank = [](CpgAction x) {
      switch (x) {
        case CpgAction::Write: return 5;
        case CpgAction::Accept: return 4;
        case CpgAction::Compute: return 3;
        case CpgAction::WaitGpe: return 2;
        case CpgAction::Blocked: return 1;
        default: return 0;
      }
    };
    int best = write_;
    for (int k = 1, i = next(write_); k < count(); ++k, i = next(i))
      if (rank(a.of(i)) > rank(a.of(best))) best = i;
    return best;
  }
  CpgAction summary(const Actions& a) const { return a.of(summary_copy(a)); }
  std::uint32_t summary_triangle(const Actions& a, std::uint32_t tri_front_id) const {
    const int c = summary_copy(a);
    return a.of(c) == CpgAction::Accept ? tri_front_id : copy(c).triangle_id();
  }

  // Cycles in a row the actions repeat while only the countdowns move (CpgBlock::repeats).
  std::uint64_t repeats(const Actions& a) const {
    if (single()) return first_.repeats(a.of(0));
    std::uint64_t n = CpgBlock::kForever;
    for (int i = 0; i < count(); ++i) n = std::min(n, copy(i).repeats(a.of(i)));
    return n;
  }
  void commit_repeated(const Actions& a, std::uint64_t n) {
    if (single()) return first_.commit_repeated(a.of(0), n);
    for (int i = 0; i < count(); ++i) copy(i).commit_repeated(a.of(i), n);
  }
  // The clock edge of every copy; the pointers step past the copy that accepted or wrote.
  void commit(const Actions& a, const TriangleFx& tri_front, ControlPointBuffer& buffers) {
    if (single()) return first_.commit(a.of(0), tri_front, buffers);  // the pointers stay 0
    const bool accepted = accepts(a), wrote = a.of(write_) == CpgAction::Write;
    for (int i = 0; i < count(); ++i) copy(i).commit(a.of(i), tri_front, buffers);
    if (accepted) accept_ = next(accept_);
    if (wrote) write_ = next(write_);
  }

  int count() const { return count_; }
  bool single() const { return count_ == 1; }
  bool busy() const {
    if (first_.busy()) return true;
    for (const CpgBlock& c : rest_)
      if (c.busy()) return true;
    return false;
  }
  bool computing() const { return first_.computing(); }  // GE mapping: the one copy
  int cycles() const { return first_.cycles(); }
  std::uint64_t tag_cycles() const {
    std::uint64_t n = first_.tag_cycles();
    for (const CpgBlock& c : rest_) n += c.tag_cycles();
    return n;
  }

 private:
  static std::size_t idx(int i) { return static_cast<std::size_t>(i); }
  // Copy 0 lives inline, so that the default single CPG costs no indirection.
  const CpgBlock& copy(int i) const { return i == 0 ? first_ : rest_[idx(i - 1)]; }
  CpgBlock& copy(int i) { return i == 0 ? first_ : rest_[idx(i - 1)]; }
  int next(int i) const { return i + 1 == count() ? 0 : i + 1; }

  CpgBlock first_;
  std::vector<CpgBlock> rest_;
  int count_;
  int accept_ = 0, write_ = 0;
};

}  // namespace tessim::sim
