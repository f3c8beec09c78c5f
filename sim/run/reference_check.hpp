// The unit's output against the float64 reference, vertex by vertex, in two measurements
// (docs/number-formats.md, Error analysis):
//  - ArithmeticCheck: the reference built from the quantized input triangle and evaluated at the
//    unit's own barycentric weights, so only the unit's arithmetic is measured; every vertex is
//    held to the derived bound (sim/values/error_bound.hpp). The co-simulation and `tessim sim
//    --errors` use it.
//  - MeshErrors: the reference of the mesh as the file gives it, evaluated at the exact domain
//    point (j/L, k/L), against the output in mesh coordinates: what a user of the unit sees
//    (input quantization, barycentric rounding and arithmetic together). `tessim sim --errors`
//    reports it; the study's error columns are these figures. A D3D11 vertex is evaluated at
//    its point of the reference's own pattern (model/d3d11_pattern.hpp), which the unit's point
//    must equal bit for bit.
// Positions are relative to the bounding-box diagonal, normal errors are angles in radians.
#pragma once

#include <cstdint>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "model/mesh.hpp"
#include "model/pn.hpp"
#include "model/tessellate.hpp"
#include "sim/config/config.hpp"
#include "sim/values/error_bound.hpp"
#include "sim/values/host.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// Maximum and root mean square of position and normal-angle errors.
struct ErrorStats {
  std::uint64_t vertices = 0;
  std::uint64_t normals_compared = 0;  // vertices whose output normal has a direction
  double position_max = 0, position_rms = 0;
  double normal_angle_max = 0, normal_angle_rms = 0;
};

class ErrorAccumulator {
 public:
  void add_position(double relative_error);
  void add_normal_angle(double radians);
  ErrorStats result() const;

 private:
  ErrorStats e_;
  double sum_pos2_ = 0, sum_ang2_ = 0;
};

struct ArithmeticErrors {
  ErrorStats stats;
  std::uint64_t beyond_bound = 0;  // vertices outside the derived bound
  std::uint64_t saturated = 0;     // vertices of saturated patches: the bound does not apply
  std::uint64_t scalar_tagged = 0; // vertices of tagged patches: measured, no bound derived yet
  std::string worst;               // the first vertex beyond the bound, and why
};

// Patch ids index `triangle(id)`: the quantized input the unit received for that patch.
class ArithmeticCheck {
 public:
  using TriangleLookup = std::function<TriangleFx(std::uint32_t id)>;
  // `diagonal`: of the input in unit coordinates (the denominator of the relative error).
  ArithmeticCheck(TriangleLookup triangle, double diagonal, const UnitConfig& cfg);

  // Returns false when the vertex lies outside the bound.
  bool check(const VertexFx& v);
  ArithmeticErrors result() const;

  // The bounding-box diagonal of a stream's dequantized positions.
  static double diagonal_of(const std::vector<TriangleFx>& stream, const NumberFormat& fmt);
  // The check of a whole mesh streamed with sim::MeshSource (each patch re-quantized on demand).
  // `patterns`: as simulate() takes them. With cfg.cpg_tags the mesh's tags go along, as the
  // unit receives them.
  static ArithmeticCheck for_mesh(const Mesh& mesh, const HostScaling& scaling, const UnitConfig& cfg,
                                  MeshPatterns patterns = {});

 private:
  TriangleLookup triangle_;
  UnitConfig cfg_;
  ErrorBudget budget_;
  double diagonal_ = 1.0;
  std::optional<std::uint32_t> patch_id_;  // the patch whose reference patch_ holds
  PnPatch patch_;
  double normal_bound_ = 0;
  ErrorAccumulator acc_;
  std::uint64_t beyond_ = 0;
  std::uint64_t saturated_ = 0;
  std::uint64_t scalar_tagged_ = 0;
  bool patch_tagged_ = false;
  std::string worst_;
};

// One output vertex against the reference: position error relative to the bounding-box
// diagonal, normal angle in radians (none when the output normal vanished).
struct VertexErrors {
  double position = 0;
  std::optional<double> normal_angle;
};

class MeshErrors {
 public:
  // `scalar_tagged`: the reference of a tagged mesh is its scalar-tagged surface (the output
  // came from the fixed-point scalar-tagged arithmetic); otherwise plain PN whatever the tags.
  // `d3d11`: the D3D11 settings the unit ran with (kept by reference), needed for D3D11 vertices.
  // `silhouette`: the alpha the host rounded for a unit that takes it (the reference is then the
  // blend with the float alpha), or none.
  MeshErrors(const Mesh& mesh, const HostScaling& scaling, const UnitConfig& cfg, bool scalar_tagged = false,
             const TessSettings* d3d11 = nullptr, const MeshSilhouette* silhouette = nullptr);
  // Measures the vertex, adds it to the statistics and returns its own errors (the heat maps
  // of `tessim render --color error-position|error-normal`). Throws std::logic_error for a
  // D3D11 vertex that is not its index's point of the reference pattern.
  VertexErrors add(const VertexFx& v);
  ErrorStats result() const { return acc_.result(); }

 private:
  const Mesh& mesh_;
  HostScaling scaling_;
  UnitConfig cfg_;
  bool scalar_tagged_ = false;
  const MeshSilhouette* silhouette_ = nullptr;
  double diagonal_ = 1.0;
  std::optional<std::uint32_t> patch_id_;
  PnPatch patch_;
  std::optional<PatternCache> d3d11_;     // the reference's D3D11 patterns
  std::vector<glm::dvec2> patch_points_;  // the current patch's points of it
  ErrorAccumulator acc_;
};

// One line per vertex for messages: patch, lattice point, factor, position, normal, weights.
std::string describe(const VertexFx& v);

nlohmann::json to_json(const ErrorStats& e);
nlohmann::json to_json(const ArithmeticErrors& e);

}  // namespace tessim::sim
