// Drives tess_fifo under a 4-state simulator (iverilog) with the X checks of tess_assert.svh as
// immediate checks (TESS_ASSERT_IMMEDIATE): with +x=1 the push strobe, a valid, is X for one
// cycle out of reset and PushKnown_A must fire; with +x=0 every input is known and nothing may
// fire. tests/rtl/x_check_test.sh runs both.
module x_check_tb;
  logic       clk = 1'b0;
  logic       rst_ni = 1'b0;
  logic       push = 1'b0;
  logic       pop = 1'b0;
  logic [7:0] data = 8'h00;
  logic [7:0] head;
  logic [1:0] count;
  logic       full, empty;
  integer     x_on;

  tess_fifo #(.Width(8), .Depth(2)) dut (
    .clk_i  (clk),
    .rst_ni (rst_ni),
    .push_i (push),
    .data_i (data),
    .pop_i  (pop),
    .data_o (head),
    .count_o(count),
    .full_o (full),
    .empty_o(empty)
  );

  always #5 clk = ~clk;

  initial begin
    if (!$value$plusargs("x=%d", x_on)) x_on = 0;
    repeat (2) @(negedge clk);
    rst_ni = 1'b1;
    @(negedge clk);
    push = 1'b1;
    data = 8'h5a;
    @(negedge clk);
    push = (x_on != 0) ? 1'bx : 1'b0;
    @(negedge clk);
    push = 1'b0;
    pop  = 1'b1;
    @(negedge clk);
    pop = 1'b0;
    @(negedge clk);
    $display("x_check_tb: done, x=%0d", x_on);
    $finish;
  end
endmodule
