// A system of units (sim/system/system.hpp) clocked on several threads, cycle for cycle and bit for
// bit the run of UnitSystem::tick() (docs/microarchitecture.md §13, "Threaded runs").
//
// The calling thread runs the coordinating logic (distributor, reassembly buffer, ports: one
// UnitSystem::coordinate() a cycle) and some of the units; helper threads run the others. A unit
// runs ahead of the coordinator as far as what it needs is already certain — a conservative
// parallel simulation whose lookahead comes from the unit's TRI FIFO and the buffer's free slots:
//   - a triangle the distributor pushes in cycle c changes nothing inside the unit while its TRI
//     FIFO holds another one (the CPG reads only "empty" and the front), so it is injected late
//     (Unit::inject); a unit whose TRI FIFO is empty waits until the coordinator has done the
//     cycles before its next one;
//   - a vertex the unit offers in cycle k is certainly admitted if, after some cycle c < k with O
//     slots taken, k <= c + floor((R - 1 - O) / M): even M admissions a cycle and no port taking
//     any leave a slot for it (the admission horizon). Beyond it the unit waits for the
//     coordinator's decision of that cycle.
// The coordinator reads each unit's outputs at the start of a cycle from a record the unit wrote
// after its previous clock edge, and checks every admission a unit took on trust.
//
// Where units wait for the coordinator nearly every cycle (a nearly full buffer: a horizon of a
// cycle or two; units starved of triangles) the exchange costs more than it saves, so the run
// also has a serial mode — the helpers parked, the calling thread ticking the whole system with
// UnitSystem::tick() — and switches between the two by their measured speed. Either way each
// cycle is UnitSystem::tick()'s.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "sim/system/system.hpp"

namespace tessim::sim {

// What `--threads auto` takes for a system of `units` units (docs/microarchitecture.md §13): the
// parallel mode pays only on cores of its own. On two idle cores it ran at 0.92-1.35x the speed
// of one thread, and with another process competing for them 2-8x slower, so auto takes one thread
// per idle hardware thread (at most one per unit) when at least kAutoMinIdleThreads are idle, and
// one thread otherwise. `runnable` is the machine's count of runnable tasks, the caller included.
inline constexpr unsigned kAutoMinIdleThreads = 4;
int auto_system_threads(int units, unsigned hardware_threads, unsigned runnable);
// The same for this machine, now: std::thread::hardware_concurrency() and the runnable tasks of
// /proc/loadavg (all of them busy when it cannot be read).
int auto_system_threads(int units);

class ThreadedSystem {
 public:
  // `threads` >= 1 threads in all (the calling one included), at most one per unit. The system
  // must be fresh from reset. `alternate_every` > 0 (for tests): switch modes every that many
  // cycles instead of by speed.
  ThreadedSystem(UnitSystem& system, int threads, std::uint64_t alternate_every = 0);
  ~ThreadedSystem();  // stops and joins the helpers (after an exception: without finishing)
  ThreadedSystem(const ThreadedSystem&) = delete;
  ThreadedSystem& operator=(const ThreadedSystem&) = delete;

  // One cycle, as UnitSystem::tick(): `tri` is offered when tri_valid; returns whether the
  // distributor took it; system().emitted() holds what the ports took. On the calling thread.
  bool tick(bool tri_valid, const TriangleFx& tri);
  // UnitSystem::fast_forward() in the serial mode (0 in the parallel one, whose units run ahead
  // of the coordinator); the skipped cycles count as ticked.
  std::uint64_t fast_forward(bool tri_valid, const TriangleFx& tri, std::uint64_t limit);
  // The run ends after the cycles ticked so far: every unit is clocked to the same cycle count and
  // the helpers are joined; then the system's units read as after as many UnitSystem::tick() calls.
  void finish();

  // Switches between the parallel and the serial mode so far.
  int mode_switches() const { return switches_; }

 private:
  // What the coordinator reads of a unit at the start of cycle k (record k % kRing).
  struct Record {
    std::uint32_t tri_pops = 0;  // triangles the CPG has taken before cycle k
    std::uint8_t vtx_valid = 0;
  };
  struct Push {
    std::uint64_t cycle = 0;
    TriangleFx tri;
  };
  // One unit's side of the exchange, laid out so that a cache line is written by one thread only.
  struct alignas(64) Lane {
    // Written by the unit's thread (`done` every cycle; the rest is its private state).
    std::atomic<std::uint64_t> done{0};   // clock edges taken
    std::uint64_t injected = 0;           // pushes injected
    std::uint64_t vertices_recorded = 0;  // vertices written to `vertices`, in output order
    std::uint64_t vertices_popped = 0;    // vertices the buffer has taken, as the unit saw them
    std::uint64_t horizon_seen = 0;       // the unit thread's copy of the admission horizon
    std::uint64_t coordinator_seen = 0;   // its copy of the coordinator's progress
    UnitInputs inputs;                    // the unit's inputs, kept (clearing a TriangleFx costs)
    // The rings, fixed after construction; each element is written by one side only.
    alignas(64) std::vector<Record> records;  // kRing, by the unit: its outputs at the start of cycle k
    std::vector<VertexFx> vertices;           // kRing, by the unit: its output vertices by number
    std::vector<Push> pushes;                 // tri_fifo_depth + 1, by the coordinator
    std::vector<std::uint8_t> decisions;      // kRing, by the coordinator: admitted in cycle c
    // Written by the coordinator when it dispatches a triangle to the unit.
    alignas(64) std::atomic<std::uint64_t> pushed{0};
  };
  // The coordinator's private view of a unit.
  struct Seen {
    std::uint64_t done = 0;            // its copy of Lane::done
    std::uint64_t pushed = 0;          // triangles dispatched
    std::uint64_t vertices_taken = 0;  // vertices admitted into the buffer
  };
  static constexpr std::uint64_t kRing = 256;

  // Clocks unit u as far as it can go, at most `budget` cycles; returns how many it took.
  std::uint64_t advance(int u, std::uint64_t budget);
  void write_record(int u, std::uint64_t k);  // the record of the start of cycle k
  bool tick_parallel(bool tri_valid, const TriangleFx& tri);
  void choose_mode();     // after each cycle
  void start_parallel();  // every lane from the system's state at cycle_; the helpers released
  void go_serial();       // at cycle_ == limit_: the helpers parked, the late pushes injected
  void helper(int t);
  void advance_own(int t, bool& moved);
  void fail(std::exception_ptr e);
  void rethrow_if_failed();
  void stop_helpers();

  UnitSystem& system_;
  std::vector<std::unique_ptr<Lane>> lanes_;
  std::vector<Seen> seen_;
  std::vector<std::vector<int>> owner_groups_;  // units clocked by each thread; 0: the calling one
  std::vector<UnitOutputs> outputs_;
  std::vector<std::thread> helpers_;
  std::uint64_t cycle_ = 0;  // cycles coordinated
  bool parallel_ = true;     // the mode (the calling thread's)
  bool switching_ = false;   // going serial at limit_
  std::uint64_t alternate_every_;
  std::uint64_t window_cycles_ = 0;  // cycles into the mode's current window
  std::chrono::steady_clock::time_point window_start_;
  double cost_[2] = {0, 0};  // seconds per cycle, serial and parallel (0: not measured)
  int age_[2] = {0, 0};      // windows since each was measured
  int probe_every_[2] = {8, 8};  // windows after which each is measured again
  bool probing_ = false;     // the current mode is on trial
  int switches_ = 0;
  bool finished_ = false;
  // Each on a line of its own: progress_ and horizon_ change every cycle, the rest rarely.
  alignas(64) std::atomic<std::uint64_t> progress_{0};  // cycles coordinated, for the units' threads
  alignas(64) std::atomic<std::uint64_t> horizon_{0};   // cycles before it: admission certain
  alignas(64) std::atomic<std::uint64_t> limit_{~std::uint64_t{0}};  // no unit is clocked past it
  std::atomic<std::uint32_t> epoch_{0};  // odd: parallel; even: the helpers park
  std::atomic<int> parked_{0};           // helpers parked in this even epoch
  std::atomic<bool> ending_{false};      // finish(): the helpers leave once their units reach limit_
  std::atomic<bool> stop_{false};
  std::atomic<bool> failed_{false};
  alignas(64) std::mutex error_mutex_;
  std::exception_ptr error_;
};

}  // namespace tessim::sim
