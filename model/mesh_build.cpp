#include "model/mesh_build.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "model/base/error.hpp"

namespace tessim {

namespace {

// Relative: a sum shorter than this times the summed lengths is rounding, not a direction.
constexpr double kCancelTolerance = 1e-12;
const glm::dvec3 kFallbackNormal{0.0, 0.0, 1.0};

struct WeldKey {
  std::uint64_t x, y, z;
  bool operator==(const WeldKey&) const = default;
};

struct WeldKeyHash {
  std::size_t operator()(const WeldKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= k.y + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= k.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

// "(Δ = (x, y, z), σ = s, θ = t, β = b)" for messages.
std::string describe_tags(const VertexTags& t) {
  std::ostringstream s;
  s.precision(9);
  s << "(Δ = " << format_vec(t.delta) << ", σ = " << t.sigma << ", θ = " << t.theta << ", β = " << t.beta << ")";
  return s.str();
}

WeldKey weld_key(const glm::dvec3& p) {
  // + 0.0 turns -0.0 into +0.0 so that both weld together.
  return {std::bit_cast<std::uint64_t>(p.x + 0.0), std::bit_cast<std::uint64_t>(p.y + 0.0),
          std::bit_cast<std::uint64_t>(p.z + 0.0)};
}

}  // namespace

Mesh weld(const Mesh& mesh, const VertexNamer& name, std::vector<std::uint32_t>* first_copies) {
  const std::string file = mesh.source.empty() ? std::string("mesh") : mesh.source;
  auto vertex_name = [&](std::uint32_t v) { return name ? name(v) : "vertex " + std::to_string(v); };
  const bool tagged = !mesh.tags.empty();
  if (tagged && mesh.tags.size() != mesh.positions.size())
    throw InputError(file, "tags",
                     std::to_string(mesh.tags.size()) + " tag sets for " + std::to_string(mesh.positions.size()) + " vertices");
  Mesh out;
  out.source = mesh.source;
  std::unordered_map<WeldKey, std::uint32_t, WeldKeyHash> welded;
  std::vector<std::uint32_t> remap(mesh.positions.size());
  // First input vertex of each welded vertex, for messages.
  std::vector<std::uint32_t> origin;
  // File normals (unit) of every copy, keyed by welded vertex; deduplicated below.
  std::vector<std::pair<std::uint32_t, glm::dvec3>> normal_copies;

  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::dvec3& p = mesh.positions[v];
    if (out.positions.size() >= std::numeric_limits<std::uint32_t>::max())
      throw InputError(file, "vertices", "more than 2^32 - 1 distinct positions");
    const auto [it, inserted] = welded.try_emplace(weld_key(p), static_cast<std::uint32_t>(out.positions.size()));
    if (inserted) {
      out.positions.push_back(p);
      origin.push_back(static_cast<std::uint32_t>(v));
      if (tagged) out.tags.push_back(mesh.tags[v]);
    } else if (tagged && !(mesh.tags[v] == out.tags[it->second])) {
      const std::uint32_t first = origin[it->second];
      throw InputError(file, vertex_name(static_cast<std::uint32_t>(v)),
                       "its tags " + describe_tags(mesh.tags[v]) + " differ from those of " + vertex_name(first) + " " +
                           describe_tags(mesh.tags[first]) + ", with which it is welded at " + format_vec(p) +
                           " (copies of a vertex must carry the same tags)");
    }
    remap[v] = it->second;
    if (mesh.normals_from_file) {
      const glm::dvec3& n = mesh.normals[v];
      const double length = glm::length(n);
      // A zero-length copy carries no direction; it is an error only if no copy at this
      // position has one (checked below).
      if (length > 0.0 && std::isfinite(length)) normal_copies.emplace_back(it->second, n / length);
    }
  }
  out.triangles.reserve(mesh.triangles.size());
  for (const glm::uvec3& t : mesh.triangles) out.triangles.emplace_back(remap[t[0]], remap[t[1]], remap[t[2]]);
  if (first_copies) *first_copies = origin;
  if (!mesh.normals_from_file) return out;

  // Average the distinct normals at each position.
  std::sort(normal_copies.begin(), normal_copies.end(), [](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    if (a.second.x != b.second.x) return a.second.x < b.second.x;
    if (a.second.y != b.second.y) return a.second.y < b.second.y;
    return a.second.z < b.second.z;
  });
  normal_copies.erase(std::unique(normal_copies.begin(), normal_copies.end()), normal_copies.end());
  out.normals.assign(out.positions.size(), glm::dvec3(0.0));
  std::vector<std::size_t> copies(out.positions.size(), 0);
  for (const auto& [v, n] : normal_copies) {
    out.normals[v] += n;
    ++copies[v];
  }
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    auto element = [&] { return vertex_name(origin[v]); };
    if (copies[v] == 0)
      throw InputError(file, element(), "normal in the file has zero length (at " + format_vec(out.positions[v]) + ")");
    const double length = glm::length(out.normals[v]);
    if (!(length > kCancelTolerance * static_cast<double>(copies[v])))
      throw InputError(file, element(),
                       "the file's normals at " + format_vec(out.positions[v]) + " cancel out (" +
                           std::to_string(copies[v]) + " distinct normals summing to zero)");
    out.normals[v] /= length;
  }
  out.normals_from_file = true;
  return out;
}

std::vector<glm::dvec3> weighted_normals(const Mesh& mesh, std::size_t* fallbacks) {
  std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
  std::vector<double> magnitude(mesh.positions.size(), 0.0);
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const glm::dvec3 twice_area_normal = glm::cross(p[1] - p[0], p[2] - p[0]);
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 e1 = p[(c + 1) % 3] - p[c];
      const glm::dvec3 e2 = p[(c + 2) % 3] - p[c];
      const double angle = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
      const glm::dvec3 contribution = 0.5 * angle * twice_area_normal;  // area x angle x unit normal
      sum[t[c]] += contribution;
      magnitude[t[c]] += glm::length(contribution);
    }
  }
  std::size_t count = 0;
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double length = glm::length(sum[v]);
    if (magnitude[v] > 0.0 && length > kCancelTolerance * magnitude[v] && std::isfinite(length)) {
      sum[v] /= length;
    } else {
      sum[v] = kFallbackNormal;
      ++count;
    }
  }
  if (fallbacks) *fallbacks = count;
  return sum;
}

Mesh compute_normals(Mesh mesh) {
  mesh.normals = weighted_normals(mesh);
  mesh.normals_from_file = false;
  return mesh;
}

}  // namespace tessim
