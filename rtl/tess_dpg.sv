// DPG: domain-point generator (docs/microarchitecture.md §7). Walks the pattern of the patch in
// buffer[rd_ptr] and gives the barycentric weights of the current point and its index in the
// patch.
//
// Uniform pattern: the lattice in pattern order (rows k = 0..L, in a row j = 0..L-k),
// u = bary_weight(j, L), v = bary_weight(k, L),
// w = 2^B - u - v, where bary_weight(j, L) = floor((j 2^(B+1) + L) / 2L) is the round half up
// of j 2^B / L (sim/base/fixed.hpp).
//
// No divider: the weights are kept as quotient and remainder of that division and advanced
// exactly. Going from j to j + 1 adds 2^(B+1) to the numerator, i.e. q(L) = floor(2^B / L) to
// the quotient and r(L) = 2^(B+1) mod 2L to the remainder (with one carry when the remainder
// reaches 2L). q and r come from a 64-entry constant table indexed by L. At j = 0 the weight
// is 0 with remainder L, so a new row or patch needs no state.
//
// D3D11 pattern (docs/patterns.md; sim/values/d3d11_walk.cpp D3D11PointWalker): the outer ring
// from the corner v = 1, edge by edge, then the rings inwards, then the centre of an even
// pattern. Each point is one placement on the current edge (from the setup the FSU stored with
// the patch, stepped from the point before); an inner ring's offset from the outer edges (2/3 t_r, and half of
// it along the edge) is computed once per ring, when the walk enters it. j and k give the ring
// and the edge (3: the centre). B >= 16: the 16.16 points are exact in B bits.
`ifndef TESS_ASSERT_SVH
`include "tess_assert.svh"
`endif
module tess_dpg #(
  parameter int unsigned BaryBits = tess_pkg::BaryBits,
  localparam int unsigned LBits   = tess_pkg::FactorBits
) (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  input  logic [tess_pkg::PatchBits-1:0] patch_i,    // {setup, pattern, L} of buffer[rd_ptr]
  input  logic                           consume_i,  // a context takes the current point
  output logic [LBits-1:0]               j_o,
  output logic [LBits-1:0]               k_o,
  output logic [tess_pkg::IndexBits-1:0] index_o,
  output logic [BaryBits:0]              w_o,
  output logic [BaryBits:0]              u_o,
  output logic [BaryBits:0]              v_o,
  output logic                           last_o      // the patch's last point
);

  localparam int unsigned EW = tess_pkg::EdgeBits;
  localparam int unsigned XW = tess_pkg::IndexBits;

  logic [LBits-1:0] l_i;
  logic [1:0]       pattern;
  logic             d3d11;
  logic [tess_pkg::SetupBits-1:0] setup;
  assign {setup, pattern, l_i} = patch_i;
  assign d3d11 = (pattern != tess_pkg::PatUniform);

  localparam int unsigned B    = BaryBits;
  localparam int unsigned RemW = LBits + 1;  // remainders < 2L <= 128

  // ---- per-L step of the weight: q = floor(2^B / L), r = 2^(B+1) mod 2L, from a constant table
  // read by L (a multiplexer tree; an if per entry would chain 64 multiplexers).
  localparam int unsigned StepW = B + 1 + RemW;
  localparam int unsigned Rows  = 1 << LBits;
  function automatic logic [Rows*StepW-1:0] step_table();
    logic [Rows*StepW-1:0] t;
    t = '0;
    for (int l = 1; l <= tess_pkg::MaxFactor; l++) begin
      t[l*StepW +: StepW] = {(B + 1)'((64'd1 << B) / 64'(l)), RemW'((64'd1 << (B + 1)) % (64'd2 * 64'(l)))};
    end
    step_table = t;
  endfunction
  localparam logic [Rows*StepW-1:0] StepTable = step_table();
  logic [B:0]      step_q;
  logic [RemW-1:0] step_r;
  assign {step_q, step_r} = StepTable[l_i*StepW +: StepW];

  logic [LBits-1:0] j_q, k_q;
  logic [B:0]       u_q, v_q;      // weights of j_q, k_q (meaningful when they are > 0)
  logic [RemW-1:0]  ru_q, rv_q;    // their remainders

  // Weight and remainder of the current j and k (index 0: weight 0, remainder L).
  logic [B:0]      u_cur, v_cur;
  logic [RemW-1:0] ru_cur, rv_cur, two_l;
  assign two_l  = {l_i, 1'b0};
  assign u_cur  = (j_q == '0) ? '0 : u_q;
  assign v_cur  = (k_q == '0) ? '0 : v_q;
  assign ru_cur = (j_q == '0) ? RemW'(l_i) : ru_q;
  assign rv_cur = (k_q == '0) ? RemW'(l_i) : rv_q;

  // One lattice step of a weight: quotient + q (+ 1 on carry), remainder + r (- 2L on carry).
  logic [RemW:0]   ru_sum, rv_sum;
  logic            u_carry, v_carry;
  logic [B:0]      u_next, v_next;
  logic [RemW-1:0] ru_next, rv_next;
  assign ru_sum  = {1'b0, ru_cur} + {1'b0, step_r};
  assign rv_sum  = {1'b0, rv_cur} + {1'b0, step_r};
  assign u_carry = (ru_sum >= {1'b0, two_l});
  assign v_carry = (rv_sum >= {1'b0, two_l});
  assign u_next  = u_cur + step_q + (B + 1)'(u_carry);
  assign v_next  = v_cur + step_q + (B + 1)'(v_carry);
  assign ru_next = u_carry ? RemW'(ru_sum - {1'b0, two_l}) : ru_sum[RemW-1:0];
  assign rv_next = v_carry ? RemW'(rv_sum - {1'b0, two_l}) : rv_sum[RemW-1:0];

  logic row_continues, uni_last;
  assign uni_last      = (k_q == l_i);
  assign row_continues = ({1'b0, j_q} + {1'b0, k_q} + 8'd1 <= {1'b0, l_i});

  logic [LBits-1:0] j_d, k_d;
  logic [B:0]       u_d, v_d;
  logic [RemW-1:0]  ru_d, rv_d;
  always_comb begin
    j_d = j_q;
    k_d = k_q;
    if (consume_i && !d3d11) begin
      if (uni_last) begin
        j_d = '0;
        k_d = '0;
      end else if (row_continues) begin
        j_d = j_q + LBits'(1);
      end else begin
        j_d = '0;
        k_d = k_q + LBits'(1);
      end
    end
  end
  // Weight registers: read only for an index > 0, which was reached by a step that wrote them.
  always_comb begin
    u_d  = u_q;
    ru_d = ru_q;
    v_d  = v_q;
    rv_d = rv_q;
    if (consume_i && !d3d11 && !uni_last) begin
      if (row_continues) begin
        u_d  = u_next;
        ru_d = ru_next;
      end else begin
        v_d  = v_next;
        rv_d = rv_next;
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      j_q <= '0;
      k_q <= '0;
    end else begin
      j_q <= j_d;
      k_q <= k_d;
    end
  end
  always_ff @(posedge clk_i) begin
    u_q  <= u_d;
    ru_q <= ru_d;
    v_q  <= v_d;
    rv_q <= rv_d;
  end

  // ------------------------------------------------------------------ D3D11 walk
  // The placement t of a point on its edge (sim/values/d3d11_walk.cpp d3d11_place: the blend
  // i' fw + i cw of the unmirrored index i, rounded, mirrored past the middle; i' = i - 1 past
  // the split) is not multiplied out per point:
  // along an edge the walk moves the index by one, so i moves by at most one and the blend by
  // fw + cw, less fw where i crosses the split. The blend (biased by 2^15 for the rounding) and
  // t are registered for the current point, computed at the end of the cycle before from the
  // next state, so that the output arithmetic starts from registers (docs/rtl.md, Depth
  // budget). Every edge starts at i = 0 (outer ring) or i = r (ring r): the inner edge's blend
  // of r + 1 and the ring's offset are computed ahead, in two registered steps, while the walk
  // is on ring r. A patch's first point (the corner v = 1) needs no state from the patch.
  (* mem2reg *) logic [EW-1:0] outer_edge [3];
  logic [EW-1:0] inner_edge;
  logic [6:0]    n_inner;
  logic [XW-1:0] point_count;
  assign {point_count, n_inner, inner_edge, outer_edge[2], outer_edge[1], outer_edge[0]} = setup;

  localparam int unsigned BlW = 40;  // biased blend: < 2^33 + 2^15
  localparam logic [BlW-1:0] Bias = BlW'(32'h8000);

  logic [5:0]     ring_q;        // 0: the outer ring
  logic [1:0]     edge_q;        // 3: the centre
  logic [6:0]     p_q;           // position along the ring's edge
  logic [6:0]     ring_last_q;   // ring r >= 1: its edges take inner points r .. ring_last - 1
  logic [16:0]    perp_q, shift_q;
  logic [XW-1:0]  index_q;       // both patterns
  logic [6:0]     pidx_q;        // the point's index on its edge (not valid at a patch's first point)
  logic [5:0]     i_q;           // its unmirrored index
  logic           mirrored_q;
  logic [BlW-1:0] blend_q;       // blend of i_q + 2^15
  logic [BlW-1:0] mblend_q;      // 2^32 + 2^16 - 1 - blend_q: its bits 32..16 are 1 - position
  logic [16:0]    t_q;           // the point's placement on its edge
  logic [BlW-1:0] ring_blend_q;  // ring r >= 1: blend of i = r on the inner edge + 2^15

  logic          outer_ring, centre, first_point;
  assign outer_ring  = (ring_q == '0);
  assign centre      = (edge_q == 2'd3);
  assign first_point = (index_q == '0);

  // The current edge's setup: {points, cw, fw + cw, split, half points, odd}.
  logic [EW-1:0] cur_edge;
  logic [6:0]    cur_points, edge_end, pidx;
  logic [32:0]   cur_cw;
  logic [33:0]   cur_both;
  logic [5:0]    cur_split, cur_half;
  logic          cur_odd;
  assign cur_edge   = outer_ring ? outer_edge[edge_q] : inner_edge;
  assign {cur_points, cur_cw, cur_both, cur_split, cur_half, cur_odd} = cur_edge;
  assign edge_end   = outer_ring ? cur_points - 7'd1 : ring_last_q;
  // At a patch's first point the index is outer edge 0's last: points - 1 (i = 0, mirrored).
  assign pidx       = first_point ? cur_points - 7'd1 : pidx_q;

  logic [16:0] t, ts;
  assign t  = first_point ? 17'h10000 : t_q;
  assign ts = t - shift_q;

  // ---- the next point on the same edge: the index one on (edge 1) or back (edges 0, 2)
  logic           forwards;
  logic [6:0]     step_pidx;
  logic [5:0]     step_i;
  logic           step_mirrored, i_up, i_down;
  logic [BlW-1:0] blend_up, blend_down, step_blend;
  assign forwards  = (edge_q == 2'd1);
  assign step_pidx = forwards ? pidx + 7'd1 : pidx - 7'd1;
  assign step_mirrored = step_pidx >= 7'(cur_half);
  // i follows the index before the middle and runs against it after; it stays where the index
  // crosses the middle of an odd edge (i = h - 1 on both sides) and reaches h on an even one.
  always_comb begin
    i_up   = 1'b0;
    i_down = 1'b0;
    if (forwards) begin
      if (pidx == 7'(cur_half) - 7'd1) i_up = !cur_odd;
      else if (mirrored_q || first_point) i_down = 1'b1;
      else i_up = 1'b1;
    end else begin
      if (pidx == 7'(cur_half)) i_down = !cur_odd;
      else if (mirrored_q || first_point) i_up = 1'b1;
      else i_down = 1'b1;
    end
  end
  logic [5:0] i_cur;
  assign i_cur  = first_point ? '0 : i_q;
  assign step_i = i_up ? i_cur + 6'd1 : i_down ? i_cur - 6'd1 : i_cur;
  // The mirrored placement 1 - floor(b / 2^16) of a biased blend b is floor(m / 2^16) for
  // m = 2^32 + 2^16 - 1 - b: kept as a second accumulator, it needs no subtraction after the step.
  localparam logic [BlW-1:0] MirrorBase = BlW'(64'h1_0000_FFFF);
  logic [BlW-1:0] blend_cur, mblend_cur, inc_up, inc_down, mblend_up, mblend_down, step_mblend;
  assign blend_cur  = first_point ? Bias : blend_q;
  assign mblend_cur = first_point ? MirrorBase - Bias : mblend_q;
  // i -> i + 1 adds fw + cw, or cw alone when i is the split (i' stays); i -> i - 1 the reverse.
  assign inc_up      = (i_cur == cur_split) ? BlW'(cur_cw) : BlW'(cur_both);
  assign inc_down    = (i_cur == cur_split + 6'd1) ? BlW'(cur_cw) : BlW'(cur_both);
  assign blend_up    = blend_cur + inc_up;
  assign blend_down  = blend_cur - inc_down;
  assign mblend_up   = mblend_cur - inc_up;
  assign mblend_down = mblend_cur + inc_down;
  assign step_blend  = i_up ? blend_up : i_down ? blend_down : blend_cur;
  assign step_mblend = i_up ? mblend_up : i_down ? mblend_down : mblend_cur;

  // ---- the inner edge's blend of i = r + 1 and the offset of ring r + 1, ahead of entering it
  logic [32:0]    in_cw;
  logic [33:0]    in_sum;
  logic [5:0]     in_split, in_half;
  logic [6:0]     unused_in_points;
  logic           unused_in_odd;
  assign {unused_in_points, in_cw, in_sum, in_split, in_half, unused_in_odd} = inner_edge;
  logic [5:0]     next_ring;
  logic [BlW-1:0] in_both, in_fw, ring_prod_q, next_prod, next_blend, next_ring_blend_q;
  logic [16:0]    next_pos, next_perp, next_perp_q;
  logic [32:0]    ring_scaled;
  assign next_ring = ring_q + 6'd1;
  assign in_both   = BlW'(in_sum);
  assign in_fw     = BlW'(in_sum) - BlW'(in_cw);
  // (r + 1)(fw + cw): a product for the rings inside the first, which the walk enters at least
  // nine points after the ring before; the first ring's is fw + cw itself, ready a cycle after
  // the patch appears (its outer ring can be three points).
  assign next_prod  = (ring_q == '0) ? in_both : ring_prod_q;
  assign next_blend = next_prod + Bias - (({1'b0, next_ring} > {1'b0, in_split}) ? in_fw : '0);
  assign next_pos   = (next_ring == in_half) ? 17'h8000 : next_ring_blend_q[32:16];
  assign ring_scaled = 33'(next_pos) * 33'h0aaaa + 33'h8000;
  assign next_perp  = ring_scaled[32:16];
  always_ff @(posedge clk_i) begin
    ring_prod_q       <= BlW'(next_ring) * in_both;
    next_ring_blend_q <= next_blend;
    next_perp_q       <= next_perp;
  end

  // ---- the next state
  logic           d3d_last;
  assign d3d_last = (index_q == point_count - XW'(1));

  logic [5:0]     ring_d;
  logic [1:0]     edge_d;
  logic [6:0]     p_d, ring_last_d, pidx_d;
  logic [16:0]    perp_d, shift_d;
  logic [XW-1:0]  index_d;
  logic [5:0]     i_d;
  logic           mirrored_d;
  logic [BlW-1:0] blend_d, mblend_d, ring_blend_d;
  logic [16:0]    t_d;
  logic [5:0]     half_d;
  // The first point of the next edge: outer edges start at i = 0 (edge 1 at index 0, edge 2 at
  // its last index, mirrored), inner ones at i = r (edge 1 at index r, edges 0 and 2 at
  // ring_last, mirrored).
  logic [EW-1:0]  next_outer;
  assign next_outer = outer_edge[edge_q + 2'd1];
  always_comb begin
    ring_d       = ring_q;
    edge_d       = edge_q;
    p_d          = p_q;
    index_d      = index_q;
    ring_last_d  = ring_last_q;
    perp_d       = perp_q;
    shift_d      = shift_q;
    pidx_d       = pidx;
    i_d          = i_cur;
    mirrored_d   = first_point || mirrored_q;
    blend_d      = blend_cur;
    mblend_d     = mblend_cur;
    ring_blend_d = ring_blend_q;
    half_d       = cur_half;
    if (consume_i) begin
      index_d = last_o ? '0 : index_q + XW'(1);
      if (d3d11) begin
        if (d3d_last) begin
          ring_d = '0;
          edge_d = '0;
          p_d    = '0;
        end else if (!centre) begin
          if (p_q + 7'd1 != edge_end) begin
            p_d        = p_q + 7'd1;
            pidx_d     = step_pidx;
            i_d        = step_i;
            mirrored_d = step_mirrored;
            blend_d    = step_blend;
            mblend_d   = step_mblend;
          end else if (edge_q != 2'd2) begin
            p_d        = 7'(ring_q);
            edge_d     = edge_q + 2'd1;
            mirrored_d = (edge_q == 2'd1);  // the next edge is 2
            if (outer_ring) begin
              pidx_d  = (edge_q == 2'd0) ? '0 : next_outer[EW-1 -: 7] - 7'd1;
              i_d     = '0;
              blend_d = Bias;
              mblend_d = MirrorBase - Bias;
              half_d  = next_outer[6:1];
            end else begin
              pidx_d  = (edge_q == 2'd0) ? 7'(ring_q) : ring_last_q;
              i_d     = ring_q;
              blend_d = ring_blend_q;
              mblend_d = MirrorBase - ring_blend_q;
            end
          end else if (7'(next_ring) < (n_inner >> 1)) begin
            ring_d       = next_ring;
            edge_d       = '0;
            p_d          = 7'(next_ring);
            ring_last_d  = n_inner - 7'd1 - 7'(next_ring);
            perp_d       = next_perp_q;
            shift_d      = (next_perp_q + 17'd1) >> 1;
            pidx_d       = n_inner - 7'd1 - 7'(next_ring);
            i_d          = next_ring;
            mirrored_d   = 1'b1;
            blend_d      = next_ring_blend_q;
            mblend_d     = MirrorBase - next_ring_blend_q;
            ring_blend_d = next_ring_blend_q;
            half_d       = in_half;
          end else begin  // the centre of an even pattern, a ring of its own
            ring_d = next_ring;
            edge_d = 2'd3;
          end
        end
      end
    end
  end
  // The placement of the next point: the middle is exact, past it t is mirrored.
  assign t_d = (i_d == half_d) ? 17'h8000 : mirrored_d ? mblend_d[32:16] : blend_d[32:16];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ring_q      <= '0;
      edge_q      <= '0;
      p_q         <= '0;
      index_q     <= '0;
      ring_last_q <= '0;
      perp_q      <= '0;
      shift_q     <= '0;
    end else begin
      ring_q      <= ring_d;
      edge_q      <= edge_d;
      p_q         <= p_d;
      index_q     <= index_d;
      ring_last_q <= ring_last_d;
      perp_q      <= perp_d;
      shift_q     <= shift_d;
    end
  end
  // Data only: read at a point after the first of a patch, written by the step that reached it.
  always_ff @(posedge clk_i) begin
    pidx_q       <= pidx_d;
    i_q          <= i_d;
    mirrored_q   <= mirrored_d;
    blend_q      <= blend_d;
    mblend_q     <= mblend_d;
    t_q          <= t_d;
    ring_blend_q <= ring_blend_d;
  end

  logic [16:0] du, dv;  // 16.16
  always_comb begin
    if (centre) begin
      du = 17'h5555;
      dv = 17'h5555;
    end else if (outer_ring) begin
      du = (edge_q == 2'd0) ? '0 : t;
      dv = (edge_q == 2'd0) ? t : (edge_q == 2'd1) ? '0 : 17'h10000 - t;
    end else begin
      du = (edge_q == 2'd0) ? perp_q : ts;
      dv = (edge_q == 2'd0) ? ts : (edge_q == 2'd1) ? perp_q : 17'h10000 - ts - perp_q;
    end
  end

  // ------------------------------------------------------------------ outputs
  logic [B:0] d3d_u, d3d_v;
  if (B >= 16) begin : g_exact
    assign d3d_u = (B + 1)'(du) << (B - 16);
    assign d3d_v = (B + 1)'(dv) << (B - 16);
  end else begin : g_narrow  // refused by the software: the points are 16.16
    assign d3d_u = (B + 1)'(du >> (16 - B));
    assign d3d_v = (B + 1)'(dv >> (16 - B));
  end

  assign u_o     = d3d11 ? d3d_u : u_cur;
  assign v_o     = d3d11 ? d3d_v : v_cur;
  assign w_o     = {1'b1, {B{1'b0}}} - u_o - v_o;
  assign j_o     = d3d11 ? LBits'(ring_q) : j_q;
  assign k_o     = d3d11 ? LBits'(edge_q) : k_q;
  assign index_o = index_q;
  assign last_o  = d3d11 ? d3d_last : uni_last;

  logic unused_ring;
  assign unused_ring = ^{ring_scaled[15:0], next_ring_blend_q[BlW-1:33], next_ring_blend_q[15:0], blend_d[BlW-1:33], blend_d[15:0], mblend_d[BlW-1:33], mblend_d[15:0],
                        next_outer[EW-1-7:7], next_outer[0]};

  // The consume strobe and the last-point flag drive the TE's allocation: never X out of reset.
  `TESS_ASSERT_KNOWN(ConsumeKnown_A, consume_i, clk_i, !rst_ni)
  `TESS_ASSERT_KNOWN(LastKnown_A, last_o, clk_i, !rst_ni)
  `TESS_ASSERT_PARAM(BaryBitsRange_A, BaryBits >= 7 && BaryBits <= 20)

endmodule
