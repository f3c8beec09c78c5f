#include "sim/blocks/te.hpp"

#include <stdexcept>

namespace tessim::sim {

const char* to_string(TeClass c) {
  switch (c) {
    case TeClass::ContextLimited: return "context_limited";
    case TeClass::IntLimited: return "int_limited";
    case TeClass::Busy: return "busy";
    case TeClass::BlockedByGpe: return "blocked_by_gpe";
    case TeClass::StarvedByCpg: return "starved_by_cpg";
    case TeClass::Idle: return "idle";
    case TeClass::Pipeline: return "pipeline";
  }
  return "?";
}

Te::Te(int int_blocks, int int_latency, int contexts, NormalMode normals, const NumberFormat& format)
    : n_contexts_(contexts),
      bary_bits_(format.bary_bits),
      all_ops_((std::uint32_t{1} << int_ops::kOpCount) - 1),
      absent_ops_(int_ops::absent_ops(normals)),
      normal_op_(int_ops::normal_op(normals)),
      dpg_(format),
      ints_(int_blocks, int_latency) {
  if (contexts < 1 || contexts > kMaxContexts) throw std::invalid_argument("Te: V out of range");
  linear_normals_ = normals == NormalMode::Linear;
  slot_mask_ = static_cast<std::uint32_t>((std::uint64_t{1} << contexts) - 1);
}

void Te::reset() {
  for (Context& c : contexts_) c.issued = c.done = c.ready = 0;
  head_ = count_ = 0;
  ready_slots_ = 0;
  issued_count_ = 0;
  next_seq_ = 0;
  dpg_.reset();
  ints_.reset();
}

}  // namespace tessim::sim
