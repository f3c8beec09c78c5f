// The two control-point buffers (docs/microarchitecture.md §6): EMPTY -> FULL by the CPG
// write, FULL -> DRAINING when the DPG hands out the patch's last domain point,
// DRAINING -> EMPTY when the patch's last vertex retires. wr_ptr and rd_ptr alternate.
module tess_cpbuf #(
  parameter int unsigned CoordWidth = 24
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
  output logic                            rd_ptr_o,
  output logic [tess_pkg::PatchBits-1:0]  rd_patch_o,
  output logic [tess_pkg::IdBits-1:0]     rd_id_o,
  output logic [tess_pkg::FlagBits-1:0]   rd_flags_o,
  input  logic                            drain_i,     // last domain point handed out
  // Retirement of a patch's last vertex
  input  logic                            release_i,
  input  logic                            release_buf_i,
  // Contents of both buffers, for the INT operand reads
  output logic [2*30*CoordWidth-1:0]      b_o,
  output logic [2*18*CoordWidth-1:0]      n_o
);

  (* mem2reg *) logic [1:0] state_q [2];
  logic       wr_ptr_q, rd_ptr_q;
  (* mem2reg *) logic [30*CoordWidth-1:0]        b_q [2];
  (* mem2reg *) logic [18*CoordWidth-1:0]        n_q [2];
  (* mem2reg *) logic [tess_pkg::PatchBits-1:0]  patch_q [2];
  (* mem2reg *) logic [tess_pkg::IdBits-1:0]     id_q [2];
  (* mem2reg *) logic [tess_pkg::FlagBits-1:0]   flags_q [2];

  assign wr_empty_o = (state_q[wr_ptr_q] == tess_pkg::BufEmpty);
  assign rd_full_o  = (state_q[rd_ptr_q] == tess_pkg::BufFull);
  assign rd_ptr_o   = rd_ptr_q;
  assign rd_patch_o = patch_q[rd_ptr_q];
  assign rd_id_o    = id_q[rd_ptr_q];
  assign rd_flags_o = flags_q[rd_ptr_q];

  // The three transitions need different start states, so they never hit one buffer in
  // the same cycle.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q[0] <= tess_pkg::BufEmpty;
      state_q[1] <= tess_pkg::BufEmpty;
      wr_ptr_q   <= 1'b0;
      rd_ptr_q   <= 1'b0;
    end else begin
      if (wr_i) begin
        state_q[wr_ptr_q] <= tess_pkg::BufFull;
        wr_ptr_q          <= !wr_ptr_q;
      end
      if (drain_i) begin
        state_q[rd_ptr_q] <= tess_pkg::BufDraining;
        rd_ptr_q          <= !rd_ptr_q;
      end
      if (release_i) state_q[release_buf_i] <= tess_pkg::BufEmpty;
    end
  end

  always_ff @(posedge clk_i) begin
    if (wr_i) begin
      b_q[wr_ptr_q]     <= wr_b_i;
      n_q[wr_ptr_q]     <= wr_n_i;
      patch_q[wr_ptr_q] <= wr_patch_i;
      id_q[wr_ptr_q]    <= wr_id_i;
      flags_q[wr_ptr_q] <= wr_flags_i;
    end
  end

  assign b_o = {b_q[1], b_q[0]};
  assign n_o = {n_q[1], n_q[0]};

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      assert (!wr_i || state_q[wr_ptr_q] == tess_pkg::BufEmpty)
        else $error("tess_cpbuf: write into a buffer that is not EMPTY");
      assert (!drain_i || state_q[rd_ptr_q] == tess_pkg::BufFull)
        else $error("tess_cpbuf: drain of a buffer that is not FULL");
      assert (!release_i || state_q[release_buf_i] == tess_pkg::BufDraining)
        else $error("tess_cpbuf: release of a buffer that is not DRAINING");
    end
  end
`endif

endmodule
