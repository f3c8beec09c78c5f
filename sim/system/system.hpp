// Several units on one triangle stream (docs/microarchitecture.md §13): a distributor hands each
// triangle (or batch of `dispatch_batch` triangles) to one of M units by its policy; a reassembly
// buffer of R vertex slots, shared by the units, takes their output and hands it to P geometry-
// engine ports in stream order, so the system's output is the single unit's, vertex for vertex.
// (`reassembly unordered`, a study's bound: the ports take any unit's vertices, the units in turn.)
//
// The buffer is a pool of R slots holding one linked queue per unit (a unit's vertices arrive in
// its own order, which is stream order among its patches); an order FIFO records which unit got
// each patch. The oldest patch's vertices always find a slot (one is kept for them), so the
// system cannot deadlock whatever R >= 2. Protocol as sim::Unit: tick() is one clock edge; the
// decisions of a cycle come from the registered state.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/blocks/counters.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// What the coordinating logic (distributor, buffer, ports) reads of a unit in a cycle: its
// outputs at the start of the cycle (sim::Unit's, from the registered state).
struct UnitOutputs {
  bool tri_ready = false;
  bool vtx_valid = false;
  const VertexFx* vtx = nullptr;  // while vtx_valid
};

// The system's own statistics (the units' and the ports' are kept by them).
struct SystemStats {
  std::uint64_t cycles = 0;
  std::uint64_t vertices = 0;             // handed to the ports
  std::uint64_t dispatch_stalls = 0;      // cycles a triangle waited: the chosen unit's TRI FIFO full
  std::uint64_t unit_blocked = 0;         // unit-cycles a unit offered a vertex the buffer could not take
  std::uint64_t ports_waiting_unit = 0;   // port-cycles a ready port waited for the oldest patch's unit
  std::uint64_t ports_waiting_stream = 0; // port-cycles a ready port had no patch at all in flight
  int max_occupancy = 0;                  // most slots taken at once
  // Cycles by occupancy in 16 buckets of R/16 slots (bucket 15 includes a full buffer).
  std::array<std::uint64_t, 16> occupancy_histogram{};
  std::vector<std::uint64_t> unit_triangles, unit_vertices;  // dispatched to / out of each unit
};

class UnitSystem {
 public:
  static constexpr int kMaxUnits = 16;
  static constexpr int kMaxPorts = 16;
  // cfg must have passed validate(); the ports are GE models of K = `ge_cycles_per_vertex`.
  UnitSystem(const UnitConfig& cfg, int ge_cycles_per_vertex);

  // One cycle: `tri` is offered when tri_valid. Returns whether the distributor took it.
  bool tick(bool tri_valid, const TriangleFx& tri);
  // The same cycle split in two, for a driver that clocks the units elsewhere
  // (sim/system/system_threads.hpp): coordinate() is everything but the units' clock edges, from
  // the units' outputs at the start of the cycle (one per unit); the units' inputs of the cycle are
  // then dispatched_to() (the unit that takes `tri`, or -1) and admitted(u) (its vertex enters the
  // buffer: vtx_ready).
  bool coordinate(bool tri_valid, const TriangleFx& tri, const UnitOutputs* outputs);
  // Fast-forward (docs/microarchitecture.md §11, §13): in place of up to `limit` tick(tri_valid,
  // tri) calls, the cycles from now in which no data moves anywhere in the system — no triangle
  // dispatched, no vertex admitted into the buffer or taken by a port, every unit quiet with its
  // TE quiet (Unit::quiet_cycles, te_quiet) and every port in a countdown or waiting without a
  // vertex (Gpe::quiet_cycles) — taken at once. Returns how many (0: the next cycle moves data or
  // cannot be skipped; call tick()). Every counter and statistic is as after that many tick()
  // calls; emitted() is empty.
  std::uint64_t fast_forward(bool tri_valid, const TriangleFx& tri, std::uint64_t limit);
  int dispatched_to() const { return dispatched_to_; }
  bool admitted(int u) const { return admit_[static_cast<std::size_t>(u)] != 0; }
  Unit& unit(int u) { return units_[static_cast<std::size_t>(u)]; }
  int occupancy() const { return occupancy_; }
  const UnitConfig& config() const { return cfg_; }
  // The vertices the ports took in the cycle last ticked, in stream order.
  const std::vector<VertexFx>& emitted() const { return emitted_; }
  bool idle() const;

  int units() const { return static_cast<int>(units_.size()); }
  const Unit& unit(int u) const { return units_[static_cast<std::size_t>(u)]; }
  const Gpe& port(int p) const { return ports_[static_cast<std::size_t>(p)]; }
  int ports() const { return static_cast<int>(ports_.size()); }
  const SystemStats& stats() const { return stats_; }

 private:
  struct Slot {
    VertexFx vertex;
    int next = -1;
  };
  struct Queue {
    int head = -1, tail = -1, count = 0;
  };
  struct Dispatched {
    std::uint8_t unit = 0;
    std::uint32_t id = 0;
  };

  int choose(const TriangleFx& tri, const UnitOutputs* outputs) const;  // the unit the distributor wants for `tri`
  void read_outputs();  // outputs_ from the units' registered state
  // Whether unit u's offered vertex (o.vtx) may take the buffer's last free slot: it belongs to
  // the oldest patch in flight (unordered: any vertex may).
  bool admits_as_oldest(int u, const UnitOutputs& o) const;
  void push(int unit, const VertexFx& v);
  VertexFx pop(int unit);

  UnitConfig cfg_;
  std::vector<Unit> units_;
  std::vector<Gpe> ports_;
  // Reassembly buffer: a pool of R slots, a free list and one queue per unit.
  std::vector<Slot> slots_;
  int free_ = -1;
  int occupancy_ = 0;
  std::vector<Queue> queues_;
  // Patches in dispatch order, not yet fully handed to the ports: a ring.
  std::vector<Dispatched> order_;
  std::size_t order_head_ = 0, order_count_ = 0;
  // The distributor's view of each unit: patches and vertices dispatched and not yet out.
  std::vector<std::uint64_t> pending_patches_, pending_vertices_;
  int batch_unit_ = 0, batch_left_ = 0, next_rr_ = 0;
  int next_port_unit_ = 0;  // unordered: the unit the next port looks at first
  std::uint64_t cpg_weight_ = 0, te_weight_ = 0;  // earliest_finish: (C + 1) N and ops Mc
  std::vector<VertexFx> emitted_;
  std::vector<std::uint8_t> admit_;
  std::vector<UnitOutputs> outputs_;  // tick()'s view of the units
  UnitInputs idle_inputs_;            // a unit's inputs in a cycle without a triangle for it
  int dispatched_to_ = -1;
  SystemStats stats_;
};

}  // namespace tessim::sim
