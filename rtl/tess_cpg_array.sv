// CPG array: CpgCopies copies of the CPG (tess_cpg), each with its factor setup (tess_fsu),
// behind one TRI FIFO and one control-point buffer write port (docs/microarchitecture.md §5,
// "Several triangles in flight"; sim/blocks/cpg.hpp CpgArray).
//
// Triangles go to the copies round robin: only the copy at the accept pointer sees the TRI
// FIFO's head. The copies write in the same order: only the copy at the write pointer sees
// buffer[wr_ptr] EMPTY. Patches therefore reach the buffers in input order, and a copy that
// finishes before an older triangle's copy waits (blocked). One copy starts a triangle every
// C + 1 cycles; M copies one every ceil((C + 1) / M). With one copy the array is the CPG and
// its FSU exactly, and the pointers are constant.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_cpg_array #(
  parameter int unsigned CoordIntBits  = tess_pkg::CoordIntBits,
  parameter int unsigned CoordFracBits = tess_pkg::CoordFracBits,
  parameter int unsigned CpgLanes      = tess_pkg::CpgLanes,
  parameter int unsigned CpgDigitBits  = tess_pkg::CpgDigitBits,
  parameter int unsigned CpgProductReg = tess_pkg::CpgProductReg,
  parameter int unsigned CpgTags       = tess_pkg::CpgTags,
  parameter int unsigned AlphaBits     = tess_pkg::AlphaBits,
  parameter int unsigned CpgCopies     = tess_pkg::CpgCopies,
  localparam int unsigned W      = 1 + CoordIntBits + CoordFracBits,
  localparam int unsigned TriW   = tess_pkg::tri_w(W, CpgTags, AlphaBits)
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic [tess_pkg::ModeBits-1:0]     mode_i,
  // TRI FIFO head, as tess_cpg takes it
  input  logic                              tri_avail_i,
  input  logic [TriW-1:0]                   tri_i,
  output logic                              tri_pop_o,
  // Control-point buffer write port (buffer[wr_ptr])
  input  logic                              buf_empty_i,
  output logic                              buf_wr_o,
  output logic [30*W-1:0]                   buf_b_o,
  output logic [18*W-1:0]                   buf_n_o,
  output logic [tess_pkg::PatchBits-1:0]    buf_patch_o,  // {FSU setup, pattern, L}
  output logic [tess_pkg::IdBits-1:0]       buf_id_o,
  output logic [tess_pkg::FlagBits-1:0]     buf_flags_o,
  // Status for the counters: busy if any copy accepts, computes or writes; else blocked if
  // any holds finished control points; active if any holds a triangle.
  output logic                              busy_o,
  output logic                              blocked_o,
  output logic                              active_o
);

  localparam int unsigned M      = CpgCopies;
  localparam int unsigned PtrW   = (M > 1) ? $clog2(M) : 1;
  localparam int unsigned DescW  = tess_pkg::DescBits;
  localparam int unsigned SetupW = tess_pkg::SetupBits;
  localparam int unsigned LBits  = tess_pkg::FactorBits;
  localparam int unsigned PatchW = tess_pkg::PatchBits;
  localparam int unsigned IdBits = tess_pkg::IdBits;
  localparam int unsigned FlagW  = tess_pkg::FlagBits;
  // One copy's write port, packed: {flags, id, patch, n, b}.
  localparam int unsigned PortW  = 30 * W + 18 * W + PatchW + IdBits + FlagW;

  // ------------------------------------------------------------------ pointers
  logic [PtrW-1:0] accept_q, write_q;
  logic [M-1:0]    at_accept, at_write;
  for (genvar i = 0; i < M; i++) begin : g_turn
    assign at_accept[i] = (accept_q == PtrW'(i));
    assign at_write[i]  = (write_q == PtrW'(i));
  end

  // ------------------------------------------------------------------ the copies
  logic [M-1:0]     pop, wr, busy, blocked, active;
  (* mem2reg *) logic [PortW-1:0] port [M];

  for (genvar i = 0; i < M; i++) begin : g_copy
    logic [30*W-1:0]   b;
    logic [18*W-1:0]   n;
    logic [DescW-1:0]  desc;
    logic [SetupW-1:0] setup;
    logic [IdBits-1:0] id;
    logic [FlagW-1:0]  flags;
    logic              fsu_busy;

    tess_cpg #(
      .CoordIntBits (CoordIntBits),
      .CoordFracBits(CoordFracBits),
      .CpgLanes     (CpgLanes),
      .CpgDigitBits (CpgDigitBits),
      .CpgProductReg(CpgProductReg),
      .CpgTags      (CpgTags),
      .AlphaBits    (AlphaBits)
    ) u_cpg (
      .clk_i      (clk_i),
      .rst_ni     (rst_ni),
      .mode_i     (mode_i),
      .tri_avail_i(tri_avail_i && at_accept[i]),
      .tri_i      (tri_i),
      .tri_pop_o  (pop[i]),
      .buf_empty_i(buf_empty_i && at_write[i]),
      .buf_wr_o   (wr[i]),
      .buf_b_o    (b),
      .buf_n_o    (n),
      .buf_desc_o (desc),
      .buf_id_o   (id),
      .buf_flags_o(flags),
      .busy_o     (busy[i]),
      .blocked_o  (blocked[i]),
      .active_o   (active[i])
    );

    // Sequential beside its CPG: the records are complete five cycles after the CPG takes the
    // triangle, before it can write it (C >= 8).
    tess_fsu u_fsu (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .start_i(pop[i]),
      .desc_i (desc),
      .busy_o (fsu_busy),
      .setup_o(setup)
    );

    assign port[i] = {flags, id, setup, desc[LBits +: tess_pkg::PatternBits], desc[LBits-1:0], n, b};

    `TESS_ASSERT(FsuRecordsReady_A, !(wr[i] && fsu_busy), clk_i, !rst_ni)
  end

  // ------------------------------------------------------------------ the write port
  // AND-OR select on the one-hot turn: a constant-select structure (no shifter over the ports).
  logic [PortW-1:0] sel;
  always_comb begin
    sel = '0;
    for (int unsigned i = 0; i < M; i++) sel |= at_write[i] ? port[i] : '0;
  end
  assign {buf_flags_o, buf_id_o, buf_patch_o, buf_n_o, buf_b_o} = sel;

  assign tri_pop_o = |pop;
  assign buf_wr_o  = |wr;
  assign busy_o    = |busy;
  assign blocked_o = !busy_o && |blocked;
  assign active_o  = |active;

  // Only the copy whose turn it is can pop or write, so the pointers step past it. One copy
  // has no pointers.
  if (M > 1) begin : g_ring
    logic [PtrW-1:0] accept_d, write_d;
    always_comb begin
      accept_d = accept_q;
      if (tri_pop_o) accept_d = (accept_q == PtrW'(M - 1)) ? '0 : accept_q + PtrW'(1);
      write_d = write_q;
      if (buf_wr_o) write_d = (write_q == PtrW'(M - 1)) ? '0 : write_q + PtrW'(1);
    end
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        accept_q <= '0;
        write_q  <= '0;
      end else begin
        accept_q <= accept_d;
        write_q  <= write_d;
      end
    end
  end else begin : g_single
    assign accept_q = '0;
    assign write_q  = '0;
  end

  `TESS_ASSERT(OnePopAtItsTurn_A, (pop & ~at_accept) == '0, clk_i, !rst_ni)
  `TESS_ASSERT(OneWriteAtItsTurn_A, (wr & ~at_write) == '0, clk_i, !rst_ni)

endmodule
