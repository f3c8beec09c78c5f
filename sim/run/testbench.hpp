// The unit's environment, shared by every loop that drives a unit (tessim sim, the
// co-simulation, `tessim rtlbench`, the microbenchmark): a source of triangles offered in order
// on tri_valid/tri, and the geometry engine on vtx_ready/cpg_step. One cycle is
//     const UnitInputs& in = tb.inputs(dut);   // from the DUT's outputs (registered state)
//     dut.tick(in);                             // the clock edge
// for any DUT with tri_ready(), vtx_valid() and cpg_computing() (sim::Unit, rtl::RtlUnit).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "model/mesh.hpp"
#include "model/pattern.hpp"
#include "sim/ge/gpe.hpp"
#include "sim/unit/unit.hpp"
#include "sim/values/host.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// A source offers available() / front() / pop() and counts the vertices its triangles make.
class VectorSource {
 public:
  explicit VectorSource(const std::vector<TriangleFx>& stream) : stream_(stream) {}
  void rewind() { next_ = 0; }
  bool available() const { return next_ < stream_.size(); }
  const TriangleFx& front() const { return stream_[next_]; }
  void pop() { ++next_; }
  std::uint64_t vertices() const {
    std::uint64_t n = 0;
    for (const TriangleFx& t : stream_) n += static_cast<std::uint64_t>(patch_vertex_count(t));
    return n;
  }

 private:
  const std::vector<TriangleFx>& stream_;
  std::size_t next_ = 0;
};

// The triangles of a mesh, scaled and quantized one at a time as they are offered (streaming:
// nothing per triangle is held but its factor), each with its pattern (MeshPatterns). A range
// [first, end) of the mesh's triangles streams only those (a chunk of a chunked run); their ids
// stay their indices in the mesh. A patch its D3D11 factors cull is not offered.
class MeshSource {
 public:
  // `with_tags`: the mesh's scalar tags go along (a CPG that takes them, cpg_tags).
  MeshSource(const Mesh& mesh, const HostScaling& scaling, const NumberFormat& format, int L,
             MeshPatterns patterns = {}, bool with_tags = false, std::size_t first = 0,
             std::size_t end = SIZE_MAX)
      : mesh_(mesh), scaling_(scaling), format_(format), L_(L), patterns_(patterns), with_tags_(with_tags),
        first_(first), end_(std::min(end, mesh.triangle_count())) {
    rewind();
  }
  int factor(std::size_t t) const { return patterns_.factors.empty() ? L_ : patterns_.factors[t]; }
  const MeshPatterns& patterns() const { return patterns_; }
  std::size_t first() const { return first_; }
  std::size_t end() const { return end_; }
  // Triangle t as the unit receives it; std::nullopt when its factors cull it.
  std::optional<TriangleFx> triangle(std::size_t t) const {
    if (patterns_.d3d11) {
      std::optional<TriangleFx> tri = to_fixed(mesh_, t, scaling_, format_, *patterns_.d3d11, with_tags_);
      if (tri) *tri = with_alpha(*tri, patterns_, t, format_);
      return tri;
    }
    return with_alpha(to_fixed(mesh_, t, scaling_, format_, factor(t), with_tags_), patterns_, t, format_);
  }
  // Points of triangle t's pattern (0: culled), from its factors alone.
  int patch_points(std::size_t t) const {
    if (!patterns_.d3d11) return pattern_vertex_count(factor(t));
    const PatchFactors f = patch_factors(*patterns_.d3d11, mesh_, t);
    const D3D11Factors processed = d3d11_host_factors(f.outer, f.inner, patterns_.d3d11->partitioning);
    return processed.culled ? 0 : d3d11_setup(processed).point_count;
  }
  void rewind() {
    next_ = first_;
    load();
  }
  bool available() const { return next_ < end_; }
  const TriangleFx& front() const { return current_; }
  void pop() {
    ++next_;
    load();
  }
  std::uint64_t vertices() const {
    if (first_ >= end_) return 0;
    if (!patterns_.per_patch()) return (end_ - first_) * static_cast<std::uint64_t>(pattern_vertex_count(L_));
    std::uint64_t n = 0;
    for (std::size_t t = first_; t < end_; ++t) n += static_cast<std::uint64_t>(patch_points(t));
    return n;
  }

 private:
  // The triangle at next_, or the first one after it that is not culled.
  void load() {
    for (; next_ < end_; ++next_) {
      if (std::optional<TriangleFx> tri = triangle(next_)) {
        current_ = *tri;
        return;
      }
    }
  }

  const Mesh& mesh_;
  HostScaling scaling_;
  NumberFormat format_;
  int L_;
  MeshPatterns patterns_;
  bool with_tags_ = false;
  std::size_t first_ = 0, end_ = 0;
  std::size_t next_ = 0;
  TriangleFx current_;
};

template <class Source>
class BasicTestbench {
 public:
  BasicTestbench(Source source, const EnvironmentConfig& env) : source_(std::move(source)), gpe_(env) {
    expected_ = source_.vertices();
    load();
  }

  // Back to the start of the source with a fresh geometry engine (a reset of the DUT).
  void reset() {
    gpe_.reset();
    source_.rewind();
    pushed_ = false;
    taken_ = 0;
    accepted_ = 0;
    load();
  }

  // The inputs of the cycle. The GPE steps on the DUT's outputs; a triangle offered while the
  // DUT is ready is taken at this cycle's edge, and the next one is offered from the next cycle.
  template <class Dut>
  const UnitInputs& inputs(const Dut& dut) {
    if (pushed_) {
      source_.pop();
      load();
    }
    cycle_ = gpe_.tick(dut.vtx_valid(), dut.cpg_computing());
    in_.vtx_ready = cycle_.ready;
    in_.cpg_step = cycle_.spare;
    pushed_ = in_.tri_valid && dut.tri_ready();
    if (pushed_) ++taken_;
    if (cycle_.accepted) ++accepted_;
    return in_;
  }

  // Fast-forward (docs/microarchitecture.md §11): in place of up to `limit` inputs()/tick()
  // pairs, the cycles from now in which the GPE presents the same values and no data moves
  // between the DUT's blocks, taken at once (at most `issuing_limit` while the TE issues ops).
  // Returns how many (0: the next cycle moves data; call inputs() and tick() as usual).
  // Only for sim::Unit: the Verilated RTL has to be clocked cycle by cycle.
  std::uint64_t fast_forward(Unit& unit, std::uint64_t limit, std::uint64_t issuing_limit = Unit::kForever) {
    if (pushed_ || limit == 0) return 0;  // inputs() has a triangle to hand over first
    const bool vtx_valid = unit.vtx_valid();
    std::uint64_t n = gpe_.quiet_cycles(vtx_valid);
    if (n == 0) return 0;
    // The inputs held over the stretch (tri_valid and tri as offered; inputs() sets the others
    // again before any tick()).
    const bool ready = gpe_.ready_now();
    in_.vtx_ready = ready;
    in_.cpg_step = ready && !vtx_valid;
    n = std::min({n, unit.quiet_cycles(in_), limit});
    if (n == 0) return 0;
    const bool cpg_computing = unit.cpg_computing();  // holds over the stretch: the countdown bounds it
    n = unit.skip(n, in_, issuing_limit);
    if (n == 0) return 0;
    cycle_ = gpe_.skip(n, vtx_valid, cpg_computing);
    in_.vtx_ready = cycle_.ready;
    in_.cpg_step = cycle_.spare;
    return n;
  }

  const GpeCycle& gpe_cycle() const { return cycle_; }  // of the last inputs() or fast_forward()
  bool pushed() const { return pushed_; }               // the last inputs() handed over a triangle
  const Gpe& gpe() const { return gpe_; }
  std::size_t triangles_taken() const { return taken_; }  // triangles the DUT took since reset
  std::uint64_t accepted() const { return accepted_; }    // vertices the GPE took since reset
  std::uint64_t expected() const { return expected_; }    // vertices of the whole source
  bool done() const { return accepted_ >= expected_; }

 private:
  void load() {
    in_.tri_valid = source_.available();
    if (in_.tri_valid) in_.tri = source_.front();
  }

  Source source_;
  Gpe gpe_;
  UnitInputs in_;
  GpeCycle cycle_;
  bool pushed_ = false;
  std::size_t taken_ = 0;
  std::uint64_t accepted_ = 0;
  std::uint64_t expected_ = 0;
};

// A stream held in memory (co-simulation, benchmarks).
class Testbench : public BasicTestbench<VectorSource> {
 public:
  Testbench(const std::vector<TriangleFx>& stream, const EnvironmentConfig& env)
      : BasicTestbench<VectorSource>(VectorSource(stream), env) {}
};

}  // namespace tessim::sim
