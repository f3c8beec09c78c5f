// One lane of the geometry engine as a SIMD shader core (docs/microarchitecture.md §12) with what
// a lane costs beside its ALU: the registers of every wave in flight, the operand network that
// feeds the multiply-add and the write-back. Written to cost a shader lane
// (scripts/ge_lane_cost.sh, docs/results/load-balancing.md §15); not part of the unit.
//
// Each cycle the issue logic (ge_simd_issue) may send one instruction of one wave: d = a * b + c
// on ge_fma_lane, each operand a register of that wave, the uniform broadcast to every lane (a
// patch constant), this lane's input (its vertex's u, v or attribute), or a constant (a, b: 1.0;
// c: +0.0, so that a move, an add and a multiply are multiply-adds). The result is written to a
// register of the wave one cycle later, when the lane's result is valid; it is also the lane's
// output. An instruction may read a register the previous instruction of its wave writes only
// two cycles after it: the issue logic never issues a wave twice in a row.
module ge_shader_lane #(
  parameter int unsigned Regs  = 16,  // registers per wave (at least 2)
  parameter int unsigned Waves = 4,   // waves in flight (at least 2)
  localparam int unsigned RegW  = $clog2(Regs),
  localparam int unsigned WaveW = $clog2(Waves)
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             issue_i,    // an instruction issues this cycle
  input  logic [WaveW-1:0] wave_i,
  input  logic [1:0]       sel_a_i,    // operand kinds: 0 register, 1 uniform, 2 lane input, 3 constant
  input  logic [1:0]       sel_b_i,
  input  logic [1:0]       sel_c_i,
  input  logic [RegW-1:0]  reg_a_i,
  input  logic [RegW-1:0]  reg_b_i,
  input  logic [RegW-1:0]  reg_c_i,
  input  logic             write_i,    // the result goes to register dst_i of the wave
  input  logic [RegW-1:0]  dst_i,
  input  logic [31:0]      uniform_i,
  input  logic [31:0]      lane_in_i,
  output logic             valid_o,
  output logic [31:0]      result_o
);

  localparam logic [31:0] One  = 32'h3f80_0000;
  localparam logic [31:0] Zero = 32'h0000_0000;
  localparam int unsigned Entries = Regs * Waves;

  // The register file: every register of every wave, as flip-flops.
  logic [31:0] rf_q [Entries];

  function automatic logic [31:0] operand(input logic [1:0] sel, input logic [31:0] reg_value,
                                          input logic [31:0] uniform, input logic [31:0] lane_in,
                                          input logic [31:0] constant);
    unique case (sel)
      2'd0:    operand = reg_value;
      2'd1:    operand = uniform;
      2'd2:    operand = lane_in;
      default: operand = constant;
    endcase
  endfunction

  logic [WaveW+RegW-1:0] addr_a, addr_b, addr_c;
  assign addr_a = {wave_i, reg_a_i};
  assign addr_b = {wave_i, reg_b_i};
  assign addr_c = {wave_i, reg_c_i};

  logic [31:0] a, b, c;
  assign a = operand(sel_a_i, rf_q[addr_a], uniform_i, lane_in_i, One);
  assign b = operand(sel_b_i, rf_q[addr_b], uniform_i, lane_in_i, One);
  assign c = operand(sel_c_i, rf_q[addr_c], uniform_i, lane_in_i, Zero);

  logic [31:0] d;
  logic        d_valid;
  ge_fma_lane u_fma (
    .clk_i,
    .rst_ni,
    .valid_i(issue_i),
    .a_i    (a),
    .b_i    (b),
    .c_i    (c),
    .valid_o(d_valid),
    .d_o    (d)
  );

  // The destination travels with the instruction for the multiply-add's one cycle.
  logic                  write_q;
  logic [WaveW+RegW-1:0] dst_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) write_q <= 1'b0;
    else write_q <= issue_i && write_i;
  end
  always_ff @(posedge clk_i) begin
    dst_q <= {wave_i, dst_i};
  end

  always_ff @(posedge clk_i) begin
    if (d_valid && write_q) rf_q[dst_q] <= d;
  end

  assign valid_o  = d_valid;
  assign result_o = d;

endmodule
