// Formal harness of rtl/saturating_add.sv: for B = 4, 8 and 16, the adder equals
// saturating_add_model (an integer sum clamped by comparisons) on every pair of inputs. The
// adder is combinational, so one solver step is a proof over all 2^(2B) pairs.
module saturating_add_equal #(
  parameter int unsigned B = 8
) (
  input logic [B-1:0] a_i,
  input logic [B-1:0] b_i
);
  logic [B-1:0] y, y_model;
  saturating_add #(.B(B)) i_dut (.a_i, .b_i, .y_o(y));
  saturating_add_model #(.B(B)) i_model (.a_i, .b_i, .y_o(y_model));
  always @* assert (y == y_model);
endmodule

module saturating_add_formal (
  input logic [3:0]  a4_i,  b4_i,
  input logic [7:0]  a8_i,  b8_i,
  input logic [15:0] a16_i, b16_i
);
  saturating_add_equal #(.B(4))  i_b4  (.a_i(a4_i),  .b_i(b4_i));
  saturating_add_equal #(.B(8))  i_b8  (.a_i(a8_i),  .b_i(b8_i));
  saturating_add_equal #(.B(16)) i_b16 (.a_i(a16_i), .b_i(b16_i));
endmodule
