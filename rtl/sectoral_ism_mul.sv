// Digit-serial unsigned multiplier (the iCE40 HX has no DSP blocks): p = a * b, K bits of b
// per cycle, most significant digit first (Horner), as a two-stage pipeline (partial
// product, accumulate). A product started in cycle s is on p_o with done_o in cycle
// s + ND + 2; a new one may start every ND cycles (in the cycle of the previous one's last
// digit). tag_i travels with the product.
module sectoral_ism_mul #(
  parameter int unsigned A_W   = 24,
  parameter int unsigned B_W   = 19,
  parameter int unsigned K     = 3,
  parameter int unsigned TAG_W = 1,
  localparam int unsigned ND   = (B_W + K - 1) / K,
  localparam int unsigned P_W  = A_W + B_W
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             start_i,
  input  logic [A_W-1:0]   a_i,
  input  logic [B_W-1:0]   b_i,
  input  logic [TAG_W-1:0] tag_i,
  output logic             done_o,
  output logic [P_W-1:0]   p_o,
  output logic [TAG_W-1:0] tag_o
);
  if (K < 1 || K > B_W || A_W < 1) begin : gen_check_digit
    $error("sectoral_ism_mul: K must be 1..B_W, A_W at least 1");
  end

  localparam int unsigned BP_W  = ND * K;  // b padded to whole digits
  localparam int unsigned CNT_W = (ND > 1) ? $clog2(ND) : 1;
  localparam int unsigned PP_W  = A_W + K;

  // Digit stage.
  logic             busy_q;
  logic [CNT_W-1:0] cnt_q;
  logic [A_W-1:0]   a_q;
  logic [BP_W-1:0]  b_q;
  logic [TAG_W-1:0] tag_q;
  // Partial-product stage.
  logic             pp_valid_q, pp_first_q, pp_last_q;
  logic [PP_W-1:0]  pp_q;
  logic [TAG_W-1:0] pp_tag_q;
  // Accumulator stage.
  logic             done_q;
  logic [P_W-1:0]   acc_q;
  logic [TAG_W-1:0] out_tag_q;

  logic last_digit;
  assign last_digit = busy_q && (cnt_q == CNT_W'(ND - 1));  // the digit stage holds b's last digit

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      busy_q     <= 1'b0;
      pp_valid_q <= 1'b0;
      done_q     <= 1'b0;
    end else begin
      busy_q     <= start_i || (busy_q && !last_digit);
      pp_valid_q <= busy_q;
      done_q     <= pp_valid_q && pp_last_q;
    end
  end

  always_ff @(posedge clk_i) begin
    if (start_i) begin
      a_q   <= a_i;
      b_q   <= BP_W'(b_i);
      cnt_q <= '0;
      tag_q <= tag_i;
    end else if (busy_q) begin
      b_q   <= b_q << K;
      cnt_q <= cnt_q + CNT_W'(1);
    end
    pp_q       <= PP_W'(a_q) * PP_W'(b_q[BP_W-1 -: K]);
    pp_first_q <= (cnt_q == '0);
    pp_last_q  <= last_digit;
    if (last_digit) begin
      pp_tag_q <= tag_q;
    end
    if (pp_valid_q) begin
      acc_q <= (pp_first_q ? '0 : (acc_q << K)) + P_W'(pp_q);
    end
    if (pp_valid_q && pp_last_q) begin
      out_tag_q <= pp_tag_q;
    end
  end

  assign done_o = done_q;
  assign p_o    = acc_q;
  assign tag_o  = out_tag_q;
endmodule
