// Scalar-tagged PN control points (model/pn.hpp make_stpn_patch, docs/mathematics.md §9):
// neutral tags give plain PN bit for bit, per patch and for a whole tagged mesh through
// tessellate_mesh; hand-computed cases for σ = 0, σ = 1, θ = ±1, β and a crease edge between two
// tagged vertices. Tagged meshes themselves: tests/model/st_mesh_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include "model/mesh_io.hpp"
#include "model/pn.hpp"
#include "model/tessellate.hpp"

namespace tessim {
namespace {

constexpr int kB210 = net_index(1, 0, 3);  // tangent coefficient nearest P1 on edge P1 -> P2
constexpr int kB120 = net_index(2, 0, 3);  // nearest P2 on edge P2 -> P1
constexpr int kN110 = net_index(1, 0, 2);

bool same_bits(const PnPatch& a, const PnPatch& b) {
  return std::memcmp(a.b.data(), b.b.data(), sizeof a.b) == 0 &&
         std::memcmp(a.n_bern.data(), b.n_bern.data(), sizeof a.n_bern) == 0 &&
         std::memcmp(a.n_corner.data(), b.n_corner.data(), sizeof a.n_corner) == 0;
}

void expect_near(const glm::dvec3& got, const glm::dvec3& want, double tol = 1e-12) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// A triangle in the plane z = 0, face normal +z, edge P1 -> P2 along x with length 3.
PnInput flat_triangle() {
  PnInput in;
  in.p = {glm::dvec3(0, 0, 0), glm::dvec3(3, 0, 0), glm::dvec3(0, 3, 0)};
  in.n = {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)};
  return in;
}

// N⁺ = (0.6, 0, 0.8), N⁻ = (−0.6, 0, 0.8): N = (0, 0, 1), Δ = (1.2, 0, 0).
VertexTags crease(double sigma) {
  VertexTags t;
  t.delta = glm::dvec3(1.2, 0, 0);
  t.sigma = sigma;
  return t;
}

TEST(Stpn, NeutralTagsAreExactlyPlainPn) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(-1.0, 1.0);
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear, NormalMode::Derivative}) {
    for (int trial = 0; trial < 200; ++trial) {
      PnInput in;
      for (int i = 0; i < 3; ++i) {
        in.p[i] = glm::dvec3(x(rng), x(rng), x(rng));
        in.n[i] = glm::normalize(glm::dvec3(x(rng), x(rng), x(rng)) + glm::dvec3(0, 0, 1.5));
      }
      std::array<VertexTags, 3> tags{};
      tags[1].sigma = 0.7;  // σ and β without Δ change nothing either
      tags[2].beta = -0.4;
      ASSERT_TRUE(same_bits(make_stpn_patch(in, tags, mode), make_patch(in, mode))) << to_string(mode) << " " << trial;
    }
  }
}

TEST(Stpn, SharpnessZeroKeepsTheAverageNormal) {
  const PnInput in = flat_triangle();
  const PnPatch plain = make_patch(in, NormalMode::Quadratic);
  const PnPatch st = make_stpn_patch(in, {crease(0.0), VertexTags{}, VertexTags{}}, NormalMode::Quadratic);
  for (std::size_t i = 0; i < plain.b.size(); ++i) expect_near(st.b[i], plain.b[i]);
  expect_near(st.n_corner[0], glm::dvec3(0, 0, 1));
}

TEST(Stpn, SharpnessOneTakesTheSideNormal) {
  const PnInput in = flat_triangle();
  const PnPatch st = make_stpn_patch(in, {crease(1.0), VertexTags{}, VertexTags{}}, NormalMode::Quadratic);
  // Face normal +z, Δ·(+z) = 0 >= 0: side +1. N' = normalize(N + Δ) = (1.2, 0, 1)/sqrt(2.44).
  const double len = std::sqrt(2.44);
  expect_near(st.n_corner[0], glm::dvec3(1.2 / len, 0, 1 / len));
  // X = N'; d = P1 + (P2 − P1)/3 = (1, 0, 0); b210 = d − (X·d) X = (1 − 1.44/2.44, 0, −1.2/2.44).
  expect_near(st.b[kB210], glm::dvec3(1.0 / 2.44, 0, -1.2 / 2.44));
  // The other end of the edge is untagged: plain PN there.
  expect_near(st.b[kB120], glm::dvec3(2, 0, 0));
  // N' replaces N1 in the normal field: the normal net is plain PN's with N1 = N'.
  PnInput sharp = in;
  sharp.n[0] = st.n_corner[0];
  const PnPatch field = make_patch(sharp, NormalMode::Quadratic);
  for (std::size_t i = 0; i < field.n_bern.size(); ++i) expect_near(st.n_bern[i], field.n_bern[i]);
  EXPECT_NE(st.n_bern[kN110], make_patch(in, NormalMode::Quadratic).n_bern[kN110]);
}

TEST(Stpn, TheOtherSideOfTheCreaseTakesTheOtherNormal) {
  PnInput in = flat_triangle();
  std::swap(in.p[1], in.p[2]);  // the same triangle wound the other way: face normal −z
  VertexTags t = crease(1.0);
  t.delta = glm::dvec3(1.2, 0, -0.5);  // Δ·face < 0 for face +z, > 0 for face −z
  const PnPatch down = make_stpn_patch(in, {t, VertexTags{}, VertexTags{}}, NormalMode::Quadratic);
  const PnPatch up = make_stpn_patch(flat_triangle(), {t, VertexTags{}, VertexTags{}}, NormalMode::Quadratic);
  // Face −z, side +1: N' = normalize(N + Δ); face +z, side −1: normalize(N − Δ).
  expect_near(down.n_corner[0], glm::normalize(glm::dvec3(1.2, 0, 0.5)));
  expect_near(up.n_corner[0], glm::normalize(glm::dvec3(-1.2, 0, 1.5)));
}

TEST(Stpn, TensionMovesTheTangentAlongTheEdge) {
  const PnInput in = flat_triangle();
  VertexTags full;
  full.theta = 1.0;  // d = P1: the tangent collapses onto the corner
  expect_near(make_stpn_patch(in, {full, VertexTags{}, VertexTags{}}, NormalMode::Quadratic).b[kB210],
              glm::dvec3(0, 0, 0));
  VertexTags slack;
  slack.theta = -1.0;  // d = P1 + 2/3 (P2 − P1), in the plane of N: unchanged by the projection
  expect_near(make_stpn_patch(in, {slack, VertexTags{}, VertexTags{}}, NormalMode::Quadratic).b[kB210],
              glm::dvec3(2, 0, 0));
}

TEST(Stpn, CreaseEdgeBetweenTwoTaggedVerticesUsesTheBias) {
  // P1 -> P2 along x, both tagged with a crease across the edge direction: Δ = (0, 1.2, 0),
  // N = normalize((0, 0.6, 0.8) + (0, −0.6, 0.8)) = (0, 0, 1). The edge leaves the tangent plane
  // of N: P2 is raised, so the projection Π(P1, N, d) is not zero.
  PnInput in = flat_triangle();
  in.p[1] = glm::dvec3(3, 0, 0.9);
  VertexTags a;
  a.delta = glm::dvec3(0, 1.2, 0);
  a.sigma = 1.0;
  a.beta = 0.5;
  VertexTags b = a;
  const PnPatch st = make_stpn_patch(in, {a, b, VertexTags{}}, NormalMode::Quadratic);
  // d = P1 + (P2 − P1)/3 = (1, 0, 0.3); Π(P1, N, d) = −0.3; Y = normalize(N + βΔ) = (0, 0.6, 1)/sqrt(1.36).
  const double len = std::sqrt(1.36);
  expect_near(st.b[kB210], glm::dvec3(1, 0, 0.3) - 0.3 * glm::dvec3(0, 0.6 / len, 1 / len));
  // With β = 0 the crease edge is projected along N itself.
  a.beta = b.beta = 0.0;
  expect_near(make_stpn_patch(in, {a, b, VertexTags{}}, NormalMode::Quadratic).b[kB210], glm::dvec3(1, 0, 0));
}

// A mesh whose tags are all zero (as a PLY file with tag properties of value 0 gives) tessellates
// exactly as the same mesh without tags, in every normal mode.
TEST(Stpn, ZeroTagsTessellateAWholeMeshExactlyAsPlainPn) {
  const std::filesystem::path file = "/usr/share/assimp/models/PLY/Wuson.ply";
  if (!std::filesystem::exists(file)) FAIL() << file << " is missing: scripts/setup.sh installs assimp-testmodels";
  const Mesh plain = load_mesh(file);
  ASSERT_FALSE(plain.has_tags());
  Mesh tagged = plain;
  tagged.tags.assign(plain.vertex_count(), VertexTags{});
  for (NormalMode mode : {NormalMode::Quadratic, NormalMode::Reflect, NormalMode::Linear, NormalMode::Derivative}) {
    std::vector<glm::dvec3> expected;
    const TessellationSummary a = tessellate_mesh(plain, 3, mode, [&](const PatchView& view) {
      expected.insert(expected.end(), view.positions.begin(), view.positions.end());
      expected.insert(expected.end(), view.normals.begin(), view.normals.end());
    });
    std::size_t at = 0, differing = 0;
    const TessellationSummary b = tessellate_mesh(tagged, 3, mode, [&](const PatchView& view) {
      for (const auto& span : {view.positions, view.normals})
        for (const glm::dvec3& x : span) differing += std::memcmp(&x, &expected[at++], sizeof x) != 0;
    });
    EXPECT_EQ(at, expected.size());
    EXPECT_EQ(differing, 0u) << to_string(mode);
    EXPECT_EQ(a.int_ops, b.int_ops);
    EXPECT_EQ(a.degenerate_edges, b.degenerate_edges);
  }
}

}  // namespace
}  // namespace tessim
