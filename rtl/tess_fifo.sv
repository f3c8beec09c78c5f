// Synchronous FIFO with a registered head: data_o and count_o are functions of registered
// state only. A push while full is dropped (the unit never does that: the producers check
// full_o at the start of the cycle, and an assertion guards it), even when the FIFO pops in
// the same cycle (docs/microarchitecture.md §8, VTX FIFO).
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_fifo #(
  parameter int unsigned Width = 8,
  parameter int unsigned Depth = 2,
  localparam int unsigned PtrW = (Depth > 1) ? $clog2(Depth) : 1,
  localparam int unsigned CntW = $clog2(Depth + 1)
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             push_i,
  input  logic [Width-1:0] data_i,
  input  logic             pop_i,
  output logic [Width-1:0] data_o,
  output logic [CntW-1:0]  count_o,
  output logic             full_o,
  output logic             empty_o
);

  (* mem2reg *) logic [Width-1:0] mem_q [Depth];
  logic [PtrW-1:0] rd_ptr_q, wr_ptr_q;
  logic [CntW-1:0] count_q;
  logic            do_push, do_pop;

  assign full_o  = (count_q == CntW'(Depth));
  assign empty_o = (count_q == '0);
  assign do_push = push_i && !full_o;
  assign do_pop  = pop_i && !empty_o;

  logic [PtrW-1:0] rd_ptr_next, wr_ptr_next;
  assign rd_ptr_next = (rd_ptr_q == PtrW'(Depth - 1)) ? '0 : rd_ptr_q + PtrW'(1);
  assign wr_ptr_next = (wr_ptr_q == PtrW'(Depth - 1)) ? '0 : wr_ptr_q + PtrW'(1);

  logic [PtrW-1:0] rd_ptr_d, wr_ptr_d;
  logic [CntW-1:0] count_d;
  always_comb begin
    wr_ptr_d = do_push ? wr_ptr_next : wr_ptr_q;
    rd_ptr_d = do_pop ? rd_ptr_next : rd_ptr_q;
    count_d  = count_q;
    if (do_push && !do_pop) count_d = count_q + CntW'(1);
    else if (do_pop && !do_push) count_d = count_q - CntW'(1);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_ptr_q <= '0;
      wr_ptr_q <= '0;
      count_q  <= '0;
    end else begin
      rd_ptr_q <= rd_ptr_d;
      wr_ptr_q <= wr_ptr_d;
      count_q  <= count_d;
    end
  end

  // Storage is not reset: an entry is only read after it has been written.
  (* mem2reg *) logic [Width-1:0] mem_d [Depth];
  always_comb begin
    for (int i = 0; i < Depth; i++) mem_d[i] = (do_push && wr_ptr_q == PtrW'(i)) ? data_i : mem_q[i];
  end
  always_ff @(posedge clk_i) begin
    for (int i = 0; i < Depth; i++) mem_q[i] <= mem_d[i];
  end

  assign data_o  = mem_q[rd_ptr_q];
  assign count_o = count_q;

  `TESS_ASSERT(PushNotFull_A, !(push_i && full_o), clk_i, !rst_ni)

  // Handshakes and the fill level are never X out of reset (4-state simulation: x_check_test).
  `TESS_ASSERT_KNOWN(PushKnown_A, push_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(PopKnown_A, pop_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(CountKnown_A, count_q, clk_i, !rst_ni)
  `TESS_ASSERT_PARAM(DepthRange_A, Depth >= 1)

endmodule
