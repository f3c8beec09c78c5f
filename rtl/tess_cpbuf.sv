// The control-point buffers (docs/microarchitecture.md §6), Buffers of them in a ring:
// EMPTY -> FULL by the CPG write, FULL -> DRAINING when the DPG hands out the patch's last
// domain point, DRAINING -> EMPTY when the patch's last vertex retires. wr_ptr and rd_ptr step
// round the ring, so patches are written, drained and released in order.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_cpbuf #(
  parameter int unsigned CoordWidth = 24,
  parameter int unsigned Buffers    = tess_pkg::CpBuffers,
  localparam int unsigned PtrW      = (Buffers > 1) ? $clog2(Buffers) : 1
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  // CPG side: write buffer[wr_ptr]
  output logic                            wr_empty_o,
  input  logic                            wr_i,
  input  logic [30*CoordWidth-1:0]        wr_b_i,
  input  logic [18*CoordWidth-1:0]        wr_n_i,
  input  logic [tess_pkg::PatchBits-1:0]  wr_patch_i,  // {setup, pattern, L}
  input  logic [tess_pkg::IdBits-1:0]     wr_id_i,
  input  logic [tess_pkg::FlagBits-1:0]   wr_flags_i,
  // DPG side: buffer[rd_ptr]
  output logic                            rd_full_o,
  output logic [PtrW-1:0]                 rd_ptr_o,
  output logic [tess_pkg::PatchBits-1:0]  rd_patch_o,
  output logic [tess_pkg::IdBits-1:0]     rd_id_o,
  output logic [tess_pkg::FlagBits-1:0]   rd_flags_o,
  input  logic                            drain_i,     // last domain point handed out
  // Retirement of a patch's last vertex
  input  logic                            release_i,
  input  logic [PtrW-1:0]                 release_buf_i,
  // Contents of every buffer, for the INT operand reads: buffer b at [b 30W +: 30W]
  output logic [Buffers*30*CoordWidth-1:0] b_o,
  output logic [Buffers*18*CoordWidth-1:0] n_o
);

  (* mem2reg *) logic [1:0] state_q [Buffers];
  logic [PtrW-1:0] wr_ptr_q, rd_ptr_q;
  (* mem2reg *) logic [30*CoordWidth-1:0]        b_q [Buffers];
  (* mem2reg *) logic [18*CoordWidth-1:0]        n_q [Buffers];
  (* mem2reg *) logic [tess_pkg::PatchBits-1:0]  patch_q [Buffers];
  (* mem2reg *) logic [tess_pkg::IdBits-1:0]     id_q [Buffers];
  (* mem2reg *) logic [tess_pkg::FlagBits-1:0]   flags_q [Buffers];

  assign wr_empty_o = (state_q[wr_ptr_q] == tess_pkg::BufEmpty);
  assign rd_full_o  = (state_q[rd_ptr_q] == tess_pkg::BufFull);
  assign rd_ptr_o   = rd_ptr_q;
  assign rd_patch_o = patch_q[rd_ptr_q];
  assign rd_id_o    = id_q[rd_ptr_q];
  assign rd_flags_o = flags_q[rd_ptr_q];

  // The next buffer round the ring.
  logic [PtrW-1:0] wr_ptr_next, rd_ptr_next;
  assign wr_ptr_next = (Buffers == 1 || wr_ptr_q == PtrW'(Buffers - 1)) ? '0 : wr_ptr_q + PtrW'(1);
  assign rd_ptr_next = (Buffers == 1 || rd_ptr_q == PtrW'(Buffers - 1)) ? '0 : rd_ptr_q + PtrW'(1);

  // The three transitions need different start states, so they never hit one buffer in
  // the same cycle.
  (* mem2reg *) logic [1:0] state_d [Buffers];
  logic [PtrW-1:0] wr_ptr_d, rd_ptr_d;
  always_comb begin
    for (int b = 0; b < Buffers; b++) state_d[b] = state_q[b];
    wr_ptr_d = wr_ptr_q;
    rd_ptr_d = rd_ptr_q;
    if (wr_i) begin
      state_d[wr_ptr_q] = tess_pkg::BufFull;
      wr_ptr_d          = wr_ptr_next;
    end
    if (drain_i) begin
      state_d[rd_ptr_q] = tess_pkg::BufDraining;
      rd_ptr_d          = rd_ptr_next;
    end
    if (release_i) state_d[release_buf_i] = tess_pkg::BufEmpty;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int b = 0; b < Buffers; b++) state_q[b] <= tess_pkg::BufEmpty;
      wr_ptr_q <= '0;
      rd_ptr_q <= '0;
    end else begin
      for (int b = 0; b < Buffers; b++) state_q[b] <= state_d[b];
      wr_ptr_q <= wr_ptr_d;
      rd_ptr_q <= rd_ptr_d;
    end
  end

  // The buffers' contents: written by the CPG, not reset (read only while FULL or DRAINING).
  (* mem2reg *) logic [30*CoordWidth-1:0]        b_d [Buffers];
  (* mem2reg *) logic [18*CoordWidth-1:0]        n_d [Buffers];
  (* mem2reg *) logic [tess_pkg::PatchBits-1:0]  patch_d [Buffers];
  (* mem2reg *) logic [tess_pkg::IdBits-1:0]     id_d [Buffers];
  (* mem2reg *) logic [tess_pkg::FlagBits-1:0]   flags_d [Buffers];
  always_comb begin
    for (int b = 0; b < Buffers; b++) begin
      b_d[b]     = b_q[b];
      n_d[b]     = n_q[b];
      patch_d[b] = patch_q[b];
      id_d[b]    = id_q[b];
      flags_d[b] = flags_q[b];
      if (wr_i && wr_ptr_q == PtrW'(b)) begin
        b_d[b]     = wr_b_i;
        n_d[b]     = wr_n_i;
        patch_d[b] = wr_patch_i;
        id_d[b]    = wr_id_i;
        flags_d[b] = wr_flags_i;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    for (int b = 0; b < Buffers; b++) begin
      b_q[b]     <= b_d[b];
      n_q[b]     <= n_d[b];
      patch_q[b] <= patch_d[b];
      id_q[b]    <= id_d[b];
      flags_q[b] <= flags_d[b];
    end
  end

  for (genvar b = 0; b < Buffers; b++) begin : g_out
    assign b_o[b * 30 * CoordWidth +: 30 * CoordWidth] = b_q[b];
    assign n_o[b * 18 * CoordWidth +: 18 * CoordWidth] = n_q[b];
  end

  // Each transition from its one legal state. (Verilator 5.006 fails internally on an array
  // select inside an assertion of an --x-assign unique build: the states are read outside it.)
  logic [1:0] release_state;
  assign release_state = state_q[release_buf_i];
  `TESS_ASSERT(WriteEmpty_A, wr_i |-> wr_empty_o, clk_i, !rst_ni)
  `TESS_ASSERT(DrainFull_A, drain_i |-> rd_full_o, clk_i, !rst_ni)
  `TESS_ASSERT(ReleaseDraining_A, release_i |-> release_state == tess_pkg::BufDraining, clk_i, !rst_ni)

endmodule
