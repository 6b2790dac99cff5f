// The reference point of docs/hardware.md: a plain B-bit saturating adder, inputs and output registered.
module saturating_add_reg #(
  parameter int unsigned B = 8
) (
  input  logic         clk_i,
  input  logic [B-1:0] a_i,
  input  logic [B-1:0] b_i,
  output logic [B-1:0] y_o
);
  logic [B-1:0] a_q, b_q, y_d;
  always_ff @(posedge clk_i) begin
    a_q <= a_i;
    b_q <= b_i;
    y_o <= y_d;
  end
  saturating_add #(.B(B)) i_add (.a_i(a_q), .b_i(b_q), .y_o(y_d));
endmodule
