#include "sim/system/system.hpp"

#include <algorithm>
#include <stdexcept>

#include "sim/base/int_ops.hpp"
#include "sim/values/cpg.hpp"

namespace tessim::sim {

namespace {

const UnitConfig& checked(const UnitConfig& cfg) {
  if (cfg.units < 1 || cfg.units > UnitSystem::kMaxUnits || cfg.ge_ports < 1 || cfg.ge_ports > UnitSystem::kMaxPorts ||
      cfg.reorder_slots < 2 || cfg.dispatch_batch < 1)
    throw std::invalid_argument("UnitSystem: configuration not validated");
  return cfg;
}

}  // namespace

UnitSystem::UnitSystem(const UnitConfig& cfg, int ge_cycles_per_vertex) : cfg_(checked(cfg)) {
  const auto m = static_cast<std::size_t>(cfg.units);
  units_.reserve(m);
  for (std::size_t u = 0; u < m; ++u) units_.emplace_back(cfg);
  ports_.reserve(static_cast<std::size_t>(cfg.ge_ports));
  // Port p draws its random stalls from seed + p: each port its own stream, the same every run.
  for (int p = 0; p < cfg.ge_ports; ++p)
    ports_.emplace_back(ge_cycles_per_vertex, cfg.gpe_stall_prob, cfg.seed + static_cast<std::uint64_t>(p));
  slots_.resize(static_cast<std::size_t>(cfg.reorder_slots));
  for (std::size_t i = 0; i < slots_.size(); ++i) slots_[i].next = i + 1 < slots_.size() ? static_cast<int>(i + 1) : -1;
  free_ = 0;
  queues_.resize(m);
  // Patches in flight: each unit holds at most its TRI FIFO, its CPG copies and its buffers' patches
  // (a patch leaves the unit with its last vertex), and the reassembly buffer at most R more
  // (every patch in it has at least one vertex there).
  order_.resize(m * static_cast<std::size_t>(cfg.tri_fifo_depth + cfg.cpg.copies + cfg.cp_buffers + cfg.vtx_fifo_depth + 1) +
                static_cast<std::size_t>(cfg.reorder_slots) + 1);
  pending_patches_.assign(m, 0);
  pending_vertices_.assign(m, 0);
  // The distributor's predictions (earliest_finish): a patch takes (C + 1) / Mc cycles of the CPG,
  // a vertex ops / N cycles of the TE; both scaled by Mc N to integers.
  cpg_weight_ = static_cast<std::uint64_t>(cpg_cycles(cfg.normals, cfg.format, cfg.cpg) + 1) *
                static_cast<std::uint64_t>(cfg.int_blocks);
  te_weight_ = static_cast<std::uint64_t>(int_ops::ops_per_vertex(cfg.normals)) * static_cast<std::uint64_t>(cfg.cpg.copies);
  emitted_.reserve(static_cast<std::size_t>(cfg.ge_ports));
  admit_.assign(m, 0);
  outputs_.resize(m);
  stats_.unit_triangles.assign(m, 0);
  stats_.unit_vertices.assign(m, 0);
}

bool UnitSystem::idle() const {
  if (order_count_ > 0 || occupancy_ > 0) return false;
  for (const Unit& u : units_)
    if (!u.idle()) return false;
  return true;
}

int UnitSystem::choose(const TriangleFx& tri, const UnitOutputs* outputs) const {
  if (batch_left_ > 0) return batch_unit_;
  switch (cfg_.distribution) {
    case Distribution::RoundRobin: return next_rr_;
    case Distribution::LeastLoaded: {
      // Among the units that can take a triangle now, the fewest vertices outstanding; the lowest
      // index on a tie. None ready: the round-robin turn (the triangle waits for it).
      int best = -1;
      for (int u = 0; u < units(); ++u)
        if (outputs[u].tri_ready &&
            (best < 0 || pending_vertices_[static_cast<std::size_t>(u)] < pending_vertices_[static_cast<std::size_t>(best)]))
          best = u;
      return best < 0 ? next_rr_ : best;
    }
    case Distribution::EarliestFinish: {
      // The unit that would finish this patch first: its backlog is the longer of its CPG work
      // ((C + 1) / Mc cycles a patch outstanding) and its TE work (ops / N cycles a vertex
      // outstanding), the patch's own included. In integers, both times Mc N: the comparison of
      // the RTL's distributor.
      const auto vertices = static_cast<std::uint64_t>(patch_vertex_count(tri));
      int best = -1;
      std::uint64_t best_finish = 0;
      for (int u = 0; u < units(); ++u) {
        const auto i = static_cast<std::size_t>(u);
        if (!outputs[u].tri_ready) continue;
        const std::uint64_t finish = std::max((pending_patches_[i] + 1) * cpg_weight_,
                                              (pending_vertices_[i] + vertices) * te_weight_);
        if (best < 0 || finish < best_finish) {
          best = u;
          best_finish = finish;
        }
      }
      return best < 0 ? next_rr_ : best;
    }
  }
  return 0;
}

void UnitSystem::push(int unit, const VertexFx& v) {
  const int s = free_;
  Slot& slot = slots_[static_cast<std::size_t>(s)];
  free_ = slot.next;
  slot.vertex = v;
  slot.next = -1;
  Queue& q = queues_[static_cast<std::size_t>(unit)];
  if (q.tail >= 0) slots_[static_cast<std::size_t>(q.tail)].next = s;
  else q.head = s;
  q.tail = s;
  ++q.count;
  ++occupancy_;
}

VertexFx UnitSystem::pop(int unit) {
  Queue& q = queues_[static_cast<std::size_t>(unit)];
  const int s = q.head;
  Slot& slot = slots_[static_cast<std::size_t>(s)];
  q.head = slot.next;
  if (q.head < 0) q.tail = -1;
  --q.count;
  slot.next = free_;
  free_ = s;
  --occupancy_;
  return slot.vertex;
}

void UnitSystem::read_outputs() {
  for (int u = 0; u < units(); ++u) {
    const Unit& unit = units_[static_cast<std::size_t>(u)];
    UnitOutputs& o = outputs_[static_cast<std::size_t>(u)];
    o.tri_ready = unit.tri_ready();
    o.vtx_valid = unit.vtx_valid();
    o.vtx = o.vtx_valid ? &unit.vtx() : nullptr;
  }
}

bool UnitSystem::admits_as_oldest(int u, const UnitOutputs& o) const {
  return cfg_.reassembly != Reassembly::Ordered ||
         (order_count_ > 0 && order_[order_head_].unit == u && order_[order_head_].id == o.vtx->id);
}

bool UnitSystem::tick(bool tri_valid, const TriangleFx& tri) {
  read_outputs();
  const bool take = coordinate(tri_valid, tri, outputs_.data());
  // The units' clock edges (one idle input kept: a TriangleFx is too large to clear every cycle).
  idle_inputs_.tri_valid = false;
  for (int u = 0; u < units(); ++u) {
    const auto i = static_cast<std::size_t>(u);
    if (dispatched_to_ == u) {
      UnitInputs in;
      in.tri_valid = true;
      in.tri = tri;
      in.vtx_ready = admit_[i] != 0;
      units_[i].tick(in);
    } else {
      idle_inputs_.vtx_ready = admit_[i] != 0;
      units_[i].tick(idle_inputs_);
    }
  }
  return take;
}

std::uint64_t UnitSystem::fast_forward(bool tri_valid, const TriangleFx& tri, std::uint64_t limit) {
  if (limit == 0) return 0;
  read_outputs();
  // The distributor: a triangle it would take moves data; one refused waits through the stretch
  // (the units' tri_ready and the distributor's counts hold, so its choice does).
  const bool stalled = tri_valid;
  if (tri_valid && outputs_[static_cast<std::size_t>(choose(tri, outputs_.data()))].tri_ready) return 0;
  // The buffer admits nothing (the rule of coordinate(), with no admission before it): each
  // unit offering a vertex stays blocked.
  const bool ordered = cfg_.reassembly == Reassembly::Ordered;
  const int r = cfg_.reorder_slots;
  std::uint64_t blocked = 0;
  for (int u = 0; u < units(); ++u) {
    if (!outputs_[static_cast<std::size_t>(u)].vtx_valid) continue;
    if (occupancy_ < (admits_as_oldest(u, outputs_[static_cast<std::size_t>(u)]) ? r : r - 1)) return 0;
    ++blocked;
  }
  // The ports see the same buffer every cycle: a vertex for them or none.
  bool available = false;
  if (ordered) {
    available = order_count_ > 0 && queues_[static_cast<std::size_t>(order_[order_head_].unit)].count > 0;
  } else {
    for (const Queue& q : queues_) available = available || q.count > 0;
  }
  std::uint64_t n = limit;
  for (const Gpe& port : ports_) n = std::min(n, port.quiet_cycles(available));
  if (n == 0) return 0;
  idle_inputs_.tri_valid = false;
  idle_inputs_.vtx_ready = false;
  for (const Unit& unit : units_) {
    if (!unit.te_quiet()) return 0;
    n = std::min(n, unit.quiet_cycles(idle_inputs_));
    if (n == 0) return 0;
  }
  // n cycles, as n calls of tick() would count them.
  for (Unit& unit : units_)
    if (unit.skip(n, idle_inputs_) != n) throw std::logic_error("UnitSystem::fast_forward: a quiet unit skipped less");
  for (Gpe& port : ports_) {
    const GpeCycle c = port.skip(n, available, false);
    if (c.spare) (order_count_ == 0 ? stats_.ports_waiting_stream : stats_.ports_waiting_unit) += n;
  }
  stats_.cycles += n;
  stats_.max_occupancy = std::max(stats_.max_occupancy, occupancy_);
  stats_.occupancy_histogram[static_cast<std::size_t>(std::min(15, occupancy_ * 16 / r))] += n;
  stats_.unit_blocked += blocked * n;
  if (stalled) stats_.dispatch_stalls += n;
  emitted_.clear();
  std::fill(admit_.begin(), admit_.end(), std::uint8_t{0});
  dispatched_to_ = -1;
  return n;
}

bool UnitSystem::coordinate(bool tri_valid, const TriangleFx& tri, const UnitOutputs* outputs) {
  ++stats_.cycles;
  const int r = cfg_.reorder_slots;
  const int occupancy_at_start = occupancy_;
  stats_.max_occupancy = std::max(stats_.max_occupancy, occupancy_at_start);
  ++stats_.occupancy_histogram[static_cast<std::size_t>(std::min(15, occupancy_at_start * 16 / r))];

  // ---- The buffer's admissions, from the registered state: the oldest patch's vertices while a
  // slot is free, any other unit's while two are (one stays for the oldest patch).
  // Unordered, every slot is anyone's.
  const bool ordered = cfg_.reassembly == Reassembly::Ordered;
  int admitted = 0;
  for (int u = 0; u < units(); ++u) {
    admit_[static_cast<std::size_t>(u)] = 0;
    if (!outputs[u].vtx_valid) continue;
    if (occupancy_at_start + admitted < (admits_as_oldest(u, outputs[u]) ? r : r - 1)) {
      admit_[static_cast<std::size_t>(u)] = 1;
      ++admitted;
    } else {
      ++stats_.unit_blocked;
    }
  }

  // ---- The ports, in index order, take the buffer's vertices in stream order (unordered: the
  // next unit in turn with a vertex; order_count_ then only counts the patches in flight).
  emitted_.clear();
  for (Gpe& port : ports_) {
    if (ordered) {
      const bool waiting_stream = order_count_ == 0;
      const int head_unit = waiting_stream ? -1 : order_[order_head_].unit;
      const bool available = !waiting_stream && queues_[static_cast<std::size_t>(head_unit)].count > 0;
      const GpeCycle c = port.tick(available, false);
      if (c.accepted) {
        const VertexFx v = pop(head_unit);
        emitted_.push_back(v);
        ++stats_.vertices;
        if (v.last) {
          order_head_ = order_head_ + 1 == order_.size() ? 0 : order_head_ + 1;
          --order_count_;
        }
      } else if (c.spare) {
        ++(waiting_stream ? stats_.ports_waiting_stream : stats_.ports_waiting_unit);
      }
    } else {
      int from = -1;
      for (int i = 0; i < units() && from < 0; ++i) {
        const int u = next_port_unit_ + i < units() ? next_port_unit_ + i : next_port_unit_ + i - units();
        if (queues_[static_cast<std::size_t>(u)].count > 0) from = u;
      }
      const GpeCycle c = port.tick(from >= 0, false);
      if (c.accepted) {
        const VertexFx v = pop(from);
        emitted_.push_back(v);
        ++stats_.vertices;
        if (v.last) --order_count_;
        next_port_unit_ = from + 1 == units() ? 0 : from + 1;
      } else if (c.spare) {
        ++(order_count_ == 0 ? stats_.ports_waiting_stream : stats_.ports_waiting_unit);
      }
    }
  }

  // ---- The distributor.
  const int target = tri_valid ? choose(tri, outputs) : 0;
  const bool take = tri_valid && outputs[target].tri_ready;
  dispatched_to_ = take ? target : -1;
  if (tri_valid && !take) ++stats_.dispatch_stalls;
  if (take) {
    const auto t = static_cast<std::size_t>(target);
    ++pending_patches_[t];
    pending_vertices_[t] += static_cast<std::uint64_t>(patch_vertex_count(tri));
    ++stats_.unit_triangles[t];
    if (ordered) {
      if (order_count_ == order_.size()) throw std::logic_error("UnitSystem: more patches in flight than the order FIFO holds");
      std::size_t tail = order_head_ + order_count_;
      if (tail >= order_.size()) tail -= order_.size();
      order_[tail] = {static_cast<std::uint8_t>(target), tri.id};
    }
    ++order_count_;
    if (batch_left_ == 0) {
      batch_unit_ = target;
      batch_left_ = cfg_.dispatch_batch;
    }
    if (--batch_left_ == 0) next_rr_ = target + 1 == units() ? 0 : target + 1;
  }

  // ---- Each admitted vertex enters its unit's queue at the clock edge.
  for (int u = 0; u < units(); ++u) {
    const auto i = static_cast<std::size_t>(u);
    if (admit_[i] == 0) continue;
    const VertexFx& v = *outputs[u].vtx;
    push(u, v);
    ++stats_.unit_vertices[i];
    --pending_vertices_[i];
    if (v.last) --pending_patches_[i];
  }
  return take;
}

}  // namespace tessim::sim
