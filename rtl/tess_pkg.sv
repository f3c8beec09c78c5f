// Parameters, encodings and constants of the PN tessellation unit, in one place.
// The defaults match sim/config/config.hpp (UnitConfig); the arithmetic constants match
// sim/base/fixed.hpp. Every module names items as tess_pkg::NAME (no wildcard import: the
// Yosys 0.23 front end rejects `import pkg::*`).
package tess_pkg;

  // ---- configuration defaults (docs/microarchitecture.md §1) ----
  // A configuration that overrides a default leaves it unused; that is not a defect.
  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned CoordIntBits  = 3;   // I
  localparam int unsigned CoordFracBits = 20;  // F
  localparam int unsigned BaryBits      = 16;  // B
  localparam int unsigned AlphaBits     = 0;   // A: silhouette weight fraction bits; 0 = no alpha (plain PN)
  localparam int unsigned IntBlocks     = 2;   // N
  localparam int unsigned IntLatency    = 1;   // Λ
  localparam int unsigned Contexts      = 4;   // V
  localparam int unsigned TriFifoDepth  = 2;   // Dt
  localparam int unsigned VtxFifoDepth  = 2;   // Dv
  localparam int unsigned CpBuffers     = 2;   // Nb: control-point buffers between CPG and TE
  localparam int unsigned CpgLanes      = 1;   // CPG edge lanes: 1 (edges in turn) or 3 (at once)
  localparam int unsigned CpgDigitBits  = 1;   // r: CPG divider / square-root bits per cycle
  localparam int unsigned CpgCopies     = 1;   // Mc: CPGs taking successive triangles in turn
  localparam int unsigned CpgProductReg = 0;   // 1: the CPG's multiplier products are registered
  localparam int unsigned CpgTags       = 0;   // 1: the input stream carries scalar tags (STPN)
  // Deliberate faults that prove the co-simulation checker can fail:
  // 1 = INT rounding drops the +half (floor instead of round half up);
  // 2 = retirement of a patch's last vertex ignores a full VTX FIFO (the vertex is lost).
  localparam int unsigned InjectBug     = 0;
  /* verilator lint_on UNUSEDPARAM */

  // ---- fixed field widths of the interfaces (§3) ----
  localparam int unsigned FactorBits = 7;   // L in 1..64, lattice indices j, k in 0..64
  localparam int unsigned IdBits     = 32;
  localparam int unsigned FlagBits   = 2;
  localparam int unsigned ModeBits   = 2;
  localparam int unsigned MaxFactor  = 64;
  localparam int unsigned CounterBits = 64;

  // ---- tessellation patterns (§7; sim/values/cpg.hpp TriPattern) ----
  localparam int unsigned PatternBits = 2;
  localparam logic [1:0] PatUniform  = 2'd0;  // one factor L, the lattice (j/L, k/L)
  localparam logic [1:0] PatInteger  = 2'd1;  // D3D11 pattern, integer (and pow2) partitioning
  localparam logic [1:0] PatFracOdd  = 2'd2;  // D3D11 pattern, fractional_odd
  localparam logic [1:0] PatFracEven = 2'd3;  // D3D11 pattern, fractional_even
  localparam int unsigned FixBits    = 23;    // a D3D11 factor: unsigned 16.16, at most 64
  localparam int unsigned IndexBits  = 12;    // a point's index in its patch (< 3169)
  // The triangle's pattern descriptor: {factor[3] (inner), factor[2..0] (outer), pattern, L}.
  localparam int unsigned DescBits   = FactorBits + PatternBits + 4 * FixBits;
  // One edge's setup (tess_fsu_edge): {points 7, ceil weight 33, sum of the floor and ceil
  // weights 34, split 6, half points 6, odd 1}.
  localparam int unsigned EdgeBits   = 87;
  // A patch's setup (tess_fsu): {point count, inner points 7, inner edge, outer edges 2, 1, 0}.
  localparam int unsigned SetupBits  = 4 * EdgeBits + 7 + IndexBits;
  // What the control-point buffer keeps of a patch besides its nets: {setup, pattern, L}.
  localparam int unsigned PatchBits  = SetupBits + PatternBits + FactorBits;

  // ---- widths derived from the parameters, defined here only ----
  // Constant functions (Yosys 0.23 takes them written as an assignment to the function's name,
  // not `return`). w is the coordinate width W = 1 + CoordIntBits + CoordFracBits.
  // A TRI FIFO word: {alpha 3 (A + 1) (with AlphaBits), tags 18W (with CpgTags), id, descriptor, N 9W, P 9W}.
  function automatic int unsigned tri_w(int unsigned w, int unsigned cpg_tags, int unsigned alpha_bits);
    tri_w = 18 * w + DescBits + IdBits + ((cpg_tags != 0) ? 18 * w : 0)
            + ((alpha_bits != 0) ? 3 * (alpha_bits + 1) : 0);
  endfunction
  // A VTX FIFO word: {flags, last, id, index, l, k, j, v, u, nrm 3W, pos 3W}.
  function automatic int unsigned vtx_w(int unsigned w, int unsigned bary_bits);
    vtx_w = 6 * w + 2 * (bary_bits + 1) + 3 * FactorBits + IndexBits + IdBits + 1 + FlagBits;
  endfunction
  // Patches a unit holds at once (TRI FIFO, CPG copies, buffers, VTX FIFO, one more): bounds the
  // distributor's pending counters and the reassembly buffer's order queue.
  function automatic int unsigned unit_patches(int unsigned tri_fifo_depth, int unsigned cpg_copies,
                                                int unsigned cp_buffers, int unsigned vtx_fifo_depth);
    unit_patches = tri_fifo_depth + cpg_copies + cp_buffers + vtx_fifo_depth + 1;
  endfunction

  // ---- performance counters (§10) ----
  // tess_unit's perf_ctr_o carries counter k at [k CounterBits +: CounterBits], k one of these;
  // INT block i's busy cycles at CtrIntBusy + i (so they come last). The order is the counter
  // registry's (sim/base/counter_registry.hpp: its rows with an RTL counter, per-INT-block
  // rows last); tests/sim/counter_registry_test.cpp checks that the two lists agree.
  typedef enum int unsigned {
    CtrCycles,              // every cycle out of reset
    CtrTriIn,               // triangles accepted at the input
    CtrVtxOut,              // vertices accepted by the GPE
    CtrTriStalls,           // triangles refused (input back-pressure)
    CtrVtxStalls,           // vertices refused by the GPE (output back-pressure)
    CtrTeContextLimited,
    CtrTeIntLimited,
    CtrTeBusy,
    CtrTeBlockedByGpe,
    CtrTeStarvedByCpg,
    CtrTeIdle,
    CtrTePipeline,
    CtrCpgBusy,
    CtrCpgBlocked,
    CtrCpgIdle,
    CtrIntBusy              // first of IntBlocks
  } ctr_e;
  // Yosys 0.23 reads an enumerator inside a constant function only through a localparam.
  localparam int unsigned NumScalarCtrs = CtrIntBusy;
  function automatic int unsigned num_ctrs(int unsigned int_blocks);
    num_ctrs = NumScalarCtrs + int_blocks;
  endfunction

  // ---- normal modes (sim/values/cpg.hpp mode_code) ----
  localparam logic [1:0] ModeQuadratic = 2'd0;
  localparam logic [1:0] ModeReflect   = 2'd1;
  localparam logic [1:0] ModeLinear    = 2'd2;

  // ---- sticky patch flags (sim/base/fixed.hpp FxFlag) ----
  localparam logic [1:0] FlagSaturated = 2'b01;
  localparam logic [1:0] FlagDivByZero = 2'b10;

  // ---- control-point buffer states (§6) ----
  localparam logic [1:0] BufEmpty    = 2'd0;
  localparam logic [1:0] BufFull     = 2'd1;
  localparam logic [1:0] BufDraining = 2'd2;

  // ---- the 14 INT operations of a vertex (§8) ----
  localparam int unsigned NumOps = 14;
  // Ops that do not exist for a linear normal: allocated already issued and done.
  localparam logic [13:0] LinearSkipOps = 14'b01_0001_1000_0000;  // ops 7, 8, 12
  localparam int unsigned OpNormalL2 = 12;  // output normal, quadratic and reflect
  localparam int unsigned OpNormalL1 = 6;   // output normal, linear
  localparam int unsigned OpGeomL3   = 13;  // output position

  // ---- constants of the CPG (sim/base/fixed.hpp) ----
  // The divisions by 3 and 12 multiply by round(2^G / 3) and round(2^G / 12), G = F + 8.
  localparam int unsigned ConstGuardBits = 8;

endpackage
