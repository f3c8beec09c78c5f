// Whole-mesh runs of the cycle model: triangles streamed one by one from the mesh into the
// Unit, the Gpe consuming its vertices, results handed out vertex by vertex or patch by patch,
// and the reports built on the statistics (stats JSON, human summary).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "model/mesh.hpp"
#include "sim/config.hpp"
#include "sim/gpe.hpp"
#include "sim/host.hpp"
#include "sim/reference_check.hpp"
#include "sim/testbench.hpp"
#include "sim/timeline.hpp"
#include "sim/unit.hpp"

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

// The unit's output against the float64 reference (sim/reference_check.hpp): end to end against
// the mesh as given, and the arithmetic alone against the derived bound.
struct SimErrors {
  ErrorStats mesh;
  ArithmeticErrors arithmetic;
};

// The per-patch load of a run: the factors of its patches and the vertices they make.
struct WorkloadFactors {
  bool uniform = true;  // every patch has the configuration's factor (uniform pattern)
  std::array<std::uint64_t, kMaxTessFactor + 1> patches_with_factor{};  // uniform pattern: index L
  std::map<int, std::uint64_t> patches_with_vertices;  // vertices per patch -> patches
  std::uint64_t vertices = 0;
  std::uint64_t culled = 0;  // D3D11 patches their factors cull: never sent to the unit
  std::string pattern;       // D3D11: the settings (TessSettings::describe); empty: uniform
};

struct SimResult {
  std::string mesh;              // source of the mesh
  UnitConfig config;
  std::uint64_t triangles = 0;   // input triangles of the mesh
  int cpg_cycles = 0;            // C of the configuration (doc §5)
  std::uint64_t cpg_tag_cycles = 0;  // CPG cycles scalar tags added over the run (cpg_tags)
  UnitCounters unit;
  GpeStats gpe;
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
  // A chunked run (sim/chunked.hpp): the cycles of each chunk; empty for one run of the stream.
  std::vector<std::uint64_t> chunk_cycles;
};

// Runs every triangle of `mesh` through the unit with a uniform factor cfg.tess_factor until
// the GPE has accepted the last vertex. cfg must have passed validate(). Throws InputError for
// a mesh the host cannot convert (check_convertible) or when a patch saturates (the widths
// cannot hold the mesh). A vertex beyond the arithmetic error bound is reported in
// SimResult::errors, not thrown: it is a finding about the widths, not bad input.
// `patterns`: one uniform factor per triangle of the mesh, or the D3D11 pattern with fixed or
// adaptive factors (model/factors.hpp); empty: cfg.tess_factor for every triangle.
SimResult simulate(const Mesh& mesh, const UnitConfig& cfg, const SimHooks& hooks = {},
                   MeshPatterns patterns = {});
// The same for the triangles [first, end) of the mesh alone, on a unit fresh from reset (a chunk
// of a chunked run): ids and factors stay those of the whole mesh, the scaling is the mesh's, so
// every vertex is the one simulate() makes of that triangle. SimResult::triangles = end - first.
SimResult simulate_range(const Mesh& mesh, const UnitConfig& cfg, std::uint64_t first, std::uint64_t end,
                         const SimHooks& hooks = {}, MeshPatterns patterns = {});

// Figures derived from the statistics (docs/microarchitecture.md §10).
double throughput(const SimResult& r);         // vertices per cycle
double cycles_per_vertex(const SimResult& r);
double int_utilisation(const SimResult& r);    // sum of INT busy / (N cycles)

// Which block limits the run, as one line with the figure that shows it.
std::string bottleneck(const SimResult& r);

nlohmann::json stats_json(const SimResult& r);

// The statistics JSON's format: its version (raised when a key changes meaning or goes away),
// and the unit of every number in it by path, array elements as "[]" ("int.blocks[].busy").
// stats_json() carries both, and `tessim schema` lists the units (docs/statistics.md).
inline constexpr int kStatsSchemaVersion = 3;
nlohmann::json stats_units();
std::string summary(const SimResult& r);       // one screen for a hardware architect

// Records the issue pattern of the first cycles and the retirement cycle of the first vertices:
// the input of `tessim sim --schedule` and docs/schedule.md.
class ScheduleRecorder : public CycleObserver {
 public:
  explicit ScheduleRecorder(int table_cycles = 48, std::size_t max_vertices = 8192);
  bool on_cycle(const Unit& unit, const GpeCycle& gpe) override;

  // Cycles per vertex between retirements over the last whole multiple of 2520 vertices within
  // the second half of the recorded vertices (so any schedule period of up to 10 vertices
  // averages exactly); 0 when fewer than 16 vertices retired.
  double steady_cycles_per_vertex() const;
  // The issue table: one row per cycle from the first issue, one column per INT block,
  // cells "v<vertex>.<op>", plus allocation and retirement of the cycle.
  std::string table(int int_blocks) const;

 private:
  struct Row {
    std::uint64_t cycle;
    std::vector<IssuedOp> ops;
    bool allocated, retired;
    std::uint64_t allocated_vertex, retired_vertex;
    TeClass te;
  };
  int table_cycles_;
  std::size_t max_vertices_;
  std::vector<Row> rows_;
  std::vector<std::uint64_t> retire_cycles_;
};

}  // namespace tessim::sim
