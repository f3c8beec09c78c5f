// Parameters, encodings and constants of the PN tessellation unit, in one place.
// The defaults match sim/config.hpp (UnitConfig); the arithmetic constants match
// sim/fixed.hpp. Every module names items as tess_pkg::NAME (no wildcard import: the
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

  // ---- tessellation patterns (§7; sim/cpg.hpp TriPattern) ----
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

  // ---- normal modes (sim/cpg.hpp mode_code) ----
  localparam logic [1:0] ModeQuadratic = 2'd0;
  localparam logic [1:0] ModeReflect   = 2'd1;
  localparam logic [1:0] ModeLinear    = 2'd2;

  // ---- sticky patch flags (sim/fixed.hpp FxFlag) ----
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

  // ---- constants of the CPG (sim/fixed.hpp) ----
  // The divisions by 3 and 12 multiply by round(2^G / 3) and round(2^G / 12), G = F + 8.
  localparam int unsigned ConstGuardBits = 8;

endpackage
