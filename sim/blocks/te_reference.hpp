// The tessellation engine written as rtl/tess_te.sv is: contexts in physical slots indexed by
// integers, per-slot issued/done flags as bools, the scheduler and retirement as loops over
// slots and candidates, values computed by the INT blocks at issue and carried through their
// pipeline (rtl/tess_int.sv). It is not used by a run: the fast TE (sim/blocks/te.hpp, age-
// ordered bit masks, values computed at retirement) is checked against it cycle for cycle
// (tests/sim/te_reference_test.cpp, docs/verification.md). Same interface as Te, so that one
// harness drives either.
#pragma once

#include <array>
#include <cstdint>

#include "sim/base/fixed.hpp"
#include "sim/base/int_ops.hpp"
#include "sim/blocks/cp_buffer.hpp"
#include "sim/blocks/dpg.hpp"
#include "sim/blocks/int_blocks.hpp"
#include "sim/blocks/te.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

class TeReference {
 public:
  static constexpr int kMaxContexts = Te::kMaxContexts;
  static constexpr int kNumOps = 14;  // tess_pkg::NumOps
  static constexpr int kNumCand = kMaxContexts * kNumOps;

  TeReference(int int_blocks, int int_latency, int contexts, NormalMode normals, const NumberFormat& format);

  void reset();

  int contexts_in_use() const { return count_q_; }
  int int_blocks() const { return n_; }
  bool head_done() const;
  bool head_waiting() const;
  bool can_allocate(bool rd_full) const { return count_q_ < v_ && rd_full; }
  // Nothing ready and no INT pipeline stage valid.
  bool quiet() const;

  // The scheduler's always_comb: slot i takes the i-th ready candidate in (age, op) order.
  // Returns how many slots are valid.
  int schedule();
  bool left_over() const { return left_over_; }
  const IssuedOp* issued_ops() const;

  // The one-hot te_*_o outputs of the statistics, from the registered state and the last
  // schedule(). The head flags of Te's interface are recomputed here, not taken.
  TeClass classify(int issued, bool head_waiting, bool head_done, bool vtx_full, bool point_available,
                   bool upstream_busy) const;

  // The clock edge (always_ff): INT write-back, retirement of the head into `retire_into`
  // (null: none), allocation at the tail, the pipeline registers.
  void commit(VertexFx* retire_into, bool allocate, ControlPointBuffer& buffers, std::uint64_t* retired_seq,
              std::uint64_t* allocated_seq);

  // Registered state for the comparison with Te: the physical slot of the head, and the
  // issued/done flags of the context of age `age` (< contexts_in_use()) as op bit masks.
  int head_slot() const { return head_q_; }
  std::uint32_t issued_bits(int age) const;
  std::uint32_t done_bits(int age) const;

 private:
  struct Point {  // a context's point and patch fields (ctx_*_q)
    std::int64_t w = 0, u = 0, v = 0;
    int j = 0, k = 0, l = 0, index = 0;
    std::uint32_t id = 0;
    std::uint8_t flags = 0;
    bool last = false;
    int buf = 0;
    std::uint64_t seq = 0;  // the model's allocation number (observability, not in the RTL)
  };
  struct Stage {  // one register of an INT block's pipeline: valid, tag {ctx, op}, result
    bool valid = false;
    int ctx = 0, op = 0;
    FxVec res{};
  };

  int age_ctx(int a) const;  // physical slot of age a
  bool ready(int a, int o) const;
  FxVec int_result(int ctx, int op, const ControlPointBuffer& buffers) const;

  int n_, latency_, v_;
  int bary_bits_;
  bool mode_linear_;

  // Registered state.
  int head_q_ = 0, tail_q_ = 0, count_q_ = 0;
  std::array<Point, kMaxContexts> ctx_q_{};
  std::array<std::array<bool, kNumOps>, kMaxContexts> issued_q_{}, done_q_{};
  std::array<std::array<FxVec, kNumOps>, kMaxContexts> temp_q_{};
  // INT block i's registers: stage_q_[i][s], s = 0..latency-2 (none for latency 1).
  std::array<std::array<Stage, IntBlocks::kMaxLatency>, IntBlocks::kMaxBlocks> stage_q_{};
  std::uint64_t next_seq_ = 0;
  Dpg dpg_;

  // The scheduler's combinational outputs of the cycle (schedule()).
  std::array<bool, IntBlocks::kMaxBlocks> slot_valid_{};
  std::array<int, IntBlocks::kMaxBlocks> slot_age_{}, slot_op_{};
  std::array<std::array<bool, kNumOps>, kMaxContexts> selected_{};  // by age
  bool left_over_ = false;
  mutable std::array<IssuedOp, IntBlocks::kMaxBlocks> decoded_{};
};

}  // namespace tessim::sim
