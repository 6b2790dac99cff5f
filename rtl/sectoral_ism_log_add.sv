// The kernel's log-domain addition, golden's kernel_log_add: log2(2^a + 2^b) =
// max(a, b) + Phi(|a - b|), Phi from a ROM (log2(1 + 2^-d), zero past its last entry),
// log 0 absorbing. A log value is {zero, LOG_W-bit two's complement}. Two-stage pipeline:
// operands in cycle t, sum on res_o in cycle t + 2; one addition per cycle.
module sectoral_ism_log_add #(
  parameter int unsigned LOG_W  = 20,
  parameter int unsigned PHI_N  = 2440,
  parameter int unsigned PHI_W  = 8,    // the ROM holds Phi - 1 (every entry is at least 1)
  parameter int unsigned PHI_AW = 12,
  parameter              FILE   = "",
  parameter int unsigned TAG_W  = 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  input  logic [LOG_W:0]   a_i,
  input  logic [LOG_W:0]   b_i,
  input  logic [TAG_W-1:0] tag_i,
  output logic             valid_o,
  output logic [LOG_W:0]   res_o,
  output logic [TAG_W-1:0] tag_o
);
  // The ROM's addresses must reach every entry, and Phi - 1 fit the log word.
  if (PHI_N < 1 || PHI_N > (1 << PHI_AW) || PHI_W < 1 || PHI_W >= LOG_W) begin : gen_check_phi
    $error("sectoral_ism_log_add: PHI_N must be 1..2^PHI_AW, PHI_W 1..LOG_W - 1");
  end

  // Stage 1: compare, difference, Phi address.
  logic signed [LOG_W-1:0] a_val, b_val;
  logic signed [LOG_W:0]   diff_ab, diff_ba;
  logic                    a_ge_b;
  logic [LOG_W:0]          distance;
  logic [PHI_AW-1:0]       phi_addr;
  assign a_val   = a_i[LOG_W-1:0];
  assign b_val   = b_i[LOG_W-1:0];
  assign diff_ab = {a_val[LOG_W-1], a_val} - {b_val[LOG_W-1], b_val};
  assign diff_ba = {b_val[LOG_W-1], b_val} - {a_val[LOG_W-1], a_val};
  assign a_ge_b  = !diff_ab[LOG_W];
  assign distance    = a_ge_b ? diff_ab : diff_ba;
  assign phi_addr = distance[PHI_AW-1:0];

  logic             s1_valid_q, s1_bypass_q, s1_small_q;
  logic [LOG_W:0]   s1_pass_q;
  logic [LOG_W-1:0] s1_hi_q, s1_hi_p1_q;
  logic [PHI_AW-1:0] s1_distance_q;
  logic [TAG_W-1:0] s1_tag_q;
  logic [PHI_W-1:0] phi_m1;

  sectoral_ism_rom #(
    .WIDTH (PHI_W),
    .DEPTH (PHI_N),
    .FILE  (FILE)
  ) i_phi_rom (
    .clk_i,
    .en_i   (1'b1),
    .addr_i (phi_addr),
    .data_o (phi_m1)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else begin
      s1_valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    s1_bypass_q <= a_i[LOG_W] || b_i[LOG_W];    // log 0 + x = x
    s1_pass_q   <= a_i[LOG_W] ? b_i : a_i;
    s1_hi_q     <= a_ge_b ? a_i[LOG_W-1:0] : b_i[LOG_W-1:0];
    s1_hi_p1_q  <= (a_ge_b ? a_i[LOG_W-1:0] : b_i[LOG_W-1:0]) + LOG_W'(1);
    s1_small_q  <= (distance >> PHI_AW) == '0;      // the distance fits the ROM's address
    s1_distance_q   <= distance[PHI_AW-1:0];
    s1_tag_q    <= tag_i;
  end

  // Stage 2: the sum.
  logic              in_table;
  logic [PHI_AW:0]   distance_ext;
  logic [LOG_W-1:0]  phi, hi_sum;
  logic [LOG_W:0]    sum;
  assign distance_ext = {1'b0, s1_distance_q};
  assign in_table     = s1_small_q && (distance_ext < (PHI_AW+1)'(PHI_N));  // Phi(d) is in the table, else 0
  assign phi          = LOG_W'(phi_m1);
  assign hi_sum       = in_table ? s1_hi_p1_q + phi : s1_hi_q;
  assign sum          = s1_bypass_q ? s1_pass_q : {1'b0, hi_sum};

  logic             valid_q;
  logic [LOG_W:0]   res_q;
  logic [TAG_W-1:0] tag_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else begin
      valid_q <= s1_valid_q;
    end
  end
  always_ff @(posedge clk_i) begin
    res_q <= sum;
    tag_q <= s1_tag_q;
  end

  assign valid_o = valid_q;
  assign res_o   = res_q;
  assign tag_o   = tag_q;
endmodule
