// Chunked runs (docs/statistics.md, "Chunked runs"): the triangle stream cut into K contiguous
// chunks of nearly equal triangle count, each simulated on a unit of its own, fresh from reset,
// on its own thread; the results merged as if one run. Every output vertex is the one a single
// run makes (a vertex's value does not depend on timing); the cycles are not: each chunk fills
// an empty unit and drains it, where one run overlaps the two, so chunked cycles lie within a
// bound per chunk boundary of a single run's (chunk_boundary_bound).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "model/mesh.hpp"
#include "sim/config/config.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/timeline.hpp"

namespace tessim::sim {

// More chunks would not help a run on one host, and each chunk may keep a temporary file
// (tessim sim -o) that an interrupted run must be able to remove.
inline constexpr int kMaxChunks = 32;

// The first triangle of each of the `chunks` chunks of `triangles` triangles, then `triangles`:
// chunk k is [starts[k], starts[k + 1]), sizes differing by at most one. 1 <= chunks <= triangles.
std::vector<std::uint64_t> chunk_starts(std::uint64_t triangles, int chunks);

// The configuration chunk k runs with: the geometry engine's random stalls drawn from a seed of
// its own (chunk 0: the configuration's, so that it matches the first cycles of a single run).
UnitConfig chunk_config(const UnitConfig& cfg, int chunk);

struct ChunkCallbacks {
  // The hooks of chunk k's run, made on the calling thread before any chunk starts; they run on
  // the chunk's thread. Observers are not allowed (a cycle-by-cycle watch of one run).
  std::function<SimHooks(int chunk)> hooks;
  // Called on the calling thread once chunk k has finished, for k = 0, 1, ... in order (while
  // later chunks may still run): where the chunk's outputs are merged in stream order.
  std::function<void(int chunk)> done;
  int threads = 0;  // worker threads; 0: min(chunks, hardware threads)
};

// Runs the mesh in `chunks` chunks and merges them (merge_chunks). An exception of a chunk (bad
// input, a saturated patch) stops the others and is rethrown: the first in stream order, as a
// single run would throw it.
SimResult simulate_chunked(const Mesh& mesh, const UnitConfig& cfg, int chunks, const ChunkCallbacks& callbacks = {},
                           MeshPatterns patterns = {});

// The chunks' results (in stream order) as one run of `cfg`: every counter summed (cycles too),
// maxima of maxima, error sums weighted by their counts, the timelines concatenated
// (Timeline::concatenate), chunk_cycles the chunks' cycles.
SimResult merge_chunks(std::span<const SimResult> parts, const UnitConfig& cfg);

// By how many cycles the run of the chunk after a boundary can differ from the same triangles'
// stretch of a single run (from the acceptance of the last vertex before the boundary to that of
// the chunk's last vertex): `longer` because the chunk starts from an empty unit that the single
// run had already begun to fill with it, `shorter` because the single run's geometry engine was
// still busy with the last vertex before the boundary. docs/statistics.md ("Chunked runs")
// derives both; they hold for a geometry engine that never stalls at random. With random stalls
// the chunks draw other stalls than the single run, and the figures bound the expectation only.
// `uniform_factors`: every patch has the same factor (else the CPG can be further ahead).
struct ChunkBoundaryBound {
  std::uint64_t longer = 0;
  std::uint64_t shorter = 0;
};
ChunkBoundaryBound chunk_boundary_bound(const UnitConfig& cfg, bool uniform_factors);

}  // namespace tessim::sim
