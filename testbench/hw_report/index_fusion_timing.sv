// index_fusion inside a design (timing harness only): every port of the kernel between
// registers, its two data buses filled one bit a cycle from a pin each through shift registers,
// its output folded to one pin through two registered stages (a parity a lane, then their
// parity), so that any lane count fits the part's pins and only kernel paths limit Fmax.
module index_fusion_timing #(
  parameter int unsigned B     = 8,
  parameter int unsigned LANES = 8
) (
  input  logic clk_i,
  input  logic rst_ni,
  input  logic a_valid_i,
  output logic a_ready_o,
  input  logic a_bit_i,
  input  logic a_last_i,
  input  logic b_valid_i,
  output logic b_ready_o,
  input  logic b_bit_i,
  input  logic b_last_i,
  output logic y_valid_o,
  input  logic y_ready_i,
  output logic y_parity_o,
  output logic y_last_o
);
  logic               a_valid_q, b_valid_q, a_last_q, b_last_q, y_ready_q;
  logic [LANES*B-1:0] a_data_q, b_data_q, y_data_d, y_data_q;
  logic [LANES-1:0]   lane_parity_q;
  logic               a_ready_d, b_ready_d, y_valid_d, y_last_d;
  always_ff @(posedge clk_i) begin
    a_valid_q <= a_valid_i;
    b_valid_q <= b_valid_i;
    a_last_q  <= a_last_i;
    b_last_q  <= b_last_i;
    a_data_q  <= {a_data_q[LANES*B-2:0], a_bit_i};
    b_data_q  <= {b_data_q[LANES*B-2:0], b_bit_i};
    y_ready_q <= y_ready_i;
    a_ready_o <= a_ready_d;
    b_ready_o <= b_ready_d;
    y_valid_o <= y_valid_d;
    y_last_o  <= y_last_d;
    y_data_q  <= y_data_d;
    for (int unsigned l = 0; l < LANES; l++) lane_parity_q[l] <= ^y_data_q[l*B +: B];
    y_parity_o <= ^lane_parity_q;
  end
  index_fusion #(.B(B), .LANES(LANES)) i_dut (
    .clk_i, .rst_ni,
    .a_valid_i(a_valid_q), .a_ready_o(a_ready_d), .a_data_i(a_data_q), .a_last_i(a_last_q),
    .b_valid_i(b_valid_q), .b_ready_o(b_ready_d), .b_data_i(b_data_q), .b_last_i(b_last_q),
    .y_valid_o(y_valid_d), .y_ready_i(y_ready_q), .y_data_o(y_data_d), .y_last_o(y_last_d));
endmodule
