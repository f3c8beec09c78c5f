// Lock-step co-simulation of the cycle model (sim::Unit) and the Verilated RTL
// (rtl::RtlUnit): the same triangle stream and the same seeded geometry-engine backpressure
// drive both; every cycle their outputs are compared bit for bit, and every vertex the GPE
// accepts is checked against the float reference. The first divergence stops the run; the
// failing run is then replayed from reset with the RTL's waveform recording the window before
// it, so passing runs pay nothing for waves; an explicit window of cycles is recorded in the run
// itself, passing or failing (docs/verification.md).
#pragma once

#include <atomic>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cosim/coverage.hpp"
#include "cosim/wave.hpp"
#include "sim/config/config.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/run/reference_check.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::cosim {

// Mid-stream resets at cycles drawn from the run's seed: `count` resets, the i-th due at a cycle
// drawn uniformly from the `span` cycles after the previous one and fired at the first cycle from
// then on at which its target state holds — in turn any cycle, the DPG inside an inner ring of a
// D3D11 patch (a large pattern half walked), the CPG mid-triangle. A target that does not come
// within 8 `span` more cycles (a stream without D3D11 patches; a CPG blocked behind a large patch)
// gives way to any cycle. The report
// counts where the resets landed (CosimReport::resets), so a test can require each kind.
struct RandomResets {
  int count = 0;
  std::uint64_t span = 2000;
};

struct CosimOptions {
  sim::UnitConfig unit;            // the configuration of both implementations
  std::string variant;             // RTL build to run ("n2", "n2_verif", ...: rtl_variants())
  std::uint64_t seed = 1;          // GPE backpressure and the RTL's X randomisation
  int history = 8;                 // transactions printed before a divergence
  int wave_window = 200;           // cycles of waveform before the divergence
  std::filesystem::path wave;      // .fst or .vcd written on divergence (empty: none), .gtkw beside it
  std::optional<WaveWindow> wave_cycles;  // instead: these cycles, recorded in the run itself
  std::vector<std::uint64_t> reset_at;  // cycles at which both are reset mid-stream
  RandomResets random_resets;           // and at random cycles in chosen states (above)
  std::uint64_t hang_cycles = 100000;   // cycles without any transfer that count as a hang
  bool check_reference = true;     // compare each vertex with the float reference
  FunctionalCoverage* coverage = nullptr;  // sampled every cycle when set (cosim/coverage.hpp)
  std::atomic<std::uint64_t>* vertices_done = nullptr;  // +1 per vertex accepted (progress meter)
};

struct Divergence {
  std::uint64_t cycle = 0;
  std::string field;               // e.g. "vtx_pos[1]", "tri_ready", "counters.te_busy"
  std::string expected;            // cycle model
  std::string actual;              // RTL
  std::uint32_t triangle = 0;      // patch id of the vertex concerned (or the last accepted)
  std::vector<std::string> recent;  // the last transactions before it, oldest first
};

// Where the mid-stream resets landed, from the cycle model's state in the cycle before each.
struct ResetTally {
  std::uint64_t total = 0;
  std::uint64_t dpg_d3d11 = 0;        // the DPG part-way through a D3D11 patch
  std::uint64_t dpg_inner_ring = 0;   // ... past its outer ring (the walk's ring register > 0)
  std::uint64_t cpg_compute = 0;      // the CPG mid-triangle (counting down)
};

struct CosimReport {
  bool passed = false;
  std::string variant;
  std::uint64_t seed = 0;
  std::uint64_t cycles = 0;
  std::uint64_t triangles = 0;
  std::uint64_t vertices = 0;
  std::optional<Divergence> divergence;
  bool counters_match = false;
  sim::UnitCounters model_counters;
  sim::UnitCounters rtl_counters;
  sim::GpeStats gpe;
  sim::ArithmeticErrors reference;  // every accepted vertex against the float reference
  std::filesystem::path wave;      // written waveform, if any
  bool hang = false;
  ResetTally resets;
};

// Runs the whole stream through both implementations. Throws InputError when the RTL variant
// does not implement opts.unit (widths, N, latency, contexts, FIFO depths, CPG mapping).
CosimReport run_cosim(const std::vector<sim::TriangleFx>& stream, const CosimOptions& opts);
// The same, stopping before cycle `stop_before` (compares cycles 0 .. stop_before - 1).
CosimReport run_cosim_until(const std::vector<sim::TriangleFx>& stream, const CosimOptions& opts,
                            std::uint64_t stop_before);

// One screen for a person: configuration, seed, outcome, counters, errors, divergence.
std::string format_report(const CosimReport& r, const CosimOptions& opts);

// A random triangle stream for verification: positions in [-0.9, 0.9]^3, normals near the
// face normal, factors 1..max_L, and a share of degenerate triangles (repeated vertices,
// collinear points, opposite normals). `extent` scales the positions (clamped to the coordinate
// range): near 2^I the control points leave the range and the arithmetic saturates.
// `with_tags`: every corner also gets random scalar tags (neutral, θ only, or a crease with
// σ, θ and β, including σ = 0 and 1 and all three corners tagged), drawn from a generator of their
// own, so the geometry of a seed's stream is the same with and without them.
std::vector<sim::TriangleFx> random_triangles(std::size_t count, std::uint64_t seed,
                                              const sim::NumberFormat& fmt, int max_L,
                                              double degenerate_share = 0.1, double extent = 1.0,
                                              bool with_tags = false);

// Gives every triangle of the stream a D3D11 pattern with random factors (docs/patterns.md): each
// factor mostly in [0.5, max_factor], often within 2^-19..1 of an integer (the fractional
// partitionings' rounding boundaries), sometimes 1 or beyond the range (clamped); the inner
// factor 1 a quarter of the time. `partitioning`: the same for every triangle, or (none) one
// drawn per triangle. Drawn from a generator of its own: the geometry of a seed's stream stays.
void assign_random_patterns(std::vector<sim::TriangleFx>& stream, std::uint64_t seed, int max_factor,
                            std::optional<Partitioning> partitioning = std::nullopt);

// Gives every edge of the stream a random silhouette weight rounded to `alpha_bits` (1..16): a
// quarter each of the ends of the range that the blend's arithmetic treats specially, 0 and 1,
// of its smallest step 2^-A and of 1 - 2^-A or uniform values. Its own generator, like
// assign_random_patterns. Returns how many edges got 0, 1, 2^-A and 1 - 2^-A, in that order.
std::array<std::size_t, 4> assign_random_alpha(std::vector<sim::TriangleFx>& stream, std::uint64_t seed,
                                               int alpha_bits);

}  // namespace tessim::cosim
