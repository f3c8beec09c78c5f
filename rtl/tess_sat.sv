// Saturation of a two's-complement value to a narrower width (sim/base/fixed.hpp saturate):
// clamps to [-2^(OutW-1), 2^(OutW-1) - 1] and reports whether the value moved.
module tess_sat #(
  parameter int unsigned InW  = 32,
  parameter int unsigned OutW = 24
) (
  input  logic [InW-1:0]  x_i,
  output logic [OutW-1:0] y_o,
  output logic            sat_o
);

  if (InW > OutW) begin : g_clamp
    // The value fits iff the bits above the result's sign bit all equal the input sign.
    logic [InW-OutW:0] top;
    logic              fits;
    assign top  = x_i[InW-1:OutW-1];
    assign fits = (top == '0) || (top == '1);
    assign sat_o = !fits;
    always_comb begin
      if (fits) y_o = x_i[OutW-1:0];
      else if (x_i[InW-1]) y_o = {1'b1, {(OutW - 1){1'b0}}};
      else y_o = {1'b0, {(OutW - 1){1'b1}}};
    end
  end else if (InW == OutW) begin : g_same
    assign y_o   = x_i;
    assign sat_o = 1'b0;
  end else begin : g_extend
    assign y_o   = {{(OutW - InW){x_i[InW-1]}}, x_i};
    assign sat_o = 1'b0;
  end

endmodule
