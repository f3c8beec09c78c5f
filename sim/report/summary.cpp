#include "sim/report/report.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include "model/base/error.hpp"  // printable_text: a file name as error messages show it
#include "model/pattern.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/run/chunked.hpp"

namespace tessim::sim {

namespace {

double ratio(std::uint64_t a, std::uint64_t b) { return b == 0 ? 0.0 : static_cast<double>(a) / b; }

std::string percent(std::uint64_t part, std::uint64_t whole) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * ratio(part, whole));
  return buf;
}

// The summary's line of a block's classes: each class as a share of `cycles`.
template <class Class>
std::string classes_line(const ClassCounts<Class>& counts, std::uint64_t cycles) {
  const CounterBlockInfo& block = block_info(CounterEnum<Class>::block);
  char label[16];
  std::snprintf(label, sizeof label, "%-9s", block.label);
  std::string s = label;
  for (Class c : all_of<Class>())
    s += std::string(c == Class{} ? "" : "  ") + to_string(c) + " " + percent(counts[c], cycles);
  return s + "\n";
}

}  // namespace

std::string summary(const SimResult& r) {
  const UnitConfig& c = r.config;
  const UnitCounters& u = r.unit;
  const std::uint64_t n = u.cycles;
  std::ostringstream s;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "unit     N=%d INT (latency %d), V=%d contexts, FIFOs tri %d / vtx %d, %d CP buffers, Q%d.%d (W=%d) "
                "B=%d, CPG %s: %d cycles/triangle",
                c.int_blocks, c.int_latency, c.te_contexts, c.tri_fifo_depth, c.vtx_fifo_depth, c.cp_buffers,
                c.format.coord_int_bits, c.format.coord_frac_bits, c.format.coord_width(), c.format.bary_bits,
                to_string(c.cpg_mapping).c_str(), r.cpg_cycles);
  if (c.evaluation == Evaluation::Gpe) {
    // No TE and no INT blocks: the head of the line says so instead of N, Λ and V.
    std::snprintf(buf, sizeof buf,
                  "unit     evaluation on the geometry engine (no TE, no INT blocks; the TE line counts the DPG), "
                  "FIFOs tri %d / vtx %d, %d CP buffers, Q%d.%d (W=%d) B=%d, CPG %s: %d cycles/triangle",
                  c.tri_fifo_depth, c.vtx_fifo_depth, c.cp_buffers, c.format.coord_int_bits, c.format.coord_frac_bits,
                  c.format.coord_width(), c.format.bary_bits, to_string(c.cpg_mapping).c_str(), r.cpg_cycles);
  }
  s << buf;
  if (c.cpg.copies > 1) s << " on each of " << c.cpg.copies << " copies";
  if (c.cpg_tags)
    s << " + scalar tags (" << r.cpg_tag_cycles << " cycles over the run, "
      << ratio(r.cpg_tag_cycles, r.triangles) << " per triangle)";
  s << "\n";
  std::string factors;
  if (!r.factors.pattern.empty()) {
    const int lo = r.factors.patches_with_vertices.empty() ? 0 : r.factors.patches_with_vertices.begin()->first;
    const int hi = r.factors.patches_with_vertices.empty() ? 0 : r.factors.patches_with_vertices.rbegin()->first;
    std::snprintf(buf, sizeof buf, "D3D11 pattern %s, %d..%d vertices/patch (%.1f on average)",
                  r.factors.pattern.c_str(), lo, hi, ratio(r.factors.vertices, r.triangles - r.factors.culled));
    if (r.factors.culled) std::snprintf(buf + std::strlen(buf), sizeof buf - std::strlen(buf), ", %llu culled",
                                        static_cast<unsigned long long>(r.factors.culled));
  } else if (r.factors.uniform) {
    const int L = r.triangles ? static_cast<int>(std::find_if(r.factors.patches_with_factor.begin() + 1,
                                                              r.factors.patches_with_factor.end(),
                                                              [](std::uint64_t n) { return n > 0; }) -
                                                 r.factors.patches_with_factor.begin())
                              : c.tess_factor;
    std::snprintf(buf, sizeof buf, "L=%d (%d vertices/patch)", L, pattern_vertex_count(L));
  } else {
    int lo = 0, hi = 0;
    for (int L = 1; L <= kMaxTessFactor; ++L)
      if (r.factors.patches_with_factor[static_cast<std::size_t>(L)]) {
        if (!lo) lo = L;
        hi = L;
      }
    std::snprintf(buf, sizeof buf, "L=%d..%d per patch (%.1f vertices/patch on average)", lo, hi,
                  ratio(r.factors.vertices, r.triangles));
  }
  factors = buf;
  const std::string k_text = c.ge_core() ? "K derived (GE core)" : "K=" + std::to_string(c.gpe_cycles);
  std::snprintf(buf, sizeof buf, "workload %s: %llu triangles, %s, %s normals; GPE %s, stall %.2f, seed %llu\n",
                printable_text(r.mesh).c_str(), static_cast<unsigned long long>(r.triangles), factors.c_str(),
                std::string(to_string(c.normals)).c_str(), k_text.c_str(), c.gpe_stall_prob,
                static_cast<unsigned long long>(c.seed));
  s << buf;
  if (!c.ge_core() && r.ge.total() != r.ge.base) {
    std::snprintf(buf, sizeof buf, "GE       %d cycles/vertex: K=%d", r.ge.total(), r.ge.base);
    s << buf;
    if (r.ge.evaluation) s << " + " << r.ge.evaluation << " evaluating the patch (evaluation gpe)";
    if (r.ge.displacement) {
      std::snprintf(buf, sizeof buf, " + %d displacing (%s, amplitude %g, frequency %g)", r.ge.displacement,
                    to_string(r.displace.kind), r.displace.amplitude, r.displace.frequency);
      s << buf;
    }
    std::snprintf(buf, sizeof buf, " on %d ALU slots/cycle (docs/microarchitecture.md §12)\n", c.ge_alu_lanes);
    s << buf;
  }
  if (c.ge_core()) {
    // The GE as a shader core: its K is derived, and gpe_cycles is not used.
    const UnitConfig run = with_ge_cost(c, r.ge);
    std::snprintf(buf, sizeof buf,
                  "GE core  %d lanes x %d issue at %g MHz (unit %g MHz), %llu slots/vertex, %llu cycles/wave: "
                  "K = %.3f unit cycles/vertex; %llu waves, lanes %.1f %% used, FIFO %d (peak %llu)\n",
                  run.ge_core_lanes, run.ge_core_issue, run.ge_core_mhz, run.unit_mhz,
                  static_cast<unsigned long long>(core_program_slots(run)),
                  static_cast<unsigned long long>(core_wave_cycles(run)), core_cycles_per_vertex(run),
                  static_cast<unsigned long long>(r.ge_core.waves),
                  100 * ratio(r.ge_core.lanes_filled, r.ge_core.waves * static_cast<std::uint64_t>(run.ge_core_lanes)),
                  run.ge_core_fifo, static_cast<unsigned long long>(r.ge_core.fifo_peak));
    s << buf;
  }
  std::snprintf(buf, sizeof buf,
                "result   %llu cycles  %llu vertices  %.3f cycles/vertex  %.4f vertices/cycle\n",
                static_cast<unsigned long long>(r.run_cycles()), static_cast<unsigned long long>(u.vertices_out),
                cycles_per_vertex(r), throughput(r));
  s << buf;
  s << "limit    " << bottleneck(r) << "\n";
  if (r.system) {
    // Every line below sums the units (unit-cycles) and the ports (port-cycles).
    const SystemStats& st = r.system->stats;
    std::snprintf(buf, sizeof buf,
                  "system   %zu units (%s, batches of %d), %s reassembly buffer %d slots (at most %d taken), %zu GE "
                  "ports; the lines below sum the units and the ports\n",
                  r.system->units.size(), to_string(c.distribution).c_str(), c.dispatch_batch,
                  to_string(c.reassembly).c_str(), c.reorder_slots, st.max_occupancy, r.system->ports.size());
    s << buf;
    s << "units   ";
    for (std::size_t i = 0; i < r.system->units.size(); ++i)
      s << " " << i << ": " << st.unit_triangles[i] << " triangles " << st.unit_vertices[i] << " vertices;";
    s << "\n";
  }
  s << "INT      utilisation " << percent(static_cast<std::uint64_t>(int_utilisation(r) * 1e6), 1000000)
    << "  per block:";
  for (std::size_t i = 0; i < u.int_busy_used().size(); ++i) s << "  " << i << ":" << percent(u.int_busy[i], n);
  s << "\n";
  s << classes_line(u.te, n) << classes_line(u.cpg, n) << classes_line<GpeClass>(r.gpe, r.gpe.cycles);
  // The late intervals: the TE's three stall classes that name a limit, busy, and the rest.
  const ClassCounts<TeClass>& w = r.te_late;
  const std::uint64_t gw = w.total();
  if (r.system) {
    // Late intervals are classified for one unit's TE; a system's waits are the ports' (limit line).
  } else if (gw == 0) {  // no late interval: a line of zeros would read as a measurement
    s << "late     GPE never waited for a vertex\n";
  } else {
    s << "late     GPE waited " << percent(r.gpe_waited, n) << " of cycles; TE in the late intervals:";
    std::uint64_t other = gw;
    for (TeClass c : {TeClass::ContextLimited, TeClass::IntLimited, TeClass::StarvedByCpg, TeClass::Busy}) {
      s << (c == TeClass::ContextLimited ? " " : "  ") << to_string(c) << " " << percent(w[c], gw);
      other -= w[c];
    }
    s << "  other " << percent(other, gw) << "\n";
  }
  if (r.errors) {
    const ErrorStats& m = r.errors->mesh;
    const ArithmeticErrors& a = r.errors->arithmetic;
    std::snprintf(buf, sizeof buf,
                  "errors   vs the mesh's float reference: position max %.3g rms %.3g of the diagonal, normal max "
                  "%.3g rms %.3g rad\n         arithmetic alone: position max %.3g of the diagonal, normal max %.3g "
                  "rad, %llu vertices beyond the derived bound\n",
                  m.position_max, m.position_rms, m.normal_angle_max, m.normal_angle_rms, a.stats.position_max,
                  a.stats.normal_angle_max, static_cast<unsigned long long>(a.beyond_bound));
    s << buf;
    if (a.beyond_bound) s << "         first beyond the bound: " << a.worst << "\n";
  }
  if (!r.chunk_cycles.empty()) {
    const ChunkBoundaryBound b = chunk_boundary_bound(c, r.factors.uniform);
    const std::uint64_t boundaries = r.chunk_cycles.size() - 1;
    std::snprintf(buf, sizeof buf,
                  "chunks   %zu chunks in parallel, each from reset: cycles are their sum; a single run: %llu..%llu "
                  "cycles (%llu longer .. %llu shorter per boundary%s)\n",
                  r.chunk_cycles.size(), static_cast<unsigned long long>(n - std::min(n, boundaries * b.longer)),
                  static_cast<unsigned long long>(n + boundaries * b.shorter), static_cast<unsigned long long>(b.longer),
                  static_cast<unsigned long long>(b.shorter), c.gpe_stall_prob > 0 ? ", on average: random stalls" : "");
    s << buf;
  }
  if (r.degenerate_patches > 0 || r.zero_normals > 0)
    s << "warning  " << r.degenerate_patches << " patches hit a zero divisor (zero-length edge or "
      << "vanishing mid-edge normal), " << r.zero_normals << " output normals vanished\n";
  return s.str();
}

}  // namespace tessim::sim
