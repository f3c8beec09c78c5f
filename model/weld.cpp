#include "model/weld.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "model/mesh_io.hpp"
#include "model/pattern.hpp"

namespace tessim {

WeldKey domain_key(const glm::uvec3& triangle, std::uint64_t wn, std::uint64_t un, std::uint64_t vn,
                   std::uint64_t den) {
  std::array<std::pair<std::uint64_t, std::uint64_t>, 3> terms{};  // (mesh vertex, reduced weight)
  int n = 0;
  const std::array<std::uint64_t, 3> weights{wn, un, vn};
  for (int i = 0; i < 3; ++i) {
    if (weights[static_cast<std::size_t>(i)] == 0) continue;
    const std::uint64_t w = weights[static_cast<std::size_t>(i)];
    const std::uint64_t g = std::gcd(w, den);
    terms[static_cast<std::size_t>(n++)] = {triangle[i], (w / g) << 32 | (den / g)};
  }
  for (int i = 1; i < n; ++i)  // at most three terms: insertion sort by vertex
    for (int j = i; j > 0 && terms[static_cast<std::size_t>(j)] < terms[static_cast<std::size_t>(j - 1)]; --j)
      std::swap(terms[static_cast<std::size_t>(j)], terms[static_cast<std::size_t>(j - 1)]);
  WeldKey key;
  key.fill(~std::uint64_t{0});
  for (int i = 0; i < n; ++i) {
    key[static_cast<std::size_t>(2 * i)] = terms[static_cast<std::size_t>(i)].first;
    key[static_cast<std::size_t>(2 * i + 1)] = terms[static_cast<std::size_t>(i)].second;
  }
  return key;
}

void patch_weld_keys(const Mesh& mesh, const PatchView& patch, std::vector<WeldKey>& keys) {
  const glm::uvec3 tri = mesh.triangles[patch.triangle];
  keys.clear();
  if (patch.L > 0) {
    const auto L = static_cast<std::uint64_t>(patch.L);
    for (const DomainPoint& p : pattern_points(patch.L)) {
      const auto j = static_cast<std::uint64_t>(p.j), k = static_cast<std::uint64_t>(p.k);
      keys.push_back(domain_key(tri, L - j - k, j, k, L));
    }
    return;
  }
  constexpr double kOne = 65536.0;
  for (const glm::dvec2& uv : patch.domain) {
    const double u = uv.x * kOne, v = uv.y * kOne;
    if (u != std::floor(u) || v != std::floor(v) || u < 0 || v < 0 || u + v > kOne)
      throw std::logic_error("patch_weld_keys: a domain point is not 16.16 fixed point");
    const auto qu = static_cast<std::uint64_t>(u), qv = static_cast<std::uint64_t>(v);
    keys.push_back(domain_key(tri, 65536 - qu - qv, qu, qv, 65536));
  }
}

WeldKey bits_key(const glm::dvec3& p, const glm::dvec3& n) {
  return {std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y), std::bit_cast<std::uint64_t>(p.z),
          std::bit_cast<std::uint64_t>(n.x), std::bit_cast<std::uint64_t>(n.y), std::bit_cast<std::uint64_t>(n.z)};
}

std::size_t WeldingWriter::KeyHash::operator()(const WeldKey& k) const {
  std::uint64_t h = 0x9E3779B97F4A7C15ull;
  for (std::uint64_t w : k) {
    h ^= w + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ull;
  }
  return static_cast<std::size_t>(h ^ (h >> 31));
}

void WeldingWriter::add_patch(std::span<const glm::dvec3> positions, std::span<const glm::dvec3> normals,
                              std::span<const WeldKey> keys, std::span<const std::uint32_t> indices) {
  if (positions.size() != normals.size() || positions.size() != keys.size())
    throw std::invalid_argument("WeldingWriter: positions, normals and keys differ in number");
  std::vector<std::uint32_t> local(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto [it, inserted] = index_.try_emplace(keys[i], static_cast<std::uint32_t>(positions_.size()));
    if (inserted) {
      if (positions_.size() >= std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("WeldingWriter: more than 2^32 - 1 vertices");
      positions_.push_back(positions[i]);
      normals_.push_back(normals[i]);
    }
    local[i] = it->second;
  }
  vertices_in_ += positions.size();
  for (std::uint32_t i : indices) indices_.push_back(local.at(i));
}

void WeldingWriter::write(const std::filesystem::path& path) const {
  MeshWriter writer(path, positions_.size(), triangles());
  writer.add_patch(positions_, normals_, indices_);
  writer.finish();
}

}  // namespace tessim
