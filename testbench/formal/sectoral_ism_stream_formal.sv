// Formal harness of the ISM output stage, rtl/sectoral_ism_stream.sv (stage 1, the bank's
// registered read, and the spill register), on a small configuration, with the index RAM
// modelled as in rtl/sdp_ram.sv (a registered read that holds while re is low) over a
// bank content that is an unconstrained input. The environment is that of rtl/sectoral_ism.sv:
// once a bank is full it stays full, with the same window, below index and content, until the
// stream releases it; after the release anything may follow. Resets may come at any cycle.
//
// Proved (asserts below):
// - reads: the stream reads only a full bank, cell by cell in ring-major order (the address
//   {ring, sector} of each cell), and raises release_o exactly once a bank, with the read of its
//   last cell;
// - no wasted ready cycle while a bank is full: it reads a cell in every cycle in which fewer
//   than three cells (stage 1 and the two spill entries) are in flight, and y_valid_o is low
//   with a cell in flight only in the cycle after that cell's read;
// - y holds (valid, data, last) while y_valid_o && !y_ready_i; reset empties the output;
// - the output sequence equals a reference that computes each cell's index from its position
//   in the bank, ring-major: the bank's below index for rings before the window, 0 after it,
//   and the RAM word {ring - 1, bin / (BINS / SECTORS)} inside it; last on the bank's last cell.
// The proof is unbounded (k-induction): the stream's registers (exposed by Yosys' `expose`, see
// testbench/formal.cmake) are tied to the harness's book-keeping, each cell in stage 1 and in
// the spill register to the reference's value for its position.

// The reference index of the cell at position cell_i (ring-major) of a bank.
module sectoral_ism_cell_model #(
  parameter int unsigned RINGS   = 3,
  parameter int unsigned BINS    = 4,
  parameter int unsigned SECTORS = 2,
  parameter int unsigned IDX_W   = 4,
  parameter int unsigned RING_W  = 3,
  parameter int unsigned RIDX_W  = 2,
  parameter int unsigned J_W     = 1,
  parameter int unsigned IDX_AW  = 3,
  parameter int unsigned CELL_W  = 4
) (
  input  logic [CELL_W-1:0]              cell_i,
  input  logic [RING_W-1:0]              r_lo_i,
  input  logic [RING_W-1:0]              r_hi_i,
  input  logic [IDX_W-1:0]               below_i,
  input  logic [(IDX_W << IDX_AW) - 1:0] bank_i,
  output logic [IDX_W:0]                 cell_o  // {last, index}
);
  localparam int unsigned BPS = BINS / SECTORS;

  logic [RING_W-1:0] ring;    // 1-based
  logic [J_W-1:0]    sector;  // of the cell's bin
  logic [IDX_W-1:0]  index;
  always @* begin
    ring   = RING_W'(cell_i / CELL_W'(BINS)) + 1'b1;
    sector = J_W'((cell_i % CELL_W'(BINS)) / CELL_W'(BPS));
    if (ring < r_lo_i) begin
      index = below_i;
    end else if (ring > r_hi_i) begin
      index = '0;
    end else begin
      index = bank_i[{RIDX_W'(ring - 1'b1), sector} * IDX_W +: IDX_W];
    end
  end
  assign cell_o = {cell_i == CELL_W'(RINGS * BINS - 1), index};
endmodule

module sectoral_ism_stream_formal #(
  parameter int unsigned RINGS   = 3,
  parameter int unsigned BINS    = 4,
  parameter int unsigned SECTORS = 2,
  parameter int unsigned IDX_W   = 4,
  // derived, as in sectoral_ism_stream
  parameter int unsigned RING_W  = $clog2(RINGS + 2),
  parameter int unsigned RIDX_W  = (RINGS > 1) ? $clog2(RINGS) : 1,
  parameter int unsigned J_W     = (SECTORS > 1) ? $clog2(SECTORS) : 1,
  parameter int unsigned IDX_AW  = RIDX_W + J_W
) (
  input logic                            clk_i,
  input logic                            rst_ni,
  input logic                            full_i,
  input logic [RING_W-1:0]               r_lo_i,
  input logic [RING_W-1:0]               r_hi_i,
  input logic [IDX_W-1:0]                below_i,
  input logic [(IDX_W << IDX_AW) - 1:0]  bank_i,  // the RAM word at address w: bits [w*IDX_W +: IDX_W]
  input logic                            y_ready_i
);
  localparam int unsigned CELLS = RINGS * BINS;
  localparam int unsigned BPS   = BINS / SECTORS;
  localparam int unsigned CELL_W = $clog2(CELLS);  // a cell's position in its bank
  localparam int unsigned POS_W  = CELL_W + 1;     // a position counted past the bank's end
  localparam logic [CELL_W-1:0] LastCell = CELL_W'(CELLS - 1);

  logic              release_cell, re;
  logic [IDX_AW-1:0] raddr;
  logic [IDX_W-1:0]  rdata_q, y_data;
  logic              y_valid, y_last;

  localparam int unsigned BPS_W = (BPS > 1) ? $clog2(BPS) : 1;
  logic [RIDX_W-1:0] ring_q;  // the stream's registers, exposed for the induction only
  logic [J_W-1:0]    sec_q;
  logic [BPS_W-1:0]  bin_q;
  logic              s1_valid_q, s1_last_q, s1_const_q, a_full_q, b_full_q;
  logic [IDX_W-1:0]  s1_const_idx_q;
  logic [IDX_W:0]    a_data_q, b_data_q;

  // The parameters are set by chparam in formal.cmake, to the values above.
  sectoral_ism_stream i_dut (
    .clk_i, .rst_ni, .full_i, .r_lo_i, .r_hi_i, .below_i,
    .release_o(release_cell), .re_o(re), .raddr_o(raddr), .rdata_i(rdata_q),
    .y_valid_o(y_valid), .y_ready_i, .y_data_o(y_data), .y_last_o(y_last),
    .ring_q, .sec_q, .bin_q, .s1_valid_q, .s1_last_q, .s1_const_q, .s1_const_idx_q,
    .\i_spill.a_full_q (a_full_q), .\i_spill.b_full_q (b_full_q),
    .\i_spill.a_data_q (a_data_q), .\i_spill.b_data_q (b_data_q)
  );

  // The index RAM's read port.
  always_ff @(posedge clk_i) begin
    if (re) begin
      rdata_q <= bank_i[raddr * IDX_W +: IDX_W];
    end
  end

  // Last cycle's values, for the properties that span a clock edge (kept as registers here so
  // that every check is an immediate one on the current step).
  logic                           past_rst_n_q, past_hold_q, past_re_q, past_stall_q;
  logic [RING_W-1:0]              past_lo_q, past_hi_q;
  logic [IDX_W-1:0]               past_below_q, past_y_data_q;
  logic                           past_y_last_q;
  logic [(IDX_W << IDX_AW) - 1:0] past_bank_q;
  always_ff @(posedge clk_i) begin
    past_rst_n_q  <= rst_ni;
    past_hold_q   <= full_i && !release_cell;  // a full bank not released at this edge
    past_re_q     <= re;
    past_stall_q  <= y_valid && !y_ready_i;
    past_lo_q     <= r_lo_i;
    past_hi_q     <= r_hi_i;
    past_below_q  <= below_i;
    past_bank_q   <= bank_i;
    past_y_data_q <= y_data;
    past_y_last_q <= y_last;
  end

  // The environment: a full bank holds still until its release.
  always @* begin
    if (!$initstate && past_rst_n_q && past_hold_q) begin
      assume (full_i);
      assume (r_lo_i == past_lo_q && r_hi_i == past_hi_q && below_i == past_below_q);
      assume (bank_i == past_bank_q);
    end
  end

  // Book-keeping: cells read from the current bank, cells in flight, the position of the next
  // output cell in its bank, and the bank released but not yet fully sent.
  logic        y_fire;
  logic [CELL_W-1:0] issued_q, out_q;
  logic [2:0]        in_flight_q;
  logic        prev_q;
  logic [RING_W-1:0] prev_lo_q, prev_hi_q;
  logic [IDX_W-1:0]  prev_below_q;
  logic [(IDX_W << IDX_AW) - 1:0] prev_bank_q;
  assign y_fire = y_valid && y_ready_i;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      issued_q    <= '0;
      in_flight_q <= '0;
      out_q       <= '0;
      prev_q      <= 1'b0;
    end else begin
      if (re) begin
        issued_q <= (issued_q == LastCell) ? '0 : issued_q + 1'b1;
      end
      in_flight_q <= in_flight_q + {2'b0, re} - {2'b0, y_fire};
      if (y_fire) begin
        out_q <= (out_q == LastCell) ? '0 : out_q + 1'b1;
      end
      if (release_cell) begin
        prev_q       <= 1'b1;
        prev_lo_q    <= r_lo_i;
        prev_hi_q    <= r_hi_i;
        prev_below_q <= below_i;
        prev_bank_q  <= bank_i;
      end else if (y_fire && out_q == LastCell) begin
        prev_q <= 1'b0;
      end
    end
  end

  // The reference: the cells in flight are the next ones to leave, at offsets 0, 1 and 2 from
  // out_q; an offset past the bank's end is a cell of the bank after.
  logic [3*(IDX_W+1)-1:0] expected;  // {last, index} of offset k: bits [k*(IDX_W+1) +: IDX_W+1]
  for (genvar k = 0; k < 3; k++) begin : gen_expected
    logic [POS_W-1:0]  at;
    logic              next_bank, from_prev;
    logic [CELL_W-1:0] cell;
    assign at        = POS_W'({1'b0, out_q} + k);
    assign next_bank = at >= POS_W'(CELLS);
    assign cell      = next_bank ? CELL_W'(at - POS_W'(CELLS)) : CELL_W'(at);
    assign from_prev = prev_q && !next_bank;
    sectoral_ism_cell_model #(
      .RINGS(RINGS), .BINS(BINS), .SECTORS(SECTORS), .IDX_W(IDX_W), .RING_W(RING_W),
      .RIDX_W(RIDX_W), .J_W(J_W), .IDX_AW(IDX_AW), .CELL_W(CELL_W)
    ) i_model (
      .cell_i (cell),
      .r_lo_i (from_prev ? prev_lo_q : r_lo_i),
      .r_hi_i (from_prev ? prev_hi_q : r_hi_i),
      .below_i(from_prev ? prev_below_q : below_i),
      .bank_i (from_prev ? prev_bank_q : bank_i),
      .cell_o (expected[k*(IDX_W+1) +: IDX_W+1])
    );
  end

  always @* begin
    if ($initstate) begin
      assume (!rst_ni);
    end else begin
      // reads
      if (re) begin
        assert (full_i);
        assert (raddr == {RIDX_W'(issued_q / CELL_W'(BINS)),
                          J_W'((issued_q % CELL_W'(BINS)) / CELL_W'(BPS))});
      end
      assert (release_cell == (re && issued_q == LastCell));
      if (release_cell) begin
        assert (!prev_q || (y_fire && out_q == LastCell));  // the bank before has left
      end
      // no wasted ready cycle
      assert (in_flight_q <= 3'd3);
      if (full_i && in_flight_q < 3'd3) begin
        assert (re);
      end
      if (past_rst_n_q && !y_valid && in_flight_q != 3'd0) begin
        assert (in_flight_q == 3'd1 && past_re_q);  // only the cell read in the last cycle
      end
      // y
      if (!past_rst_n_q) begin
        assert (!y_valid);  // reset empties the output
      end else if (past_stall_q) begin
        assert (y_valid && y_data == past_y_data_q && y_last == past_y_last_q);
      end
      // the output sequence
      if (y_valid) begin
        assert ({y_last, y_data} == expected[IDX_W:0]);
      end
`ifdef FORMAL_INDUCTION
      // Induction strengthening: the stream's registers agree with the book-keeping ...
      assert (issued_q <= LastCell && out_q <= LastCell);
      assert (ring_q == RIDX_W'(issued_q / CELL_W'(BINS)));
      assert (sec_q == J_W'((issued_q % CELL_W'(BINS)) / CELL_W'(BPS)));
      assert (bin_q == BPS_W'(issued_q % CELL_W'(BPS)));
      assert (!b_full_q || a_full_q);
      assert (in_flight_q == {2'b0, s1_valid_q} + {2'b0, a_full_q} + {2'b0, b_full_q});
      assert ({1'b0, out_q} + POS_W'(in_flight_q)
              == (prev_q ? POS_W'(CELLS) : '0) + {1'b0, issued_q});
      if (issued_q != '0) begin
        assert (past_rst_n_q && past_hold_q);  // a bank being read is held
      end
      // ... and every cell in flight holds the reference's value for its position.
      if (a_full_q) begin
        assert (a_data_q == expected[IDX_W:0]);
      end
      if (b_full_q) begin
        assert (b_data_q == expected[IDX_W+1 +: IDX_W+1]);
      end
      if (s1_valid_q) begin
        assert ({s1_last_q, s1_const_q ? s1_const_idx_q : rdata_q}
                == expected[(a_full_q + b_full_q) * (IDX_W+1) +: IDX_W+1]);
      end
`endif
    end
  end

endmodule
