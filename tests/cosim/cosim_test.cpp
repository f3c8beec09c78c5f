// Lock-step co-simulation of the Verilated RTL against the cycle model (docs/verification.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/cosim.hpp"
#include "model/base/error.hpp"
#include "model/mesh_io.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/values/host.hpp"
#include "tests/support/rtl_build_config.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim::cosim {
namespace {

CosimOptions options(int n, double stall, int gpe_cycles, std::uint64_t seed) {
  CosimOptions o;
  o.unit.int_blocks = n;
  o.unit.gpe_stall_prob = stall;
  o.unit.gpe_cycles = gpe_cycles;
  o.unit.seed = seed;
  // Formatted into a buffer: GCC 12 warns (-Wrestrict, a false positive) about building the
  // name from a string literal and std::to_string, appended or not.
  char variant[16];
  std::snprintf(variant, sizeof variant, "n%d", n);
  o.variant = variant;
  o.seed = seed;
  return o;
}

void expect_pass(const CosimReport& r, const CosimOptions& o) {
  EXPECT_TRUE(r.passed) << format_report(r, o);
  EXPECT_TRUE(r.counters_match);
  EXPECT_EQ(r.reference.beyond_bound, 0u) << r.reference.worst;
  EXPECT_GT(r.vertices, 0u);
}

std::uint64_t expected_vertices(const std::vector<sim::TriangleFx>& s) {
  std::uint64_t n = 0;
  for (const auto& t : s) n += static_cast<std::uint64_t>((t.L + 1) * (t.L + 2) / 2);
  return n;
}

// Random triangles (10% degenerate) under the three kinds of backpressure, N = 1..4.
struct Backpressure {
  const char* name;
  double stall;
  int gpe_cycles;
};
class CosimRandom : public ::testing::TestWithParam<std::tuple<int, Backpressure>> {};

TEST_P(CosimRandom, AgreesOnManySeeds) {
  const auto [n, bp] = GetParam();
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const CosimOptions o = options(n, bp.stall, bp.gpe_cycles, seed * 7919 + static_cast<std::uint64_t>(n));
    const auto stream = random_triangles(24, o.seed, o.unit.format, 6);
    const CosimReport r = run_cosim(stream, o);
    expect_pass(r, o);
    EXPECT_EQ(r.vertices, expected_vertices(stream));
    if (!r.passed) break;
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllRtlBuilds, CosimRandom,
    ::testing::Combine(::testing::Values(1, 2, 3, 4),
                       ::testing::Values(Backpressure{"none", 0.0, 1}, Backpressure{"constant_k", 0.0, 8},
                                         Backpressure{"random", 0.3, 2})),
    [](const auto& info) {
      return "N" + std::to_string(std::get<0>(info.param)) + "_" + std::get<1>(info.param).name;
    });

std::vector<sim::TriangleFx> mesh_stream(const char* path, const sim::NumberFormat& fmt, int L) {
  const Mesh mesh = load_mesh(path);
  const auto scaling = sim::host_scaling(mesh);
  std::vector<sim::TriangleFx> s;
  for (std::size_t i = 0; i < mesh.triangle_count(); ++i) s.push_back(sim::to_fixed(mesh, i, scaling, fmt, L));
  return s;
}

TEST(CosimMesh, RealMeshesAgree) {
  struct Case {
    const char* path;
    int n, L;
    double stall;
  };
  for (const Case c : {Case{"/usr/share/assimp/models/OFF/Wuson.off", 2, 3, 0.3},
                       Case{"/usr/share/assimp/models/STL/sphereWithHole.stl", 3, 2, 0.0},
                       Case{"/usr/share/assimp/models/OBJ/spider.obj", 4, 2, 0.2},
                       Case{"/usr/share/assimp/models/OBJ/spider.obj", 1, 1, 0.0}}) {
    CosimOptions o = options(c.n, c.stall, 4, 11);
    o.unit.tess_factor = c.L;
    const auto stream = mesh_stream(c.path, o.unit.format, c.L);
    const CosimReport r = run_cosim(stream, o);
    SCOPED_TRACE(c.path);
    expect_pass(r, o);
    EXPECT_EQ(r.vertices, expected_vertices(stream));
  }
}

// A shader-core geometry engine (docs/microarchitecture.md §12) drives vtx_ready through its
// cross-clock FIFO: bursts of room as waves launch, gaps while the synchronizers catch up. The
// RTL follows it cycle for cycle, with and without random stalls, at N = 1 and 3.
TEST(CosimGeCore, AgreesUnderAShaderCoresBackpressure) {
  for (const int n : {1, 3}) {
    for (const double stall : {0.0, 0.15}) {
      CosimOptions o = options(n, stall, 8, 97 + static_cast<std::uint64_t>(n));
      o.unit.ge_core_lanes = 4;
      o.unit.ge_core_mhz = 170;
      o.unit.unit_mhz = 200;
      o.unit.ge_core_fifo = 5;
      const auto stream = random_triangles(16, o.seed, o.unit.format, 5);
      const CosimReport r = run_cosim(stream, o);
      SCOPED_TRACE("N = " + std::to_string(n) + ", stall " + std::to_string(stall));
      expect_pass(r, o);
      EXPECT_EQ(r.vertices, expected_vertices(stream));
      // The core limited the run (K = 65 / 4 × 200 / 170 ≈ 19.1): it issued most cycles.
      EXPECT_GT(r.gpe[sim::GpeClass::Busy], r.cycles * 3 / 4);
    }
  }
}

TEST(CosimModes, ReflectAndLinearAgree) {
  for (NormalMode m : {NormalMode::Reflect, NormalMode::Linear}) {
    CosimOptions o = options(2, 0.2, 3, 5);
    o.unit.normals = m;
    const auto stream = random_triangles(20, 99, o.unit.format, 5);
    const CosimReport r = run_cosim(stream, o);
    expect_pass(r, o);
  }
}

TEST(CosimReset, ResetInTheMiddleOfAStreamRecovers) {
  CosimOptions o = options(2, 0.25, 2, 3);
  o.reset_at = {150, 1000};  // while the first triangles are in CPG and TE
  const auto stream = random_triangles(16, 3, o.unit.format, 5);
  const CosimReport r = run_cosim(stream, o);
  expect_pass(r, o);
  EXPECT_EQ(r.vertices, expected_vertices(stream));  // a complete pass after the last reset
}

TEST(CosimDegenerate, DegenerateTrianglesPassWithoutXOrHang) {
  // Only degenerate triangles, on the X-randomising verification build with several seeds.
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    CosimOptions o = options(2, 0.1, 2, seed);
    o.variant = "n2_verif";
    const auto stream = random_triangles(24, seed, o.unit.format, 4, /*degenerate_share=*/1.0);
    const CosimReport r = run_cosim(stream, o);
    EXPECT_FALSE(r.hang);
    expect_pass(r, o);
  }
}

// The checker can fail: RTL builds with an injected bug must be caught, at a named cycle.
TEST(CosimInjectedBug, RoundingBugIsCaughtAtTheFirstDivergentCycle) {
  CosimOptions o = options(2, 0.0, 1, 4);
  o.variant = "n2_bug1";
  const auto wave = std::filesystem::temp_directory_path() / "tessim_cosim_bug1.fst";
  std::filesystem::remove(wave);
  o.wave = wave;
  o.wave_window = 50;
  const auto stream = random_triangles(8, 4, o.unit.format, 4, 0.0);
  const CosimReport r = run_cosim(stream, o);
  ASSERT_TRUE(r.divergence.has_value()) << format_report(r, o);
  EXPECT_FALSE(r.passed);
  const Divergence& d = *r.divergence;
  EXPECT_TRUE(d.field.rfind("vtx_pos", 0) == 0 || d.field.rfind("vtx_nrm", 0) == 0) << d.field;
  EXPECT_NE(d.expected, d.actual);
  // Every output before the reported cycle agreed: the same run stopped one cycle earlier
  // is clean, so the reported cycle is the first divergent one.
  const auto clean = run_cosim_until(stream, o, d.cycle);
  EXPECT_FALSE(clean.divergence.has_value());
  ASSERT_TRUE(std::filesystem::exists(wave));
  EXPECT_GT(std::filesystem::file_size(wave), 100u);
  // The gtkwave layout opens at the divergence, its marker on the divergent cycle.
  std::ifstream gtkw(gtkw_path(wave));
  const std::string layout((std::istreambuf_iterator<char>(gtkw)), std::istreambuf_iterator<char>());
  EXPECT_NE(layout.find("*-4.000000 " + std::to_string(2 * d.cycle) + "\n"), std::string::npos) << layout;
  std::filesystem::remove(wave);
  std::filesystem::remove(gtkw_path(wave));
}

TEST(CosimInjectedBug, DroppedStallIsCaught) {
  // The fault needs a full VTX FIFO when a patch's last vertex retires: a fast CPG (linear
  // normals), large patches and a slow, stalling GPE make the TE outrun its consumer.
  CosimOptions o = options(2, 0.5, 4, 8);
  o.variant = "n2_bug2";
  o.unit.normals = NormalMode::Linear;
  const auto stream = random_triangles(12, 8, o.unit.format, 8, 0.0);
  const CosimReport r = run_cosim(stream, o);
  ASSERT_TRUE(r.divergence.has_value()) << format_report(r, o);
  EXPECT_FALSE(r.passed);
  EXPECT_GT(r.divergence->cycle, 0u);
  EXPECT_FALSE(run_cosim_until(stream, o, r.divergence->cycle).divergence.has_value());
  // The fault-free build passes the same run.
  o.variant = "n2";
  expect_pass(run_cosim(stream, o), o);
}

// The build away from the defaults (N = 3, INT latency 3, V = 6, a CPG that takes scalar tags)
// on random triangles, plain and tagged, under each kind of backpressure and in every normal
// mode: the pipeline registers of the INT blocks and results arriving Λ cycles after issue are
// covered by the default test matrix.
TEST(CosimLatency3, AgreesInEveryModeAndUnderBackpressure) {
  for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    for (const Backpressure bp : {Backpressure{"none", 0.0, 1}, Backpressure{"random", 0.3, 2}}) {
      for (const bool tagged : {false, true}) {
        CosimOptions o = options(3, bp.stall, bp.gpe_cycles, 41);
        o.variant = "n3_lat3";
        o.unit.int_latency = 3;
        o.unit.te_contexts = 6;
        o.unit.cpg = {3, 5, 2, 1};
        o.unit.cpg_tags = 1;
        o.unit.format.alpha_bits = 8;
        o.unit.normals = mode;
        const auto stream = random_triangles(24, o.seed, o.unit.format, 6, 0.1, 1.0, tagged);
        const CosimReport r = run_cosim(stream, o);
        SCOPED_TRACE(std::string(to_string(mode)) + " " + bp.name + (tagged ? " tagged" : " plain"));
        expect_pass(r, o);
        EXPECT_EQ(r.vertices, expected_vertices(stream));
      }
    }
  }
}

// Waveforms: an explicit window is recorded in a passing run, as FST or (through fst2vcd) VCD,
// exactly the cycles asked for; the .gtkw beside it names only signals the dump has, with the
// widths of the build (two builds of different widths and CPG shapes).
std::map<std::string, int> vcd_signals(const std::filesystem::path& vcd, std::vector<std::uint64_t>* times) {
  std::ifstream in(vcd);
  std::map<std::string, int> names;  // full name as gtkwave spells it -> width
  std::vector<std::string> scope;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string w;
    words >> w;
    if (w == "$scope") {
      std::string kind, name;
      words >> kind >> name;
      scope.push_back(name);
    } else if (w == "$upscope") {
      scope.pop_back();
    } else if (w == "$var") {
      std::string type, id, name, range;
      int width = 0;
      words >> type >> width >> id >> name >> range;
      std::string full;
      for (const std::string& s : scope) full += s + ".";
      full += name + (range.rfind('[', 0) == 0 ? range : "");
      names[full] = width;
    } else if (!w.empty() && w[0] == '#') {
      times->push_back(std::stoull(w.substr(1)));
    }
  }
  return names;
}

TEST(CosimWave, ExplicitWindowOfAPassingRunWithAMatchingLayout) {
  tessim::testing::TempDir dir;
  for (const char* name : {"n2", "n3_lat3"}) {
    CosimOptions o = options(2, 0.2, 2, 7);
    o.variant = name;
    o.unit = tessim::testing::with_rtl_build(o.unit, name);
    const auto stream = random_triangles(6, 7, o.unit.format, 3);
    for (const char* ext : {".fst", ".vcd"}) {
      o.wave = dir.path() / (std::string(name) + ext);
      o.wave_cycles = WaveWindow{100, 160};
      const CosimReport r = run_cosim(stream, o);
      expect_pass(r, o);
      ASSERT_EQ(r.wave, o.wave);
      ASSERT_TRUE(std::filesystem::exists(o.wave)) << o.wave;
      const auto gtkw = gtkw_path(o.wave);
      ASSERT_TRUE(std::filesystem::exists(gtkw));
      if (std::string(ext) == ".fst") continue;
      EXPECT_FALSE(std::filesystem::exists(wave_recording_path(o.wave))) << "the temporary FST is removed";
      std::vector<std::uint64_t> times;
      const auto signals = vcd_signals(o.wave, &times);
      ASSERT_FALSE(times.empty());
      EXPECT_EQ(times.front(), 200u);  // cycle 100 at time 2c
      EXPECT_EQ(times.back(), 321u);   // cycle 160 after its rising edge, 2c + 1
      std::ifstream layout(gtkw);
      int listed = 0;
      for (std::string line; std::getline(layout, line);) {
        if (line.rfind("tess.", 0) != 0) continue;
        ++listed;
        EXPECT_TRUE(signals.contains(line)) << name << ": " << line << " is not in the dump";
      }
      EXPECT_GT(listed, 30);
    }
  }
}

// The CPG variants (docs/microarchitecture.md §5): one lane with radix-16 steps (N = 1), three
// lanes with radix-256 steps (N = 2) and with a whole quotient a cycle (N = 4), in every mode,
// with and without random stalls, in range and saturating, on plain and on scalar-tagged streams
// (these builds take tags). n3_lat3 (three lanes, steps that do not divide W) is covered above.
// The values must not change and the timing must agree.
TEST(CosimCpgVariants, AgreeInEveryModeUnderBackpressureAndSaturation) {
  for (const char* name : {"n1_r4", "n2_l3r8", "n4_l3r24"}) {
    for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
      for (const Backpressure bp : {Backpressure{"none", 0.0, 1}, Backpressure{"random", 0.3, 2}}) {
        for (const bool tagged : {false, true}) {
          CosimOptions o = options(2, bp.stall, bp.gpe_cycles, 61);
          o.variant = name;
          o.unit = tessim::testing::with_rtl_build(o.unit, name);
          o.unit.normals = mode;
          const auto stream = random_triangles(24, o.seed, o.unit.format, 6, 0.1, 1.0, tagged);
          const CosimReport r = run_cosim(stream, o);
          SCOPED_TRACE(std::string(name) + " " + std::string(to_string(mode)) + " " + bp.name +
                       (tagged ? " tagged" : " plain"));
          expect_pass(r, o);
          EXPECT_EQ(r.vertices, expected_vertices(stream));
          if (tagged) {
            EXPECT_GT(r.model_counters.cpg[sim::CpgClass::Busy], 24u * sim::cpg_cycles(mode, o.unit.format, o.unit.cpg));
          }
        }
      }
      for (const bool tagged : {false, true}) {
        CosimOptions o = options(2, 0.0, 1, 5);
        o.variant = name;
        o.unit = tessim::testing::with_rtl_build(o.unit, name);
        o.unit.normals = mode;
        const CosimReport r = run_cosim(random_triangles(60, o.seed, o.unit.format, 3, 0.1, 30.0, tagged), o);
        expect_pass(r, o);
        EXPECT_GT(r.reference.saturated, 0u) << name << " " << to_string(mode);
      }
    }
  }
}

// Triangles spread over the whole coordinate range: control points and CPG intermediates leave
// it, every saturating path of the RTL (tess_sat, the CPG's clamps) runs, and both sides must
// still agree bit for bit, flags included. Saturated patches are outside the error bound's
// premise, so the reference check counts them instead of comparing them.
TEST(CosimSaturation, ClampedPatchesAgreeBitForBit) {
  for (const NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    for (const int n : {1, 3}) {
      CosimOptions o = options(n, 0.0, 1, 5);
      o.unit.normals = mode;
      const auto stream = random_triangles(120, o.seed, o.unit.format, 3, 0.1, 30.0);
      const CosimReport r = run_cosim(stream, o);
      expect_pass(r, o);
      EXPECT_GT(r.reference.saturated, 0u) << "the stream must saturate";
      EXPECT_LT(r.reference.saturated, r.vertices) << "and leave some patches in range";
    }
  }
}

// Functional coverage: every cycle lands in exactly one bin of each per-cycle group, resets are
// binned by the CPG's state, and what the stream cannot reach stays at zero.
TEST(CosimCoverage, BinsCountCyclesAndEvents) {
  CosimOptions o = options(2, 0.0, 1, 3);
  FunctionalCoverage cov;
  o.coverage = &cov;
  o.reset_at = {1, 300};
  const auto stream = random_triangles(10, 3, o.unit.format, 3, 0.0);
  const CosimReport r = run_cosim(stream, o);
  expect_pass(r, o);
  const nlohmann::json bins = cov.to_json()["bins"];
  std::uint64_t issued = 0, classes = 0;
  for (int k = 0; k <= 2; ++k) issued += bins["te.ops_issued/" + std::to_string(k)].get<std::uint64_t>();
  for (const auto& [bin, n] : bins.items())
    if (bin.rfind("te.class/", 0) == 0) classes += n.get<std::uint64_t>();
  EXPECT_EQ(issued, r.cycles);
  EXPECT_EQ(classes, r.cycles);
  EXPECT_EQ(bins["reset.in_cpg/idle"], 1u);     // cycle 0: nothing in the TRI FIFO yet
  EXPECT_EQ(bins["reset.in_cpg/compute"], 1u);  // cycle 299: mid-triangle
  EXPECT_GT(bins["factor.quadratic/L=3"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(bins["factor.quadratic/L=4"], 0u);  // the stream's factors are 1..3
  EXPECT_EQ(bins["patch/saturated"], 0u);
  EXPECT_FALSE(bins.contains("cpg.action/wait_gpe"));  // a dedicated CPG never waits for the GPE
  EXPECT_LT(cov.covered(), cov.bins());
}

TEST(CosimConfig, MismatchedConfigurationIsRejected) {
  CosimOptions o = options(2, 0.0, 1, 1);
  o.variant = "n3";  // the build has N = 3, the configuration N = 2
  EXPECT_THROW(run_cosim(random_triangles(2, 1, o.unit.format, 2), o), tessim::InputError);
  o.variant = "n2";
  o.unit.int_latency = 2;  // no such build
  EXPECT_THROW(run_cosim(random_triangles(2, 1, o.unit.format, 2), o), tessim::InputError);
}

}  // namespace
}  // namespace tessim::cosim
