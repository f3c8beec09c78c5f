#include "sim/blocks/te.hpp"

#include <bit>
#include <stdexcept>

namespace tessim::sim {

Te::Te(int int_blocks, int int_latency, int contexts, NormalMode normals, const NumberFormat& format)
    : n_contexts_(contexts),
      words_(OpMasks::words_for(contexts)),
      bary_bits_(format.bary_bits),
      all_ops_((std::uint32_t{1} << int_ops::kOpCount) - 1),
      absent_ops_(int_ops::absent_ops(normals)),
      normal_op_(int_ops::normal_op(normals)),
      dpg_(format),
      ints_(int_blocks, int_latency) {
  if (contexts < 1 || contexts > kMaxContexts) throw std::invalid_argument("Te: V out of range");
  linear_normals_ = normals == NormalMode::Linear;
  for (int a = contexts - 1; a < OpMasks::kMaxLanes; ++a) empty_lanes_from_last_.set_lane(a, OpMasks::kLane);
  reset();
}

void Te::reset() {
  issued_.word.fill(~std::uint64_t{0});  // no context anywhere
  done_.word.fill(0);
  ready_.word.fill(0);
  issued_now_.word.fill(0);
  head_ = count_ = issued_head_ = 0;
  retired_ = 0;
  left_over_ = false;
  next_seq_ = 0;
  dpg_.reset();
  ints_.reset();
}

const IssuedOp* Te::issued_ops() const {
  int block = 0;
  for (int w = 0; w < words_; ++w) {
    for (std::uint64_t ops = issued_now_.word[static_cast<std::size_t>(w)]; ops != 0; ops &= ops - 1) {
      const int bit = std::countr_zero(ops);
      int slot = issued_head_ + w * OpMasks::kLanesPerWord + bit / OpMasks::kLaneBits;
      if (slot >= n_contexts_) slot -= n_contexts_;
      decoded_[static_cast<std::size_t>(block)] =
          IssuedOp{block, slot, bit % OpMasks::kLaneBits, contexts_[static_cast<std::size_t>(slot)].seq};
      ++block;
    }
  }
  return decoded_.data();
}

void Te::allocate_into(int age, ControlPointBuffer& buffers, std::uint64_t* allocated_seq) {
  const ControlPointBuffer::Entry& buf = buffers.rd();
  int slot = head_ + age;
  if (slot >= n_contexts_) slot -= n_contexts_;
  Context& ctx = contexts_[static_cast<std::size_t>(slot)];
  const DpgPoint p = dpg_.point(buf);
  // pos and nrm are written at retirement.
  ctx.tag.u = p.u;
  ctx.tag.v = p.v;
  ctx.tag.j = p.j;
  ctx.tag.k = p.k;
  ctx.tag.L = buf.pattern == TriPattern::uniform ? buf.L : 0;
  ctx.tag.index = p.index;
  ctx.tag.id = buf.id;
  ctx.tag.last = p.last;
  ctx.tag.flags = buf.cp.flags;
  ctx.w = p.w;
  ctx.buffer = static_cast<std::uint8_t>(buffers.rd_ptr());
  ctx.seq = next_seq_++;
  if (allocated_seq) *allocated_seq = ctx.seq;
  // Ops that do not exist in this mode are allocated issued and done, so they never become ready.
  issued_.set_lane(age, absent_ops_);
  done_.set_lane(age, absent_ops_);
  dpg_.consume(buf);
  if (p.last) buffers.drain();
}

}  // namespace tessim::sim
