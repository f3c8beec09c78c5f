#include "cosim/coverage.hpp"

#include <bit>
#include <sstream>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/pattern.hpp"
#include "sim/base/fixed.hpp"

namespace tessim::cosim {

namespace {

constexpr sim::CpgAction kCpgActions[] = {sim::CpgAction::Idle,    sim::CpgAction::Accept, sim::CpgAction::Compute,
                                          sim::CpgAction::WaitGpe, sim::CpgAction::Write,  sim::CpgAction::Blocked};

std::string group_of(const std::string& bin) { return bin.substr(0, bin.find('/')); }

}  // namespace

void FunctionalCoverage::declare(const sim::UnitConfig& cfg) {
  contexts_ = cfg.te_contexts;
  blocks_ = cfg.int_blocks;
  tri_depth_ = cfg.tri_fifo_depth;
  vtx_depth_ = cfg.vtx_fifo_depth;
  // Scheduler: contexts in flight 0..V; ops issued per cycle 0..N. The i-th issued op goes to
  // INT block i, so the busy/idle combinations of the blocks are exactly these N + 1 prefixes.
  for (int c = 0; c <= contexts_; ++c) declare_bin("te.contexts_in_flight/" + std::to_string(c));
  for (int k = 0; k <= blocks_; ++k) declare_bin("te.ops_issued/" + std::to_string(k));
  for (sim::TeClass c : sim::kTeClasses) declare_bin(std::string("te.class/") + sim::to_string(c));
  // A dedicated CPG (the RTL's) never waits for the GPE, and the GPE never spends a cycle on it.
  const bool gpe_cpg = cfg.cpg_mapping == sim::CpgMapping::Gpe;
  for (sim::CpgAction a : kCpgActions)
    if (gpe_cpg || a != sim::CpgAction::WaitGpe) declare_bin(std::string("cpg.action/") + sim::to_string(a));
  for (sim::GpeClass c : sim::kGpeClasses)
    if (gpe_cpg || c != sim::GpeClass::Cpg) declare_bin(std::string("gpe.class/") + sim::to_string(c));
  for (const char* b : {"tri_fifo/empty", "tri_fifo/full", "vtx_fifo/empty", "vtx_fifo/full"}) declare_bin(b);
  for (const char* b : {"backpressure/vertex_stalled", "backpressure/last_vertex_stalled",
                        "backpressure/triangle_stalled"})
    declare_bin(b);
  for (int L = 1; L <= kMaxTessFactor; ++L)
    declare_bin("factor." + std::string(to_string(cfg.normals)) + "/L=" + std::to_string(L));
  for (const char* b : {"patch/degenerate", "patch/saturated", "patch/clean"}) declare_bin(b);
  for (sim::CpgAction a : kCpgActions)
    if (gpe_cpg || a != sim::CpgAction::WaitGpe) declare_bin(std::string("reset.in_cpg/") + sim::to_string(a));
}

void FunctionalCoverage::sample_cycle(const sim::UnitInputs& in, bool vtx_valid, const sim::VertexFx& vtx_front,
                                      const sim::GpeCycle& gpe, const sim::Unit& after) {
  const sim::CycleActivity& act = after.activity();
  hit("te.contexts_in_flight/" + std::to_string(after.contexts_in_use()));
  hit("te.ops_issued/" + std::to_string(act.ops_issued));
  hit(std::string("te.class/") + sim::to_string(act.te));
  hit(std::string("cpg.action/") + sim::to_string(act.cpg_action));
  hit(std::string("gpe.class/") + sim::to_string(gpe.cls));
  if (after.tri_fifo_count() == 0) hit("tri_fifo/empty");
  if (after.tri_fifo_count() == tri_depth_) hit("tri_fifo/full");
  if (after.vtx_fifo_count() == 0) hit("vtx_fifo/empty");
  if (after.vtx_fifo_count() == vtx_depth_) hit("vtx_fifo/full");
  if (vtx_valid && !in.vtx_ready) {
    hit("backpressure/vertex_stalled");
    if (vtx_front.last) hit("backpressure/last_vertex_stalled");
  }
  if (in.tri_valid && !act.tri_pushed) hit("backpressure/triangle_stalled");
}

void FunctionalCoverage::sample_triangle(const sim::TriangleFx& tri, NormalMode mode) {
  if (tri.pattern != sim::TriPattern::uniform) {
    // D3D11 patterns: by partitioning and by points per patch in powers of two (not declared:
    // streams of the uniform pattern do not reach them).
    const int points = sim::patch_vertex_count(tri);
    hit(std::string("pattern/") + partitioning_name(sim::tri_partitioning(tri.pattern)) + "/points<" +
        std::to_string(1 << std::bit_width(static_cast<unsigned>(points))));
    return;
  }
  hit("factor." + std::string(to_string(mode)) + "/L=" + std::to_string(tri.L));
}

void FunctionalCoverage::sample_vertex(const sim::VertexFx& v) {
  if (!v.last) return;  // once per patch
  if (v.flags & sim::kFlagDivByZero) hit("patch/degenerate");
  if (v.flags & sim::kFlagSaturated) hit("patch/saturated");
  if (v.flags == 0) hit("patch/clean");
}

void FunctionalCoverage::sample_reset(const sim::Unit& before) {
  hit(std::string("reset.in_cpg/") + sim::to_string(before.activity().cpg_action));
}

void FunctionalCoverage::merge(const FunctionalCoverage& other) {
  for (const auto& [bin, n] : other.hits_) hits_[bin] += n;
}

std::size_t FunctionalCoverage::covered() const {
  std::size_t n = 0;
  for (const auto& [bin, hits] : hits_) n += hits > 0;
  return n;
}

std::vector<std::string> FunctionalCoverage::uncovered() const {
  std::vector<std::string> out;
  for (const auto& [bin, hits] : hits_)
    if (hits == 0) out.push_back(bin);
  return out;
}

nlohmann::json FunctionalCoverage::to_json() const {
  nlohmann::json bins = nlohmann::json::object();
  for (const auto& [bin, hits] : hits_) bins[bin] = hits;
  return {{"bins", bins}, {"covered", covered()}, {"total", hits_.size()}};
}

FunctionalCoverage FunctionalCoverage::from_json(const nlohmann::json& j, const std::string& source) {
  FunctionalCoverage c;
  if (!j.is_object() || !j.contains("bins") || !j["bins"].is_object())
    throw InputError(source, "bins", "not a coverage file of tessim cosim --coverage");
  for (const auto& [bin, hits] : j["bins"].items()) {
    if (!hits.is_number_unsigned()) throw InputError(source, "bins." + bin, "hit count is not a non-negative integer");
    c.hits_[bin] = hits.get<std::uint64_t>();
  }
  return c;
}

std::string FunctionalCoverage::summary() const {
  std::map<std::string, std::pair<std::size_t, std::size_t>> groups;  // covered, total
  std::map<std::string, std::vector<std::string>> missing;
  for (const auto& [bin, hits] : hits_) {
    auto& g = groups[group_of(bin)];
    ++g.second;
    if (hits > 0) ++g.first;
    else missing[group_of(bin)].push_back(bin.substr(bin.find('/') + 1));
  }
  std::ostringstream os;
  os << "functional coverage: " << covered() << " of " << hits_.size() << " bins\n";
  for (const auto& [group, ct] : groups) {
    os << "  " << group << ": " << ct.first << "/" << ct.second;
    if (!missing[group].empty()) {
      os << "  never:";
      std::size_t shown = 0;
      for (const std::string& m : missing[group]) {
        if (shown++ == 12) {
          os << " ... (" << missing[group].size() - 12 << " more)";
          break;
        }
        os << " " << m;
      }
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace tessim::cosim
