// Scalar-tagged meshes (ST-meshes, docs/stpn.md): the checks every tagged mesh passes before
// it is tessellated, and the tag statistics of `tessim info`.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "model/mesh.hpp"
#include "model/mesh_build.hpp"

namespace tessim {

// Why one vertex's tags are unusable, or nothing: a value that is NaN or infinite, σ < 0, θ or
// β outside [-1, 1].
std::optional<std::string> tag_value_problem(const VertexTags& tags);

// Checks a tagged mesh (nothing to check when it has no tags): one tag set per vertex, every
// value usable (tag_value_problem), the normalizations of docs/mathematics.md §9 defined
// (N ± σΔ, N + βΔ and the blend (1 − σ) N + σ N' do not vanish), and the two rules of the
// format — a tagged vertex has at most 2 tagged neighbours, a triangle at most 2 tagged
// vertices. Throws InputError naming the file, the first offending vertex (by `name`) or
// triangle, and the reason; the message lists further violations of the two rules, up to ten.
void validate_tags(const Mesh& mesh, const VertexNamer& name = {});

// What `tessim info` shows about the tags of a mesh.
struct TagStats {
  bool present = false;              // the mesh carries tags (all zero counts as present)
  std::size_t tagged = 0;            // Δ != 0
  std::size_t crease = 0;            // tagged with σ > 0: a sharp crease passes through
  std::size_t softened = 0;          // tagged with σ = 0: marks a crease edge, normal stays N
  std::size_t corner_like = 0;       // untagged with θ > 0: tangents pulled onto the vertex
  std::size_t tagged_edges = 0;      // edges between two tagged vertices (δ = 1: crease edges)
  double sigma_min = 0.0, sigma_max = 0.0;  // over tagged vertices (0, 0 with none)
  double theta_min = 0.0, theta_max = 0.0;  // over all vertices
  double beta_min = 0.0, beta_max = 0.0;    // over tagged vertices
  double delta_min = 0.0, delta_max = 0.0;  // |Δ| over tagged vertices
};
TagStats tag_stats(const Mesh& mesh);

}  // namespace tessim
