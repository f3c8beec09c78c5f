// Lock-step co-simulation on scalar-tagged meshes (docs/stpn.md, docs/verification.md): the RTL
// builds that take tags (CpgTags) against the cycle model, N = 1..4, both CPG lane counts, every
// hardware normal mode, with random geometry-engine stalls.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cosim/cosim.hpp"
#include "model/base/error.hpp"
#include "model/stpn_import.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/host.hpp"
#include "tests/support/rtl_build_config.hpp"

namespace tessim::cosim {
namespace {

// The builds that take scalar tags (their parameters from rtl/builds.json; they also take alpha,
// unread here: every alpha is 1).
struct TagBuild {
  const char* name;
};
constexpr TagBuild kTagBuilds[] = {{"n1_r4"}, {"n2_l3r8"}, {"n3_lat3"}, {"n4_l3r24"}};

int int_blocks(const TagBuild& b) { return tessim::testing::with_rtl_build({}, b.name).int_blocks; }

CosimOptions tag_options(const TagBuild& b, NormalMode mode, double stall, std::uint64_t seed) {
  CosimOptions o;
  o.variant = b.name;
  o.unit = tessim::testing::with_rtl_build(o.unit, b.name);
  o.unit.normals = mode;
  o.unit.gpe_stall_prob = stall;
  o.unit.gpe_cycles = 2;
  o.unit.seed = seed;
  o.seed = seed;
  return o;
}

// The ST-mesh stpn-import makes of a hard-edged model, as the unit's input stream (tags along).
std::vector<sim::TriangleFx> tagged_stream(const char* path, const sim::NumberFormat& fmt, int L,
                                           std::size_t* tagged_triangles) {
  const Mesh mesh = import_st_mesh(path, StImportOptions{}).mesh;
  const sim::HostScaling scaling = sim::host_scaling(mesh);
  std::vector<sim::TriangleFx> s;
  *tagged_triangles = 0;
  for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
    s.push_back(sim::to_fixed(mesh, i, scaling, fmt, L, true));
    const auto& t = s.back().tags;
    *tagged_triangles += !(t[0].neutral() && t[1].neutral() && t[2].neutral());
  }
  return s;
}

TEST(CosimStpn, TaggedRealMeshesAgreeForEveryBuildAndMode) {
  for (const char* path : {"/usr/share/assimp/models/Collada/Cinema4D.dae", "/usr/share/assimp/models/OBJ/box.obj"}) {
    for (const TagBuild& b : kTagBuilds) {
      for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
        const CosimOptions o = tag_options(b, mode, 0.3, 17 + static_cast<std::uint64_t>(int_blocks(b)));
        std::size_t tagged = 0;
        const auto stream = tagged_stream(path, o.unit.format, 2, &tagged);
        ASSERT_GT(tagged, 0u) << path << ": the ST-mesh must have tagged triangles";
        const CosimReport r = run_cosim(stream, o);
        SCOPED_TRACE(std::string(path) + " " + b.name + " " + std::string(to_string(mode)));
        EXPECT_TRUE(r.passed) << format_report(r, o);
        EXPECT_TRUE(r.counters_match);
        EXPECT_GT(r.reference.scalar_tagged, 0u) << "tagged vertices reach the reference check";
        // The tag pass ran: the copies together were busy for more than the plain C + 1 per
        // triangle (a busy cycle has at most Mc copies at work).
        const std::uint64_t plain = stream.size() * static_cast<std::uint64_t>(sim::cpg_cycles(mode, o.unit.format, o.unit.cpg) + 1);
        EXPECT_GT(r.model_counters.cpg[sim::CpgClass::Busy] * static_cast<std::uint64_t>(o.unit.cpg.copies), plain);
        if (!r.passed) return;
      }
    }
  }
}

// Random tags on random triangles (all kinds: creases with σ = 0 and 1, θ only, three tagged
// corners, degenerate geometry), many seeds per build under random stalls.
TEST(CosimStpn, RandomTagsAgreeOnManySeeds) {
  for (const TagBuild& b : kTagBuilds) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const NormalMode mode = seed % 3 == 0 ? NormalMode::Linear : seed % 3 == 1 ? NormalMode::Quadratic : NormalMode::Reflect;
      const CosimOptions o = tag_options(b, mode, 0.3, seed * 104729 + static_cast<std::uint64_t>(int_blocks(b)));
      const auto stream = random_triangles(30, o.seed, o.unit.format, 4, 0.1, 1.0, true);
      const CosimReport r = run_cosim(stream, o);
      SCOPED_TRACE(std::string(b.name) + " seed " + std::to_string(seed));
      EXPECT_TRUE(r.passed) << format_report(r, o);
      if (!r.passed) return;
    }
  }
}

// A tagged stream the RTL is not built for is refused before anything runs: a plain build has no
// tag inputs in its TRI FIFO, so the configuration check names cpg_tags.
TEST(CosimStpn, PlainBuildRefusesATaggedConfiguration) {
  CosimOptions o;
  o.variant = "n2";
  o.unit.cpg_tags = 1;
  try {
    run_cosim(random_triangles(2, 1, o.unit.format, 2, 0.0, 1.0, true), o);
    FAIL() << "a plain build must refuse cpg_tags 1";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cpg_tags"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessim::cosim
