#include "sim/run/reference_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "model/silhouette.hpp"

namespace tessim::sim {

void ErrorAccumulator::add_position(double relative_error) {
  ++e_.vertices;
  e_.position_max = std::max(e_.position_max, relative_error);
  sum_pos2_ += relative_error * relative_error;
}

void ErrorAccumulator::add_normal_angle(double radians) {
  ++e_.normals_compared;
  e_.normal_angle_max = std::max(e_.normal_angle_max, radians);
  sum_ang2_ += radians * radians;
}

ErrorStats ErrorAccumulator::result() const {
  ErrorStats r = e_;
  if (r.vertices) r.position_rms = std::sqrt(sum_pos2_ / static_cast<double>(r.vertices));
  if (r.normals_compared) r.normal_angle_rms = std::sqrt(sum_ang2_ / static_cast<double>(r.normals_compared));
  return r;
}

namespace {

std::string vec_str(const FxVec& v) {
  std::ostringstream os;
  os << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return os.str();
}

// The angle between two directions, accurate for small angles too (acos of a dot product near 1
// cannot resolve angles below about 1e-8 rad, where the bounds of wide formats lie).
double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

std::string describe(const VertexFx& x) {
  std::ostringstream os;
  os << "patch " << x.id;
  if (x.L > 0) os << " (j,k)=(" << x.j << "," << x.k << ") L=" << x.L;
  else os << " point " << x.index << " (ring " << x.j << ", edge " << x.k << ")";
  os << " pos=" << vec_str(x.pos)
     << " nrm=" << vec_str(x.nrm) << " u=" << x.u << " v=" << x.v << (x.last ? " last" : "")
     << (x.flags ? " flags=" + std::to_string(x.flags) : "");
  return os.str();
}

ArithmeticCheck::ArithmeticCheck(TriangleLookup triangle, double diagonal, const UnitConfig& cfg)
    : triangle_(std::move(triangle)), cfg_(cfg), budget_(position_error_budget(cfg.format)), diagonal_(diagonal) {}

double ArithmeticCheck::diagonal_of(const std::vector<TriangleFx>& stream, const NumberFormat& fmt) {
  if (stream.empty()) return 1.0;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const TriangleFx& t : stream)
    for (const FxVec& p : t.p) {
      const glm::dvec3 x = dequantize(p, fmt);
      lo = glm::min(lo, x);
      hi = glm::max(hi, x);
    }
  return std::max(glm::length(hi - lo), 1e-12);
}

ArithmeticCheck ArithmeticCheck::for_mesh(const Mesh& mesh, const HostScaling& scaling, const UnitConfig& cfg,
                                          MeshPatterns patterns) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::dvec3& p : mesh.positions) {
    const glm::dvec3 x = dequantize(quantize(scaling.to_unit(p), cfg.format), cfg.format);
    lo = glm::min(lo, x);
    hi = glm::max(hi, x);
  }
  const double diagonal = mesh.positions.empty() ? 1.0 : std::max(glm::length(hi - lo), 1e-12);
  return ArithmeticCheck(
      [&mesh, scaling, cfg, patterns](std::uint32_t id) {
        // Only patches that produced vertices are looked up: never a culled one.
        if (patterns.d3d11)
          return with_alpha(*to_fixed(mesh, id, scaling, cfg.format, *patterns.d3d11, cfg.cpg_tags), patterns, id, cfg.format);
        return with_alpha(to_fixed(mesh, id, scaling, cfg.format,
                                   patterns.factors.empty() ? cfg.tess_factor : patterns.factors[id], cfg.cpg_tags),
                          patterns, id, cfg.format);
      },
      diagonal, cfg);
}

bool ArithmeticCheck::check(const VertexFx& v) {
  // A clamped patch is outside the bound's premise (no result left the range): counted, not compared.
  if (v.flags & kFlagSaturated) {
    ++saturated_;
    return true;
  }
  if (patch_id_ != v.id) {
    const TriangleFx tri = triangle_(v.id);
    patch_tagged_ = !(tri.tags[0].neutral() && tri.tags[1].neutral() && tri.tags[2].neutral());
    if (patch_tagged_) {
      std::array<VertexTags, 3> tags;
      for (int c = 0; c < 3; ++c)
        tags[c] = {dequantize(tri.tags[c].delta, cfg_.format), std::ldexp(double(tri.tags[c].sigma), -cfg_.format.coord_frac_bits),
                   std::ldexp(double(tri.tags[c].theta), -cfg_.format.coord_frac_bits),
                   std::ldexp(double(tri.tags[c].beta), -cfg_.format.coord_frac_bits)};
      patch_ = make_stpn_patch(dequantized_input(tri, cfg_.format), tags, cfg_.normals);
    } else if (cfg_.format.takes_alpha()) {
      // The blend with the alpha the unit received (the host's rounding of the float alpha is
      // the interface's, docs/number-formats.md; the bound covers the unit's arithmetic).
      const PnInput in = dequantized_input(tri, cfg_.format);
      PatchSilhouette s;
      for (std::size_t e = 0; e < 3; ++e) {
        s.alpha[e] = std::ldexp(static_cast<double>(tri.alpha[e]), -kAlphaFracBits);
        s.normals[e] = in.n[e];
      }
      patch_ = make_silhouette_patch(in, s, cfg_.normals);
    } else {
      patch_ = make_patch(dequantized_input(tri, cfg_.format), cfg_.normals);
    }
    normal_bound_ = normal_error_bound(tri, cfg_.normals, cfg_.format);
    patch_id_ = v.id;
  }
  const double scale = static_cast<double>(cfg_.format.bary_one());
  const PnVertex ref = eval_bernstein(patch_, static_cast<double>(v.u) / scale, static_cast<double>(v.v) / scale);
  const glm::dvec3 pos = dequantize(v.pos, cfg_.format);
  const glm::dvec3 nrm = dequantize(v.nrm, cfg_.format);
  const double pos_err = glm::length(pos - ref.position);
  acc_.add_position(pos_err / diagonal_);
  if (patch_tagged_) {  // measured against the scalar-tagged reference; no derived bound yet
    ++scalar_tagged_;
    const double len = glm::length(nrm);
    if (len > 0 && glm::length(ref.normal) > 0)
      acc_.add_normal_angle(angle_between(nrm, ref.normal));
    return true;
  }
  bool beyond = pos_err > budget_.position_units + 1e-12;
  std::string why =
      beyond ? "position error " + std::to_string(pos_err) + " > bound " + std::to_string(budget_.position_units) : "";
  const double len = glm::length(nrm);
  const double angle_bound = normal_angle_bound(normal_bound_, len);
  if (angle_bound >= 0) {  // the output normal has a direction to compare
    const double angle = angle_between(nrm, ref.normal);
    acc_.add_normal_angle(angle);
    if (angle > angle_bound + 1e-9) {
      beyond = true;
      why = "normal angle " + std::to_string(angle) + " rad > bound " + std::to_string(angle_bound);
    }
  }
  if (beyond) {
    if (beyond_ == 0) worst_ = describe(v) + ": " + why;
    ++beyond_;
  }
  return !beyond;
}

ArithmeticErrors ArithmeticCheck::result() const {
  ArithmeticErrors e{acc_.result(), beyond_, saturated_, scalar_tagged_, worst_};
  return e;
}

MeshErrors::MeshErrors(const Mesh& mesh, const HostScaling& scaling, const UnitConfig& cfg, bool scalar_tagged,
                       const TessSettings* d3d11, const MeshSilhouette* silhouette)
    : mesh_(mesh), scaling_(scaling), cfg_(cfg), scalar_tagged_(scalar_tagged && mesh.has_tags()),
      silhouette_(cfg.format.takes_alpha() ? silhouette : nullptr), diagonal_(bounding_box(mesh).diagonal()) {
  if (!(diagonal_ > 0)) diagonal_ = 1.0;  // a single point: absolute errors
  if (d3d11 && d3d11->kind == PatternKind::D3D11) d3d11_.emplace(*d3d11);
}

VertexErrors MeshErrors::add(const VertexFx& v) {
  if (patch_id_ != v.id) {
    const glm::uvec3& tri = mesh_.triangles[v.id];
    PnInput in;
    std::array<VertexTags, 3> tags{};
    for (int c = 0; c < 3; ++c) {
      in.p[c] = mesh_.positions[tri[c]];
      in.n[c] = mesh_.normals[tri[c]];
      if (scalar_tagged_) tags[c] = mesh_.tags[tri[c]];
    }
    if (silhouette_) {  // the float alpha: the host's rounding of it is part of the measured error
      PatchSilhouette s;
      s.alpha = silhouette_->alpha(v.id);
      s.normals = in.n;
      patch_ = make_silhouette_patch(in, s, cfg_.normals);
    } else {
      patch_ = scalar_tagged_ ? make_stpn_patch(in, tags, cfg_.normals) : make_patch(in, cfg_.normals);
    }
    patch_id_ = v.id;
    // A copy: the cache may drop its patterns when it grows.
    if (v.L == 0 && d3d11_) patch_points_ = d3d11_->pattern(mesh_, v.id).points;
  }
  // The reference at the exact domain point, as `tessim tessellate` evaluates it: (j/L, k/L) of
  // the uniform pattern, the 16.16 point of a D3D11 pattern (L = 0; exact in B >= 16 bits), which
  // is the reference pattern's point of that index: the unit's walk and the reference are two
  // implementations of the pattern (docs/patterns.md §8).
  glm::dvec2 point;
  if (v.L > 0) {
    const double segments = static_cast<double>(v.L);
    point = {v.j / segments, v.k / segments};
  } else {
    point = {std::ldexp(static_cast<double>(v.u), -cfg_.format.bary_bits),
             std::ldexp(static_cast<double>(v.v), -cfg_.format.bary_bits)};
    const auto i = static_cast<std::size_t>(v.index);
    if (d3d11_ && (i >= patch_points_.size() || patch_points_[i] != point))
      throw std::logic_error("cycle model: D3D11 vertex " + describe(v) + " is not point " + std::to_string(i) +
                             " of the reference pattern of its patch");
  }
  const PnVertex ref = eval_de_casteljau(patch_, point.x, point.y);
  const glm::dvec3 pos = position_from_fixed(v.pos, scaling_, cfg_.format);
  VertexErrors e;
  e.position = glm::length(pos - ref.position) / diagonal_;
  acc_.add_position(e.position);
  const glm::dvec3 nrm = normal_from_fixed(v.nrm, cfg_.format);
  if (glm::length(nrm) > 0) {  // a vanished normal has no direction to compare
    e.normal_angle = angle_between(nrm, ref.normal);
    acc_.add_normal_angle(*e.normal_angle);
  }
  return e;
}

nlohmann::json to_json(const ErrorStats& e) {
  return {{"vertices", e.vertices},
          {"normals_compared", e.normals_compared},
          {"position_max", e.position_max},
          {"position_rms", e.position_rms},
          {"normal_angle_max", e.normal_angle_max},
          {"normal_angle_rms", e.normal_angle_rms}};
}

nlohmann::json to_json(const ArithmeticErrors& e) {
  nlohmann::json j = to_json(e.stats);
  j["beyond_bound"] = e.beyond_bound;
  j["saturated_vertices"] = e.saturated;
  j["scalar_tagged_vertices"] = e.scalar_tagged;
  if (!e.worst.empty()) j["worst"] = e.worst;
  return j;
}

}  // namespace tessim::sim
