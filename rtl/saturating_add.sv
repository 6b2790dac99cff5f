// One lane of S_eps index fusion: y = a + b saturated to +-(2^(B-1) - 1), all three B-bit two's
// complement. -2^(B-1) is a legal input (it saturates like any other out-of-range sum) but never an
// output. Purely combinational; index_fusion registers its result.
module saturating_add #(
  parameter int unsigned B = 8
) (
  input  logic [B-1:0] a_i,
  input  logic [B-1:0] b_i,
  output logic [B-1:0] y_o
);
  // The largest index magnitude, 2^(B-1) - 1, as a B-bit pattern (01...1); its negation is 10...01.
  localparam logic [B-1:0] MaxIndex = {1'b0, {(B - 1){1'b1}}};
  localparam logic [B-1:0] MinIndex = {1'b1, {(B - 2){1'b0}}, 1'b1};

  // The exact sum needs B+1 bits: [-2^B, 2^B - 2]. Its top two bits tell the range apart.
  logic [B:0] sum;
  assign sum = {a_i[B-1], a_i} + {b_i[B-1], b_i};

  logic above, below, at_min;
  assign at_min = sum[B-2:0] == '0;                      // with sum[B:B-1] = 2'b11: sum = -2^(B-1)
  assign above  = !sum[B] && sum[B-1];                   // sum >= 2^(B-1): over +(2^(B-1) - 1)
  assign below  = sum[B] && (!sum[B-1] || at_min);       // sum <= -2^(B-1): under -(2^(B-1) - 1)

  always_comb begin
    if (above) begin
      y_o = MaxIndex;
    end else if (below) begin
      y_o = MinIndex;
    end else begin
      y_o = sum[B-1:0];
    end
  end
endmodule
