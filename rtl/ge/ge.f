// The geometry-engine ALU lanes costed against the unit (scripts/ge_lane_cost.sh), not part of
// the unit: the package first, then the lanes. Paths are relative to this file.
../tess_pkg.sv
ge_fma_lane.sv
ge_mac_lane.sv
ge_shader_lane.sv
ge_simd_issue.sv
