// The unit's datapath without its timing: what the CPG, the DPG and the INT blocks compute for
// a patch, in the plain order of the mathematics (control points, then de Casteljau level by
// level, docs/mathematics.md §6), with the unit's fixed-point operations (sim/base/fixed.hpp,
// sim/values/cpg.hpp). The cycle model and the RTL must produce exactly these vertices whatever
// their schedule; the tests and the co-simulation check them against it. Written from the nets'
// indexing (model/pn.hpp, net_index), not from the TE's operation table (sim/base/int_ops.hpp), so
// that the table is checked too.
#pragma once

#include <vector>

#include "model/normal_mode.hpp"
#include "sim/base/fixed.hpp"
#include "sim/values/cpg.hpp"
#include "sim/values/unit_io.hpp"

namespace tessim::sim {

// The vertex at lattice point (j, k) of a patch with factor L and id `id`, from its control points.
VertexFx evaluate_vertex(const ControlPointsFx& cp, int j, int k, int L, std::uint32_t id, NormalMode mode,
                         const NumberFormat& format);

// Every vertex of a triangle's patch, in the order the unit emits them (DPG order: j fastest).
std::vector<VertexFx> evaluate_patch(const TriangleFx& tri, NormalMode mode, const NumberFormat& format);

}  // namespace tessim::sim
