#include "sim/system/system_threads.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace tessim::sim {

namespace {

// Cycles a unit is clocked in one turn of its thread before the thread looks at its other units.
constexpr std::uint64_t kBudget = 64;
// How far ahead the coordinator prefetches a unit's records and vertices.
constexpr std::uint64_t kPrefetchCycles = 16;
constexpr std::uint64_t kPrefetchVertices = 3;
// The coordinator publishes its progress and the horizon at least this often (cycles).
constexpr std::uint64_t kPublish = 32;
// The mode is chosen by measured speed: each window of kWindow cycles is timed, and the run takes
// the faster mode (by kHysteresis), trying the other one again after kProbeEvery windows.
constexpr std::uint64_t kWindow = 8192;
constexpr int kProbeEvery = 8;
constexpr int kProbeEveryMax = 256;
constexpr double kHysteresis = 0.9;

void relax(unsigned& spins) {
  if (++spins < 256) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  } else {
    // Another thread has the core (more threads than cores, or a loaded machine): give it up.
    std::this_thread::yield();
  }
}

// The calling thread's guard against a hang of the exchange (a bug: every wait ends by design):
// a wait with no progress for kStallSeconds is an internal error.
constexpr double kStallSeconds = 120;

class StallGuard {
 public:
  explicit StallGuard(const char* what) : what_(what) {}
  void check(unsigned spins) {
    if (spins % 4096 != 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - since_).count() > kStallSeconds)
      throw std::logic_error(std::string("ThreadedSystem: no progress for ") + std::to_string(kStallSeconds) + " s " + what_);
  }

 private:
  const char* what_;
  std::chrono::steady_clock::time_point since_ = std::chrono::steady_clock::now();
};

// Units per thread: the calling thread also coordinates, which costs about what kCoordinatorShare
// units a unit of the system cost, so it clocks that many fewer.
constexpr double kCoordinatorShare = 0.15;

std::vector<std::vector<int>> partition(int units, int threads) {
  std::vector<std::vector<int>> groups(static_cast<std::size_t>(threads));
  const double work = units * (1.0 + kCoordinatorShare);
  int first = static_cast<int>(std::lround(work / threads - kCoordinatorShare * units));
  first = std::clamp(first, 0, units - (threads - 1));
  int u = 0;
  for (; u < first; ++u) groups[0].push_back(u);
  for (int t = 1; t < threads; ++t) {
    const int share = (units - first) / (threads - 1) + (t - 1 < (units - first) % (threads - 1) ? 1 : 0);
    for (int i = 0; i < share; ++i) groups[static_cast<std::size_t>(t)].push_back(u++);
  }
  return groups;
}

// Cycles ahead of the one after the last coordinated that every offer is certain to be admitted:
// floor((R - 1 - O) / M), or -1 when no slot is sure.
std::int64_t lookahead(const UnitSystem& system) {
  const int free_for_all = system.config().reorder_slots - 1 - system.occupancy();
  return free_for_all < 0 ? -1 : free_for_all / system.units();
}

}  // namespace

ThreadedSystem::ThreadedSystem(UnitSystem& system, int threads, std::uint64_t alternate_every)
    : system_(system), alternate_every_(alternate_every) {
  const int m = system.units();
  if (threads < 1 || threads > m) throw std::invalid_argument("ThreadedSystem: 1 to " + std::to_string(m) + " threads");
  for (int u = 0; u < m; ++u)
    if (!system.unit(u).idle() || system.unit(u).stats().cycles != 0)
      throw std::invalid_argument("ThreadedSystem: the system must be fresh from reset");
  lanes_.reserve(static_cast<std::size_t>(m));
  for (int u = 0; u < m; ++u) {
    auto lane = std::make_unique<Lane>();
    lane->records.resize(kRing);
    lane->vertices.resize(kRing);
    lane->decisions.assign(kRing, 0);
    lane->pushes.resize(static_cast<std::size_t>(system.config().tri_fifo_depth) + 1);
    lanes_.push_back(std::move(lane));
  }
  seen_.resize(static_cast<std::size_t>(m));
  outputs_.resize(static_cast<std::size_t>(m));
  owner_groups_ = partition(m, threads);
  start_parallel();
  helpers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t) helpers_.emplace_back([this, t] { helper(t); });
}

ThreadedSystem::~ThreadedSystem() { stop_helpers(); }

void ThreadedSystem::stop_helpers() {
  stop_.store(true, std::memory_order_release);
  // Wake parked helpers (the epoch keeps its parity).
  epoch_.fetch_add(2, std::memory_order_acq_rel);
  epoch_.notify_all();
  for (std::thread& h : helpers_)
    if (h.joinable()) h.join();
}

void ThreadedSystem::fail(std::exception_ptr e) {
  {
    std::lock_guard<std::mutex> lock(error_mutex_);
    if (!error_) error_ = e;
  }
  failed_.store(true, std::memory_order_release);
}

void ThreadedSystem::rethrow_if_failed() {
  if (!failed_.load(std::memory_order_acquire)) return;
  stop_helpers();
  std::lock_guard<std::mutex> lock(error_mutex_);
  std::rethrow_exception(error_);
}

// The unit's outputs at the start of its cycle k, for the coordinator.
void ThreadedSystem::write_record(int u, std::uint64_t k) {
  Lane& lane = *lanes_[static_cast<std::size_t>(u)];
  const Unit& unit = system_.unit(u);
  Record& rec = lane.records[k % kRing];
  rec.tri_pops = static_cast<std::uint32_t>(lane.injected - static_cast<std::uint64_t>(unit.tri_fifo_count()));
  rec.vtx_valid = unit.vtx_valid() ? 1 : 0;
  // The VTX FIFO's front is the vertex after the ones popped; the coordinator finds it by number.
  if (rec.vtx_valid && lane.vertices_recorded == lane.vertices_popped) {
    lane.vertices[lane.vertices_recorded % kRing] = unit.vtx();
    ++lane.vertices_recorded;
  }
}

// Called with the helpers parked (or not yet started): the lanes restart from the system's state.
void ThreadedSystem::start_parallel() {
  for (int u = 0; u < system_.units(); ++u) {
    Lane& lane = *lanes_[static_cast<std::size_t>(u)];
    // The triangles in the TRI FIFO count as pushed and injected: none is pending.
    const auto in_fifo = static_cast<std::uint64_t>(system_.unit(u).tri_fifo_count());
    lane.done.store(cycle_, std::memory_order_relaxed);
    lane.injected = in_fifo;
    lane.vertices_recorded = 0;
    lane.vertices_popped = 0;
    lane.horizon_seen = 0;
    lane.coordinator_seen = cycle_;
    lane.inputs = UnitInputs{};
    lane.pushed.store(in_fifo, std::memory_order_relaxed);
    seen_[static_cast<std::size_t>(u)] = {cycle_, in_fifo, 0};
    write_record(u, cycle_);
  }
  progress_.store(cycle_, std::memory_order_relaxed);
  horizon_.store(cycle_ + static_cast<std::uint64_t>(std::max<std::int64_t>(0, lookahead(system_))),
                 std::memory_order_relaxed);
  limit_.store(~std::uint64_t{0}, std::memory_order_relaxed);
  parked_.store(0, std::memory_order_relaxed);
  parallel_ = true;
  switching_ = false;
  window_cycles_ = 0;
  window_start_ = std::chrono::steady_clock::now();
  // Releases every store above to the helpers.
  epoch_.fetch_add(1, std::memory_order_acq_rel);
  epoch_.notify_all();
}

void ThreadedSystem::go_serial() {
  epoch_.fetch_add(1, std::memory_order_acq_rel);  // even: park
  unsigned spins = 0;
  StallGuard guard("waiting for the helpers to park");
  while (parked_.load(std::memory_order_acquire) < static_cast<int>(helpers_.size())) {
    rethrow_if_failed();
    relax(spins);
    guard.check(spins);
  }
  // Every unit stands at cycle_; the pushes not yet injected are of earlier cycles.
  for (int u = 0; u < system_.units(); ++u) {
    Lane& lane = *lanes_[static_cast<std::size_t>(u)];
    const std::uint64_t pushed = seen_[static_cast<std::size_t>(u)].pushed;
    for (; lane.injected < pushed; ++lane.injected) system_.unit(u).inject(lane.pushes[lane.injected % lane.pushes.size()].tri);
  }
  parallel_ = false;
  switching_ = false;
  window_cycles_ = 0;
  window_start_ = std::chrono::steady_clock::now();
  ++switches_;
}

std::uint64_t ThreadedSystem::advance(int u, std::uint64_t budget) {
  Lane& lane = *lanes_[static_cast<std::size_t>(u)];
  Unit& unit = system_.unit(u);
  std::uint64_t k = lane.done.load(std::memory_order_relaxed);  // this thread's own count
  std::uint64_t taken = 0;
  auto coordinator_at_least = [&](std::uint64_t cycles) {
    if (lane.coordinator_seen < cycles) lane.coordinator_seen = progress_.load(std::memory_order_acquire);
    return lane.coordinator_seen >= cycles;
  };
  while (taken < budget) {
    if (k >= limit_.load(std::memory_order_acquire)) break;
    // The record written after this edge must not replace one the coordinator has not read.
    if (!coordinator_at_least(k + 2 > kRing ? k + 2 - kRing : 0)) break;
    if (unit.tri_fifo_count() == 0) {
      // The CPG and the TE's classification would see the FIFO empty: every push of the cycles
      // before k must be in it first, and the coordinator must have done those cycles.
      const bool known = coordinator_at_least(k);
      const std::uint64_t pushed = lane.pushed.load(std::memory_order_acquire);
      while (lane.injected < pushed) {
        const Push& p = lane.pushes[lane.injected % lane.pushes.size()];
        if (p.cycle >= k) break;
        unit.inject(p.tri);
        ++lane.injected;
      }
      if (unit.tri_fifo_count() == 0) {
        if (!known) break;
        // An idle unit could be past the run's end: it waits until the coordinator has done its
        // cycle (or the run has ended).
        if (unit.idle() && !coordinator_at_least(k + 1)) break;
      }
    }
    UnitInputs& in = lane.inputs;  // never a triangle: those are injected
    in.vtx_ready = false;
    if (unit.vtx_valid()) {
      // The coordinator's decision where it has made it; else the horizon's promise. A horizon
      // computed after cycle c covers the cycles after c only; progress_ read right after it is at
      // least c + 1, so a cycle not yet coordinated is one the horizon covers.
      if (lane.coordinator_seen < k + 1 && k >= lane.horizon_seen) {
        lane.horizon_seen = horizon_.load(std::memory_order_acquire);
        lane.coordinator_seen = progress_.load(std::memory_order_acquire);
      }
      if (lane.coordinator_seen >= k + 1)
        in.vtx_ready = lane.decisions[k % kRing] != 0;
      else if (k < lane.horizon_seen)
        in.vtx_ready = true;  // certainly admitted
      else
        break;
    }
    unit.tick(in);
    if (in.vtx_ready) ++lane.vertices_popped;
    ++k;
    ++taken;
    write_record(u, k);
    lane.done.store(k, std::memory_order_release);
  }
  return taken;
}

void ThreadedSystem::advance_own(int t, bool& moved) {
  for (const int u : owner_groups_[static_cast<std::size_t>(t)])
    if (advance(u, kBudget) > 0) moved = true;
}

void ThreadedSystem::helper(int t) {
  try {
    unsigned spins = 0;
    std::uint32_t parked_in = 0;  // the even epoch this thread has reported parked in
    for (;;) {
      if (stop_.load(std::memory_order_acquire) || failed_.load(std::memory_order_acquire)) return;
      const std::uint32_t epoch = epoch_.load(std::memory_order_acquire);
      if (epoch % 2 == 0) {
        // Serial: this thread no longer touches its units.
        if (parked_in != epoch) {
          parked_in = epoch;
          parked_.fetch_add(1, std::memory_order_acq_rel);
        }
        epoch_.wait(epoch, std::memory_order_acquire);
        continue;
      }
      bool moved = false;
      advance_own(t, moved);
      if (moved) {
        spins = 0;
        continue;
      }
      if (ending_.load(std::memory_order_acquire)) {
        const std::uint64_t end = limit_.load(std::memory_order_acquire);
        bool all_done = true;
        for (const int u : owner_groups_[static_cast<std::size_t>(t)])
          if (lanes_[static_cast<std::size_t>(u)]->done.load(std::memory_order_relaxed) < end) all_done = false;
        if (all_done) return;
      }
      relax(spins);
    }
  } catch (...) {
    fail(std::current_exception());
  }
}

bool ThreadedSystem::tick(bool tri_valid, const TriangleFx& tri) {
  if (finished_) throw std::logic_error("ThreadedSystem: tick() after finish()");
  if (parallel_ && switching_ && cycle_ == limit_.load(std::memory_order_relaxed)) {
    // Every unit stands at limit_ once the coordinator may coordinate it.
    unsigned spins = 0;
    StallGuard guard("waiting for the units to reach the serial mode's first cycle");
    for (int u = 0; u < system_.units(); ++u) {
      Lane& lane = *lanes_[static_cast<std::size_t>(u)];
      while (lane.done.load(std::memory_order_acquire) < cycle_) {
        bool moved = false;
        advance_own(0, moved);
        if (!moved) {
          rethrow_if_failed();
          relax(spins);
          guard.check(spins);
        }
      }
    }
    go_serial();
  }
  if (parallel_) return tick_parallel(tri_valid, tri);
  const bool take = system_.tick(tri_valid, tri);
  ++cycle_;
  choose_mode();
  return take;
}

std::uint64_t ThreadedSystem::fast_forward(bool tri_valid, const TriangleFx& tri, std::uint64_t limit) {
  if (finished_) throw std::logic_error("ThreadedSystem: fast_forward() after finish()");
  if (parallel_) return 0;
  // Not counted in the mode's window: a stretch taken at once says nothing of a cycle's cost.
  const std::uint64_t n = system_.fast_forward(tri_valid, tri, limit);
  cycle_ += n;
  return n;
}

void ThreadedSystem::choose_mode() {
  const std::uint64_t window = alternate_every_ > 0 ? alternate_every_ : kWindow;
  if (++window_cycles_ < window) return;
  window_cycles_ = 0;
  if (helpers_.empty() || switching_) return;
  bool other = true;
  if (alternate_every_ == 0) {
    const auto now = std::chrono::steady_clock::now();
    const double per_cycle = std::chrono::duration<double>(now - window_start_).count() / static_cast<double>(window);
    window_start_ = now;
    const int m = parallel_ ? 1 : 0;
    const int o = 1 - m;
    cost_[m] = cost_[m] == 0 ? per_cycle : (cost_[m] + per_cycle) / 2;
    age_[m] = 0;
    ++age_[o];
    if (probing_) {
      // A mode that loses its probe is tried again half as often.
      probe_every_[m] = cost_[m] > cost_[o] ? std::min(probe_every_[m] * 2, kProbeEveryMax) : kProbeEvery;
      probing_ = false;
    }
    const bool faster = cost_[o] != 0 && cost_[o] < kHysteresis * cost_[m];
    probing_ = !faster && (cost_[o] == 0 || age_[o] >= probe_every_[o]);
    other = faster || probing_;
  }
  if (!other) return;
  if (parallel_) {
    // No unit is past the published progress + kRing: they all stop at that cycle, where the run
    // goes serial.
    switching_ = true;
    limit_.store(cycle_ + kRing, std::memory_order_release);
  } else {
    start_parallel();
    ++switches_;
  }
}

bool ThreadedSystem::tick_parallel(bool tri_valid, const TriangleFx& tri) {
  const std::uint64_t c = cycle_;
  const int m = system_.units();
  // Every unit's outputs at the start of cycle c: each must have taken c clock edges.
  unsigned spins = 0;
  StallGuard guard("waiting for the units' outputs");
  for (;;) {
    bool ready = true;
    for (int u = 0; u < m; ++u) {
      Seen& seen = seen_[static_cast<std::size_t>(u)];
      if (seen.done < c) seen.done = lanes_[static_cast<std::size_t>(u)]->done.load(std::memory_order_acquire);
      if (seen.done < c) ready = false;
    }
    if (ready) break;
    bool moved = false;
    advance_own(0, moved);
    if (!moved) {
      rethrow_if_failed();
      relax(spins);
      guard.check(spins);
    }
  }
  const int depth = system_.config().tri_fifo_depth;
  for (int u = 0; u < m; ++u) {
    const Lane& lane = *lanes_[static_cast<std::size_t>(u)];
    const Seen& seen = seen_[static_cast<std::size_t>(u)];
    const Record& rec = lane.records[c % kRing];
    UnitOutputs& o = outputs_[static_cast<std::size_t>(u)];
    o.tri_ready = seen.pushed - rec.tri_pops < static_cast<std::uint64_t>(depth);
    o.vtx_valid = rec.vtx_valid != 0;
    o.vtx = o.vtx_valid ? &lane.vertices[seen.vertices_taken % kRing] : nullptr;
    // The records and vertices come from another core's cache: ask for the next ones early.
    __builtin_prefetch(&lane.records[(c + kPrefetchCycles) % kRing]);
    const VertexFx* ahead = &lane.vertices[(seen.vertices_taken + kPrefetchVertices) % kRing];
    __builtin_prefetch(ahead);
    __builtin_prefetch(reinterpret_cast<const char*>(ahead) + sizeof(VertexFx) - 1);
  }
  const bool take = system_.coordinate(tri_valid, tri, outputs_.data());
  const std::uint64_t horizon = horizon_.load(std::memory_order_relaxed);  // written only here
  for (int u = 0; u < m; ++u) {
    Lane& lane = *lanes_[static_cast<std::size_t>(u)];
    const bool admitted = system_.admitted(u);
    if (outputs_[static_cast<std::size_t>(u)].vtx_valid && c < horizon && !admitted)
      throw std::logic_error("ThreadedSystem: unit " + std::to_string(u) + " offered a vertex in cycle " +
                             std::to_string(c) + " within the admission horizon and the buffer refused it");
    lane.decisions[c % kRing] = admitted ? 1 : 0;
    if (admitted) ++seen_[static_cast<std::size_t>(u)].vertices_taken;
  }
  if (const int d = system_.dispatched_to(); d >= 0) {
    Lane& lane = *lanes_[static_cast<std::size_t>(d)];
    const std::uint64_t n = seen_[static_cast<std::size_t>(d)].pushed++;
    lane.pushes[n % lane.pushes.size()] = {c, tri};
    lane.pushed.store(n + 1, std::memory_order_release);
  }
  ++cycle_;
  // Publishing costs the other cores' copies of the line: progress_ is stored when a unit may be
  // waiting for it (one not known to be past this cycle) and every kPublish cycles for the rings;
  // the horizon when a unit may be near it and every kPublish cycles. Publishing later is only
  // more conservative.
  bool unit_near = false, unit_near_horizon = false;
  for (const Seen& seen : seen_) {
    unit_near = unit_near || seen.done <= cycle_;
    unit_near_horizon = unit_near_horizon || seen.done + kPublish >= horizon;
  }
  if (unit_near || cycle_ % kPublish == 0) progress_.store(cycle_, std::memory_order_release);
  // After this cycle every offer in cycles c + 1 .. c + lookahead finds a slot. Stored after
  // progress_ (the units rely on that order: progress_ read right after the horizon is >= c + 1).
  const std::int64_t ahead = lookahead(system_);
  if (ahead >= 0) {
    const std::uint64_t h = c + 1 + static_cast<std::uint64_t>(ahead);
    if (h > horizon && (unit_near_horizon || h >= horizon + kPublish)) {
      progress_.store(cycle_, std::memory_order_release);
      horizon_.store(h, std::memory_order_release);
    }
  }
  choose_mode();
  return take;
}

void ThreadedSystem::finish() {
  if (finished_) return;
  finished_ = true;
  if (!parallel_) {
    stop_helpers();
    rethrow_if_failed();
    return;
  }
  progress_.store(cycle_, std::memory_order_release);
  limit_.store(cycle_, std::memory_order_release);
  ending_.store(true, std::memory_order_release);
  unsigned spins = 0;
  StallGuard guard("waiting for the units to reach the end");
  for (;;) {
    bool moved = false;
    advance_own(0, moved);
    if (moved) continue;
    rethrow_if_failed();
    bool all_done = true;
    for (const int u : owner_groups_[0])
      if (lanes_[static_cast<std::size_t>(u)]->done.load(std::memory_order_relaxed) < cycle_) all_done = false;
    if (all_done) break;
    relax(spins);
    guard.check(spins);
  }
  for (std::thread& h : helpers_) h.join();
  rethrow_if_failed();
  for (int u = 0; u < system_.units(); ++u) {
    const std::uint64_t done = lanes_[static_cast<std::size_t>(u)]->done.load(std::memory_order_acquire);
    if (done != cycle_)
      throw std::logic_error("ThreadedSystem: unit " + std::to_string(u) + " took " + std::to_string(done) +
                             " clock edges in a run of " + std::to_string(cycle_) + " cycles");
  }
}

int auto_system_threads(int units, unsigned hardware_threads, unsigned runnable) {
  const unsigned busy = runnable > 0 ? runnable - 1 : 0;  // the caller's own thread is not load
  const unsigned idle = hardware_threads > busy ? hardware_threads - busy : 0;
  if (idle < kAutoMinIdleThreads || units < 2) return 1;
  return static_cast<int>(std::min<unsigned>(idle, static_cast<unsigned>(units)));
}

int auto_system_threads(int units) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  unsigned runnable = hardware + 1;  // unknown: as if every hardware thread were busy
  // /proc/loadavg: "0.52 0.58 0.59 3/512 12345": the fourth field is runnable/total tasks.
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    double a = 0, b = 0, c = 0;
    unsigned running = 0, total = 0;
    if (std::fscanf(f, "%lf %lf %lf %u/%u", &a, &b, &c, &running, &total) == 5) runnable = running;
    std::fclose(f);
  }
  return auto_system_threads(units, hardware, runnable);
}

}  // namespace tessim::sim
