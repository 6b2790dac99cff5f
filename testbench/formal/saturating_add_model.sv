// The reference of S_eps fusion for the formal harnesses, written unlike rtl/saturating_add.sv:
// the sum as a 32-bit signed integer of the sign-extended inputs, clamped by comparisons to
// +-(2^(B-1) - 1).
module saturating_add_model #(
  parameter int unsigned B = 8
) (
  input  logic [B-1:0] a_i,
  input  logic [B-1:0] b_i,
  output logic [B-1:0] y_o
);
  localparam logic signed [31:0] Max = (1 <<< (B - 1)) - 1;  // the largest index magnitude

  logic signed [31:0] sum, clamped;
  always @* begin
    sum = $signed({{(32 - B){a_i[B-1]}}, a_i}) + $signed({{(32 - B){b_i[B-1]}}, b_i});
    if (sum > Max) begin
      clamped = Max;
    end else if (sum < -Max) begin
      clamped = -Max;
    end else begin
      clamped = sum;
    end
  end
  assign y_o = clamped[B-1:0];
endmodule
