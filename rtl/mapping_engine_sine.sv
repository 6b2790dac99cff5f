// The quarter-wave sine of the mapping engine, S(e) = sin(2 pi e / 2^16) 2^16 rounded for
// e = 0 .. 2^14, held as every 16th entry (1025 of 17 bits) and the 3-bit steps after each (15 a
// block, a 45-bit word): 63 kbit where the whole quarter wave takes 278. A lookup (re_i with
// entry_i) reads both words; from the next cycle on, magnitude_o is the coarse entry plus the
// steps up to the entry, held until the next lookup. hls::MappingEngine::quarter_sine is the
// same sum.
module mapping_engine_sine (
  input  logic        clk_i,
  // loads: a coarse entry (S(16 j)) or a block's steps, at address j
  input  logic        we_coarse_i,
  input  logic        we_steps_i,
  input  logic [10:0] waddr_i,
  input  logic [44:0] wdata_i,
  // lookup
  input  logic        re_i,
  input  logic [14:0] entry_i,  // 0 .. 16384
  output logic [16:0] magnitude_o
);
  logic [16:0] coarse;
  logic [44:0] steps;
  logic [3:0]  within_q;  // the entry's place in its block, 0..15

  sdp_ram #(
    .WIDTH(17),
    .DEPTH(1025)
  ) i_coarse (
    .clk_i,
    .we_i   (we_coarse_i),
    .waddr_i(waddr_i),
    .wdata_i(wdata_i[16:0]),
    .re_i,
    .raddr_i(entry_i[14:4]),
    .rdata_o(coarse)
  );
  // Block 1024 is the last coarse entry alone (within 0): its steps are never used.
  sdp_ram #(
    .WIDTH(45),
    .DEPTH(1024)
  ) i_steps (
    .clk_i,
    .we_i   (we_steps_i && waddr_i < 11'd1024),
    .waddr_i(waddr_i[9:0]),
    .wdata_i(wdata_i),
    .re_i,
    .raddr_i(entry_i[13:4]),
    .rdata_o(steps)
  );

  always_ff @(posedge clk_i) begin
    if (re_i) within_q <= entry_i[3:0];
  end

  always_comb begin
    logic [6:0] rise;  // at most 15 steps of 7
    rise = '0;
    for (int i = 1; i < 16; i++) begin
      if (4'(i) <= within_q) rise = rise + 7'(steps[3*(i-1) +: 3]);
    end
    magnitude_o = coarse + 17'(rise);
  end
endmodule
