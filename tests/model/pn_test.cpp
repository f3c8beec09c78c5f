// Float64 reference of PN triangles (model/pn.hpp, model/tessellate.hpp): docs/mathematics.md.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "model/base/error.hpp"
#include "model/mesh.hpp"
#include "model/mesh_io.hpp"
#include "model/pattern.hpp"
#include "model/pn.hpp"
#include "model/tessellate.hpp"
#include "tests/support/shared_edges.hpp"

namespace tessim {
namespace {

constexpr NormalMode kAllModes[] = {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear,
                                    NormalMode::Derivative};

std::uint64_t ops_per_vertex(NormalMode mode) {
  switch (mode) {
    case NormalMode::Quadratic:
    case NormalMode::Reflect: return 10 + 4;
    case NormalMode::Linear: return 10 + 1;
    case NormalMode::Derivative: return 10 + 0;
  }
  return 0;
}

bool is_finite(const glm::dvec3& x) {
  return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
}

::testing::AssertionResult near(const glm::dvec3& actual, const glm::dvec3& expected, double tol) {
  const double err = glm::length(actual - expected);
  if (err <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "(" << actual.x << ", " << actual.y << ", " << actual.z << ") differs from (" << expected.x
         << ", " << expected.y << ", " << expected.z << ") by " << err << " > " << tol;
}

// Random triangles with normals inside a 60-degree cone around the face normal, the way
// smooth meshes look; the derivative normal at a corner equals Ni only for such normals.
class RandomTriangles {
 public:
  explicit RandomTriangles(std::uint64_t seed) : rng_(seed) {}

  glm::dvec3 unit_vector() {
    for (;;) {
      const glm::dvec3 x(coord_(rng_), coord_(rng_), coord_(rng_));
      const double len = glm::length(x);
      if (len > 0.1 && len <= 1.0) return x / len;
    }
  }

  PnInput next() {
    PnInput in;
    glm::dvec3 face;
    do {
      for (auto& p : in.p) p = glm::dvec3(coord_(rng_), coord_(rng_), coord_(rng_));
      face = glm::cross(in.p[1] - in.p[0], in.p[2] - in.p[0]);
    } while (glm::length(face) < 0.05);
    face = glm::normalize(face);
    for (auto& n : in.n) {
      do {
        n = unit_vector();
      } while (glm::dot(n, face) < 0.5);
    }
    return in;
  }

  glm::dvec2 domain_point() {
    for (;;) {
      const double u = unit_(rng_), v = unit_(rng_);
      if (u + v <= 1.0) return {u, v};
    }
  }

 private:
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> coord_{-1.0, 1.0};
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
};

TEST(PnPatch, CornersInterpolatePositionsAndNormals) {
  RandomTriangles gen(1);
  const glm::dvec2 corners[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
  for (int trial = 0; trial < 200; ++trial) {
    const PnInput in = gen.next();
    for (NormalMode mode : kAllModes) {
      const PnPatch patch = make_patch(in, mode);
      EXPECT_EQ(patch.degenerate_edges, 0);
      for (int c = 0; c < 3; ++c) {
        const PnVertex bern = eval_bernstein(patch, corners[c].x, corners[c].y);
        const PnVertex cast = eval_de_casteljau(patch, corners[c].x, corners[c].y);
        EXPECT_TRUE(near(bern.position, in.p[c], 1e-14)) << to_string(mode) << " corner " << c;
        EXPECT_TRUE(near(cast.position, in.p[c], 1e-14)) << to_string(mode) << " corner " << c;
        // The derivative normal at a corner is the normal of the plane spanned by the two
        // tangent points, which are the edges projected onto the plane orthogonal to Ni.
        EXPECT_TRUE(near(bern.normal, in.n[c], 1e-12)) << to_string(mode) << " corner " << c;
        EXPECT_TRUE(near(cast.normal, in.n[c], 1e-12)) << to_string(mode) << " corner " << c;
      }
    }
  }
}

TEST(PnPatch, DeCasteljauEqualsBernsteinAndCountsIntOps) {
  RandomTriangles gen(2);
  const int L = 7;
  for (int trial = 0; trial < 200; ++trial) {
    PnInput in = gen.next();
    // Half of the trials take arbitrary unit normals (back-facing ones included).
    if (trial % 2)
      for (auto& n : in.n) n = gen.unit_vector();
    for (NormalMode mode : kAllModes) {
      const PnPatch patch = make_patch(in, mode);
      std::vector<glm::dvec2> points;
      for (const DomainPoint& d : pattern_points(L)) points.emplace_back(d.j / double(L), d.k / double(L));
      for (int r = 0; r < 20; ++r) points.push_back(gen.domain_point());
      for (const glm::dvec2& uv : points) {
        std::uint64_t ops = 0;
        const PnVertex cast = eval_de_casteljau(patch, uv.x, uv.y, &ops);
        const PnVertex bern = eval_bernstein(patch, uv.x, uv.y);
        ASSERT_EQ(ops, ops_per_vertex(mode)) << to_string(mode);
        EXPECT_TRUE(near(cast.position, bern.position, 1e-12)) << to_string(mode) << " at " << uv.x << "," << uv.y;
        EXPECT_TRUE(near(cast.normal, bern.normal, 1e-12)) << to_string(mode) << " at " << uv.x << "," << uv.y;
        EXPECT_NEAR(glm::length(cast.normal), 1.0, 1e-14);
        EXPECT_NEAR(glm::length(bern.normal), 1.0, 1e-14);
      }
    }
  }
}

TEST(PnPatch, IntOpsAccumulate) {
  RandomTriangles gen(3);
  const PnInput in = gen.next();
  for (NormalMode mode : kAllModes) {
    const PnPatch patch = make_patch(in, mode);
    std::uint64_t ops = 1000;  // the evaluator adds to the running total
    for (int i = 0; i < 5; ++i) eval_de_casteljau(patch, 0.2, 0.3, &ops);
    EXPECT_EQ(ops, 1000 + 5 * ops_per_vertex(mode)) << to_string(mode);
    EXPECT_EQ(de_casteljau_ops(mode), static_cast<int>(ops_per_vertex(mode))) << to_string(mode);
  }
}

TEST(PnPatch, PlanarPatchStaysPlanar) {
  RandomTriangles gen(4);
  for (int trial = 0; trial < 50; ++trial) {
    PnInput in = gen.next();
    const glm::dvec3 face = glm::normalize(glm::cross(in.p[1] - in.p[0], in.p[2] - in.p[0]));
    in.n = {face, face, face};
    Mesh mesh;
    mesh.source = "planar";
    mesh.positions = {in.p[0], in.p[1], in.p[2]};
    mesh.normals = {face, face, face};
    mesh.triangles = {glm::uvec3(0, 1, 2)};
    for (NormalMode mode : kAllModes) {
      std::size_t checked = 0;
      tessellate_mesh(mesh, 9, mode, [&](const PatchView& patch) {
        for (std::size_t i = 0; i < patch.positions.size(); ++i) {
          EXPECT_LE(std::abs(glm::dot(patch.positions[i] - in.p[0], face)), 1e-12) << to_string(mode);
          EXPECT_TRUE(near(patch.normals[i], face, 1e-12)) << to_string(mode);
          ++checked;
        }
      });
      EXPECT_EQ(checked, static_cast<std::size_t>(pattern_vertex_count(9)));
      const PnPatch patch = make_patch(in, mode);
      for (int r = 0; r < 20; ++r) {
        const glm::dvec2 uv = gen.domain_point();
        const PnVertex bern = eval_bernstein(patch, uv.x, uv.y);
        EXPECT_LE(std::abs(glm::dot(bern.position - in.p[0], face)), 1e-12) << to_string(mode);
        EXPECT_TRUE(near(bern.normal, face, 1e-12)) << to_string(mode);
      }
    }
  }
}

// Reflection of s across the plane orthogonal to e.
glm::dvec3 reflect_across(const glm::dvec3& s, const glm::dvec3& e) {
  return s - 2.0 * glm::dot(s, e) / glm::dot(e, e) * e;
}

TEST(PnPatch, ReflectMidEdgeNormalIsTheReflectedSum) {
  RandomTriangles gen(5);
  // Mid-edge domain points of edges 1-2, 2-3, 3-1.
  const glm::dvec2 mids[3] = {{0.5, 0.0}, {0.5, 0.5}, {0.0, 0.5}};
  double largest_quadratic_deviation = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const PnInput in = gen.next();
    const PnPatch reflect = make_patch(in, NormalMode::Reflect);
    const PnPatch quadratic = make_patch(in, NormalMode::Quadratic);
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      const glm::dvec3 expected =
          glm::normalize(reflect_across(in.n[i] + in.n[j], in.p[j] - in.p[i]));
      EXPECT_TRUE(near(eval_de_casteljau(reflect, mids[e].x, mids[e].y).normal, expected, 1e-12));
      EXPECT_TRUE(near(eval_bernstein(reflect, mids[e].x, mids[e].y).normal, expected, 1e-12));
      largest_quadratic_deviation =
          std::max(largest_quadratic_deviation,
                   glm::length(eval_de_casteljau(quadratic, mids[e].x, mids[e].y).normal - expected));
    }
  }
  // The property belongs to the reflect variant: the quadratic mode blends the reflected
  // direction with N1 + N2 and misses it.
  EXPECT_GT(largest_quadratic_deviation, 1e-3);
}

TEST(PnPatch, QuadraticMidEdgeNormalIsTheNormalizedReflection) {
  // With v_ij = 2 (Pj - Pi).(Ni + Nj) / |Pj - Pi|^2, n_ij = normalize(Ni + Nj - v_ij (Pj - Pi))
  // is the unit vector along the mirror image of Ni + Nj in the plane orthogonal to the edge.
  RandomTriangles gen(8);
  const glm::dvec2 mids[3] = {{0.5, 0.0}, {0.5, 0.5}, {0.0, 0.5}};
  const int mid_index[3] = {net_index(1, 0, 2), net_index(1, 1, 2), net_index(0, 1, 2)};
  for (int trial = 0; trial < 200; ++trial) {
    const PnInput in = gen.next();
    const PnPatch patch = make_patch(in, NormalMode::Quadratic);
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      const glm::dvec3 sum = in.n[i] + in.n[j];
      const glm::dvec3 n_ij = glm::normalize(reflect_across(sum, in.p[j] - in.p[i]));
      EXPECT_TRUE(near(patch.n_bern[mid_index[e]], n_ij / 2.0, 1e-14));
      // At the edge midpoint the field is (Ni + Nj)/4 + n_ij/4.
      const glm::dvec3 expected = glm::normalize(sum + n_ij);
      EXPECT_TRUE(near(eval_de_casteljau(patch, mids[e].x, mids[e].y).normal, expected, 1e-12));
    }
  }
}

TEST(PnPatch, EquilateralTriangleKnownValues) {
  // Unit equilateral triangle in z = 0, counter-clockwise seen from +z. Each normal leans
  // 45 degrees outward from the centroid: Ni = (r_i + z) / sqrt(2), r_i the unit direction
  // from the centroid V to Pi; circumradius R = 1/sqrt(3).
  const double s3 = std::sqrt(3.0);
  const double R = 1.0 / s3;
  PnInput in;
  in.p = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0.5, s3 / 2, 0)};
  const glm::dvec3 V(0.5, s3 / 6, 0);
  for (int c = 0; c < 3; ++c)
    in.n[c] = glm::normalize((in.p[c] - V) / R + glm::dvec3(0, 0, 1));

  // By hand: w_ij = -3R/(2 sqrt 2), so every tangent point is (2Pi + Pj)/3 + (R/4)(r_i + z);
  // E = V + (R/4) z, b111 = V + (3R/8) z, and the centre
  //   b(1/3,1/3,1/3) = (3V + 3(6E) + 6 b111) / 27 = V + (R/4) z = (1/2, sqrt3/6, sqrt3/12).
  const glm::dvec3 centre(0.5, s3 / 6, s3 / 12);
  // Mid-edge 1-2: (P1 + P2)/2 + (3/8)(R/4)(r1 + r2 + 2z) with r1 + r2 = -r3 = (0,-1,0):
  //   (1/2, -sqrt3/32, sqrt3/16).
  const glm::dvec3 mid12(0.5, -s3 / 32, s3 / 16);
  // N1 + N2 = (-r3 + 2z)/sqrt2 is orthogonal to P2 - P1, so v12 = t12 = 0 and the quadratic,
  // reflect and linear mid-edge normals all point along (0, -1, 2).
  const glm::dvec3 field_mid12 = glm::dvec3(0, -1, 2) / std::sqrt(5.0);
  // Derivative mode: the edge tangent at the midpoint is +x (mirror symmetry), and the
  // cross-edge derivative / 3 = (1/4)(b201 - b300) + (1/2)(b111 - b210) + (1/4)(b021 - b120)
  // has (y, z) = (17 sqrt3/96, 4 sqrt3/96); x times it points along (0, -4, 17).
  const glm::dvec3 surface_mid12 = glm::dvec3(0, -4, 17) / std::sqrt(305.0);

  for (NormalMode mode : kAllModes) {
    const PnPatch patch = make_patch(in, mode);
    for (int form = 0; form < 2; ++form) {
      auto eval = [&](double u, double v) {
        return form == 0 ? eval_bernstein(patch, u, v) : eval_de_casteljau(patch, u, v);
      };
      const PnVertex c = eval(1.0 / 3.0, 1.0 / 3.0);
      EXPECT_TRUE(near(c.position, centre, 1e-14)) << to_string(mode);
      EXPECT_TRUE(near(c.normal, glm::dvec3(0, 0, 1), 1e-14)) << to_string(mode);
      const PnVertex m = eval(0.5, 0.0);
      EXPECT_TRUE(near(m.position, mid12, 1e-14)) << to_string(mode);
      EXPECT_TRUE(near(m.normal, mode == NormalMode::Derivative ? surface_mid12 : field_mid12, 1e-14))
          << to_string(mode);
    }
  }
  // The control points themselves.
  const PnPatch patch = make_patch(in, NormalMode::Quadratic);
  EXPECT_TRUE(near(patch.b[net_index(1, 1, 3)], V + glm::dvec3(0, 0, 3 * R / 8), 1e-15));
  EXPECT_TRUE(near(patch.b[net_index(1, 0, 3)],
                   in.p[0] * (2.0 / 3) + in.p[1] / 3.0 + (R / 4) * ((in.p[0] - V) / R + glm::dvec3(0, 0, 1)),
                   1e-15));
  EXPECT_TRUE(near(patch.n_bern[net_index(1, 0, 2)], field_mid12 / 2.0, 1e-15));
}

TEST(PnPatch, ZeroLengthEdgeFallsBackAndIsCounted) {
  RandomTriangles gen(6);
  for (int trial = 0; trial < 20; ++trial) {
    PnInput in = gen.next();
    in.p[1] = in.p[0];  // edge 1-2 collapses
    for (NormalMode mode : kAllModes) {
      const PnPatch patch = make_patch(in, mode);
      EXPECT_EQ(patch.degenerate_edges, 1) << to_string(mode);
      // The mid-edge normal of the collapsed edge lies along N1 + N2: unit in quadratic mode,
      // unnormalized (|N1 + N2|, like every reflect mid-edge normal) in reflect mode.
      if (mode == NormalMode::Quadratic) {
        EXPECT_TRUE(near(patch.n_bern[net_index(1, 0, 2)], glm::normalize(in.n[0] + in.n[1]) / 2.0, 1e-15));
      }
      if (mode == NormalMode::Reflect) {
        EXPECT_TRUE(near(patch.n_bern[net_index(1, 0, 2)], (in.n[0] + in.n[1]) / 2.0, 1e-15));
      }
      for (const DomainPoint& d : pattern_points(6)) {
        for (const PnVertex& x : {eval_bernstein(patch, d.j / 6.0, d.k / 6.0),
                                  eval_de_casteljau(patch, d.j / 6.0, d.k / 6.0)}) {
          ASSERT_TRUE(is_finite(x.position) && is_finite(x.normal)) << to_string(mode);
          EXPECT_NEAR(glm::length(x.normal), 1.0, 1e-14) << to_string(mode);
        }
      }
    }
  }
}

TEST(PnPatch, DegenerateInputNeverProducesNaN) {
  RandomTriangles gen(7);
  const glm::dvec3 up(0, 0, 1);
  std::vector<std::pair<const char*, PnInput>> cases;
  {
    PnInput in = gen.next();
    in.p = {in.p[0], in.p[0], in.p[0]};  // a point: three zero-length edges
    cases.emplace_back("point", in);
  }
  {
    PnInput in;
    in.p = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
    in.n = {up, -up, up};  // opposite normals across edge 1-2 and edge 2-3
    cases.emplace_back("opposite normals", in);
  }
  {
    PnInput in;
    in.p = {glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 0), glm::dvec3(0, 1, 0)};
    in.n = {up, -up, up};  // opposite normals on a zero-length edge
    cases.emplace_back("opposite normals on a zero-length edge", in);
  }
  {
    PnInput in;
    in.p = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(2, 0, 0)};
    in.n = {up, up, up};  // collinear: zero area, but no zero-length edge
    cases.emplace_back("collinear", in);
  }
  for (const auto& [name, in] : cases) {
    for (NormalMode mode : kAllModes) {
      const PnPatch patch = make_patch(in, mode);
      for (const glm::dvec3& b : patch.b) ASSERT_TRUE(is_finite(b)) << name;
      for (const glm::dvec3& n : patch.n_bern) ASSERT_TRUE(is_finite(n)) << name;
      for (const DomainPoint& d : pattern_points(8)) {
        for (const PnVertex& x : {eval_bernstein(patch, d.j / 8.0, d.k / 8.0),
                                  eval_de_casteljau(patch, d.j / 8.0, d.k / 8.0)}) {
          ASSERT_TRUE(is_finite(x.position) && is_finite(x.normal)) << name << " " << to_string(mode);
          EXPECT_NEAR(glm::length(x.normal), 1.0, 1e-14) << name << " " << to_string(mode);
        }
      }
    }
  }
  EXPECT_EQ(make_patch(cases[0].second, NormalMode::Quadratic).degenerate_edges, 3);
  EXPECT_EQ(make_patch(cases[1].second, NormalMode::Quadratic).degenerate_edges, 0);
  EXPECT_EQ(make_patch(cases[2].second, NormalMode::Reflect).degenerate_edges, 1);
  EXPECT_EQ(make_patch(cases[3].second, NormalMode::Linear).degenerate_edges, 0);
}

Mesh two_triangle_mesh() {
  Mesh mesh;
  mesh.source = "two triangles";
  mesh.positions = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0.2), glm::dvec3(0, 1, 0.1), glm::dvec3(1, 1, 0.4)};
  for (const glm::dvec3& p : mesh.positions) mesh.normals.push_back(glm::normalize(glm::dvec3(-p.x, -p.y, 2.0)));
  mesh.triangles = {glm::uvec3(0, 1, 2), glm::uvec3(1, 3, 2)};
  return mesh;
}

TEST(Tessellate, RejectsFactorsOutOfRange) {
  const Mesh mesh = two_triangle_mesh();
  int calls = 0;
  auto sink = [&](const PatchView&) { ++calls; };
  EXPECT_THROW(tessellate_mesh(mesh, 0, NormalMode::Quadratic, sink), InputError);
  EXPECT_THROW(tessellate_mesh(mesh, -3, NormalMode::Quadratic, sink), InputError);
  EXPECT_THROW(tessellate_mesh(mesh, kMaxTessFactor + 1, NormalMode::Quadratic, sink), InputError);
  EXPECT_EQ(calls, 0);
  EXPECT_NO_THROW(tessellate_mesh(mesh, 1, NormalMode::Quadratic, sink));
  EXPECT_NO_THROW(tessellate_mesh(mesh, kMaxTessFactor, NormalMode::Quadratic, sink));
  EXPECT_EQ(calls, 4);
}

TEST(Tessellate, RejectsBrokenMeshesBeforeStreaming) {
  int calls = 0;
  auto sink = [&](const PatchView&) { ++calls; };
  Mesh bad_index = two_triangle_mesh();
  bad_index.triangles.push_back(glm::uvec3(0, 1, 4));
  EXPECT_THROW(tessellate_mesh(bad_index, 2, NormalMode::Quadratic, sink), InputError);
  Mesh nan_position = two_triangle_mesh();
  nan_position.positions[3].y = std::nan("");
  EXPECT_THROW(tessellate_mesh(nan_position, 2, NormalMode::Quadratic, sink), InputError);
  EXPECT_EQ(calls, 0);
}

TEST(Tessellate, StreamsPatchesInOrderThroughFixedBuffers) {
  const Mesh mesh = two_triangle_mesh();
  for (NormalMode mode : kAllModes) {
    for (int L : {1, 2, 5, 16}) {
      std::vector<std::uint32_t> order;
      const glm::dvec3* first_buffer = nullptr;
      const TessellationSummary s = tessellate_mesh(mesh, L, mode, [&](const PatchView& view) {
        order.push_back(view.triangle);
        EXPECT_EQ(view.L, L);
        ASSERT_EQ(view.positions.size(), static_cast<std::size_t>(pattern_vertex_count(L)));
        ASSERT_EQ(view.normals.size(), view.positions.size());
        if (!first_buffer) first_buffer = view.positions.data();
        EXPECT_EQ(view.positions.data(), first_buffer);  // no per-patch allocation
        // Patch vertices equal a direct evaluation of the same patch.
        const glm::uvec3 t = mesh.triangles[view.triangle];
        PnInput in;
        for (int c = 0; c < 3; ++c) {
          in.p[c] = mesh.positions[t[c]];
          in.n[c] = mesh.normals[t[c]];
        }
        const PnPatch patch = make_patch(in, mode);
        const auto points = pattern_points(L);
        for (std::size_t i = 0; i < points.size(); ++i) {
          const PnVertex x = eval_bernstein(patch, points[i].j / double(L), points[i].k / double(L));
          EXPECT_TRUE(near(view.positions[i], x.position, 1e-12));
          EXPECT_TRUE(near(view.normals[i], x.normal, 1e-12));
        }
      });
      EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 1}));
      EXPECT_EQ(s.patches, 2u);
      EXPECT_EQ(s.vertices, 2u * pattern_vertex_count(L));
      EXPECT_EQ(s.triangles, 2u * pattern_triangle_count(L));
      EXPECT_EQ(s.int_ops, s.vertices * ops_per_vertex(mode));
      EXPECT_EQ(s.degenerate_edges, 0u);
      EXPECT_EQ(s.degenerate_triangles, 0u);
    }
  }
}

// Large uniform jobs are evaluated on several threads (tessellate.cpp): the sink must still see
// every patch in input order, each bit-identical to a direct evaluation of the same patch, with
// the INT operations de Casteljau performs for them; and a sink that fails stops the workers and
// reaches the caller.
TEST(Tessellate, ParallelEvaluationKeepsOrderValuesAndSummary) {
  const Mesh mesh = load_mesh("/usr/share/assimp/models/PLY/Wuson.ply");
  const int L = 8;  // 3732 patches x 45 vertices: several batches
  const auto points = pattern_points(L);
  std::uint32_t expected = 0;
  std::uint64_t mismatches = 0, int_ops = 0;
  double max_difference = 0.0;
  const TessellationSummary s = tessellate_mesh(mesh, L, NormalMode::Quadratic, [&](const PatchView& view) {
    ASSERT_EQ(view.triangle, expected++);
    const glm::uvec3 t = mesh.triangles[view.triangle];
    PnInput in;
    for (int c = 0; c < 3; ++c) {
      in.p[c] = mesh.positions[t[c]];
      in.n[c] = mesh.normals[t[c]];
    }
    const PnPatch patch = make_patch(in, NormalMode::Quadratic);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double u = points[i].j / double(L), v = points[i].k / double(L);
      const PnVertex x = eval_bernstein(patch, u, v);
      mismatches += view.positions[i] != x.position || view.normals[i] != x.normal;
      // The same surface as de Casteljau, up to rounding.
      const PnVertex y = eval_de_casteljau(patch, u, v, &int_ops);
      max_difference = std::max({max_difference, glm::length(x.position - y.position), glm::length(x.normal - y.normal)});
    }
  });
  EXPECT_EQ(expected, mesh.triangles.size());
  EXPECT_EQ(mismatches, 0u);
  EXPECT_LT(max_difference, 1e-13);
  EXPECT_EQ(s.patches, mesh.triangles.size());
  EXPECT_EQ(s.vertices, mesh.triangles.size() * points.size());
  EXPECT_EQ(s.int_ops, int_ops);

  std::uint32_t seen = 0;
  EXPECT_THROW(tessellate_mesh(mesh, L, NormalMode::Quadratic,
                               [&](const PatchView& view) {
                                 if (view.triangle == 2500) throw std::runtime_error("disk full");
                                 ++seen;
                               }),
               std::runtime_error);
  EXPECT_EQ(seen, 2500u);
}

TEST(Tessellate, CountsDegenerateEdgesAndTriangles) {
  Mesh mesh = two_triangle_mesh();
  mesh.triangles.push_back(glm::uvec3(0, 0, 3));  // repeated vertex: one zero-length edge
  mesh.triangles.push_back(glm::uvec3(2, 2, 2));  // a point: three
  mesh.positions.push_back(glm::dvec3(2, 2, 0.8));  // collinear with vertices 0 and 3
  mesh.normals.push_back(glm::dvec3(0, 0, 1));
  mesh.triangles.push_back(glm::uvec3(0, 3, 4));
  for (NormalMode mode : kAllModes) {
    const TessellationSummary s = tessellate_mesh(mesh, 4, mode, [&](const PatchView& view) {
      for (std::size_t i = 0; i < view.positions.size(); ++i)
        ASSERT_TRUE(is_finite(view.positions[i]) && is_finite(view.normals[i]));
    });
    EXPECT_EQ(s.patches, 5u);
    EXPECT_EQ(s.degenerate_edges, 4u) << to_string(mode);
    EXPECT_EQ(s.degenerate_triangles, 3u) << to_string(mode);
  }
}

TEST(BoundingBox, CoversAllPositions) {
  const Mesh mesh = two_triangle_mesh();
  const BoundingBox box = bounding_box(mesh);
  EXPECT_EQ(box.lo, glm::dvec3(0, 0, 0));
  EXPECT_EQ(box.hi, glm::dvec3(1, 1, 0.4));
  EXPECT_DOUBLE_EQ(box.diagonal(), std::sqrt(2.16));
  EXPECT_EQ(bounding_box(Mesh{}).diagonal(), 0.0);
}

TEST(Tessellate, AdjacentPatchesShareEdgePointsOnARealMesh) {
  const std::filesystem::path file = "/usr/share/assimp/models/PLY/Wuson.ply";
  if (!std::filesystem::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
  const Mesh mesh = load_mesh(file);
  ASSERT_GT(mesh.triangle_count(), 100u);
  const double tol = 1e-12 * bounding_box(mesh).diagonal();
  const int L = 5;

  for (NormalMode mode : kAllModes) {
    // Every point on an edge, keyed by (lower vertex, upper vertex, steps from lower vertex).
    std::map<testing::EdgePointKey, std::pair<glm::dvec3, glm::dvec3>> first_seen;
    std::size_t compared = 0;
    double worst_position = 0.0, worst_normal = 0.0;
    testing::for_each_edge_point(mesh, L, mode, [&](const PatchView& view, std::size_t idx, const testing::EdgePointKey& key) {
      const auto [it, inserted] = first_seen.try_emplace(key, view.positions[idx], view.normals[idx]);
      if (inserted) return;
      ++compared;
      worst_position = std::max(worst_position, glm::length(view.positions[idx] - it->second.first));
      worst_normal = std::max(worst_normal, glm::length(view.normals[idx] - it->second.second));
    });
    EXPECT_GT(compared, mesh.triangle_count() * L);  // most edges are shared
    EXPECT_LE(worst_position, tol) << to_string(mode);
    // The normal fields along an edge depend only on that edge's data; the surface normal
    // (derivative mode) does not, since PN patches meet with C0 continuity only.
    if (mode != NormalMode::Derivative) {
      EXPECT_LE(worst_normal, 1e-12) << to_string(mode);
    }
    std::ostringstream measured;
    measured << "position " << worst_position / bounding_box(mesh).diagonal() << " of the diagonal, normal "
             << worst_normal << " over " << compared << " shared edge points";
    RecordProperty(std::string(to_string(mode)), measured.str());
  }
}

TEST(Tessellate, RealMeshWithDegenerateTrianglesStaysFinite) {
  // spider.obj has repeated vertices in some faces: zero-length edges and zero-area triangles.
  const std::filesystem::path file = "/usr/share/assimp/models/OBJ/spider.obj";
  if (!std::filesystem::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
  const Mesh mesh = load_mesh(file);
  for (NormalMode mode : kAllModes) {
    std::size_t bad = 0;
    const TessellationSummary s = tessellate_mesh(mesh, 3, mode, [&](const PatchView& view) {
      for (std::size_t i = 0; i < view.positions.size(); ++i)
        if (!is_finite(view.positions[i]) || !(std::abs(glm::length(view.normals[i]) - 1.0) <= 1e-14)) ++bad;
    });
    EXPECT_EQ(bad, 0u) << to_string(mode);
    EXPECT_GT(s.degenerate_edges, 0u) << to_string(mode);
    EXPECT_GT(s.degenerate_triangles, 0u) << to_string(mode);
    EXPECT_EQ(s.patches, mesh.triangle_count());
  }
}

}  // namespace
}  // namespace tessim
