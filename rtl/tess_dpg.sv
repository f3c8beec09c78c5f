// DPG: domain-point generator (docs/microarchitecture.md §7). Walks the pattern of the patch in
// buffer[rd_ptr] and gives the barycentric weights of the current point and its index in the
// patch.
//
// Uniform pattern: the lattice in pattern order (rows k = 0..L, in a row j = 0..L-k),
// u = bary_weight(j, L), v = bary_weight(k, L),
// w = 2^B - u - v, where bary_weight(j, L) = floor((j 2^(B+1) + L) / 2L) is the round half up
// of j 2^B / L (sim/fixed.hpp).
//
// No divider: the weights are kept as quotient and remainder of that division and advanced
// exactly. Going from j to j + 1 adds 2^(B+1) to the numerator, i.e. q(L) = floor(2^B / L) to
// the quotient and r(L) = 2^(B+1) mod 2L to the remainder (with one carry when the remainder
// reaches 2L). q and r come from a 64-entry constant table indexed by L. At j = 0 the weight
// is 0 with remainder L, so a new row or patch needs no state.
//
// D3D11 pattern (docs/patterns.md; sim/d3d11_walk.cpp D3D11PointWalker): the outer ring
// from the corner v = 1, edge by edge, then the rings inwards, then the centre of an even
// pattern. Each point is one placement on the current edge (tess_dpg_place, from the setup the
// FSU stored with the patch); an inner ring's offset from the outer edges (2/3 t_r, and half of
// it along the edge) is computed once per ring, when the walk enters it. j and k give the ring
// and the edge (3: the centre). B >= 16: the 16.16 points are exact in B bits.
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

  // ---- per-L step of the weight: q = floor(2^B / L), r = 2^(B+1) mod 2L
  logic [B:0]      step_q;
  logic [RemW-1:0] step_r;
  always_comb begin
    step_q = '0;
    step_r = '0;
    for (int l = 1; l <= tess_pkg::MaxFactor; l++) begin
      if (l_i == LBits'(l)) begin
        step_q = (B + 1)'((64'd1 << B) / 64'(l));
        step_r = RemW'((64'd1 << (B + 1)) % (64'd2 * 64'(l)));
      end
    end
  end

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
  (* mem2reg *) logic [EW-1:0] outer_edge [3];
  logic [EW-1:0] inner_edge;
  logic [6:0]    n_inner;
  logic [XW-1:0] point_count;
  assign {point_count, n_inner, inner_edge, outer_edge[2], outer_edge[1], outer_edge[0]} = setup;

  logic [5:0]    ring_q;        // 0: the outer ring
  logic [1:0]    edge_q;        // 3: the centre
  logic [6:0]    p_q;           // position along the ring's edge
  logic [6:0]    ring_last_q;   // ring r >= 1: its edges take inner points r .. ring_last - 1
  logic [16:0]   perp_q, shift_q;
  logic [XW-1:0] index_q;       // both patterns

  logic          outer_ring, centre;
  logic [EW-1:0] cur_edge;
  logic [6:0]    cur_points, place_index, edge_end;
  logic [16:0]   t, ts;
  assign outer_ring  = (ring_q == '0);
  assign centre      = (edge_q == 2'd3);
  assign cur_edge    = outer_ring ? outer_edge[edge_q] : inner_edge;
  assign cur_points  = cur_edge[EW-1 -: 7];
  // Edge 1 is walked forwards, edges 0 and 2 backwards (the ring turns at the corners).
  assign place_index = (edge_q == 2'd1) ? p_q
                     : outer_ring ? cur_points - 7'd1 - p_q : ring_last_q + 7'(ring_q) - p_q;
  assign edge_end    = outer_ring ? cur_points - 7'd1 : ring_last_q;

  tess_dpg_place u_place (.edge_i(cur_edge), .index_i(place_index), .t_o(t));
  assign ts = t - shift_q;

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

  // Entering ring r + 1: its edges lie at barycentric distance d = 2/3 t_(r+1) from the outer
  // ones (t times 0xAAAA, rounded) and points move d/2 (rounded up) along the edge.
  logic [5:0]  next_ring;
  logic [16:0] ring_t, next_perp;
  logic [32:0] ring_scaled;
  assign next_ring   = ring_q + 6'd1;
  tess_dpg_place u_ring_place (.edge_i(inner_edge), .index_i(7'(next_ring)), .t_o(ring_t));
  assign ring_scaled = 33'(ring_t) * 33'h0aaaa + 33'h8000;
  assign next_perp   = ring_scaled[32:16];

  logic d3d_last;
  assign d3d_last = (index_q == point_count - XW'(1));

  logic [5:0]    ring_d;
  logic [1:0]    edge_d;
  logic [6:0]    p_d, ring_last_d;
  logic [16:0]   perp_d, shift_d;
  logic [XW-1:0] index_d;
  always_comb begin
    ring_d      = ring_q;
    edge_d      = edge_q;
    p_d         = p_q;
    index_d     = index_q;
    ring_last_d = ring_last_q;
    perp_d      = perp_q;
    shift_d     = shift_q;
    if (consume_i) begin
      index_d = last_o ? '0 : index_q + XW'(1);
      if (d3d11) begin
        if (d3d_last) begin
          ring_d = '0;
          edge_d = '0;
          p_d    = '0;
        end else if (!centre) begin
          if (p_q + 7'd1 != edge_end) begin
            p_d = p_q + 7'd1;
          end else if (edge_q != 2'd2) begin
            p_d    = 7'(ring_q);
            edge_d = edge_q + 2'd1;
          end else if (7'(next_ring) < (n_inner >> 1)) begin
            ring_d      = next_ring;
            edge_d      = '0;
            p_d         = 7'(next_ring);
            ring_last_d = n_inner - 7'd1 - 7'(next_ring);
            perp_d      = next_perp;
            shift_d     = (next_perp + 17'd1) >> 1;
          end else begin  // the centre of an even pattern, a ring of its own
            ring_d = next_ring;
            edge_d = 2'd3;
          end
        end
      end
    end
  end

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
  assign unused_ring = ^{ring_scaled[15:0]};

endmodule
