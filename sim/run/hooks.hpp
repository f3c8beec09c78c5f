// What a whole-mesh run (sim/run/simulate.hpp) offers to those who watch it: every accepted vertex,
// every finished patch, every cycle (CycleObserver), and the run's cancellation and progress.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "sim/ge/gpe.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// Watches a run cycle by cycle (traces, schedule printouts). on_cycle() is called after every
// cycle, with the unit's activity of that cycle, until it returns false.
class CycleObserver {
 public:
  virtual ~CycleObserver() = default;
  virtual bool on_cycle(const Unit& unit, const GpeCycle& gpe) = 0;
};

// One finished patch, converted back into the mesh's coordinates (normals normalized).
struct PatchOut {
  std::uint32_t triangle = 0;
  int L = 1;                              // the uniform pattern's factor; 0: a D3D11 pattern
  std::span<const glm::dvec3> positions;  // pattern order
  std::span<const glm::dvec3> normals;
  std::span<const std::uint32_t> indices;  // D3D11: the pattern's triangles (local indices, ccw)
};

struct SimHooks {
  std::function<void(const VertexFx&)> on_vertex;  // every vertex the GPE accepts, in order
  std::function<void(const PatchOut&)> on_patch;   // every patch once its last vertex is accepted
  std::vector<CycleObserver*> observers;
  bool measure_errors = false;  // every vertex against the float reference (SimResult::errors)
  // Take the cycles in which nothing moves at once (exact; docs/microarchitecture.md §11). Off
  // whenever an observer watches the run cycle by cycle.
  bool fast_forward = true;
  // A system of several units (UnitConfig::units > 1): the threads that clock it, the calling one
  // included (sim/system/system_threads.hpp; every cycle and bit as with one). 1: one thread; at
  // most one per unit.
  int system_threads = 1;
  // Set by another thread to stop the run at the next patch boundary (SimCancelled is thrown):
  // the other chunks of a chunked run after one of them failed.
  const std::atomic<bool>* cancel = nullptr;
  // Progress for a person (model/base/progress.hpp): every patch adds its vertices once the GPE has
  // accepted its last one. Shared by the chunks of a chunked run.
  std::atomic<std::uint64_t>* vertices_done = nullptr;
};

// Thrown by a run stopped through SimHooks::cancel.
struct SimCancelled : std::exception {
  const char* what() const noexcept override { return "simulation cancelled"; }
};

}  // namespace tessim::sim
