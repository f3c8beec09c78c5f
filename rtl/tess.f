// The unit's SystemVerilog sources, in the order every tool reads them: the assertion macros
// first (Verilator finds an `include only on -I paths, so the list gives it), then the package,
// then the modules in name order. Paths are relative to this file. Read by rtl/CMakeLists.txt,
// tests/CMakeLists.txt and scripts/ (synthesis, costs, lint); a new module is added here only.
tess_assert.svh
tess_pkg.sv
tess_cpbuf.sv
tess_cpg.sv
tess_cpg_array.sv
tess_cpg_edge.sv
tess_cpg_tag.sv
tess_div.sv
tess_dpg.sv
tess_fifo.sv
tess_fsu.sv
tess_fsu_edge.sv
tess_int.sv
tess_isqrt.sv
tess_sat.sv
tess_te.sv
tess_unit.sv
