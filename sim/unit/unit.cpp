// The top of the cycle model, rtl/tess_unit.sv: the blocks of sim/blocks/ wired together. A
// cycle first takes every decision from the registered state and the inputs, then commits the
// clock edge block by block (docs/microarchitecture.md §2).
#include "sim/unit/unit.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "model/pattern.hpp"

namespace tessim::sim {

namespace {

// The input stream carries L in 7 bits, 1..64, D3D11 factors in their partitioning's range and
// alpha rounded to alpha_bits (sim/values/cpg.hpp, tri_pattern_problem, tri_alpha_problem);
// anything else is a caller bug.
[[noreturn, gnu::cold, gnu::noinline]] void throw_bad_factor(const TriangleFx& tri, const NumberFormat& fmt) {
  const int bary_bits = fmt.bary_bits;
  std::string msg = "Unit: triangle ";
  msg += std::to_string(tri.id);
  msg += ": ";
  std::string problem = tri_alpha_problem(tri, fmt);
  if (problem.empty()) problem = tri_pattern_problem(tri);
  msg += problem.empty() ? "a D3D11 pattern needs bary_bits >= 16 (its points are 16.16), not " + std::to_string(bary_bits)
                         : problem;
  throw std::invalid_argument(msg);
}

const HardwareConfig& checked(const HardwareConfig& cfg, NormalMode normals) {
  if (!hardware_supports(normals)) throw std::invalid_argument("Unit: normal mode not implemented by the unit");
  if (cfg.int_blocks < 1 || cfg.int_latency < 1 || cfg.te_contexts < 1 || cfg.tri_fifo_depth < 1 ||
      cfg.vtx_fifo_depth < 1 || cfg.te_contexts > 255)
    throw std::invalid_argument("Unit: configuration not validated");
  return cfg;
}

// Dedicated: accept, C - 1 compute cycles, write (doc §5). GPE mapping: the counter is loaded
// with C so that the CPG consumes exactly C spare GPE cycles per triangle.
int cpg_counter_load(const HardwareConfig& cfg, NormalMode normals, int cpg_gpe_cycles) {
  return cfg.cpg_mapping == CpgMapping::Gpe ? cpg_gpe_cycles : cpg_cycles(normals, cfg.format, cfg.cpg);
}

}  // namespace

Unit::Unit(const HardwareConfig& cfg, NormalMode normals, int cpg_gpe_cycles)
    : hw_(checked(cfg, normals)),
      tri_fifo_(cfg.tri_fifo_depth),
      cpg_(cfg.cpg.copies, normals, cfg.format, cpg_counter_load(cfg, normals, cpg_gpe_cycles),
           cfg.cpg_mapping == CpgMapping::Gpe, cfg.cpg_tags != 0, cfg.cpg),
      buffers_(cfg.cp_buffers),
      te_(cfg.int_blocks, cfg.int_latency, cfg.te_contexts, normals, cfg.format),
      vtx_fifo_(cfg.vtx_fifo_depth),
      counters_(cfg.int_blocks) {
  reset();
}

void Unit::reset() {
  tri_fifo_.reset();
  cpg_.reset();
  buffers_.reset();
  te_.reset();
  vtx_fifo_.reset();
  counters_.reset();
  act_ = CycleActivity{};
}

bool Unit::idle() const {
  return tri_fifo_.empty() && !cpg_.busy() && buffers_.empty() && te_.contexts_in_use() == 0 && vtx_fifo_.empty();
}

void Unit::check_factors(const TriangleFx& tri) const {
  if ((tri.pattern == TriPattern::uniform ? tri.L < 1 || tri.L > kMaxTessFactor
                                          : hw_.format.bary_bits < 16 || !tri_pattern_problem(tri).empty()) ||
      !alpha_in_contract(tri, hw_.format))
    throw_bad_factor(tri, hw_.format);
}

void Unit::inject(const TriangleFx& tri) {
  if (tri_fifo_.full()) throw std::logic_error("Unit: triangle injected into a full TRI FIFO");
  check_factors(tri);
  tri_fifo_.tail() = tri;
  tri_fifo_.commit(true, false);
  counters_.add_event(RunCounter::TrianglesIn);
}

void Unit::tick(const UnitInputs& in) {
  // ---- Every decision of the cycle, from the registered state and the inputs.
  const BoundaryCycle boundary = boundary_cycle(in, tri_fifo_.full(), vtx_fifo_.empty());
  const bool tri_push = boundary.tri_push, vtx_pop = boundary.vtx_pop;
  if (tri_push) check_factors(in.tri);
  const bool head_done = te_.head_done();
  const bool retire = head_done && !vtx_fifo_.full();
  const bool point_available = buffers_.rd_full();
  const bool allocate = te_.can_allocate(point_available);
  const CpgArray::Actions cpg = cpg_.decide(!tri_fifo_.empty(), buffers_.wr_empty(), in.cpg_step);
  const bool head_waiting = te_.head_waiting();
  const int issued = te_.schedule();  // from the ready masks as registered

  // ---- Statistics of the cycle, from the same registered state.
  const TeClass te = te_.classify(issued, head_waiting, head_done, vtx_fifo_.full(), point_available,
                                  cpg_.busy() || !tri_fifo_.empty());
  const CpgClass cpg_class = cpg_.classify(cpg);
  act_.cycle = counters_.cycles();
  counters_.count(issued, te, cpg_class, boundary.events);
  act_.ops_issued = issued;
  act_.te = te;
  act_.cpg = cpg_class;
  act_.cpg_action = cpg_.summary(cpg);
  act_.cpg_triangle = cpg_.summary_triangle(cpg, tri_fifo_.front().id);
  act_.tri_pushed = tri_push;
  act_.vtx_popped = vtx_pop;
  act_.allocated = allocate;
  if (allocate) act_.allocated_patch = buffers_.rd().id;
  act_.retired = retire;

  // ---- The clock edge: each block's registers from the decisions above. Pushes write the
  // FIFOs' tail slots of the start of the cycle, so a simultaneous pop cannot collide.
  te_.commit(retire ? &vtx_fifo_.tail() : nullptr, allocate, buffers_, &act_.retired_vertex, &act_.allocated_vertex);
  vtx_fifo_.commit(retire, vtx_pop);
  const bool tri_pop = cpg_.accepts(cpg);  // before the commit moves the accept pointer
  cpg_.commit(cpg, tri_fifo_.front(), buffers_);
  if (tri_push) tri_fifo_.tail() = in.tri;
  tri_fifo_.commit(tri_push, tri_pop);
}

std::uint64_t Unit::quiet_cycles(const UnitInputs& in) const {
  if (in.tri_valid && !tri_fifo_.full()) return 0;  // push
  if (in.vtx_ready && !vtx_fifo_.empty()) return 0;  // pop
  if (te_.head_done() && !vtx_fifo_.full()) return 0;  // retirement
  if (te_.can_allocate(buffers_.rd_full())) return 0;  // allocation
  return cpg_.repeats(cpg_.decide(!tri_fifo_.empty(), buffers_.wr_empty(), in.cpg_step));
}

std::uint64_t Unit::skip(std::uint64_t n, const UnitInputs& in, std::uint64_t issuing_limit) {
  if (n == 0) return 0;
  // The decisions of tick() outside the TE, which quiet_cycles() guarantees are the same in each
  // of the n cycles.
  const bool point_available = buffers_.rd_full();
  const bool vtx_full = vtx_fifo_.full();
  const bool upstream_busy = cpg_.busy() || !tri_fifo_.empty();
  const CpgArray::Actions cpg = cpg_.decide(!tri_fifo_.empty(), buffers_.wr_empty(), in.cpg_step);
  const CpgClass cpg_class = cpg_.classify(cpg);
  // The boundary pushes and pops nothing in a quiet stretch: a triangle offered is refused in each
  // of its cycles (the TRI FIFO is full).
  const RunEvents events = boundary_cycle(in, tri_fifo_.full(), vtx_fifo_.empty()).events;
  int issued = 0;
  TeClass te = TeClass::Idle;
  if (te_.quiet()) {
    // Nothing issues or completes: n identical cycles at once.
    const bool head_done = te_.head_done();
    const bool head_waiting = te_.head_waiting();
    issued = te_.schedule();  // issues nothing
    te = te_.classify(issued, head_waiting, head_done, vtx_full, point_available, upstream_busy);
    counters_.count(0, te, cpg_class, events, n);
    te_.skip(n);
  } else {
    // The TE issues and completes ops, cycle by cycle, and nothing else moves; the stretch ends
    // early where the head context finishes with room in the VTX FIFO (a retirement) or the TE
    // falls quiet (the rest is taken at once by the next call).
    n = std::min(n, issuing_limit);
    std::uint64_t cycles = 0;
    while (cycles < n && !(cycles > 0 && te_.quiet())) {
      const bool head_done = te_.head_done();
      if (head_done && !vtx_full) break;
      const bool head_waiting = te_.head_waiting();
      issued = te_.schedule();
      te = te_.classify(issued, head_waiting, head_done, vtx_full, point_available, upstream_busy);
      counters_.count(issued, te, cpg_class, events);
      te_.advance();
      ++cycles;
    }
    n = cycles;
    if (n == 0) return 0;
  }
  act_.cycle = counters_.cycles() - 1;
  act_.ops_issued = issued;
  act_.tri_pushed = act_.vtx_popped = act_.allocated = act_.retired = false;
  act_.te = te;
  act_.cpg = cpg_class;
  act_.cpg_action = cpg_.summary(cpg);
  act_.cpg_triangle = cpg_.summary_triangle(cpg, 0);  // a quiet stretch never accepts
  cpg_.commit_repeated(cpg, n);
  return n;
}

}  // namespace tessim::sim
