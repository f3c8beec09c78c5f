// The issue logic of the geometry engine as a SIMD shader core (docs/microarchitecture.md §12),
// shared by its lanes (ge_shader_lane): a program counter per wave in flight, a round-robin choice
// of the wave that issues, and the decode of its instruction into the lanes' controls. Written
// to cost the share of a lane in the core's control (scripts/ge_lane_cost.sh); not part of the
// unit. The program store is outside: pc_o addresses it, instr_i is its word in the same cycle.
//
// Instruction word (low 24 bits): [23:22] op (0: multiply-add written to dst, 1: multiply-add to
// the output only, 2: end of the program), [21:18] dst, then for c, b, a: [17:16] kind and
// [15:12] register, [11:10] and [9:6], [5:4] and [3:0] (kinds as ge_shader_lane's sel_*_i).
// A wave issues at most every other cycle, so that it reads a result its previous instruction
// wrote (the multiply-add's one cycle): with one wave active, every other cycle is a bubble.
module ge_simd_issue #(
  parameter int unsigned Waves  = 4,  // waves in flight: a power of two, at least 2
  parameter int unsigned PcBits = 9,  // program store of 2^PcBits instructions
  localparam int unsigned WaveW = $clog2(Waves)
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              launch_i,       // a wave starts at pc 0 (it must not be active)
  input  logic [WaveW-1:0]  launch_wave_i,
  output logic [PcBits-1:0] pc_o,
  input  logic [31:0]       instr_i,
  output logic              issue_o,        // a multiply-add issues on every lane
  output logic [WaveW-1:0]  wave_o,
  output logic [1:0]        sel_a_o,
  output logic [1:0]        sel_b_o,
  output logic [1:0]        sel_c_o,
  output logic [3:0]        reg_a_o,
  output logic [3:0]        reg_b_o,
  output logic [3:0]        reg_c_o,
  output logic              write_o,
  output logic [3:0]        dst_o,
  output logic              done_o,         // wave_o reached the end of the program this cycle
  output logic [Waves-1:0]  active_o
);

  localparam logic [1:0] OpWrite = 2'd0;
  localparam logic [1:0] OpOut   = 2'd1;

  logic [Waves-1:0]  active_q, active_d;
  logic [Waves*PcBits-1:0] pc_q;  // wave w's program counter at [w * PcBits +: PcBits]
  logic [WaveW-1:0]  last_q;      // the wave that issued last
  logic              last_valid_q;

  // Round robin: the first active wave after the last one to issue, not the last one itself
  // in the cycle right after it issued.
  // Waves is a power of two: the candidate's index wraps by truncation.
  logic             pick_valid;
  logic [WaveW-1:0] pick, cand;
  always_comb begin
    pick_valid = 1'b0;
    pick       = '0;
    cand       = last_q;
    for (int unsigned k = 0; k < Waves; k++) begin
      cand = cand + 1'b1;
      if (!pick_valid && active_q[cand] && !(last_valid_q && cand == last_q)) begin
        pick_valid = 1'b1;
        pick       = cand;
      end
    end
  end

  assign pc_o   = pc_q[pick*PcBits+:PcBits];
  assign wave_o = pick;

  logic [1:0] op;
  assign op      = instr_i[23:22];
  assign issue_o = pick_valid && (op == OpWrite || op == OpOut);
  assign done_o  = pick_valid && !(op == OpWrite || op == OpOut);
  assign write_o = op == OpWrite;
  assign dst_o   = instr_i[21:18];
  assign sel_c_o = instr_i[17:16];
  assign reg_c_o = instr_i[15:12];
  assign sel_b_o = instr_i[11:10];
  assign reg_b_o = instr_i[9:6];
  assign sel_a_o = instr_i[5:4];
  assign reg_a_o = instr_i[3:0];

  always_comb begin
    active_d = active_q;
    if (done_o) active_d[pick] = 1'b0;
    if (launch_i) active_d[launch_wave_i] = 1'b1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      active_q     <= '0;
      last_q       <= '0;
      last_valid_q <= 1'b0;
    end else begin
      active_q     <= active_d;
      last_valid_q <= pick_valid;
      if (pick_valid) last_q <= pick;
    end
  end

  always_ff @(posedge clk_i) begin
    for (int unsigned w = 0; w < Waves; w++) begin
      if (launch_i && WaveW'(w) == launch_wave_i) pc_q[w*PcBits+:PcBits] <= '0;
      else if (pick_valid && WaveW'(w) == pick) pc_q[w*PcBits+:PcBits] <= pc_q[w*PcBits+:PcBits] + 1'b1;
    end
  end

  assign active_o = active_q;

  logic unused_instr;
  assign unused_instr = ^instr_i[31:24];

endmodule
