// The output phase: streams a written bank of the index RAM as R * A cells, ring-major,
// one per cycle while the consumer takes them. Each (ring, sector) index repeats for the
// sector's bins; rings outside the set-up window take a constant (the bank's `below` index
// before the window, 0 after it). Stage 1 is the RAM's registered read (it holds while the
// spill register is full); the spill register cuts the ready path to the consumer.
module sectoral_ism_stream #(
  parameter int unsigned RINGS   = 40,
  parameter int unsigned BINS    = 16,
  parameter int unsigned SECTORS = 4,
  parameter int unsigned IDX_W   = 8,
  // derived (sectoral_ism_pkg)
  localparam int unsigned RING_W = sectoral_ism_pkg::ring_bits(RINGS),
  localparam int unsigned RIDX_W = sectoral_ism_pkg::addr_bits(RINGS),
  localparam int unsigned J_W    = sectoral_ism_pkg::addr_bits(SECTORS),
  localparam int unsigned IDX_AW = RIDX_W + J_W
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              full_i,     // the bank to stream is written
  input  logic [RING_W-1:0] r_lo_i,     // its window
  input  logic [RING_W-1:0] r_hi_i,
  input  logic [IDX_W-1:0]  below_i,
  output logic              release_o,  // its last cell is read: the bank is free
  output logic              re_o,
  output logic [IDX_AW-1:0] raddr_o,
  input  logic [IDX_W-1:0]  rdata_i,
  output logic              y_valid_o,
  input  logic              y_ready_i,
  output logic [IDX_W-1:0]  y_data_o,
  output logic              y_last_o
);
  // Every sector streams BINS / SECTORS bins: a remainder would silently drop bins.
  if (SECTORS < 1 || SECTORS > BINS || BINS % SECTORS != 0) begin : gen_check_sectors
    $error("sectoral_ism_stream: SECTORS must divide BINS");
  end
  if (RINGS < 1) begin : gen_check_rings
    $error("sectoral_ism_stream: RINGS must be at least 1");
  end

  localparam int unsigned BPS   = BINS / SECTORS;
  localparam int unsigned BPS_W = (BPS > 1) ? $clog2(BPS) : 1;

  logic [RIDX_W-1:0] ring_q;   // the next cell to read: ring index, sector, bin in sector
  logic [J_W-1:0]    sec_q;
  logic [BPS_W-1:0]  bin_q;
  logic              s1_valid_q, s1_last_q, s1_const_q;
  logic [IDX_W-1:0]  s1_const_idx_q;
  logic              sp_ready;

  logic s1_advance, issue, last_cell, below, above;
  assign s1_advance = !s1_valid_q || sp_ready;  // stage 1 is empty or its cell enters the spill register
  assign issue      = full_i && s1_advance;     // read the next cell of the bank into stage 1
  assign last_cell  = (ring_q == RIDX_W'(RINGS - 1)) && (sec_q == J_W'(SECTORS - 1))
                   && (bin_q == BPS_W'(BPS - 1));
  assign below      = RING_W'(ring_q) + RING_W'(1) < r_lo_i;
  assign above      = RING_W'(ring_q) + RING_W'(1) > r_hi_i;
  assign release_o  = issue && last_cell;      // the bank's last cell is read
  assign re_o       = issue;
  assign raddr_o    = {ring_q, sec_q};

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ring_q     <= '0;
      sec_q      <= '0;
      bin_q      <= '0;
      s1_valid_q <= 1'b0;
    end else begin
      if (issue) begin
        s1_valid_q <= 1'b1;
        if (bin_q != BPS_W'(BPS - 1)) begin
          bin_q <= bin_q + BPS_W'(1);
        end else begin
          bin_q <= '0;
          if (sec_q != J_W'(SECTORS - 1)) begin
            sec_q <= sec_q + J_W'(1);
          end else begin
            sec_q  <= '0;
            ring_q <= last_cell ? '0 : ring_q + RIDX_W'(1);
          end
        end
      end else if (s1_advance) begin
        s1_valid_q <= 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (issue) begin
      s1_last_q      <= last_cell;
      s1_const_q     <= below || above;
      s1_const_idx_q <= below ? below_i : '0;
    end
  end

  logic [IDX_W:0] sp_data_in, sp_data_out;
  assign sp_data_in = {s1_last_q, s1_const_q ? s1_const_idx_q : rdata_i};

  spill_register #(.WIDTH(IDX_W + 1)) i_spill (
    .clk_i, .rst_ni,
    .valid_i (s1_valid_q),
    .ready_o (sp_ready),
    .data_i  (sp_data_in),
    .valid_o (y_valid_o),
    .ready_i (y_ready_i),
    .data_o  (sp_data_out)
  );
  assign y_data_o = sp_data_out[IDX_W-1:0];
  assign y_last_o = sp_data_out[IDX_W];

`ifndef SYNTHESIS
  // Checkers, simulation only (Yosys defines SYNTHESIS); Verilator needs --assert. Stability of
  // y is checked in i_spill.
  // Throughput while a bank is full: stage 1 reads a cell whenever it is empty or its cell can
  // move on, so the bank's cells reach y one per cycle.
  bank_read_without_wait: assert property (@(posedge clk_i) disable iff (!rst_ni)
      full_i && (!s1_valid_q || !i_spill.b_full_q) |-> re_o)
    else $error("sectoral_ism_stream: a full bank waits with room in stage 1 (bubble)");
  // A cell in stage 1 is on y in the next cycle (it enters the spill register, or that one is full).
  stage_feeds_output: assert property (@(posedge clk_i) disable iff (!rst_ni)
      s1_valid_q |=> y_valid_o)
    else $error("sectoral_ism_stream: a read cell is not on y in the next cycle (bubble)");
  // y_last on every RINGS * BINS-th cell and on no other, counted here independently.
  localparam int unsigned CELLS = RINGS * BINS;
  int unsigned sent_q;  // cells of the current reading already sent
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      sent_q <= 0;
    end else if (y_valid_o && y_ready_i) begin
      sent_q <= (sent_q == CELLS - 1) ? 0 : sent_q + 1;
    end
  end
  last_every_reading: assert property (@(posedge clk_i) disable iff (!rst_ni)
      y_valid_o |-> y_last_o == (sent_q == CELLS - 1))
    else $error("sectoral_ism_stream: y_last on cell %0d of a reading of %0d", sent_q, CELLS);
  // Only a four-state simulator can see X here (two-state Verilator cannot).
  known_after_reset: assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown({y_valid_o, re_o, release_o}) && (!y_valid_o || !$isunknown({y_last_o, y_data_o})))
    else $error("sectoral_ism_stream: unknown output after reset");
`endif
endmodule
