// Host-side conversion (sim/values/host.hpp) and the unit's numbers on real meshes: scaling and
// rounding, saturation reported as bad input, the end-to-end error bound against the float
// reference (docs/number-formats.md), and watertightness of shared edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "model/base/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"
#include "sim/config/config.hpp"
#include "sim/run/simulate.hpp"
#include "sim/values/error_bound.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {
namespace {

const char* const kWuson = "/usr/share/assimp/models/PLY/Wuson.ply";
constexpr double kSqrt3 = 1.7320508075688772;

UnitConfig fast_config(int L, NormalMode mode) {
  UnitConfig c;
  c.tess_factor = L;
  c.normals = mode;
  c.gpe_cycles = 1;
  c.int_blocks = 4;
  c.validate("test");
  return c;
}

// ---------------------------------------------------------------------------------------------
// Scaling and rounding

TEST(HostScaling, CentredAndFilling) {
  const Mesh mesh = load_mesh(kWuson);
  const HostScaling s = host_scaling(mesh);
  const BoundingBox box = bounding_box(mesh);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const glm::dvec3& p : mesh.positions) {
    const glm::dvec3 q = s.to_unit(p);
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
    EXPECT_LT(glm::length(s.from_unit(q) - p), 1e-12 * box.diagonal());
  }
  // Centred: each axis symmetric; the largest axis spans exactly [-1, 1].
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(lo[c], -hi[c], 1e-12);
  EXPECT_NEAR(std::max({hi.x, hi.y, hi.z}), 1.0, 1e-12);
}

TEST(HostScaling, RoundsToNearestTiesUp) {
  NumberFormat f;
  f.coord_frac_bits = 8;
  const double lsb = 1.0 / 256;
  EXPECT_EQ(quantize(0.5 * lsb, f), 1);
  EXPECT_EQ(quantize(-0.5 * lsb, f), 0);
  EXPECT_EQ(quantize(0.49 * lsb, f), 0);
  EXPECT_EQ(quantize(-0.51 * lsb, f), -1);
  EXPECT_EQ(quantize(1.0, f), 256);
  EXPECT_EQ(quantize(-1.0, f), -256);
  for (double x : {0.123456, -0.7, 0.999}) EXPECT_LE(std::abs(dequantize(quantize(glm::dvec3(x), f), f).x - x), 0.5 * lsb);
  EXPECT_EQ(normal_from_fixed({0, 0, 0}, f), glm::dvec3(0.0));
  EXPECT_NEAR(glm::length(normal_from_fixed({3, -4, 12}, f)), 1.0, 1e-15);
}

TEST(HostScaling, DegenerateMeshesGetUnitScale) {
  Mesh point;
  point.source = "point";
  point.positions = {glm::dvec3(2, 3, 4), glm::dvec3(2, 3, 4), glm::dvec3(2, 3, 4)};
  point.normals = {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)};
  point.triangles = {{0, 1, 2}};
  const HostScaling s = host_scaling(point);
  EXPECT_EQ(s.half_extent, 1.0);
  EXPECT_EQ(s.to_unit(glm::dvec3(2, 3, 4)), glm::dvec3(0.0));
  // A zero-area triangle still tessellates, without NaN, and is counted as degenerate.
  const SimResult r = simulate(point, fast_config(3, NormalMode::Quadratic));
  EXPECT_EQ(r.unit.vertices_out, 10u);
  EXPECT_EQ(r.degenerate_patches, 1u);
}

TEST(HostScaling, RejectsMeshesItCannotConvert) {
  Mesh mesh;
  mesh.source = "made.obj";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}};
  const UnitConfig cfg = fast_config(2, NormalMode::Quadratic);
  EXPECT_NO_THROW(simulate(mesh, cfg));
  auto expect_error = [&](Mesh bad, const std::string& element) {
    try {
      simulate(bad, cfg);
      FAIL() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("made.obj: " + element), std::string::npos) << e.what();
    }
  };
  Mesh nan = mesh;
  nan.positions[1].y = std::nan("");
  expect_error(nan, "vertex 1");
  Mesh zero = mesh;
  zero.normals[2] = glm::dvec3(0.0);
  expect_error(zero, "vertex 2");
  Mesh index = mesh;
  index.triangles[0].z = 3;
  expect_error(index, "triangle 0");
}

// ---------------------------------------------------------------------------------------------
// Widths that cannot hold the mesh

TEST(HostSaturation, IsAnInputErrorNamingMeshAndTriangle) {
  // With one integer bit the range is [-2, 2): the corner normal net 2 N saturates for a unit
  // normal along an axis. Triangle 1 has one; triangle 0 does not.
  Mesh mesh;
  mesh.source = "axis-normals.obj";
  const glm::dvec3 tilted = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.2}};
  mesh.normals = {tilted, tilted, tilted, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
  UnitConfig cfg = fast_config(2, NormalMode::Quadratic);
  cfg.format.coord_int_bits = 1;
  cfg.validate("test");
  bool wrote = false;
  SimHooks hooks;
  hooks.on_patch = [&](const PatchOut& p) { wrote = wrote || p.triangle == 1; };
  try {
    simulate(mesh, cfg, hooks);
    FAIL() << "saturation not reported";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("axis-normals.obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find("triangle 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot hold"), std::string::npos) << msg;
  }
  EXPECT_FALSE(wrote) << "no part of the saturated patch reaches the output";
  cfg.format.coord_int_bits = 2;
  EXPECT_NO_THROW(simulate(mesh, cfg));
}

// ---------------------------------------------------------------------------------------------
// End-to-end error against the float reference on the real mesh (docs/number-formats.md §5).
//
// Three terms, each bounded per patch in unit coordinates:
//   arithmetic  the unit against the reference built from the quantized input at the
//               quantized barycentrics (sim/values/error_bound.hpp);
//   input       the reference moved by quantizing P and N (|dP_c|, |dN_c| <= eps = 2^-(F+1));
//   domain      the reference moved by evaluating at the quantized barycentrics
//               (|du|, |dv| <= 2^-(B+1), w = 1 - u - v exact).

struct PatchBounds {
  double position = 0;        // Euclidean, unit coordinates
  double normal = -1;         // Euclidean, in units of the unit's normal output; < 0: undefined
};

double max_difference(const auto& net, int degree, int dj, int dk) {
  double m = 0;
  for (int k = 0; k < degree; ++k)
    for (int j = 0; j + k < degree; ++j)
      m = std::max(m, glm::length(net[static_cast<std::size_t>(net_index(j + dj, k + dk, degree))] -
                                  net[static_cast<std::size_t>(net_index(j, k, degree))]));
  return m;
}

PatchBounds patch_bounds(const PnInput& unit_in, const TriangleFx& tri, const UnitConfig& cfg) {
  const NumberFormat& f = cfg.format;
  const double eps = std::ldexp(1.0, -(f.coord_frac_bits + 1));
  const double dbary = std::ldexp(1.0, -(f.bary_bits + 1));
  const PnPatch patch = make_patch(unit_in, cfg.normals);
  PatchBounds b;

  // Positions. Tangent point near a on edge a->b: 3 dt = 2 dPa + dPb - d(w N) with
  // |dw| <= |dd| + |d| |dN| + |dd| |dN| (|N| = 1), |dd| <= 2 sqrt3 eps, |dN| <= sqrt3 eps.
  double tangent = 0;
  for (int e = 0; e < 3; ++e) {
    const double d = glm::length(unit_in.p[static_cast<std::size_t>((e + 1) % 3)] - unit_in.p[static_cast<std::size_t>(e)]);
    const double dw = 2 * kSqrt3 * eps + kSqrt3 * eps * d + 6 * eps * eps;
    tangent = std::max(tangent, eps + (dw * (1 + eps) + d * eps) / 3);
  }
  const double center = 1.5 * tangent + 0.5 * eps;
  const double input_pos = kSqrt3 * std::max({eps, tangent, center});
  const double domain_pos = 3 * (max_difference(patch.b, 3, 1, 0) + max_difference(patch.b, 3, 0, 1)) * dbary;
  b.position = position_error_budget(f).position_units + input_pos + domain_pos;

  // Normals, in output units (2 x field for quadratic and reflect, the field for linear).
  const double arith = normal_error_bound(tri, cfg.normals, f);
  if (arith < 0) return b;
  double input_n = 0, domain_n = 0;
  if (cfg.normals == NormalMode::Linear) {
    input_n = kSqrt3 * eps;
    const auto& n = patch.n_corner;
    domain_n = (glm::length(n[1] - n[0]) + glm::length(n[2] - n[0])) * dbary;
  } else {
    input_n = 2 * kSqrt3 * eps;  // corners 2 N
    // Mid-edge m = s - k (d^.s) d^: |dm| <= (1 + k)|ds| + 4k |s| |dd| / |d|, |ds|, |dd| <= 2 sqrt3 eps;
    // quadratic stores m / |m| (|m| = |s|), whose error is at most 2 |dm| / |m|.
    const double k = cfg.normals == NormalMode::Quadratic ? 2 : 4;
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::size_t>(e), c = static_cast<std::size_t>((e + 1) % 3);
      const double d = glm::length(unit_in.p[c] - unit_in.p[a]);
      const double s = glm::length(unit_in.n[a] + unit_in.n[c]);
      if (d == 0) return b;
      const double dm = (1 + k) * 2 * kSqrt3 * eps + 4 * k * s * 2 * kSqrt3 * eps / d;
      if (cfg.normals == NormalMode::Reflect) {
        input_n = std::max(input_n, dm);
      } else {
        if (s <= 2 * dm) return b;
        input_n = std::max(input_n, 2 * dm / s);
      }
    }
    std::array<glm::dvec3, 6> net2;
    for (std::size_t i = 0; i < 6; ++i) net2[i] = 2.0 * patch.n_bern[i];
    domain_n = 2 * (max_difference(net2, 2, 1, 0) + max_difference(net2, 2, 0, 1)) * dbary;
  }
  b.normal = kSqrt3 * arith + input_n + domain_n;
  return b;
}

// The reference field in output units at (u, v).
glm::dvec3 reference_field(const PnPatch& patch, double u, double v) {
  const double w = 1 - u - v;
  if (patch.mode == NormalMode::Linear) return w * patch.n_corner[0] + u * patch.n_corner[1] + v * patch.n_corner[2];
  const auto& n = patch.n_bern;
  return 2.0 * (w * w * n[0] + 2 * w * u * n[1] + u * u * n[2] + 2 * w * v * n[3] + 2 * u * v * n[4] + v * v * n[5]);
}

struct ErrorStats {
  std::uint64_t vertices = 0, normals = 0, beyond = 0;
  double max_pos = 0, sum_pos2 = 0, max_angle = 0, sum_angle2 = 0;
  double max_pos_arith = 0, max_angle_arith = 0;  // against the reference on quantized input
  double max_pos_bound = 0;
  std::string worst;
};

ErrorStats measure_errors(const Mesh& mesh, const UnitConfig& cfg) {
  const HostScaling s = host_scaling(mesh);
  const double diag = bounding_box(mesh).diagonal();
  const double bary_one = static_cast<double>(cfg.format.bary_one());
  const int L = cfg.tess_factor;
  ErrorStats st;
  std::uint32_t cached = ~0u;
  PnPatch ref, ref_quantized;
  PatchBounds bounds;
  SimHooks hooks;
  hooks.on_vertex = [&](const VertexFx& v) {
    if (v.id != cached) {
      const glm::uvec3& t = mesh.triangles[v.id];
      PnInput in, unit_in, quantized;
      const TriangleFx tri = to_fixed(mesh, v.id, s, cfg.format, L);
      for (int i = 0; i < 3; ++i) {
        in.p[static_cast<std::size_t>(i)] = mesh.positions[t[i]];
        in.n[static_cast<std::size_t>(i)] = mesh.normals[t[i]];
        unit_in.p[static_cast<std::size_t>(i)] = s.to_unit(mesh.positions[t[i]]);
        unit_in.n[static_cast<std::size_t>(i)] = mesh.normals[t[i]];
        quantized.p[static_cast<std::size_t>(i)] = dequantize(tri.p[static_cast<std::size_t>(i)], cfg.format);
        quantized.n[static_cast<std::size_t>(i)] = dequantize(tri.n[static_cast<std::size_t>(i)], cfg.format);
      }
      ref = make_patch(in, cfg.normals);
      ref_quantized = make_patch(quantized, cfg.normals);
      bounds = patch_bounds(unit_in, tri, cfg);
      cached = v.id;
    }
    const double u = static_cast<double>(v.j) / L, w = static_cast<double>(v.k) / L;
    const PnVertex exact = eval_bernstein(ref, u, w);
    const glm::dvec3 pos = position_from_fixed(v.pos, s, cfg.format);
    const double err = glm::length(pos - exact.position);
    const double bound = bounds.position * s.half_extent + 1e-12 * diag;
    ++st.vertices;
    st.max_pos = std::max(st.max_pos, err / diag);
    st.sum_pos2 += (err / diag) * (err / diag);
    st.max_pos_bound = std::max(st.max_pos_bound, bound / diag);
    if (err > bound) {
      if (st.beyond++ == 0) st.worst = "position of (" + std::to_string(v.id) + ", " + std::to_string(v.j) + ", " +
                                       std::to_string(v.k) + "): " + std::to_string(err) + " > " + std::to_string(bound);
    }
    // The unit's arithmetic alone: reference on the quantized input at the quantized weights.
    const PnVertex at_q = eval_bernstein(ref_quantized, static_cast<double>(v.u) / bary_one, static_cast<double>(v.v) / bary_one);
    st.max_pos_arith = std::max(st.max_pos_arith, glm::length(dequantize(v.pos, cfg.format) - at_q.position) * s.half_extent / diag);

    const double field = glm::length(reference_field(ref, u, w));
    if (bounds.normal >= 0 && field > 2 * bounds.normal) {
      const glm::dvec3 n = normal_from_fixed(v.nrm, cfg.format);
      const double angle = std::acos(std::clamp(glm::dot(n, exact.normal), -1.0, 1.0));
      const double angle_bound = std::asin(bounds.normal / field) + 1e-9;
      ++st.normals;
      st.max_angle = std::max(st.max_angle, angle);
      st.sum_angle2 += angle * angle;
      st.max_angle_arith = std::max(st.max_angle_arith, std::acos(std::clamp(glm::dot(n, at_q.normal), -1.0, 1.0)));
      if (angle > angle_bound && st.beyond++ == 0)
        st.worst = "normal of (" + std::to_string(v.id) + ", " + std::to_string(v.j) + ", " + std::to_string(v.k) +
                   "): " + std::to_string(angle) + " rad > " + std::to_string(angle_bound);
    }
  };
  simulate(mesh, cfg, hooks);
  return st;
}

class RealMeshError : public ::testing::TestWithParam<NormalMode> {};

TEST_P(RealMeshError, WusonWithinTheDerivedBound) {
  const Mesh mesh = load_mesh(kWuson);
  const UnitConfig cfg = fast_config(8, GetParam());
  const ErrorStats st = measure_errors(mesh, cfg);
  EXPECT_EQ(st.vertices, mesh.triangle_count() * 45);
  EXPECT_EQ(st.beyond, 0u) << st.worst;
  // Almost every normal has a defined bound on a smooth mesh.
  EXPECT_GT(st.normals, st.vertices * 99 / 100);
  std::printf(
      "[ errors   ] Wuson L=8 %s, Q%d.%d B=%d: position max %.3e rms %.3e (x bbox diagonal; bound up to "
      "%.3e; arithmetic alone max %.3e), normal angle max %.3e rms %.3e rad (arithmetic alone max %.3e)\n",
      std::string(to_string(GetParam())).c_str(), cfg.format.coord_int_bits, cfg.format.coord_frac_bits,
      cfg.format.bary_bits, st.max_pos, std::sqrt(st.sum_pos2 / static_cast<double>(st.vertices)), st.max_pos_bound,
      st.max_pos_arith, st.max_angle, std::sqrt(st.sum_angle2 / static_cast<double>(st.normals)), st.max_angle_arith);
  // The scale of the result: a few LSB of the 20-bit fraction, relative to a diagonal >= 2.
  EXPECT_LT(st.max_pos, 1e-5);
  EXPECT_LT(st.max_angle, 1e-2);
}

INSTANTIATE_TEST_SUITE_P(Modes, RealMeshError,
                         ::testing::Values(NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(RealMeshError, NarrowFormatStillWithinBound) {
  const Mesh mesh = load_mesh(kWuson);
  UnitConfig cfg = fast_config(6, NormalMode::Quadratic);
  cfg.format = NumberFormat{3, 12, 9};
  cfg.validate("test");
  const ErrorStats st = measure_errors(mesh, cfg);
  EXPECT_EQ(st.beyond, 0u) << st.worst;
  std::printf("[ errors   ] Wuson L=6 quadratic, Q3.12 B=9: position max %.3e (bound up to %.3e), normal angle max %.3e rad\n",
              st.max_pos, st.max_pos_bound, st.max_angle);
  // Fewer bits, larger errors: the bound is not vacuous.
  EXPECT_GT(st.max_pos, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Watertightness: a vertex on an edge shared by two patches is bit-identical in both.

TEST(Watertight, SharedEdgeVerticesBitIdenticalOnWuson) {
  const Mesh mesh = load_mesh(kWuson);
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear}) {
    const int L = 8;
    const UnitConfig cfg = fast_config(L, mode);
    // Key: (lower vertex index, higher vertex index, steps from the lower one along the edge).
    std::map<std::tuple<unsigned, unsigned, int>, std::pair<FxVec, FxVec>> seen;
    std::uint64_t compared = 0, mismatched = 0;
    SimHooks hooks;
    hooks.on_vertex = [&](const VertexFx& v) {
      const glm::uvec3& t = mesh.triangles[v.id];
      // Corner a -> corner b and the step count from a, for each edge the point lies on.
      std::vector<std::tuple<unsigned, unsigned, int>> on;
      if (v.k == 0) on.emplace_back(t[0], t[1], v.j);                // P1 -> P2
      if (v.j + v.k == L) on.emplace_back(t[1], t[2], v.k);          // P2 -> P3
      if (v.j == 0) on.emplace_back(t[2], t[0], L - v.k);            // P3 -> P1
      for (auto [a, b, step] : on) {
        const auto key = a < b ? std::make_tuple(a, b, step) : std::make_tuple(b, a, L - step);
        const auto [it, inserted] = seen.try_emplace(key, v.pos, v.nrm);
        if (!inserted) {
          ++compared;
          if (it->second.first != v.pos || it->second.second != v.nrm) ++mismatched;
        }
      }
    };
    simulate(mesh, cfg, hooks);
    EXPECT_GT(compared, mesh.triangle_count() * 9) << "most edges are shared";
    EXPECT_EQ(mismatched, 0u) << to_string(mode);
  }
}

// ---------------------------------------------------------------------------------------------
// Output in the mesh's own coordinates

TEST(HostOutput, PatchesAreInMeshCoordinatesWithUnitNormals) {
  const Mesh mesh = load_mesh(kWuson);
  const UnitConfig cfg = fast_config(2, NormalMode::Quadratic);
  const BoundingBox box = bounding_box(mesh);
  std::uint64_t patches = 0;
  SimHooks hooks;
  hooks.on_patch = [&](const PatchOut& p) {
    ASSERT_EQ(p.triangle, patches);
    ASSERT_EQ(p.positions.size(), 6u);
    const glm::uvec3& t = mesh.triangles[p.triangle];
    // The corners of the patch are the input vertices, up to the input quantization.
    const double tol = box.diagonal() * 1e-5;
    EXPECT_LT(glm::length(p.positions[0] - mesh.positions[t[0]]), tol);
    EXPECT_LT(glm::length(p.positions[static_cast<std::size_t>(pattern_index(2, 0, 2))] - mesh.positions[t[1]]), tol);
    EXPECT_LT(glm::length(p.positions[static_cast<std::size_t>(pattern_index(0, 2, 2))] - mesh.positions[t[2]]), tol);
    for (const glm::dvec3& n : p.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
    ++patches;
  };
  simulate(mesh, cfg, hooks);
  EXPECT_EQ(patches, mesh.triangle_count());
}

}  // namespace
}  // namespace tessim::sim
