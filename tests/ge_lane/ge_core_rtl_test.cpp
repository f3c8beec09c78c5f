// The geometry engine as a SIMD shader core in RTL (rtl/ge/ge_shader_lane.sv, ge_simd_issue.sv),
// costed in docs/results/ge_lane/: a lane runs multiply-add programs of two interleaved waves, its
// registers kept per wave, results bit for bit std::fmaf; the issue logic runs every wave's
// program in order, round robin, never one wave twice in a row, and retires a wave at its end.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "Vge_shader_lane.h"
#include "Vge_simd_issue.h"
#include "verilated.h"

namespace {

template <class Model>
class Clocked {
 public:
  Clocked() : model_(std::make_unique<Model>(&context_, "core")) {
    model_->clk_i = 0;
    model_->rst_ni = 0;
    model_->eval();
    model_->rst_ni = 1;
    model_->eval();
  }
  Model& operator*() { return *model_; }
  Model* operator->() { return model_.get(); }
  // The inputs as set hold through a rising edge; outputs of the cycle are read before it.
  void edge() {
    model_->clk_i = 1;
    model_->eval();
    model_->clk_i = 0;
    model_->eval();
  }

 private:
  VerilatedContext context_;
  std::unique_ptr<Model> model_;
};

enum Kind : std::uint8_t { Reg = 0, Uniform = 1, LaneIn = 2, Const = 3 };
struct Op {
  Kind ka, kb, kc;
  int ra, rb, rc;
  bool write;
  int dst;
};

float fma_of(const Op& op, const std::vector<float>& regs, float uniform, float in) {
  auto value = [&](Kind k, int r, float constant) {
    return k == Reg ? regs[static_cast<std::size_t>(r)] : k == Uniform ? uniform : k == LaneIn ? in : constant;
  };
  return std::fmaf(value(op.ka, op.ra, 1.0f), value(op.kb, op.rb, 1.0f), value(op.kc, op.rc, 0.0f));
}

TEST(GeShaderLane, TwoWavesRunMultiplyAddsInTheirOwnRegisters) {
  // r0 = in; r1 = uniform; r2 = r0 r1 + r0; r3 = r2 r2 + r1; r0 = r3 r0 + r2; out: r0 r1 + r3.
  const std::vector<Op> program{{LaneIn, Const, Const, 0, 0, 0, true, 0},  {Uniform, Const, Const, 0, 0, 0, true, 1},
                                {Reg, Reg, Reg, 0, 1, 0, true, 2},          {Reg, Reg, Reg, 2, 2, 1, true, 3},
                                {Reg, Reg, Reg, 3, 0, 2, true, 0},          {Reg, Reg, Reg, 0, 1, 3, false, 0}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> dist(0.5f, 2.0f);
  Clocked<Vge_shader_lane> lane;
  for (int trial = 0; trial < 50; ++trial) {
    const float in[2] = {dist(rng), dist(rng)}, uniform[2] = {dist(rng), dist(rng)};
    std::vector<float> regs[2] = {std::vector<float>(16, 0.0f), std::vector<float>(16, 0.0f)};
    std::vector<float> want(2), got(2);
    // The waves alternate: each instruction of wave w reads what its previous one wrote two cycles
    // before. A result is valid the cycle after its issue.
    std::vector<std::pair<int, float>> pending;  // (wave, expected) of the instruction issued last cycle
    int issued = 0;
    for (int cycle = 0; cycle <= 2 * static_cast<int>(program.size()); ++cycle) {
      if (lane->valid_o) {
        ASSERT_FALSE(pending.empty());
        EXPECT_EQ(lane->result_o, std::bit_cast<std::uint32_t>(pending.front().second)) << trial << " " << cycle;
        pending.clear();
      } else {
        EXPECT_TRUE(pending.empty());
      }
      lane->issue_i = 0;
      if (issued < 2 * static_cast<int>(program.size())) {
        const int w = issued % 2;
        const Op& op = program[static_cast<std::size_t>(issued / 2)];
        lane->issue_i = 1;
        lane->wave_i = static_cast<std::uint8_t>(w);
        lane->sel_a_i = op.ka;
        lane->sel_b_i = op.kb;
        lane->sel_c_i = op.kc;
        lane->reg_a_i = static_cast<std::uint8_t>(op.ra);
        lane->reg_b_i = static_cast<std::uint8_t>(op.rb);
        lane->reg_c_i = static_cast<std::uint8_t>(op.rc);
        lane->write_i = op.write;
        lane->dst_i = static_cast<std::uint8_t>(op.dst);
        lane->uniform_i = std::bit_cast<std::uint32_t>(uniform[w]);
        lane->lane_in_i = std::bit_cast<std::uint32_t>(in[w]);
        const float d = fma_of(op, regs[w], uniform[w], in[w]);
        if (op.write) regs[w][static_cast<std::size_t>(op.dst)] = d;
        else want[static_cast<std::size_t>(w)] = d;
        pending.emplace_back(w, d);
        ++issued;
      }
      lane.edge();
    }
    EXPECT_NE(want[0], want[1]);  // different inputs: the waves' registers did not mix
  }
}

// The instruction word of ge_simd_issue.sv.
std::uint32_t word(int op, int dst, int ka, int ra, int kb, int rb, int kc, int rc) {
  return static_cast<std::uint32_t>(op << 22 | dst << 18 | kc << 16 | rc << 12 | kb << 10 | rb << 6 | ka << 4 | ra);
}

TEST(GeSimdIssue, WavesRunTheirProgramsInOrderRoundRobinNeverTwiceInARow) {
  // A program of 5 multiply-adds (the fields tell the instructions apart) and the end.
  std::vector<std::uint32_t> store;
  for (int i = 0; i < 5; ++i) store.push_back(word(i == 4 ? 1 : 0, i, i % 4, i, (i + 1) % 4, 15 - i, 3, i + 3));
  store.push_back(word(2, 0, 0, 0, 0, 0, 0, 0));
  Clocked<Vge_simd_issue> issue;
  std::vector<int> next_pc(4, 0);
  std::vector<int> issues_of(4, 0);
  std::vector<bool> done(4, false);
  int last_wave = -1, cycles = 0, busy = 0;
  for (; cycles < 200; ++cycles) {
    // Three waves launched in the first cycles, a fourth later, alone at the end.
    issue->launch_i = cycles < 3 || cycles == 40;
    issue->launch_wave_i = static_cast<std::uint8_t>(cycles < 3 ? cycles : 3);
    issue->eval();
    issue->instr_i = store[std::min<std::size_t>(issue->pc_o, store.size() - 1)];
    issue->eval();
    const int w = issue->wave_o;
    if (issue->issue_o || issue->done_o) {
      EXPECT_NE(w, last_wave) << "cycle " << cycles;
      EXPECT_EQ(static_cast<int>(issue->pc_o), next_pc[static_cast<std::size_t>(w)]) << "wave " << w;
      ++next_pc[static_cast<std::size_t>(w)];
      last_wave = w;
      ++busy;
    } else {
      last_wave = -1;
    }
    if (issue->issue_o) {
      const int pc = static_cast<int>(issue->pc_o);
      EXPECT_EQ(issue->reg_a_o, pc);
      EXPECT_EQ(issue->sel_a_o, pc % 4);
      EXPECT_EQ(issue->reg_b_o, 15 - pc);
      EXPECT_EQ(issue->sel_c_o, 3);
      EXPECT_EQ(issue->reg_c_o, pc + 3);
      EXPECT_EQ(issue->dst_o, pc);
      EXPECT_EQ(issue->write_o, pc != 4);
      ++issues_of[static_cast<std::size_t>(w)];
    }
    if (issue->done_o) {
      EXPECT_EQ(static_cast<int>(issue->pc_o), 5);
      done[static_cast<std::size_t>(w)] = true;
    }
    issue.edge();
  }
  for (int w = 0; w < 4; ++w) {
    EXPECT_TRUE(done[static_cast<std::size_t>(w)]) << w;
    EXPECT_EQ(issues_of[static_cast<std::size_t>(w)], 5) << w;
  }
  EXPECT_EQ(issue->active_o, 0);
  // Three waves keep the issue busy every cycle; the lone fourth wave issues every other cycle:
  // 18 + 6 cycles with an instruction or an end.
  EXPECT_EQ(busy, 24);
}

}  // namespace
