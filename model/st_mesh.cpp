#include "model/st_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "model/base/error.hpp"

namespace tessim {

namespace {

// Relative: a sum shorter than this times its summands' lengths has no reliable direction.
constexpr double kVanishing = 1e-12;
constexpr std::size_t kListedViolations = 10;

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(9);
  s << x;
  return s.str();
}

// Distinct edges between distinct vertices, as sorted (low, high) pairs.
std::vector<std::pair<std::uint32_t, std::uint32_t>> mesh_edges(const Mesh& mesh) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const glm::uvec3& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      if (a != b) edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

bool vanishes(const glm::dvec3& sum, double summand_lengths) {
  return !(glm::length(sum) > kVanishing * summand_lengths);
}

// Which normalization of docs/mathematics.md §9 would divide by zero at a tagged vertex with
// normal `n`, if any.
std::optional<std::string> vanishing_normal(const glm::dvec3& n, const VertexTags& t) {
  const double delta = glm::length(t.delta);
  for (const double side : {1.0, -1.0}) {
    const glm::dvec3 sum = n + side * t.sigma * t.delta;
    const char* which = side > 0 ? "N + σΔ" : "N − σΔ";
    if (vanishes(sum, glm::length(n) + t.sigma * delta)) return std::string(which) + " vanishes";
    const glm::dvec3 blend = (1.0 - t.sigma) * n + t.sigma * glm::normalize(sum);
    if (vanishes(blend, std::abs(1.0 - t.sigma) * glm::length(n) + t.sigma))
      return std::string("(1 − σ) N + σ N' vanishes on the side of ") + which;
  }
  if (vanishes(n + t.beta * t.delta, glm::length(n) + std::abs(t.beta) * delta)) return std::string("N + βΔ vanishes");
  return std::nullopt;
}

}  // namespace

std::optional<std::string> tag_value_problem(const VertexTags& t) {
  const std::pair<const char*, double> values[] = {{"dx", t.delta.x}, {"dy", t.delta.y}, {"dz", t.delta.z},
                                                    {"sigma", t.sigma}, {"theta", t.theta}, {"beta", t.beta}};
  for (const auto& [property, value] : values)
    if (!std::isfinite(value)) return "tag " + std::string(property) + " is " + format_number(value) + " (tags must be finite)";
  if (t.sigma < 0.0) return "sharpness sigma " + format_number(t.sigma) + " is negative (it is in [0, inf))";
  if (t.theta < -1.0 || t.theta > 1.0) return "tension theta " + format_number(t.theta) + " is outside [-1, 1]";
  if (t.beta < -1.0 || t.beta > 1.0) return "bias beta " + format_number(t.beta) + " is outside [-1, 1]";
  return std::nullopt;
}

void validate_tags(const Mesh& mesh, const VertexNamer& name) {
  if (mesh.tags.empty()) return;
  const std::string file = mesh.source.empty() ? std::string("mesh") : mesh.source;
  auto vertex = [&](std::uint32_t v) { return name ? name(v) : "vertex " + std::to_string(v); };
  if (mesh.tags.size() != mesh.positions.size())
    throw InputError(file, "tags",
                     std::to_string(mesh.tags.size()) + " tag sets for " + std::to_string(mesh.positions.size()) + " vertices");
  const bool have_normals = mesh.normals.size() == mesh.positions.size();
  for (std::uint32_t v = 0; v < mesh.tags.size(); ++v) {
    const VertexTags& t = mesh.tags[v];
    if (const auto problem = tag_value_problem(t)) throw InputError(file, vertex(v), *problem);
    if (!t.tagged() || !have_normals) continue;
    if (const auto problem = vanishing_normal(mesh.normals[v], t))
      throw InputError(file, vertex(v),
                       "its tags leave a normal of the scalar-tagged formulas undefined: " + *problem + " (N " +
                           format_vec(mesh.normals[v]) + ", Δ " + format_vec(t.delta) + ", σ " + format_number(t.sigma) +
                           ", β " + format_number(t.beta) + ")");
  }

  // The two rules, every violation collected: (element, reason).
  std::vector<std::pair<std::string, std::string>> violations;
  std::vector<std::vector<std::uint32_t>> tagged_neighbours(mesh.positions.size());
  for (const auto& [a, b] : mesh_edges(mesh)) {
    if (a >= mesh.tags.size() || b >= mesh.tags.size()) continue;  // tessellate_mesh reports bad indices
    if (!mesh.tags[a].tagged() || !mesh.tags[b].tagged()) continue;
    tagged_neighbours[a].push_back(b);
    tagged_neighbours[b].push_back(a);
  }
  for (std::uint32_t v = 0; v < tagged_neighbours.size(); ++v) {
    const auto& around = tagged_neighbours[v];
    if (around.size() <= 2) continue;
    std::string list;
    for (std::uint32_t u : around) list += (list.empty() ? "" : ", ") + vertex(u);
    violations.emplace_back(vertex(v), "tagged, with " + std::to_string(around.size()) + " tagged neighbours (" + list +
                                           "); a tagged vertex may have at most 2 (docs/stpn.md)");
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    if (tri[0] >= mesh.tags.size() || tri[1] >= mesh.tags.size() || tri[2] >= mesh.tags.size()) continue;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) continue;  // fewer than 3 vertices
    if (!mesh.tags[tri[0]].tagged() || !mesh.tags[tri[1]].tagged() || !mesh.tags[tri[2]].tagged()) continue;
    violations.emplace_back("triangle " + std::to_string(t),
                            "all three of its vertices (" + vertex(tri[0]) + ", " + vertex(tri[1]) + ", " +
                                vertex(tri[2]) + ") are tagged; a triangle may have at most 2 (docs/stpn.md)");
  }
  if (violations.empty()) return;
  std::string reason = violations.front().second;
  if (violations.size() > 1) {
    reason += "; " + std::to_string(violations.size() - 1) + " more violation" + (violations.size() > 2 ? "s" : "") +
              " of the tag rules at ";
    for (std::size_t i = 1; i < violations.size() && i <= kListedViolations; ++i)
      reason += (i > 1 ? ", " : "") + violations[i].first;
    if (violations.size() - 1 > kListedViolations) reason += ", ...";
  }
  throw InputError(file, violations.front().first, reason);
}

TagStats tag_stats(const Mesh& mesh) {
  TagStats s;
  if (mesh.tags.empty()) return s;
  s.present = true;
  bool first_tagged = true, first_vertex = true;
  for (const VertexTags& t : mesh.tags) {
    if (first_vertex) s.theta_min = s.theta_max = t.theta;
    first_vertex = false;
    s.theta_min = std::min(s.theta_min, t.theta);
    s.theta_max = std::max(s.theta_max, t.theta);
    if (!t.tagged()) {
      if (t.theta > 0.0) ++s.corner_like;
      continue;
    }
    ++s.tagged;
    if (t.sigma > 0.0) ++s.crease;
    else ++s.softened;
    const double delta = glm::length(t.delta);
    if (first_tagged) {
      s.sigma_min = s.sigma_max = t.sigma;
      s.beta_min = s.beta_max = t.beta;
      s.delta_min = s.delta_max = delta;
      first_tagged = false;
    }
    s.sigma_min = std::min(s.sigma_min, t.sigma);
    s.sigma_max = std::max(s.sigma_max, t.sigma);
    s.beta_min = std::min(s.beta_min, t.beta);
    s.beta_max = std::max(s.beta_max, t.beta);
    s.delta_min = std::min(s.delta_min, delta);
    s.delta_max = std::max(s.delta_max, delta);
  }
  for (const auto& [a, b] : mesh_edges(mesh))
    if (a < mesh.tags.size() && b < mesh.tags.size() && mesh.tags[a].tagged() && mesh.tags[b].tagged()) ++s.tagged_edges;
  return s;
}

}  // namespace tessim
