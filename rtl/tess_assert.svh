// Named assertions of the unit, after lowRISC Ibex's prim_assert.sv: one macro per kind, the
// name first, so that a failure names the property (and a waveform viewer or a formal tool can
// address it). Names end in _A.
//
//   `TESS_ASSERT(Name, Prop, Clk, Rst)  concurrent: Prop holds at every rising edge of Clk
//                                       while Rst is 0 (Prop may use |->, |=>, $stable, $past)
//
// They are checked in the Verilated builds with --assert (n2_verif, docs/rtl.md); a failure is
// an $error, which RtlUnit::tick turns into rtl::RtlAssertionError. Under SYNTHESIS (Yosys
// defines it) they expand to nothing.
//
// rtl/tess.f lists this file first, so every tool that reads the list has the macros before any
// module. A module includes it only when they are not defined yet: Yosys finds the file beside
// the module, Verilator only with -I rtl (docs/rtl.md, Lint).
`ifndef TESS_ASSERT_SVH
`define TESS_ASSERT_SVH

`ifndef SYNTHESIS
`define TESS_ASSERT(Name, Prop, Clk, Rst) \
  Name: assert property (@(posedge Clk) disable iff (Rst) (Prop)) \
    else $error("%m: %s failed", `"Name`");
`else
`define TESS_ASSERT(Name, Prop, Clk, Rst)
`endif

`endif
