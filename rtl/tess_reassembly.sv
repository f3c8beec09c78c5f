// Reassembly buffer of a system of units (sim/system/system.cpp UnitSystem::tick, push, pop): the
// units' vertices back in stream order for GePorts geometry-engine ports.
//
// A pool of ReorderSlots (R) vertex slots holds one linked queue per unit (head, tail, count, a
// next pointer per slot; free slot indices in a circular FIFO), and an order FIFO holds, per
// patch dispatched and not yet fully handed to the ports, its unit and id. Every decision comes
// from the state at the start of the cycle:
//
//  - admission: units in index order with a running count; unit u's vertex is admitted while
//    occupancy + admitted before it < R when it belongs to the oldest patch (the order FIFO's
//    head: same unit, same id), < R - 1 otherwise (one slot stays for the oldest patch);
//  - slots: the admitted units, in index order, take the free FIFO's first entries (unit u the
//    entry after those of the admitted units before it: a prefix count, no search over R); the
//    slots the ports take are appended at its tail in lane order;
//  - lanes: lane k is the k-th next vertex in stream order (the head unit's queue until a last
//    vertex, then the next patch's unit's queue), valid while each lane before it is;
//  - ports: port p is offered lane k_p, k_p the number of ports before it that are ready (each
//    ready port before it takes a lane, or finds none and so does every later one). So
//    port_valid_o[p] and port_vtx_o[p] depend combinationally on port_ready_i[p-1:0], never on
//    port_ready_i[p]: the consumer's ready must not depend on valid (a GE presents ready from its
//    own state, sim::Gpe::tick).
//
// Vertices admitted in a cycle enter their queues at its end: no port sees them before the next
// cycle. The queues pop first and push after (a queue emptied and refilled in one cycle restarts
// at the new slot). Vertex words are opaque here except the id at [IdLsb +: IdBits] and the last
// flag at LastBit.
//
// RuntimeConfig = 1 takes R from slots_i (2..ReorderSlots, static during a run: the slots above
// it are never used), 0 from the parameter.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_reassembly #(
  parameter int unsigned Units         = 2,
  parameter int unsigned GePorts       = 1,
  parameter int unsigned ReorderSlots  = 4,
  parameter int unsigned RuntimeConfig = 0,
  parameter int unsigned UnitPatches   = tess_pkg::unit_patches(tess_pkg::TriFifoDepth, tess_pkg::CpgCopies,
                                                                tess_pkg::CpBuffers, tess_pkg::VtxFifoDepth),
  parameter int unsigned VtxW          = tess_pkg::vtx_w(1 + tess_pkg::CoordIntBits + tess_pkg::CoordFracBits,
                                                         tess_pkg::BaryBits),
  parameter int unsigned IdLsb         = VtxW - tess_pkg::FlagBits - 1 - tess_pkg::IdBits,
  parameter int unsigned LastBit       = VtxW - tess_pkg::FlagBits - 1,
  localparam int unsigned UW  = (Units > 1) ? $clog2(Units) : 1,
  localparam int unsigned SW  = (ReorderSlots > 1) ? $clog2(ReorderSlots) : 1,
  localparam int unsigned SCW = $clog2(ReorderSlots + 1),
  localparam int unsigned IdW = tess_pkg::IdBits
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic [SCW-1:0]           slots_i,       // R in use, read with RuntimeConfig only
  // The units' vertex outputs
  input  logic [Units-1:0]         unit_valid_i,
  input  logic [Units*VtxW-1:0]    unit_vtx_i,    // unit u at [u VtxW +: VtxW]
  output logic [Units-1:0]         unit_ready_o,  // admitted this cycle
  // The distributor's dispatch: a patch's unit and id, in stream order
  input  logic                     push_i,
  input  logic [UW-1:0]            push_unit_i,
  input  logic [IdW-1:0]           push_id_i,
  // Geometry-engine ports
  output logic [GePorts-1:0]       port_valid_o,
  input  logic [GePorts-1:0]       port_ready_i,
  output logic [GePorts*VtxW-1:0]  port_vtx_o     // port p at [p VtxW +: VtxW]
);

  // Patches in flight: each unit holds at most UnitPatches, the buffer at most R more.
  localparam int unsigned OrderDepth = Units * UnitPatches + ReorderSlots + 1;
  localparam int unsigned OPW = $clog2(OrderDepth);
  localparam int unsigned OCW = $clog2(OrderDepth + 1);
  localparam int unsigned AW  = $clog2(ReorderSlots + Units + 1);  // occupancy + admissions
  localparam int unsigned KW  = $clog2(GePorts + 1);               // 0..GePorts lanes

  logic [SCW-1:0] slots;
  if (RuntimeConfig != 0) begin : g_runtime
    assign slots = slots_i;
  end else begin : g_fixed
    assign slots = SCW'(ReorderSlots);
    logic unused_slots;
    assign unused_slots = ^slots_i;
  end

  // ------------------------------------------------------------------ registered state
  (* mem2reg *) logic [VtxW-1:0] slot_vtx_q [ReorderSlots];   // data: written before read
  (* mem2reg *) logic [SW-1:0]   slot_next_q [ReorderSlots];  // data: written before read
  // Free slot indices, circular over ReorderSlots entries (with RuntimeConfig only `slots` of
  // them are ever in use). Its count is R - occupancy, so occ_q serves as the count register.
  (* mem2reg *) logic [SW-1:0] free_idx_q [ReorderSlots];
  logic [SW-1:0]           free_head_q;
  logic [SCW-1:0]          occ_q;
  (* mem2reg *) logic [SW-1:0]  head_q [Units];   // meaningful while count > 0
  (* mem2reg *) logic [SW-1:0]  tail_q [Units];   // meaningful while count > 0
  (* mem2reg *) logic [SCW-1:0] count_q [Units];
  (* mem2reg *) logic [UW-1:0]  ord_unit_q [OrderDepth];   // data
  (* mem2reg *) logic [IdW-1:0] ord_id_q [OrderDepth];     // data
  logic [OPW-1:0] ord_head_q;
  logic [OCW-1:0] ord_count_q;

  (* mem2reg *) logic [VtxW-1:0] uvtx [Units];
  for (genvar u = 0; u < Units; u++) begin : g_unit_vtx
    assign uvtx[u] = unit_vtx_i[u*VtxW +: VtxW];
  end

  // ------------------------------------------------------------------ admission
  logic [UW-1:0]  oldest_unit;
  logic [IdW-1:0] oldest_id;
  assign oldest_unit = ord_unit_q[ord_head_q];
  assign oldest_id   = ord_id_q[ord_head_q];

  logic [Units-1:0] admit, oldest;
  logic [AW-1:0]    admitted;
  (* mem2reg *) logic [AW-1:0] admitted_before [Units];  // unit u's entry of the free FIFO
  for (genvar u = 0; u < Units; u++) begin : g_oldest
    assign oldest[u] = ord_count_q != '0 && oldest_unit == UW'(u) && oldest_id == uvtx[u][IdLsb +: IdW];
  end
  always_comb begin
    admitted = '0;
    for (int u = 0; u < Units; u++) begin
      admitted_before[u] = admitted;
      admit[u] = unit_valid_i[u] && (AW'(occ_q) + admitted < (oldest[u] ? AW'(slots) : AW'(slots) - AW'(1)));
      admitted = admitted + AW'(admit[u]);
    end
  end
  assign unit_ready_o = admit;

  // ------------------------------------------------------------------ lanes
  // State after taking lanes 0..k-1, k = 0..GePorts: each unit's queue cursor (slot, count left)
  // and the order FIFO's head and count. Packed: [(k Units + u) SW +: SW] and so on.
  logic [(GePorts+1)*Units*SW-1:0]  cur_slot;
  logic [(GePorts+1)*Units*SCW-1:0] cur_count;
  logic [(GePorts+1)*OPW-1:0]       cur_ord;
  logic [(GePorts+1)*OCW-1:0]       cur_left;
  logic [GePorts-1:0]               lane_valid;
  logic [GePorts*SW-1:0]            lane_slot;
  logic [GePorts*VtxW-1:0]          lane_vtx;
  logic [UW-1:0]                    lunit;
  logic [SW-1:0]                    lslot;
  logic                             lnonempty, llast, lprev;
  logic [OPW-1:0]                   optr;
  logic [OCW-1:0]                   oleft;
  always_comb begin
    cur_slot   = '0;
    cur_count  = '0;
    cur_ord    = '0;
    cur_left   = '0;
    lane_valid = '0;
    lane_slot  = '0;
    lane_vtx   = '0;
    for (int u = 0; u < Units; u++) begin
      cur_slot[u*SW +: SW]    = head_q[u];
      cur_count[u*SCW +: SCW] = count_q[u];
    end
    cur_ord[0 +: OPW]  = ord_head_q;
    cur_left[0 +: OCW] = ord_count_q;
    lprev = 1'b1;
    lunit = '0;
    lslot = '0;
    lnonempty = 1'b0;
    llast = 1'b0;
    optr = '0;
    oleft = '0;
    for (int k = 0; k < GePorts; k++) begin
      optr      = cur_ord[k*OPW +: OPW];
      oleft     = cur_left[k*OCW +: OCW];
      lunit     = ord_unit_q[optr];
      lslot     = '0;
      lnonempty = 1'b0;
      for (int u = 0; u < Units; u++) begin
        if (lunit == UW'(u)) begin
          lslot     = cur_slot[(k*Units+u)*SW +: SW];
          lnonempty = cur_count[(k*Units+u)*SCW +: SCW] != '0;
        end
      end
      lane_valid[k]             = lprev && oleft != '0 && lnonempty;
      lprev                     = lane_valid[k];
      lane_slot[k*SW +: SW]     = lslot;
      lane_vtx[k*VtxW +: VtxW]  = slot_vtx_q[lslot];
      llast                     = slot_vtx_q[lslot][LastBit];
      // Taken: the unit's cursor steps, and a last vertex steps the order FIFO.
      for (int u = 0; u < Units; u++) begin
        cur_slot[((k+1)*Units+u)*SW +: SW] = (lunit == UW'(u)) ? slot_next_q[lslot]
                                                               : cur_slot[(k*Units+u)*SW +: SW];
        cur_count[((k+1)*Units+u)*SCW +: SCW] = cur_count[(k*Units+u)*SCW +: SCW] - SCW'(lunit == UW'(u));
      end
      cur_ord[(k+1)*OPW +: OPW]  = !llast ? optr : (optr == OPW'(OrderDepth - 1)) ? '0 : optr + OPW'(1);
      cur_left[(k+1)*OCW +: OCW] = oleft - OCW'(llast);
    end
  end

  // ------------------------------------------------------------------ ports
  logic [KW-1:0] taken;  // lanes taken this cycle: 0..taken-1
  logic [KW-1:0] ready_before;
  always_comb begin
    ready_before = '0;
    taken        = '0;
    port_valid_o = '0;
    port_vtx_o   = '0;
    for (int p = 0; p < GePorts; p++) begin
      for (int k = 0; k <= p; k++) begin
        if (ready_before == KW'(k)) begin
          port_valid_o[p]            = lane_valid[k];
          port_vtx_o[p*VtxW +: VtxW] = lane_vtx[k*VtxW +: VtxW];
        end
      end
      taken        = taken + KW'(port_ready_i[p] && port_valid_o[p]);
      ready_before = ready_before + KW'(port_ready_i[p]);
    end
  end

  // ------------------------------------------------------------------ next state
  // The queues and the order FIFO after the pops: the lane state after `taken` lanes.
  (* mem2reg *) logic [SW-1:0]  head_pop [Units];
  (* mem2reg *) logic [SCW-1:0] count_pop [Units];
  logic [OPW-1:0] ord_head_pop;
  logic [OCW-1:0] ord_count_pop;
  always_comb begin
    for (int u = 0; u < Units; u++) begin
      head_pop[u]  = '0;
      count_pop[u] = '0;
    end
    ord_head_pop  = '0;
    ord_count_pop = '0;
    for (int k = 0; k <= GePorts; k++) begin
      if (taken == KW'(k)) begin
        for (int u = 0; u < Units; u++) begin
          head_pop[u]  = cur_slot[(k*Units+u)*SW +: SW];
          count_pop[u] = cur_count[(k*Units+u)*SCW +: SCW];
        end
        ord_head_pop  = cur_ord[k*OPW +: OPW];
        ord_count_pop = cur_left[k*OCW +: OCW];
      end
    end
  end

  // The free FIFO, circular over entries 0..ReorderSlots-1 (head + an offset below R wraps at
  // most once). Allocation: the first M entries are read independently of the admission, and
  // unit u takes the one after those of the admitted units before it (admissions never exceed the
  // free slots: occupancy + admitted <= R, so those entries hold free slots). Freeing: the k-th
  // lane taken goes to tail + k, tail = head + R - occupancy: the allocations move the head and
  // shorten the count alike, so the tail does not depend on them; free + taken <= R, so no write
  // lands on an entry that holds a free slot of the start of the cycle.
  localparam int unsigned FW = $clog2(2 * ReorderSlots + Units + GePorts);
  // entries head .. head + M - 1, read every cycle: Units <= ReorderSlots (every build's)
  (* mem2reg *) logic [SW-1:0] free_first [Units];
  (* mem2reg *) logic [SW-1:0] alloc [Units];
  (* mem2reg *) logic [SW-1:0] free_put [GePorts];  // where lane k's slot goes if taken
  logic [FW-1:0]  fpos;
  logic [SW-1:0]  free_head_d;
  (* mem2reg *) logic [SW-1:0] free_idx_d [ReorderSlots];
  always_comb begin
    fpos = '0;
    for (int j = 0; j < Units; j++) begin
      fpos          = FW'(free_head_q) + FW'(j);
      free_first[j] = free_idx_q[(fpos >= FW'(ReorderSlots)) ? SW'(fpos - FW'(ReorderSlots)) : SW'(fpos)];
    end
    for (int u = 0; u < Units; u++) begin
      alloc[u] = '0;
      for (int j = 0; j <= u; j++) begin
        if (admitted_before[u] == AW'(j)) alloc[u] = free_first[j];
      end
    end
    for (int k = 0; k < GePorts; k++) begin
      fpos        = FW'(free_head_q) + FW'(slots) - FW'(occ_q) + FW'(k);
      free_put[k] = (fpos >= FW'(ReorderSlots)) ? SW'(fpos - FW'(ReorderSlots)) : SW'(fpos);
    end
    fpos        = FW'(free_head_q) + FW'(admitted);
    free_head_d = (fpos >= FW'(ReorderSlots)) ? SW'(fpos - FW'(ReorderSlots)) : SW'(fpos);
    for (int i = 0; i < ReorderSlots; i++) begin
      free_idx_d[i] = free_idx_q[i];
      for (int k = 0; k < GePorts; k++) begin
        if (KW'(k) < taken && free_put[k] == SW'(i)) free_idx_d[i] = lane_slot[k*SW +: SW];
      end
    end
  end

  (* mem2reg *) logic [SW-1:0]  head_d [Units];
  (* mem2reg *) logic [SW-1:0]  tail_d [Units];
  (* mem2reg *) logic [SCW-1:0] count_d [Units];
  (* mem2reg *) logic [VtxW-1:0] slot_vtx_d [ReorderSlots];
  (* mem2reg *) logic [SW-1:0]   slot_next_d [ReorderSlots];
  logic [SCW-1:0]          occ_d;
  always_comb begin
    for (int u = 0; u < Units; u++) begin
      head_d[u]  = head_pop[u];
      tail_d[u]  = tail_q[u];
      count_d[u] = count_pop[u];
      if (admit[u]) begin
        if (count_pop[u] == '0) head_d[u] = alloc[u];
        tail_d[u]  = alloc[u];
        count_d[u] = count_pop[u] + SCW'(1);
      end
    end
    for (int s = 0; s < ReorderSlots; s++) begin
      slot_vtx_d[s]  = slot_vtx_q[s];
      slot_next_d[s] = slot_next_q[s];
      for (int u = 0; u < Units; u++) begin
        if (admit[u] && alloc[u] == SW'(s)) slot_vtx_d[s] = uvtx[u];
        if (admit[u] && count_pop[u] != '0 && tail_q[u] == SW'(s)) slot_next_d[s] = alloc[u];
      end
    end
    occ_d  = SCW'(AW'(occ_q) + admitted - AW'(taken));
  end

  // The order FIFO: one push a cycle at the tail (the head and count of the start of the cycle
  // give it: pops move both), up to GePorts pops.
  logic [OPW-1:0] ord_tail;
  logic [OCW-1:0] ord_count_d;
  assign ord_tail    = (OCW'(ord_head_q) + ord_count_q >= OCW'(OrderDepth))
                         ? OPW'(OCW'(ord_head_q) + ord_count_q - OCW'(OrderDepth))
                         : OPW'(OCW'(ord_head_q) + ord_count_q);
  assign ord_count_d = ord_count_pop + OCW'(push_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      free_head_q <= '0;
      occ_q       <= '0;
      ord_head_q  <= '0;
      ord_count_q <= '0;
    end else begin
      free_head_q <= free_head_d;
      occ_q       <= occ_d;
      ord_head_q  <= ord_head_pop;
      ord_count_q <= ord_count_d;
    end
  end
  for (genvar u = 0; u < Units; u++) begin : g_queue
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) count_q[u] <= '0;
      else count_q[u] <= count_d[u];
    end
    always_ff @(posedge clk_i) begin
      head_q[u] <= head_d[u];
      tail_q[u] <= tail_d[u];
    end
  end
  // Reset: every slot free, entry i holding slot i (with RuntimeConfig the first `slots`).
  for (genvar i = 0; i < ReorderSlots; i++) begin : g_free
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) free_idx_q[i] <= SW'(i);
      else free_idx_q[i] <= free_idx_d[i];
    end
  end
  for (genvar s = 0; s < ReorderSlots; s++) begin : g_slot
    always_ff @(posedge clk_i) begin
      slot_vtx_q[s]  <= slot_vtx_d[s];
      slot_next_q[s] <= slot_next_d[s];
    end
  end
  (* mem2reg *) logic [UW-1:0]  ord_unit_d [OrderDepth];
  (* mem2reg *) logic [IdW-1:0] ord_id_d [OrderDepth];
  always_comb begin
    for (int i = 0; i < OrderDepth; i++) begin
      ord_unit_d[i] = (push_i && ord_tail == OPW'(i)) ? push_unit_i : ord_unit_q[i];
      ord_id_d[i]   = (push_i && ord_tail == OPW'(i)) ? push_id_i : ord_id_q[i];
    end
  end
  for (genvar i = 0; i < OrderDepth; i++) begin : g_order
    always_ff @(posedge clk_i) begin
      ord_unit_q[i] <= ord_unit_d[i];
      ord_id_q[i]   <= ord_id_d[i];
    end
  end

  // The order FIFO never overflows (UnitSystem throws if it would), the occupancy stays within R.
  `TESS_ASSERT(OrderNoOverflow_A, !(push_i && ord_count_pop == OCW'(OrderDepth)), clk_i, !rst_ni)
  `TESS_ASSERT(OccupancyInRange_A, occ_q <= slots, clk_i, !rst_ni)
  `TESS_ASSERT(SlotsInRange_A, slots >= SCW'(2) && slots <= SCW'(ReorderSlots), clk_i, !rst_ni)

endmodule
