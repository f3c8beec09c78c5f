// One FP32 lane of the geometry engine's ALU array: d = round(a * b + c), fused (one rounding,
// to nearest even), IEEE binary32 with a GPU shader lane's fast path. Written only to measure
// what one GE ALU lane costs under the unit's synthesis flow (scripts/ge_lane_cost.sh); it is
// not part of the unit (rtl/tess.f does not list it).
//
// Number rules (tests/ge_lane/ge_lane_test.cpp checks every one against std::fmaf):
//  - Subnormal inputs are zeros of their sign (an exponent field of 0 is zero).
//  - A subnormal result is flushed to a zero of its sign, decided on the IEEE result, i.e. after
//    rounding at the subnormal quantum 2^-149: an exact result in [2^-126 - 2^-150, 2^-126)
//    rounds up to 2^-126 and is kept, every smaller nonzero one is flushed.
//  - A NaN operand, inf * 0 and inf - inf give the quiet NaN 0x7fc00000; an infinite product or
//    addend otherwise gives that infinity; overflow rounds to infinity.
//  - An exact zero is -0 only when the product and the addend are both -0; cancellation gives +0.
//
// Datapath: the 48-bit product and the addend are added exactly in a 75-bit window (the addend's
// 24 bits, 2 guard bits, the product's 48 bits, and one bit below the product that collects the
// addend bits shifted out of the window, as a sticky bit), then normalised and rounded once.
// The output is registered once (valid_i -> valid_o: one cycle).
module ge_fma_lane (
  input  logic        clk_i,
  input  logic        rst_ni,
  input  logic        valid_i,
  input  logic [31:0] a_i,
  input  logic [31:0] b_i,
  input  logic [31:0] c_i,
  output logic        valid_o,
  output logic [31:0] d_o
);

  localparam logic [31:0] QuietNaN = 32'h7fc0_0000;
  localparam int unsigned WinW     = 75;  // 24 + 2 + 48 + 1 (sticky)
  localparam int unsigned PosW     = 7;   // alignment shift 0..75, leading zeros 0..127
  localparam int unsigned ExpW     = 11;  // signed biased exponents: -225..409
  localparam logic [PosW-1:0] ShiftMax = PosW'(WinW);      // the addend entirely below the window
  localparam logic [PosW-1:0] CLowPos  = PosW'(WinW - 24);  // addend's LSB at shift 0 (bit 51)

  // ---- unpack: an exponent field of 0 is a zero (subnormal operands flush, sign kept) ----
  logic        sa, sb, sc;
  logic [7:0]  ea, eb, ec;
  logic [22:0] fa, fb, fc;
  assign {sa, ea, fa} = a_i;
  assign {sb, eb, fb} = b_i;
  assign {sc, ec, fc} = c_i;

  logic a_zero, b_zero, c_zero, a_inf, b_inf, c_inf, a_nan, b_nan, c_nan;
  assign a_zero = ea == 8'd0;
  assign b_zero = eb == 8'd0;
  assign c_zero = ec == 8'd0;
  assign a_inf  = (ea == 8'hff) && (fa == '0);
  assign b_inf  = (eb == 8'hff) && (fb == '0);
  assign c_inf  = (ec == 8'hff) && (fc == '0);
  assign a_nan  = (ea == 8'hff) && (fa != '0);
  assign b_nan  = (eb == 8'hff) && (fb != '0);
  assign c_nan  = (ec == 8'hff) && (fc != '0);

  logic sp, sub, prod_inf, prod_zero, invalid;
  assign sp        = sa ^ sb;  // sign of the product
  assign sub       = sp ^ sc;  // effective subtraction
  assign prod_inf  = a_inf || b_inf;
  assign prod_zero = a_zero || b_zero;
  assign invalid   = a_nan || b_nan || c_nan || (prod_inf && prod_zero) ||
                     (prod_inf && c_inf && sub);

  // ---- exact product of the significands, in [2^46, 2^48) ----
  logic [47:0] prod;
  assign prod = {24'd0, 1'b1, fa} * {24'd0, 1'b1, fb};

  // ---- alignment of the addend against the product ----
  // Window bit i weighs 2^(i - 1) product LSBs: the product sits at [48:1]. With the addend's
  // significand at the top ([74:51]) its exponent would be ea + eb - 100 (biased): prod_exp.
  // The addend moves right by prod_exp - ec. If it would have to move left (it is far above the
  // product), it stays at the top and the window follows it: the product, then below half an
  // ulp of any result, still decides the rounding exactly as a sticky bit would.
  logic signed [ExpW-1:0] prod_exp, shift_raw, base_exp;
  logic                   c_top;
  logic [PosW-1:0]        shift;
  assign prod_exp  = $signed({3'b0, ea}) + $signed({3'b0, eb}) - ExpW'(100);
  assign shift_raw = prod_exp - $signed({3'b0, ec});
  assign c_top     = !c_zero && (shift_raw <= 0);
  always_comb begin
    if (c_zero || shift_raw >= $signed(ExpW'(WinW))) shift = ShiftMax;
    else if (c_top) shift = '0;
    else shift = shift_raw[PosW-1:0];
  end
  // Biased exponent of the window's top bit.
  assign base_exp = c_top ? $signed({3'b0, ec}) : prod_exp;

  logic [23:0]     mc, lost_mask;
  logic [WinW-1:0] c_win, c_al, p_win;
  logic            c_sticky;
  assign mc        = c_zero ? '0 : {1'b1, fc};
  assign c_win     = {mc, (WinW - 24)'(0)} >> shift;
  // Addend bits shifted below bit 0 only matter as "nonzero": they are ORed into bit 0, which
  // keeps the floor of the exact sum and the fact that a remainder exists (the result then has
  // its MSB at bit 46 or above, so bit 0 is only ever a sticky bit for the rounding).
  assign lost_mask = (shift > CLowPos) ? (24'hff_ffff >> (ShiftMax - shift)) : '0;
  assign c_sticky  = |(mc & lost_mask);
  assign c_al      = {c_win[WinW-1:1], c_win[0] | c_sticky};
  assign p_win     = {(WinW - 49)'(0), prod, 1'b0};

  // ---- exact sum, and its magnitude ----
  logic [WinW:0]   sum;
  logic [WinW-1:0] mag;
  logic            neg, s_res;
  assign sum   = {1'b0, p_win} + ({1'b0, c_al} ^ {(WinW + 1){sub}}) + (WinW + 1)'(sub);
  assign neg   = sum[WinW];  // only when subtracting: the addend was the larger
  assign mag   = neg ? -sum[WinW-1:0] : sum[WinW-1:0];
  assign s_res = sp ^ neg;

  // ---- normalise: shift the MSB to bit 74, counting leading zeros in 7 steps (64 .. 1) ----
  logic [WinW-1:0] nrm;
  logic [PosW-1:0] lz;
  always_comb begin
    nrm = mag;
    for (int k = PosW - 1; k >= 0; k--) begin
      lz[k] = (nrm >> (WinW - (1 << k))) == '0;  // the top 2^k bits are zero
      if (lz[k]) nrm = nrm << (1 << k);
    end
  end

  // ---- round to nearest even at 24 bits ----
  logic [23:0]            mant;
  logic                   guard, sticky, round_up, mant_ones;
  logic [24:0]            mant_r;
  logic signed [ExpW-1:0] e_r, e_fin;
  assign mant      = nrm[WinW-1 -: 24];
  assign guard     = nrm[WinW-25];
  assign sticky    = |nrm[WinW-26:0];
  assign round_up  = guard && (sticky || mant[0]);
  assign mant_r    = {1'b0, mant} + 25'(round_up);
  assign e_r       = base_exp - $signed({4'b0, lz});
  assign e_fin     = e_r + $signed(ExpW'(mant_r[24]));  // a carry out of the significand
  assign mant_ones = mant[22:0] == '1;

  // ---- result ----
  logic [31:0] d_d, d_q;
  logic        valid_q;
  always_comb begin
    if (invalid) d_d = QuietNaN;
    else if (prod_inf) d_d = {sp, 8'hff, 23'd0};
    else if (c_inf) d_d = {sc, 8'hff, 23'd0};
    else if (prod_zero) d_d = c_zero ? {sp && sc, 31'd0} : c_i;  // 0 + c is c, exactly
    else if (mag == '0) d_d = 32'd0;  // exact cancellation: +0 under round to nearest
    else if (e_r > 0) begin
      if (e_fin >= $signed(ExpW'(255))) d_d = {s_res, 8'hff, 23'd0};  // overflow
      else d_d = {s_res, e_fin[7:0], mant_r[22:0]};
    end
    // Just below 2^-126, IEEE rounds at the subnormal quantum (two of our ulps): it reaches
    // 2^-126 iff all 23 fraction bits are ones. Everything else down here is subnormal: flushed.
    else if (e_r == 0 && mant_ones) d_d = {s_res, 8'd1, 23'd0};
    else d_d = {s_res, 31'd0};
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_q <= 1'b0;
    else valid_q <= valid_i;
  end
  always_ff @(posedge clk_i) begin
    d_q <= d_d;
  end
  assign valid_o = valid_q;
  assign d_o     = d_q;

  // The upper exponent bits only matter through the comparisons above.
  logic unused_bits;
  assign unused_bits = ^{e_fin[ExpW-1:8], mant_r[23]};

endmodule
