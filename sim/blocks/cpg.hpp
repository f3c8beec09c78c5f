// Control-point generation as a timed block, rtl/tess_cpg.sv (docs/microarchitecture.md §5):
// accepts a triangle from the TRI FIFO, computes for C cycles, writes the control points into
// the buffer at wr_ptr when that one is EMPTY. The values come from the untimed fixed-point
// CPG (sim/cpg.hpp, compute_control_points); this block only decides when.
//
// Mappings: dedicated (own datapath: accept, C - 1 compute cycles, write) or on the geometry
// engine (the counter is loaded with C and counts only cycles the GPE grants, cpg_step).
#pragma once

#include <array>
#include <cstdint>

#include "sim/blocks/counter_registry.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/cpg.hpp"

namespace tessim::sim {

// What the CPG does in a cycle (finer than its statistics class, for traces).
enum class CpgAction : std::uint8_t { Idle, Accept, Compute, WaitGpe, Write, Blocked };
// Its statistics class is a CpgClass (sim/blocks/counter_registry.hpp).

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

}  // namespace tessim::sim
