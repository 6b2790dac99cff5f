// mapping_engine inside a design (timing harness only): every port of the engine between
// registers, the command, read and load ports' data filled one bit a cycle from a pin each
// through shift registers (their valids and the read result's ready registered from pins), its
// read result folded to one pin through a registered parity, so that the engine's 200-odd port
// bits fit the part's pins and only engine paths limit Fmax.
module mapping_engine_timing #(
  parameter int unsigned B          = 8,
  parameter int unsigned TILE_BITS  = 4,
  parameter int unsigned BINS       = 300,
  parameter int unsigned TAIL_CELLS = 64
) (
  input  logic clk_i,
  input  logic rst_ni,
  input  logic in_valid_i,
  output logic in_ready_o,
  input  logic in_bit_i,
  input  logic rd_valid_i,
  output logic rd_ready_o,
  input  logic rd_bit_i,
  output logic rd_valid_o,
  input  logic rd_ready_i,
  output logic rd_parity_o,
  output logic idle_o,
  input  logic ld_valid_i,
  input  logic ld_bit_i
);
  localparam int unsigned TileAw = 2 * TILE_BITS;
  // pose, cx, cy, px, py, angle, range
  localparam int unsigned InW    = 1 + 26 + 26 + 15 + 15 + 16 + 18;
  localparam int unsigned LdW    = 3 + 16 + 64;                      // target, address, data
  logic              rst_nq, in_valid_q, rd_valid_q, rd_ready_q, ld_valid_q;
  logic [InW-1:0]    in_q;
  logic [TileAw-1:0] rd_addr_q;
  logic [LdW-1:0]    ld_q;
  logic              in_ready_d, rd_ready_d, rd_valid_d, idle_d;
  logic [B-1:0]      rd_data_d;
  always_ff @(posedge clk_i) begin
    rst_nq      <= rst_ni;
    in_valid_q  <= in_valid_i;
    rd_valid_q  <= rd_valid_i;
    rd_ready_q  <= rd_ready_i;
    ld_valid_q  <= ld_valid_i;
    in_q        <= {in_q[InW-2:0], in_bit_i};
    rd_addr_q   <= {rd_addr_q[TileAw-2:0], rd_bit_i};
    ld_q        <= {ld_q[LdW-2:0], ld_bit_i};
    in_ready_o  <= in_ready_d;
    rd_ready_o  <= rd_ready_d;
    rd_valid_o  <= rd_valid_d;
    rd_parity_o <= ^rd_data_d;
    idle_o      <= idle_d;
  end
  mapping_engine #(
    .B(B),
    .TILE_BITS(TILE_BITS),
    .BINS(BINS),
    .TAIL_CELLS(TAIL_CELLS)
  ) i_dut (
    .clk_i,
    .rst_ni     (rst_nq),
    .in_valid_i (in_valid_q),
    .in_ready_o (in_ready_d),
    .in_pose_i  (in_q[InW-1]),
    .in_cx_i    (in_q[InW-2-:26]),
    .in_cy_i    (in_q[InW-28-:26]),
    .in_px_i    (in_q[InW-54-:15]),
    .in_py_i    (in_q[InW-69-:15]),
    .in_angle_i (in_q[InW-84-:16]),
    .in_range_i (in_q[17:0]),
    .rd_valid_i (rd_valid_q),
    .rd_ready_o (rd_ready_d),
    .rd_addr_i  (rd_addr_q),
    .rd_valid_o (rd_valid_d),
    .rd_ready_i (rd_ready_q),
    .rd_data_o  (rd_data_d),
    .idle_o     (idle_d),
    .ld_valid_i (ld_valid_q),
    .ld_target_i(ld_q[LdW-1-:3]),
    .ld_addr_i  (ld_q[LdW-4-:16]),
    .ld_data_i  (ld_q[63:0])
  );
endmodule
