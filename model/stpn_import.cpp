#include "model/stpn_import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "model/base/error.hpp"
#include "model/io/import.hpp"
#include "model/mesh_build.hpp"
#include "model/st_mesh.hpp"

namespace tessim {

namespace {

constexpr double kPi = 3.14159265358979323846;
// |N⁺ + N⁻| below this: the two sides face opposite ways (more than 179.9° apart) and have no
// reliable average normal N.
constexpr double kFoldLength = 2e-3;
// Relative: |n_T · Δ| below this times |n_T| |Δ| does not decide a side reliably.
constexpr double kSideMargin = 1e-9;

double radians(double degrees) { return degrees * kPi / 180.0; }

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }
  std::size_t groups() {
    std::size_t n = 0;
    for (std::size_t i = 0; i < parent_.size(); ++i) n += find(i) == i;
    return n;
  }

 private:
  std::vector<std::size_t> parent_;
};

// Compressed lists: the items of key k are items[begin[k] .. begin[k + 1]).
struct Lists {
  std::vector<std::size_t> begin;
  std::vector<std::uint32_t> items;
  std::span<const std::uint32_t> operator[](std::size_t k) const {
    return {items.data() + begin[k], begin[k + 1] - begin[k]};
  }
};

Lists make_lists(std::size_t keys, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  Lists l;
  l.begin.assign(keys + 1, 0);
  for (const auto& [k, item] : pairs) ++l.begin[k + 1];
  std::partial_sum(l.begin.begin(), l.begin.end(), l.begin.begin());
  l.items.resize(pairs.size());
  std::vector<std::size_t> next(l.begin.begin(), l.begin.end() - 1);
  for (const auto& [k, item] : pairs) l.items[next[k]++] = item;
  return l;
}

struct Edge {
  std::uint32_t a = 0, b = 0;          // a < b
  std::vector<std::uint32_t> faces;    // distinct triangles holding the edge
  bool crease = false;
  std::uint32_t other(std::uint32_t v) const { return v == a ? b : a; }
};

int corner_of(const glm::uvec3& tri, std::uint32_t v) { return tri[0] == v ? 0 : tri[1] == v ? 1 : 2; }

// What the fan of faces around a vertex is.
enum class VertexKind { Smooth, Crease, CreaseEnd, Corner, NonManifold };

// The two sides of a crease vertex.
struct CreaseSides {
  glm::dvec3 normal{0.0}, delta{0.0};
  double opening = 0.0;                      // angle between N⁺ and N⁻: sharpest first
  std::vector<std::uint32_t> faces;          // the vertex's faces ...
  std::vector<bool> plus;                    // ... and whether each lies on the N⁺ side
  bool defined = false;
};

}  // namespace

StImport make_st_mesh(const Mesh& mesh, std::span<const glm::dvec3> corner_normals, const StImportOptions& options) {
  const std::string file = mesh.source.empty() ? std::string("mesh") : mesh.source;
  const std::size_t vertex_count = mesh.positions.size(), triangle_count = mesh.triangles.size();
  if (mesh.normals.size() != vertex_count) throw std::logic_error("make_st_mesh: a normal per vertex is needed");
  if (!corner_normals.empty() && corner_normals.size() != 3 * triangle_count)
    throw std::logic_error("make_st_mesh: 3 corner normals per triangle");
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] >= vertex_count) throw InputError(file, "triangles", "vertex index " + std::to_string(t[c]) + " out of range");
  const double split_angle = radians(kNormalSplitAngle);
  const auto& P = mesh.positions;

  // Face normals exactly as make_stpn_patch computes them (it decides sides by their sign).
  std::vector<glm::dvec3> face_cross(triangle_count), face_unit(triangle_count, glm::dvec3(0.0));
  for (std::size_t t = 0; t < triangle_count; ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    face_cross[t] = glm::cross(P[tri[1]] - P[tri[0]], P[tri[2]] - P[tri[0]]);
    if (!is_zero_area(P[tri[0]], P[tri[1]], P[tri[2]])) face_unit[t] = glm::normalize(face_cross[t]);
  }
  auto file_normal = [&](std::size_t corner) -> std::optional<glm::dvec3> {
    const glm::dvec3 n = corner_normals[corner];
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    return n / length;
  };
  auto corner_normal = [&](std::uint32_t t, std::uint32_t v) {
    return file_normal(3 * t + static_cast<std::size_t>(corner_of(mesh.triangles[t], v)));
  };
  // Flat normals (every corner's its face's, up to the split angle, as flat-shaded exports
  // write them) split at every edge: they tell nothing about creases.
  bool faceted = !corner_normals.empty();
  for (std::size_t corner = 0; faceted && corner < corner_normals.size(); ++corner) {
    const glm::dvec3& face = face_unit[corner / 3];
    const auto n = file_normal(corner);
    if (n && face != glm::dvec3(0.0) && angle_between(*n, face) > split_angle) faceted = false;
  }
  const bool file_normals = !corner_normals.empty() && !faceted;

  StImport result;
  StImportSummary& summary = result.summary;
  summary.vertices = vertex_count;
  summary.triangles = triangle_count;
  summary.normal_splits = file_normals;
  summary.faceted_normals = faceted;
  summary.dihedral_test = !file_normals || options.crease_angle.has_value();
  summary.crease_angle = options.crease_angle.value_or(kDefaultCreaseAngle);
  const double crease_angle = radians(summary.crease_angle);

  // Edges and the faces around each.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> records;
  records.reserve(3 * triangle_count);
  for (std::uint32_t t = 0; t < triangle_count; ++t)
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t a = mesh.triangles[t][i], b = mesh.triangles[t][(i + 1) % 3];
      if (a != b) records.emplace_back(std::min(a, b) << 32 | std::max(a, b), t);
    }
  std::sort(records.begin(), records.end());
  records.erase(std::unique(records.begin(), records.end()), records.end());
  std::vector<Edge> edges;
  for (const auto& [key, t] : records) {
    if (edges.empty() || (std::uint64_t{edges.back().a} << 32 | edges.back().b) != key)
      edges.push_back({static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key & 0xFFFFFFFFu), {}, false});
    edges.back().faces.push_back(t);
  }
  for (Edge& e : edges) {
    if (e.faces.size() != 2) continue;
    const std::uint32_t t1 = e.faces[0], t2 = e.faces[1];
    if (summary.dihedral_test && face_unit[t1] != glm::dvec3(0.0) && face_unit[t2] != glm::dvec3(0.0) &&
        angle_between(face_unit[t1], face_unit[t2]) > crease_angle)
      e.crease = true;
    if (file_normals)
      for (const std::uint32_t v : {e.a, e.b}) {
        const auto n1 = corner_normal(t1, v), n2 = corner_normal(t2, v);
        if (n1 && n2 && angle_between(*n1, *n2) > split_angle) e.crease = true;
      }
    summary.crease_edges += e.crease;
  }

  std::vector<std::pair<std::uint32_t, std::uint32_t>> vertex_faces, vertex_edges;
  for (std::uint32_t t = 0; t < triangle_count; ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c)
      if (corner_of(tri, tri[c]) == c) vertex_faces.emplace_back(tri[c], t);  // a repeated vertex once
  }
  for (std::uint32_t e = 0; e < edges.size(); ++e) {
    vertex_edges.emplace_back(edges[e].a, e);
    vertex_edges.emplace_back(edges[e].b, e);
  }
  const Lists faces_of = make_lists(vertex_count, vertex_faces);
  const Lists edges_of = make_lists(vertex_count, vertex_edges);

  // Classify every vertex by the sides its creases cut its fan into; sides of crease vertices.
  std::vector<VertexKind> kind(vertex_count, VertexKind::Smooth);
  std::vector<CreaseSides> sides(vertex_count);
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    const auto faces = faces_of[v];
    if (faces.empty()) continue;
    auto local = [&](std::uint32_t t) {
      return static_cast<std::size_t>(std::find(faces.begin(), faces.end(), t) - faces.begin());
    };
    UnionFind fan(faces.size()), sector(faces.size());
    std::size_t creases = 0;
    bool non_manifold = false;
    for (const std::uint32_t e : edges_of[v]) {
      const Edge& edge = edges[e];
      if (edge.faces.size() > 2) non_manifold = true;
      if (edge.faces.size() != 2) continue;
      fan.join(local(edge.faces[0]), local(edge.faces[1]));
      if (edge.crease) ++creases;
      else sector.join(local(edge.faces[0]), local(edge.faces[1]));
    }
    if (non_manifold || fan.groups() > 1) {
      kind[v] = VertexKind::NonManifold;
      continue;
    }
    const std::size_t side_count = sector.groups();
    if (side_count >= 3) kind[v] = VertexKind::Corner;
    else if (side_count == 2) kind[v] = VertexKind::Crease;
    else kind[v] = creases > 0 ? VertexKind::CreaseEnd : VertexKind::Smooth;
    if (kind[v] != VertexKind::Crease) continue;

    // N⁺ from the side holding the vertex's first face, N⁻ from the other: the file's distinct
    // normals there averaged, or else the area x angle weighted face normals.
    CreaseSides& s = sides[v];
    s.faces.assign(faces.begin(), faces.end());
    const std::size_t plus_root = sector.find(0);
    for (std::size_t i = 0; i < faces.size(); ++i) s.plus.push_back(sector.find(i) == plus_root);
    glm::dvec3 side_normal[2];
    bool side_defined[2] = {false, false};
    for (int side = 0; side < 2; ++side) {
      const bool plus = side == 0;
      if (file_normals) {
        std::vector<glm::dvec3> distinct;
        for (std::size_t i = 0; i < faces.size(); ++i)
          if (s.plus[i] == plus)
            if (const auto n = corner_normal(faces[i], v)) distinct.push_back(*n);
        std::sort(distinct.begin(), distinct.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
          return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
        });
        distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
        glm::dvec3 sum(0.0);
        for (const glm::dvec3& n : distinct) sum += n;
        if (glm::length(sum) > 1e-12 * static_cast<double>(distinct.size())) {
          side_normal[side] = glm::normalize(sum);
          side_defined[side] = true;
          continue;
        }
      }
      glm::dvec3 sum(0.0);
      for (std::size_t i = 0; i < faces.size(); ++i) {
        if (s.plus[i] != plus) continue;
        const glm::uvec3& tri = mesh.triangles[faces[i]];
        const int c = corner_of(tri, v);
        const glm::dvec3 e1 = P[tri[(c + 1) % 3]] - P[v], e2 = P[tri[(c + 2) % 3]] - P[v];
        const double angle = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
        sum += 0.5 * angle * face_cross[faces[i]];
      }
      const double length = glm::length(sum);
      if (length > 0.0 && std::isfinite(length)) {
        side_normal[side] = sum / length;
        side_defined[side] = true;
      }
    }
    if (!side_defined[0] || !side_defined[1]) continue;
    const glm::dvec3 sum = side_normal[0] + side_normal[1];
    const double length = glm::length(sum);
    if (!(length > kFoldLength)) continue;
    // N = (N⁺ + N⁻)/|N⁺ + N⁻| and Δ = (N⁺ − N⁻)/|N⁺ + N⁻|: then N ± Δ = 2 N± / |N⁺ + N⁻|, so
    // the sharp normal normalize(N ± σΔ) is exactly N⁺ or N⁻ at σ = 1.
    s.normal = sum / length;
    s.delta = (side_normal[0] - side_normal[1]) / length;
    s.opening = angle_between(side_normal[0], side_normal[1]);
    s.defined = s.delta != glm::dvec3(0.0);
  }

  // Neighbours of each vertex, for the two rules.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> neighbour_pairs;
  for (const Edge& e : edges) {
    neighbour_pairs.emplace_back(e.a, e.b);
    neighbour_pairs.emplace_back(e.b, e.a);
  }
  const Lists neighbours = make_lists(vertex_count, neighbour_pairs);

  // Tag crease vertices, sharpest first (then by index), each only if the rules still hold
  // with it: at most 2 tagged neighbours for it and for each tagged neighbour, at most 2
  // tagged vertices in each of its triangles.
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    if (kind[v] != VertexKind::Crease) continue;
    ++summary.crease_vertices;
    if (sides[v].defined) candidates.push_back(v);
    else ++summary.folded;
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return sides[a].opening > sides[b].opening; });
  std::vector<bool> tagged(vertex_count, false);
  std::vector<int> tagged_around(vertex_count, 0);
  auto may_tag = [&](std::uint32_t v) {
    bool allowed = tagged_around[v] <= 2;
    for (const std::uint32_t u : neighbours[v]) allowed = allowed && (!tagged[u] || tagged_around[u] < 2);
    for (const std::uint32_t t : faces_of[v]) {
      const glm::uvec3& tri = mesh.triangles[t];
      const int c = corner_of(tri, v);
      const std::uint32_t a = tri[(c + 1) % 3], b = tri[(c + 2) % 3];
      if (a != b && a != v && b != v && tagged[a] && tagged[b]) allowed = false;
    }
    return allowed;
  };
  auto tag = [&](std::uint32_t v) {
    tagged[v] = true;
    for (const std::uint32_t u : neighbours[v]) ++tagged_around[u];
  };
  for (const std::uint32_t v : candidates) {
    if (may_tag(v)) tag(v);
    else ++summary.restricted;
  }

  // Where a crease from a tagged vertex ends (a crease end or a corner), tag the end too, with
  // σ = 0, where the rules allow: the crease edge then has two tagged ends (δ = 1), so the
  // vertex before it keeps its σ (see the closing pass below). With σ = 0 and β = 0 the end's
  // own coefficients and normal stay those of an untagged vertex. Its Δ is the crease vector
  // of the first such crease edge, from the normals of the edge's two faces.
  std::vector<glm::dvec3> end_delta(vertex_count, glm::dvec3(0.0));
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    if (kind[v] != VertexKind::CreaseEnd && kind[v] != VertexKind::Corner) continue;
    for (const std::uint32_t e : edges_of[v]) {
      const Edge& edge = edges[e];
      if (!edge.crease || !tagged[edge.other(v)]) continue;
      const glm::dvec3 n1 = face_unit[edge.faces[0]], n2 = face_unit[edge.faces[1]];
      const double length = glm::length(n1 + n2);
      if (!(length > kFoldLength) || n1 == n2) continue;
      end_delta[v] = (n1 - n2) / length;
      break;
    }
    if (end_delta[v] != glm::dvec3(0.0) && may_tag(v)) tag(v);
  }

  Mesh& out = result.mesh;
  out.source = mesh.source;
  out.positions = mesh.positions;
  out.normals = mesh.normals;
  out.triangles = mesh.triangles;
  out.normals_from_file = mesh.normals_from_file;
  out.tags.assign(vertex_count, VertexTags{});
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    switch (kind[v]) {
      case VertexKind::Corner:
        ++summary.corners;
        out.tags[v].theta = options.corner_tension;
        break;
      case VertexKind::CreaseEnd: ++summary.crease_ends; break;
      case VertexKind::NonManifold: ++summary.non_manifold; break;
      default: break;
    }
    if (!tagged[v]) continue;
    if (kind[v] != VertexKind::Crease) {
      ++(kind[v] == VertexKind::Corner ? summary.corners_tagged : summary.crease_ends_tagged);
      out.tags[v].delta = end_delta[v];
      continue;
    }
    ++summary.tagged;
    out.normals[v] = sides[v].normal;
    out.tags[v].delta = sides[v].delta;
    out.tags[v].sigma = options.sigma;
  }

  // Keep the surface closed. The tangent coefficient of a tagged vertex on an edge to an
  // untagged one depends, through σ, on the side of the crease the triangle lies on, which
  // make_stpn_patch decides by the sign of (face normal)·Δ. Where that sign does not follow the
  // vertex's sides, or the two faces of such an edge fall on different sides (a crease running
  // into an untagged vertex), σ = 0 makes the coefficient side-free: softened.
  if (options.sigma != 0.0) {
    for (std::uint32_t v = 0; v < vertex_count; ++v) {
      if (!tagged[v] || kind[v] != VertexKind::Crease) continue;
      const glm::dvec3& delta = out.tags[v].delta;
      auto on_plus_side = [&](std::uint32_t t) { return glm::dot(face_cross[t], delta) >= 0.0; };
      // A sign within rounding of zero could come out the other way in make_stpn_patch (another
      // compiler's contractions): such a face counts as on the wrong side.
      auto decided = [&](std::uint32_t t) {
        return std::abs(glm::dot(face_cross[t], delta)) > kSideMargin * glm::length(face_cross[t]) * glm::length(delta);
      };
      bool wrong_side = false, open_end = false;
      for (std::size_t i = 0; i < sides[v].faces.size(); ++i)
        wrong_side = wrong_side || !decided(sides[v].faces[i]) || on_plus_side(sides[v].faces[i]) != sides[v].plus[i];
      for (const std::uint32_t e : edges_of[v]) {
        if (tagged[edges[e].other(v)]) continue;
        for (const std::uint32_t t : edges[e].faces) open_end = open_end || on_plus_side(t) != on_plus_side(edges[e].faces[0]);
      }
      if (!wrong_side && !open_end) continue;
      out.tags[v].sigma = 0.0;
      ++summary.softened;
      if (wrong_side) ++summary.softened_sides;
      else ++summary.softened_ends;
    }
  }

  try {
    validate_tags(out);
  } catch (const InputError& e) {
    throw std::logic_error(std::string("stpn import broke the tag rules: ") + e.what());
  }
  return result;
}

StImport import_st_mesh(const std::filesystem::path& path, const StImportOptions& options,
                        std::vector<std::string>* warnings) {
  io::ImportedMesh imported = io::import_mesh(path);
  // An ST-mesh given again: its tags are replaced by the ones found here, which is said, not
  // done silently (it loses whatever was set by hand). They are still checked as every command
  // checks them, on the welded mesh: a malformed file is refused, not silently repaired by
  // replacing what is wrong in it; and the count is of welded vertices, as `tessim info` counts.
  const bool has_tags = std::any_of(imported.mesh.tags.begin(), imported.mesh.tags.end(),
                                    [](const VertexTags& t) { return !t.neutral(); });
  if (has_tags) {
    std::vector<std::uint32_t> first_copies;
    Mesh given = weld(imported.mesh, [&](std::uint32_t v) { return imported.vertex_name(v); }, &first_copies);
    if (!given.normals_from_file) given = compute_normals(std::move(given));
    validate_tags(given, [&](std::uint32_t v) { return imported.vertex_name(first_copies[v]); });
    const auto acting =
        std::count_if(given.tags.begin(), given.tags.end(), [](const VertexTags& t) { return !t.neutral(); });
    imported.warnings.push_back(path.string() + ": tags: " + std::to_string(acting) +
                                " vertices already carry scalar tags; they are replaced by the tags derived from "
                                "the mesh's creases (the file's own tags are not kept)");
  }
  for (const std::string& w : imported.warnings) {
    if (warnings) warnings->push_back(w);
    else std::fprintf(stderr, "tessim: warning: %s\n", printable_text(w, 960).c_str());
  }
  imported.mesh.tags.clear();  // replaced by the ones found here
  Mesh mesh = weld(imported.mesh, [&](std::uint32_t v) { return imported.vertex_name(v); });
  if (!mesh.normals_from_file) mesh = compute_normals(std::move(mesh));
  std::vector<glm::dvec3> corner_normals;
  if (imported.mesh.normals_from_file) {
    corner_normals.reserve(3 * imported.mesh.triangles.size());
    for (const glm::uvec3& t : imported.mesh.triangles)
      for (int c = 0; c < 3; ++c) corner_normals.push_back(imported.mesh.normals[t[c]]);
  }
  return make_st_mesh(mesh, corner_normals, options);
}

}  // namespace tessim
