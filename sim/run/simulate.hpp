// Whole-mesh runs of the cycle model: triangles streamed one by one from the mesh into the
// Unit, the Gpe consuming its vertices, results handed out vertex by vertex or patch by patch
// (sim/run/hooks.hpp). The reports built on a run's statistics (stats JSON, summary) are in
// sim/report/report.hpp.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/mesh.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/ge_cost.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/run/hooks.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/run/testbench.hpp"
#include "sim/run/workload.hpp"
#include "sim/system/system.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/host.hpp"
#include "sim/values/timeline.hpp"

namespace tessim::sim {

// The unit's output against the float64 reference (sim/run/reference_check.hpp): end to end against
// the mesh as given, and the arithmetic alone against the derived bound.
struct SimErrors {
  ErrorStats mesh;
  ArithmeticErrors arithmetic;
};

// A system of several units (cfg.units > 1, sim/system/system.hpp): its own counts, each unit's and
// each GE port's. SimResult::unit then sums the units (its cycles are unit-cycles, M per system
// cycle) and SimResult::gpe the ports (P per system cycle); system_cycles() is the run's length.
struct SystemResult {
  SystemStats stats;
  std::vector<UnitCounters> units;
  std::vector<GpeStats> ports;
};

struct SimResult {
  std::string mesh;              // source of the mesh
  UnitConfig config;
  // The geometry engine's cycles per vertex by part (K; evaluation gpe; --displace), and the
  // displacement it applied to every output vertex.
  GeVertexCost ge;
  DisplaceSettings displace;
  std::uint64_t triangles = 0;   // input triangles of the mesh
  int cpg_cycles = 0;            // C of the configuration (doc §5)
  std::uint64_t cpg_tag_cycles = 0;  // CPG cycles scalar tags added over the run (cpg_tags)
  UnitCounters unit;
  GpeStats gpe;
  // The cycles the geometry engine needs after the run's last acceptance to finish the vertices
  // it took (a fixed K's rest; a shader core's FIFO and last wave); not part of run_cycles().
  std::uint64_t gpe_drain_cycles = 0;
  GeCoreStats ge_core;  // a shader-core geometry engine's counters (config ge_core())
  // The cycles after the GPE's first vertex in which it waited for the next one (ready, VTX
  // FIFO empty: its classes starved and cpg), and the TE's classes over the late vertex
  // intervals: the cycles after one accepted vertex up to and including the next acceptance,
  // counted when the GPE waited in them (docs/statistics.md, the limit line).
  std::uint64_t gpe_waited = 0;
  ClassCounts<TeClass> te_late;
  std::uint64_t degenerate_patches = 0;  // patches with the divide-by-zero flag
  std::uint64_t zero_normals = 0;        // output vertices whose normal vanished
  double wall_seconds = 0.0;
  HostScaling scaling;
  std::optional<SimErrors> errors;       // with SimHooks::measure_errors
  WorkloadFactors factors;               // the factors of the run's patches
  Timeline timeline;                     // the classes over time, in buckets of cycles
  // A chunked run (sim/run/chunked.hpp): the cycles of each chunk; empty for one run of the stream.
  std::vector<std::uint64_t> chunk_cycles;
  std::optional<SystemResult> system;    // a system of units (cfg.units > 1)

  // Cycles of the run: the unit's, or the system's.
  std::uint64_t run_cycles() const { return system ? system->stats.cycles : unit.cycles; }
};

// Runs every triangle of `mesh` through the unit with a uniform factor cfg.tess_factor until
// the GPE has accepted the last vertex. cfg must have passed validate(). Throws InputError for
// a mesh the host cannot convert (check_convertible) or when a patch saturates (the widths
// cannot hold the mesh). A vertex beyond the arithmetic error bound is reported in
// SimResult::errors, not thrown: it is a finding about the widths, not bad input.
// `patterns`: one uniform factor per triangle of the mesh, or the D3D11 pattern with fixed or
// adaptive factors (model/factors.hpp); empty: cfg.tess_factor for every triangle.
// `on_patch` behind the geometry engine's displacement: every point of a patch displaced in float
// (model/displace.hpp) from the unit's output converted back into the mesh's coordinates; a vertex
// whose normal vanished keeps its point.
std::function<void(const PatchOut&)> displaced(std::function<void(const PatchOut&)> on_patch,
                                               const DisplaceSettings& displace);

SimResult simulate(const Mesh& mesh, const UnitConfig& cfg, const SimHooks& hooks = {},
                   MeshPatterns patterns = {});
// The same for the triangles [first, end) of the mesh alone, on a unit fresh from reset (a chunk
// of a chunked run): ids and factors stay those of the whole mesh, the scaling is the mesh's, so
// every vertex is the one simulate() makes of that triangle. SimResult::triangles = end - first.
SimResult simulate_range(const Mesh& mesh, const UnitConfig& cfg, std::uint64_t first, std::uint64_t end,
                         const SimHooks& hooks = {}, MeshPatterns patterns = {});

}  // namespace tessim::sim
