#include "sim/run/output_check.hpp"

#include <stdexcept>
#include <string>

#include "model/pattern.hpp"
#include "sim/values/host.hpp"

namespace tessim::sim {

OutputCheck::OutputCheck(const Mesh& mesh, const MeshSource& source, const NumberFormat& format, bool d3d11)
    : mesh_(mesh), source_(source), format_(format), d3d11_(d3d11) {
  expect_patch(source.first());
}

void OutputCheck::expect_patch(std::uint64_t from) {
  for (; from < source_.end(); ++from) {
    const int points = source_.patch_points(from);
    if (points == 0) continue;
    id_ = static_cast<std::uint32_t>(from);
    patch_vertices_ = points;
    L_ = d3d11_ ? 0 : source_.factor(from);
    return;
  }
  id_ = static_cast<std::uint32_t>(source_.end());
}

void OutputCheck::check(const VertexFx& v, std::uint64_t cycle) {
  if (v.id != id_ || v.index != index_ || v.L != L_ || (L_ > 0 && pattern_index(v.j, v.k, v.L) != index_) ||
      v.last != (index_ == patch_vertices_ - 1))
    throw std::logic_error("cycle model: vertex (" + std::to_string(v.id) + ", " + std::to_string(v.j) + ", " +
                           std::to_string(v.k) + ") out of order at cycle " + std::to_string(cycle));
  if (index_ == 0) {
    check_patch_flags(mesh_, v.id, v.flags, format_);
    if (v.flags & kFlagDivByZero) ++degenerate_patches_;
  }
  if (v.nrm[0] == 0 && v.nrm[1] == 0 && v.nrm[2] == 0) ++zero_normals_;
  last_ = v.last;
}

void OutputCheck::next() {
  if (last_) {
    index_ = 0;
    expect_patch(std::uint64_t{id_} + 1);
  } else {
    ++index_;
  }
}

}  // namespace tessim::sim
