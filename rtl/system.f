// The system of units' SystemVerilog sources (tess_system: distributor, units, reassembly
// buffer), read after rtl/tess.f (the unit's list, unchanged: its cost records stay valid), the
// modules in name order. Paths are relative to this file.
tess_distributor.sv
tess_patch_count.sv
tess_reassembly.sv
tess_system.sv
