// Named assertions of the unit, after lowRISC Ibex's prim_assert.sv: one macro per kind, the
// name first, so that a failure names the property (and a waveform viewer or a formal tool can
// address it). Names end in _A.
//
//   `TESS_ASSERT(Name, Prop, Clk, Rst)        concurrent: Prop holds at every rising edge of Clk
//                                             while Rst is 0 (Prop may use |->, |=>, $stable, $past)
//   `TESS_ASSERT_KNOWN(Name, Sig, Clk, Rst)   X check (Ibex's ASSERT_KNOWN): no bit of Sig is X or
//                                             Z at a rising edge of Clk while Rst is 0. Verilator
//                                             is 2-state, so only a 4-state simulator can see it
//                                             fail (tests/rtl/x_check_test.sh, under iverilog)
//   `TESS_ASSERT_PARAM(Name, Cond)            elaboration: the parameters satisfy Cond, or
//                                             elaboration stops with an error naming Name
//                                             (Verilator and Yosys; under iverilog at time 0)
//
// They are checked in the Verilated builds with --assert (n2_verif, docs/rtl.md); a failure is
// an $error, which RtlUnit::tick turns into rtl::RtlAssertionError. Under SYNTHESIS (Yosys
// defines it) TESS_ASSERT and TESS_ASSERT_KNOWN expand to nothing, so they cost nothing and leave
// the cost records unchanged; TESS_ASSERT_PARAM stays (a generate-if whose branch is empty for a
// valid configuration), so that synthesis refuses what simulation refuses.
// TESS_ASSERT_IMMEDIATE (defined by a testbench for simulators without concurrent assertions,
// such as iverilog 11) turns the X checks into immediate checks at the clock edge and drops the
// concurrent ones.
//
// rtl/tess.f lists this file first, so every tool that reads the list has the macros before any
// module. A module includes it only when they are not defined yet: Yosys finds the file beside
// the module, Verilator only with -I rtl (docs/rtl.md, Lint).
`ifndef TESS_ASSERT_SVH
`define TESS_ASSERT_SVH

`ifdef SYNTHESIS
`define TESS_ASSERT(Name, Prop, Clk, Rst)
`define TESS_ASSERT_KNOWN(Name, Sig, Clk, Rst)
`elsif TESS_ASSERT_IMMEDIATE
`define TESS_ASSERT(Name, Prop, Clk, Rst)
`define TESS_ASSERT_KNOWN(Name, Sig, Clk, Rst) \
  always @(posedge Clk) begin : Name \
    if (!(Rst) && $isunknown(Sig)) $error("%m: %s failed", `"Name`"); \
  end
`else
`define TESS_ASSERT(Name, Prop, Clk, Rst) \
  Name: assert property (@(posedge Clk) disable iff (Rst) (Prop)) \
    else $error("%m: %s failed", `"Name`");
`define TESS_ASSERT_KNOWN(Name, Sig, Clk, Rst) \
  `TESS_ASSERT(Name, !$isunknown(Sig), Clk, Rst)
`endif

`ifdef TESS_ASSERT_IMMEDIATE
// iverilog 11 takes no elaboration task in a generate block: the check runs at time 0 instead.
`define TESS_ASSERT_PARAM(Name, Cond) \
  if (!(Cond)) begin : Name \
    initial $fatal(1, `"Name: parameter out of range`"); \
  end
`else
`define TESS_ASSERT_PARAM(Name, Cond) \
  if (!(Cond)) begin : Name \
    $error(`"Name: parameter out of range`"); \
  end
`endif

`endif
