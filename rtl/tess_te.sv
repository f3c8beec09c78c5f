// TE: tessellation engine (docs/microarchitecture.md §7, §8). V vertex contexts in a
// circular queue (allocation at the tail, in-order retirement at the head), the in-order
// priority scheduler that issues the first N ready (age, op) candidates onto N INT blocks,
// the temporaries, and retirement into the VTX FIFO. The DPG supplies the domain points.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_te #(
  parameter int unsigned CoordWidth = 24,
  parameter int unsigned BaryBits   = tess_pkg::BaryBits,
  parameter int unsigned IntBlocks  = tess_pkg::IntBlocks,
  parameter int unsigned IntLatency = tess_pkg::IntLatency,
  parameter int unsigned Contexts   = tess_pkg::Contexts,
  parameter int unsigned Buffers    = tess_pkg::CpBuffers,
  parameter int unsigned InjectBug  = tess_pkg::InjectBug,
  localparam int unsigned W         = CoordWidth,
  localparam int unsigned BufW      = (Buffers > 1) ? $clog2(Buffers) : 1,
  localparam int unsigned VtxW      = tess_pkg::vtx_w(W, BaryBits)
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic [tess_pkg::ModeBits-1:0]   mode_i,
  // Control-point buffers
  input  logic                            rd_full_i,
  input  logic [BufW-1:0]                 rd_ptr_i,
  input  logic [tess_pkg::PatchBits-1:0]  rd_patch_i,  // {setup, pattern, L}
  input  logic [tess_pkg::IdBits-1:0]     rd_id_i,
  input  logic [tess_pkg::FlagBits-1:0]   rd_flags_i,
  input  logic [Buffers*30*W-1:0]         b_i,         // buffer b at [b 30W +: 30W]
  input  logic [Buffers*18*W-1:0]         n_i,
  output logic                            drain_o,
  output logic                            release_o,
  output logic [BufW-1:0]                 release_buf_o,
  // VTX FIFO
  input  logic                            vtx_full_i,
  output logic                            vtx_push_o,
  output logic [VtxW-1:0]                 vtx_o,
  // Statistics (§10)
  input  logic                            upstream_busy_i,  // CPG busy or TRI FIFO not empty
  output logic [IntBlocks-1:0]            int_busy_o,
  output logic                            te_ctx_limited_o,
  output logic                            te_int_limited_o,
  output logic                            te_busy_o,
  output logic                            te_blocked_o,
  output logic                            te_starved_o,
  output logic                            te_idle_o,
  output logic                            te_pipeline_o
);

  localparam int unsigned B       = BaryBits;
  localparam int unsigned V       = Contexts;
  localparam int unsigned N       = IntBlocks;
  localparam int unsigned NumOps  = tess_pkg::NumOps;
  localparam int unsigned LBits   = tess_pkg::FactorBits;
  localparam int unsigned IdBits  = tess_pkg::IdBits;
  localparam int unsigned FlagW   = tess_pkg::FlagBits;
  localparam int unsigned IdxW    = (V > 1) ? $clog2(V) : 1;
  localparam int unsigned CntW    = $clog2(V + 1);
  localparam int unsigned OpW     = 4;
  localparam int unsigned TagW    = IdxW + OpW;
  localparam int unsigned NumCand = V * NumOps;

  logic mode_linear;
  assign mode_linear = (mode_i == tess_pkg::ModeLinear);

  // ------------------------------------------------------------------ contexts
  logic [IdxW-1:0] head_q, tail_q;
  logic [CntW-1:0] count_q;
  (* mem2reg *) logic [B:0]         ctx_w_q [V];
  (* mem2reg *) logic [B:0]         ctx_u_q [V];
  (* mem2reg *) logic [B:0]         ctx_v_q [V];
  (* mem2reg *) logic [LBits-1:0]   ctx_j_q [V];
  (* mem2reg *) logic [LBits-1:0]   ctx_k_q [V];
  (* mem2reg *) logic [LBits-1:0]   ctx_l_q [V];
  (* mem2reg *) logic [tess_pkg::IndexBits-1:0] ctx_index_q [V];
  (* mem2reg *) logic [IdBits-1:0]  ctx_id_q [V];
  (* mem2reg *) logic [FlagW-1:0]   ctx_flags_q [V];
  (* mem2reg *) logic               ctx_last_q [V];
  (* mem2reg *) logic [BufW-1:0]    ctx_buf_q [V];
  (* mem2reg *) logic [NumOps-1:0]  issued_q [V];
  (* mem2reg *) logic [NumOps-1:0]  done_q [V];
  (* mem2reg *) logic [3*W-1:0]     temp_q [V][NumOps];

  // ------------------------------------------------------------------ DPG and allocation
  logic [LBits-1:0] dpg_j, dpg_k, rd_l;
  logic [tess_pkg::IndexBits-1:0] dpg_index;
  logic [B:0]       dpg_w, dpg_u, dpg_v;
  logic             dpg_last, alloc;
  // A D3D11 patch's vertices carry L = 0 (j, k: ring and edge).
  assign rd_l = (rd_patch_i[LBits +: tess_pkg::PatternBits] == tess_pkg::PatUniform) ? rd_patch_i[LBits-1:0] : '0;

  assign alloc = (count_q < CntW'(V)) && rd_full_i;

  tess_dpg #(.BaryBits(B)) u_dpg (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .patch_i  (rd_patch_i),
    .consume_i(alloc),
    .j_o      (dpg_j),
    .k_o      (dpg_k),
    .index_o  (dpg_index),
    .w_o      (dpg_w),
    .u_o      (dpg_u),
    .v_o      (dpg_v),
    .last_o   (dpg_last)
  );
  assign drain_o = alloc && dpg_last;

  // ------------------------------------------------------------------ scheduler
  // Candidate (age a, op o) has index a * 14 + o: the lexicographic priority order. The ready
  // mask is registered: it is computed at the end of each cycle from the next state (queue
  // pointers, issued and done bits), so that a cycle starts from it and the scheduler, the
  // operand select and the INT blocks' input register share one path of the depth budget
  // (docs/rtl.md). It equals the mask of the current state in every cycle: a retiming.
  (* mem2reg *) logic [IdxW-1:0]   age_ctx [V];      // physical context of age a
  (* mem2reg *) logic [IdxW-1:0]   age_ctx_d [V];    // ... in the next cycle
  (* mem2reg *) logic [NumOps-1:0] issued_nx [V];    // issued and done bits of the next cycle
  (* mem2reg *) logic [NumOps-1:0] done_nx [V];
  logic [IdxW-1:0]    head_d, tail_d;
  logic [CntW-1:0]    count_d;
  logic [NumCand-1:0] ready, ready_d, ready_q;
  for (genvar a = 0; a < V; a++) begin : g_age
    logic [IdxW:0]       sum, sum_d;
    logic [NumOps-1:0]   dn, rdy;
    assign sum = {1'b0, head_q} + (IdxW + 1)'(a);
    assign age_ctx[a] = (sum >= (IdxW + 1)'(V)) ? IdxW'(sum - (IdxW + 1)'(V)) : sum[IdxW-1:0];
    assign sum_d = {1'b0, head_d} + (IdxW + 1)'(a);
    assign age_ctx_d[a] = (sum_d >= (IdxW + 1)'(V)) ? IdxW'(sum_d - (IdxW + 1)'(V)) : sum_d[IdxW-1:0];
    assign dn = done_nx[age_ctx_d[a]];
    logic unused_dn;
    assign unused_dn = ^dn[13:12];  // nothing depends on ops 12 and 13
    // Dependences of the L2 and L3 operations.
    always_comb begin
      rdy = ~issued_nx[age_ctx_d[a]];
      rdy[9]  = rdy[9]  & dn[0] & dn[1] & dn[3];
      rdy[10] = rdy[10] & dn[1] & dn[2] & dn[4];
      rdy[11] = rdy[11] & dn[3] & dn[4] & dn[5];
      rdy[12] = rdy[12] & dn[6] & dn[7] & dn[8];
      rdy[13] = rdy[13] & dn[9] & dn[10] & dn[11];
    end
    assign ready_d[a*NumOps +: NumOps] = (CntW'(a) < count_d) ? rdy : '0;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ready_q <= '0;  // no context allocated
    end else begin
      ready_q <= ready_d;
    end
  end
  assign ready = ready_q;

  // The first N ready candidates issue, the i-th onto INT block i. Candidate c goes to slot i
  // when it is ready and exactly i ready candidates precede it: a parallel-prefix count of the
  // ready bits (Kogge-Stone, log2(V 14) levels), saturated at N and kept as a thermometer code
  // (bit k: at least k + 1), so the depth grows with log N rather than with N rounds of a
  // lowest-set-bit search.
  localparam int unsigned Levels = $clog2(NumCand);
  (* mem2reg *) logic [N-1:0] prefix [NumCand];      // after level l: ready bits in (c - 2^l, c]
  (* mem2reg *) logic [N-1:0] prefix_nx [NumCand];
  always_comb begin
    for (int c = 0; c < NumCand; c++) prefix[c] = N'(ready[c]);
    for (int l = 0; l < Levels; l++) begin
      for (int c = 0; c < NumCand; c++) begin
        prefix_nx[c] = prefix[c];
        if (c >= (1 << l)) begin
          // a + b >= k + 1 for thermometers a, b: some split i + (k + 1 - i) with both parts met.
          for (int k = 0; k < N; k++) begin
            prefix_nx[c][k] = prefix[c][k] | prefix[c-(1<<l)][k];
            for (int i = 1; i <= k; i++) prefix_nx[c][k] = prefix_nx[c][k] | (prefix[c][i-1] & prefix[c-(1<<l)][k-i]);
          end
        end
      end
      for (int c = 0; c < NumCand; c++) prefix[c] = prefix_nx[c];
    end
  end
  // Ready candidates before c (exclusive prefix), saturated at N.
  (* mem2reg *) logic [N-1:0] preceding [NumCand];
  assign preceding[0] = '0;
  for (genvar c = 1; c < NumCand; c++) begin : g_before
    assign preceding[c] = prefix[c-1];
  end

  logic [N-1:0]       slot_valid;
  (* mem2reg *) logic [NumCand-1:0] slot_hot [N];
  (* mem2reg *) logic [V-1:0]       slot_age_hot [N];  // one-hot age of slot i's candidate
  (* mem2reg *) logic [NumOps-1:0]  slot_op_hot [N];   // one-hot op
  logic [NumCand-1:0] remaining;  // ready, left after the N slots
  logic [NumCand-1:0] selected;
  for (genvar c = 0; c < NumCand; c++) begin : g_select
    assign selected[c]  = ready[c] && !preceding[c][N-1];
    assign remaining[c] = ready[c] && preceding[c][N-1];
  end
  for (genvar i = 0; i < N; i++) begin : g_slot
    for (genvar c = 0; c < NumCand; c++) begin : g_hot
      // exactly i before c: at least i (bit i - 1) and not at least i + 1 (bit i)
      if (i == 0) begin : g_first
        assign slot_hot[i][c] = ready[c] && !preceding[c][0];
      end else begin : g_next
        assign slot_hot[i][c] = ready[c] && preceding[c][i-1] && !preceding[c][i];
      end
    end
    assign slot_valid[i] = (slot_hot[i] != '0);
    always_comb begin
      slot_age_hot[i] = '0;
      slot_op_hot[i]  = '0;
      for (int c = 0; c < NumCand; c++) begin
        slot_age_hot[i][c / NumOps] |= slot_hot[i][c];
        slot_op_hot[i][c % NumOps]  |= slot_hot[i][c];
      end
    end
  end

  // Per age, from the registers alone (in parallel with the scheduler): its context and buffer
  // one-hot and its temporaries.
  (* mem2reg *) logic [V-1:0]       age_ctx_hot [V];
  (* mem2reg *) logic [Buffers-1:0] age_bank_hot [V];
  (* mem2reg *) logic [3*W-1:0]     age_temp [V][12];  // used without the choice register
  always_comb begin
    for (int a = 0; a < V; a++) begin
      age_ctx_hot[a]  = '0;
      age_bank_hot[a] = '0;
      for (int x = 0; x < V; x++) age_ctx_hot[a][x] = (age_ctx[a] == IdxW'(x));
      for (int x = 0; x < V; x++) begin
        for (int b = 0; b < Buffers; b++) age_bank_hot[a][b] |= age_ctx_hot[a][x] && (ctx_buf_q[x] == BufW'(b));
      end
      for (int k = 0; k < 12; k++) begin
        age_temp[a][k] = '0;
        for (int x = 0; x < V; x++) age_temp[a][k] |= age_ctx_hot[a][x] ? temp_q[x][k] : '0;
      end
    end
  end

  // ------------------------------------------------------------------ INT blocks
  logic [N-1:0]      wb_valid;
  (* mem2reg *) logic [TagW-1:0]   wb_tag [N];
  (* mem2reg *) logic [3*W-1:0]    wb_res [N];

  // With IntLatency >= 3 the slots' choices are registered: the issue cycle ends with the
  // scheduler, the operands are selected in the next and the INT block (one register fewer)
  // multiplies and adds in the one after, so the result is written in the same cycle as with the
  // registers inside the block. The operands read a cycle later are the same: an op's sources
  // are done before it issues and its context cannot retire while it is in flight.
  localparam bit ChoiceReg = (IntLatency >= 3);
  for (genvar i = 0; i < N; i++) begin : g_int
    // Every select below is an AND-OR over one-hot lines taken from the slot's candidate, so
    // that no binary index is encoded and decoded again on the issue path.
    logic [IdxW-1:0]    ctx;
    logic [OpW-1:0]     op;
    logic [V-1:0]       ctx_hot;   // the physical context of the slot's age
    logic [Buffers-1:0] bank_hot;  // its control-point buffer
    logic               sel_valid;
    logic [V-1:0]       sel_ctx_hot;
    logic [Buffers-1:0] sel_bank_hot;
    logic [NumOps-1:0]  sel_op_hot;
    (* mem2reg *) logic [3*W-1:0]  bsel [10];
    (* mem2reg *) logic [3*W-1:0]  nsel [6];
    (* mem2reg *) logic [3*W-1:0]  tsel [12];
    logic [3*W-1:0]  opa, opb, opc;
    logic [B:0]      wsel, usel, vsel;
    always_comb begin
      ctx_hot  = '0;
      bank_hot = '0;
      for (int a = 0; a < V; a++) begin
        ctx_hot  |= slot_age_hot[i][a] ? age_ctx_hot[a] : '0;
        bank_hot |= slot_age_hot[i][a] ? age_bank_hot[a] : '0;
      end
    end
    if (ChoiceReg) begin : g_choice_reg
      logic               valid_d, valid_q;
      logic [V-1:0]       ctx_hot_d, ctx_hot_q;
      logic [Buffers-1:0] bank_hot_d, bank_hot_q;
      logic [NumOps-1:0]  op_hot_d, op_hot_q;
      assign valid_d    = slot_valid[i];
      assign ctx_hot_d  = ctx_hot;
      assign bank_hot_d = bank_hot;
      assign op_hot_d   = slot_op_hot[i];
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          valid_q <= 1'b0;
        end else begin
          valid_q <= valid_d;
        end
      end
      always_ff @(posedge clk_i) begin
        ctx_hot_q  <= ctx_hot_d;
        bank_hot_q <= bank_hot_d;
        op_hot_q   <= op_hot_d;
      end
      assign sel_valid    = valid_q;
      assign sel_ctx_hot  = ctx_hot_q;
      assign sel_bank_hot = bank_hot_q;
      assign sel_op_hot   = op_hot_q;
      // Temporaries T0..T11 of the chosen context.
      always_comb begin
        for (int k = 0; k < 12; k++) begin
          tsel[k] = '0;
          for (int x = 0; x < V; x++) tsel[k] |= ctx_hot_q[x] ? temp_q[x][k] : '0;
        end
      end
    end else begin : g_choice_comb
      assign sel_valid    = slot_valid[i];
      assign sel_ctx_hot  = ctx_hot;
      assign sel_bank_hot = bank_hot;
      assign sel_op_hot   = slot_op_hot[i];
      // Temporaries T0..T11 of the slot's age (the ages' temporaries are selected from the
      // registers in parallel with the scheduler).
      always_comb begin
        for (int k = 0; k < 12; k++) begin
          tsel[k] = '0;
          for (int a = 0; a < V; a++) tsel[k] |= slot_age_hot[i][a] ? age_temp[a][k] : '0;
        end
      end
    end
    always_comb begin
      ctx = '0;
      for (int x = 0; x < V; x++) ctx |= sel_ctx_hot[x] ? IdxW'(x) : '0;
      op = '0;
      for (int o = 0; o < NumOps; o++) op |= sel_op_hot[o] ? OpW'(o) : '0;
      wsel = '0;
      usel = '0;
      vsel = '0;
      for (int x = 0; x < V; x++) begin
        wsel |= sel_ctx_hot[x] ? ctx_w_q[x] : '0;
        usel |= sel_ctx_hot[x] ? ctx_u_q[x] : '0;
        vsel |= sel_ctx_hot[x] ? ctx_v_q[x] : '0;
      end
    end
    // The operands of the context's buffer, with constant part-selects (a part-select at a
    // variable offset would make Yosys build a shifter over every buffer's bits).
    always_comb begin
      for (int k = 0; k < 10; k++) begin
        bsel[k] = '0;
        for (int b = 0; b < Buffers; b++) bsel[k] |= sel_bank_hot[b] ? b_i[(30 * b + 3 * k) * W +: 3 * W] : '0;
      end
      for (int k = 0; k < 6; k++) begin
        nsel[k] = '0;
        for (int b = 0; b < Buffers; b++) nsel[k] |= sel_bank_hot[b] ? n_i[(18 * b + 3 * k) * W +: 3 * W] : '0;
      end
    end
    // Operands of the 14 operations (§8 table; linear op 6 combines N1, N2, N3), selected by the
    // one-hot op.
    (* mem2reg *) logic [3*W-1:0] op_a [NumOps], op_b [NumOps], op_c [NumOps];
    always_comb begin
      op_a[0]  = bsel[0]; op_b[0]  = bsel[1];  op_c[0]  = bsel[4];
      op_a[1]  = bsel[1]; op_b[1]  = bsel[2];  op_c[1]  = bsel[5];
      op_a[2]  = bsel[2]; op_b[2]  = bsel[3];  op_c[2]  = bsel[6];
      op_a[3]  = bsel[4]; op_b[3]  = bsel[5];  op_c[3]  = bsel[7];
      op_a[4]  = bsel[5]; op_b[4]  = bsel[6];  op_c[4]  = bsel[8];
      op_a[5]  = bsel[7]; op_b[5]  = bsel[8];  op_c[5]  = bsel[9];
      op_a[6]  = nsel[0];
      op_b[6]  = mode_linear ? nsel[2] : nsel[1];
      op_c[6]  = mode_linear ? nsel[5] : nsel[3];
      op_a[7]  = nsel[1]; op_b[7]  = nsel[2];  op_c[7]  = nsel[4];
      op_a[8]  = nsel[3]; op_b[8]  = nsel[4];  op_c[8]  = nsel[5];
      op_a[9]  = tsel[0]; op_b[9]  = tsel[1];  op_c[9]  = tsel[3];
      op_a[10] = tsel[1]; op_b[10] = tsel[2];  op_c[10] = tsel[4];
      op_a[11] = tsel[3]; op_b[11] = tsel[4];  op_c[11] = tsel[5];
      op_a[12] = tsel[6]; op_b[12] = tsel[7];  op_c[12] = tsel[8];
      op_a[13] = tsel[9]; op_b[13] = tsel[10]; op_c[13] = tsel[11];
      opa = '0;
      opb = '0;
      opc = '0;
      for (int o = 0; o < NumOps; o++) begin
        opa |= sel_op_hot[o] ? op_a[o] : '0;
        opb |= sel_op_hot[o] ? op_b[o] : '0;
        opc |= sel_op_hot[o] ? op_c[o] : '0;
      end
    end

    tess_int #(
      .CoordWidth(W),
      .BaryBits  (B),
      .Latency   (IntLatency - 32'(ChoiceReg)),
      .TagWidth  (TagW),
      .InjectBug (InjectBug)
    ) u_int (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .valid_i(sel_valid),
      .tag_i  ({ctx, op}),
      .w_i    (wsel),
      .u_i    (usel),
      .v_i    (vsel),
      .a_i    (opa),
      .b_i    (opb),
      .c_i    (opc),
      .valid_o(wb_valid[i]),
      .tag_o  (wb_tag[i]),
      .res_o  (wb_res[i])
    );
  end

  // ------------------------------------------------------------------ retirement
  logic head_done, retire;
  assign head_done = (count_q != '0) && (done_q[head_q] == '1);
  if (InjectBug == 2) begin : g_bug_drop_stall
    // Fault: the last vertex of a patch retires even into a full VTX FIFO (and is lost).
    assign retire = head_done && (!vtx_full_i || ctx_last_q[head_q]);
  end else begin : g_retire
    assign retire = head_done && !vtx_full_i;
  end

  assign vtx_push_o    = retire;
  assign release_o     = retire && ctx_last_q[head_q];
  assign release_buf_o = ctx_buf_q[head_q];
  // Entry: {flags, last, id, L, k, j, v, u, normal, position}
  logic [3*W-1:0] head_pos, head_nrm;
  always_comb begin
    head_pos = '0;
    head_nrm = '0;
    for (int x = 0; x < V; x++) begin
      if (head_q == IdxW'(x)) begin
        head_pos = temp_q[x][tess_pkg::OpGeomL3];
        head_nrm = mode_linear ? temp_q[x][tess_pkg::OpNormalL1] : temp_q[x][tess_pkg::OpNormalL2];
      end
    end
  end
  assign vtx_o = {ctx_flags_q[head_q], ctx_last_q[head_q], ctx_id_q[head_q], ctx_index_q[head_q], ctx_l_q[head_q],
                  ctx_k_q[head_q], ctx_j_q[head_q], ctx_v_q[head_q], ctx_u_q[head_q],
                  head_nrm, head_pos};

  // ------------------------------------------------------------------ queue state
  always_comb begin
    tail_d  = tail_q;
    head_d  = head_q;
    count_d = count_q;
    if (alloc) tail_d = (tail_q == IdxW'(V - 1)) ? '0 : tail_q + IdxW'(1);
    if (retire) head_d = (head_q == IdxW'(V - 1)) ? '0 : head_q + IdxW'(1);
    if (alloc && !retire) count_d = count_q + CntW'(1);
    else if (retire && !alloc) count_d = count_q - CntW'(1);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q  <= '0;
      tail_q  <= '0;
      count_q <= '0;
    end else begin
      head_q  <= head_d;
      tail_q  <= tail_d;
      count_q <= count_d;
    end
  end

  // Context fields are written at allocation; issued/done/temporaries are only read for
  // allocated contexts, so none of them needs a reset.
  for (genvar x = 0; x < V; x++) begin : g_ctx
    logic              alloc_here;
    logic [NumOps-1:0] issue_set, done_set;
    assign alloc_here = alloc && (tail_q == IdxW'(x));
    always_comb begin
      issue_set = '0;
      for (int a = 0; a < V; a++) begin
        if (age_ctx[a] == IdxW'(x)) issue_set |= selected[a*NumOps +: NumOps];
      end
      done_set = '0;
      for (int i = 0; i < N; i++) begin
        for (int o = 0; o < NumOps; o++) begin
          if (wb_valid[i] && wb_tag[i] == {IdxW'(x), OpW'(o)}) done_set[o] = 1'b1;
        end
      end
    end

    // The point and patch fields: taken at allocation, held until the context is allocated again.
    logic [B:0]         w_d, u_d, v_d;
    logic [LBits-1:0]   j_d, k_d, l_d;
    logic [tess_pkg::IndexBits-1:0] index_d;
    logic [IdBits-1:0]  id_d;
    logic [FlagW-1:0]   flags_d;
    logic               last_d;
    logic [BufW-1:0]    buf_d;
    logic [NumOps-1:0]  issued_d, done_d;
    always_comb begin
      if (alloc_here) begin
        w_d      = dpg_w;
        u_d      = dpg_u;
        v_d      = dpg_v;
        j_d      = dpg_j;
        k_d      = dpg_k;
        l_d      = rd_l;
        index_d  = dpg_index;
        id_d     = rd_id_i;
        flags_d  = rd_flags_i;
        last_d   = dpg_last;
        buf_d    = rd_ptr_i;
        issued_d = mode_linear ? tess_pkg::LinearSkipOps : '0;
        done_d   = mode_linear ? tess_pkg::LinearSkipOps : '0;
      end else begin
        w_d      = ctx_w_q[x];
        u_d      = ctx_u_q[x];
        v_d      = ctx_v_q[x];
        j_d      = ctx_j_q[x];
        k_d      = ctx_k_q[x];
        l_d      = ctx_l_q[x];
        index_d  = ctx_index_q[x];
        id_d     = ctx_id_q[x];
        flags_d  = ctx_flags_q[x];
        last_d   = ctx_last_q[x];
        buf_d    = ctx_buf_q[x];
        issued_d = issued_q[x] | issue_set;
        done_d   = done_q[x] | done_set;
      end
    end

    assign issued_nx[x] = issued_d;
    assign done_nx[x]   = done_d;

    always_ff @(posedge clk_i) begin
      ctx_w_q[x]     <= w_d;
      ctx_u_q[x]     <= u_d;
      ctx_v_q[x]     <= v_d;
      ctx_j_q[x]     <= j_d;
      ctx_k_q[x]     <= k_d;
      ctx_l_q[x]     <= l_d;
      ctx_index_q[x] <= index_d;
      ctx_id_q[x]    <= id_d;
      ctx_flags_q[x] <= flags_d;
      ctx_last_q[x]  <= last_d;
      ctx_buf_q[x]   <= buf_d;
      issued_q[x]    <= issued_d;
      done_q[x]      <= done_d;
    end

    // A temporary takes the result written back for it (an op is issued once: one block at most).
    for (genvar o = 0; o < NumOps; o++) begin : g_temp
      logic [3*W-1:0] temp_d;
      always_comb begin
        temp_d = temp_q[x][o];
        for (int i = 0; i < N; i++) begin
          if (wb_valid[i] && wb_tag[i] == {IdxW'(x), OpW'(o)}) temp_d = wb_res[i];
        end
      end
      always_ff @(posedge clk_i) begin
        temp_q[x][o] <= temp_d;
      end
    end
  end

  // ------------------------------------------------------------------ statistics
  // One class per cycle, the first that applies (§10): the head context waits on results (its
  // candidates are age 0, masked when the queue is empty); ready candidates were left after the
  // N issue slots; an op issued; then the cycles without issue.
  logic head_waiting, left_over, any_issue, no_point;
  assign head_waiting     = (count_q != '0) && !head_done && (ready[NumOps-1:0] == '0);
  assign left_over        = (remaining != '0);
  assign any_issue        = (slot_valid != '0);
  assign no_point         = (count_q == '0) && !rd_full_i;
  assign int_busy_o       = slot_valid;
  assign te_ctx_limited_o = head_waiting;
  assign te_int_limited_o = !head_waiting && left_over;
  assign te_busy_o        = !head_waiting && !left_over && any_issue;
  assign te_blocked_o     = !any_issue && head_done && vtx_full_i;
  assign te_starved_o     = !any_issue && !te_blocked_o && no_point && upstream_busy_i;
  assign te_idle_o        = !any_issue && !te_blocked_o && no_point && !upstream_busy_i;
  assign te_pipeline_o    = !head_waiting && !any_issue && !te_blocked_o && !no_point;

  `TESS_ASSERT(RetireNotFull_A, !(vtx_push_o && vtx_full_i), clk_i, !rst_ni)

endmodule
