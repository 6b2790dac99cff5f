// Kernel 2 of docs/hardware.md: the sectoral inverse sensor model in integer arithmetic. One
// reading z per input beat (READING_FRAC fractional bits, in cells); per reading, the S_eps
// index of every polar cell, one cell per output beat, ring-major (cell (r, a) at
// (r - 1) * BINS + a), y_last on the reading's last cell. Bit for bit golden's
// ism_kernel_indices; z_last_i is accepted and ignored (every reading is a whole frame).
//
// A set-up engine (sectoral_ism_setup) computes the (ring, sector) indices of a reading into
// one bank of a two-bank index RAM while the streamer (sectoral_ism_stream) sends the other
// bank's cells, so set-up and output overlap. The configuration is a folder rtl/config/<name>/
// (ROM files and the parameters in three formats, written by `intgrid hw-config` from golden);
// the defaults are cone16's. Widths that follow from the configuration are localparams.
//
// Timing: a reading is taken when the engine is idle and its next bank is free (never in reset
// nor in the first cycle after it: z_ready_o is low from a reset edge to the next edge). Set-up takes
// 2 cycles for a reading with no ring in the window (z >= reach), else
//   ND + 15 + (n + 1) * CONDITIONS * CLASSES + 2 n + n * (3 SECTORS + 1)
// cycles, n the rings within WINDOW cells of z and ND = ceil(MUL_B_W / MUL_DIGIT_W). The first
// cell leaves 3 cycles after the set-up's last cycle (if the other bank is not streaming);
// then one cell per cycle while y_ready_i is high.
module sectoral_ism #(
  // The configuration (rtl/config/<name>/: sectoral_ism_<name>.vc / .svh / .ys set all of it)
  parameter int unsigned READING_W              = 16,   // reading port, READING_FRAC fractional bits
  parameter int unsigned RINGS                  = 40,
  parameter int unsigned BINS                   = 16,
  parameter int unsigned SECTORS                = 4,    // divides BINS
  parameter int unsigned CLASSES                = 6,    // pattern classes of a ring
  parameter int unsigned WINDOW                 = 13,   // rings within WINDOW cells of z count
  parameter int unsigned IDX_W                  = 8,    // S_eps index width
  parameter int unsigned READING_FRAC           = 8,
  parameter int unsigned LOG_FRAC               = 8,
  parameter int unsigned QUAD_SHIFT             = 24,
  // Word widths that depend on the tables' values (golden's derive_ism_hw)
  parameter int unsigned LOG_W                  = 20,
  parameter int unsigned COEF_W                 = 19,
  parameter int unsigned NORM_W                 = 12,
  parameter int unsigned WEIGHT_W               = 13,
  parameter int unsigned PHI_N                  = 2440,
  parameter int unsigned PHI_W                  = 8,
  parameter int unsigned THR_W                  = 14,
  parameter int unsigned BUCKET_SHIFT           = 6,
  parameter int unsigned BUCKET_N               = 148,
  // The ROMs: $readmemh files, named relative to rtl/ (where tools run; Yosys also looks there)
  parameter              QUAD_COEF_FILE         = "config/cone16/sectoral_ism_cone16_quad_coef.mem",
  parameter              LOG_NORM_FILE          = "config/cone16/sectoral_ism_cone16_log_norm.mem",
  parameter              LOG_WEIGHT_FILE        = "config/cone16/sectoral_ism_cone16_log_weight.mem",
  parameter              LOG_ADD_FILE           = "config/cone16/sectoral_ism_cone16_log_add.mem",
  parameter              THRESHOLDS_FILE        = "config/cone16/sectoral_ism_cone16_thresholds.mem",
  parameter              THRESHOLD_BUCKET_FILE  = "config/cone16/sectoral_ism_cone16_threshold_bucket.mem",
  // Derived from the configuration (sectoral_ism_pkg), not parameters to set
  localparam int unsigned CONDITIONS  = sectoral_ism_pkg::conditions(SECTORS),
  localparam int unsigned MAX_INDEX   = sectoral_ism_pkg::max_index_of(IDX_W),
  localparam int unsigned E_W         = sectoral_ism_pkg::error_bits(WINDOW, READING_FRAC),
  localparam int unsigned SQ_W        = sectoral_ism_pkg::square_bits(WINDOW, READING_FRAC),
  localparam int unsigned MUL_B_W     = (COEF_W > E_W) ? COEF_W : E_W,
  localparam int unsigned MUL_DIGIT_W = sectoral_ism_pkg::mul_digit_bits(MUL_B_W, CLASSES,
                                                                         CONDITIONS),
  localparam int unsigned PHI_AW      = sectoral_ism_pkg::unsigned_bits(64'(PHI_N) - 64'd1),
  localparam int unsigned BUCKET_W    = sectoral_ism_pkg::unsigned_bits(64'(MAX_INDEX)),
  localparam int unsigned RING_W      = sectoral_ism_pkg::ring_bits(RINGS),
  localparam int unsigned RIDX_W      = sectoral_ism_pkg::addr_bits(RINGS),
  localparam int unsigned J_W         = sectoral_ism_pkg::addr_bits(SECTORS),
  localparam int unsigned IDX_AW      = RIDX_W + J_W
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 z_valid_i,
  output logic                 z_ready_o,
  input  logic [READING_W-1:0] z_data_i,
  input  logic                 z_last_i,
  output logic                 y_valid_o,
  input  logic                 y_ready_i,
  output logic [IDX_W-1:0]     y_data_o,
  output logic                 y_last_o
);
  // A configuration the kernel cannot run stops elaboration (the sub-modules check their own).
  if (IDX_W < 2 || IDX_W > 16) begin : gen_check_idx_w
    $error("sectoral_ism: IDX_W must be 2..16");
  end
  if (READING_W <= READING_FRAC || READING_W > 31) begin : gen_check_reading_w
    $error("sectoral_ism: READING_W must exceed READING_FRAC and be at most 31");
  end
  // Readings at or past reach = (RINGS + WINDOW) << READING_FRAC inform no cell: reach must
  // fit the port, or a reading past every ring could not be told apart.
  if ((64'(RINGS) + 64'(WINDOW)) << READING_FRAC >= 64'd1 << READING_W) begin : gen_check_reach
    $error("sectoral_ism: (RINGS + WINDOW) << READING_FRAC does not fit READING_W bits");
  end
  if (PHI_N < 1 || BUCKET_N < 1) begin : gen_check_tables
    $error("sectoral_ism: PHI_N and BUCKET_N must be at least 1");
  end

  logic unused_z_last;
  assign unused_z_last = z_last_i;

  // Two banks: the engine fills bank wb_q, the streamer empties bank rb_q.
  logic [1:0]        full_q;
  logic              wb_q, rb_q;
  logic [RING_W-1:0] lo_q [0:1];
  logic [RING_W-1:0] hi_q [0:1];
  logic [IDX_W-1:0]  below_q [0:1];

  logic              setup_idle, setup_done, stream_release;
  logic [RING_W-1:0] setup_lo, setup_hi;
  logic [IDX_W-1:0]  setup_below;
  logic              z_fire;
  // Low from a reset edge to the first edge out of reset, so that no reading is offered a ready
  // that the reset then ignores; z_ready_o stays a function of registers only.
  logic out_of_reset_q;
  always_ff @(posedge clk_i) begin
    out_of_reset_q <= rst_ni;
  end
  assign z_ready_o = out_of_reset_q && setup_idle && !full_q[wb_q];  // out of reset, the engine is idle and its next bank is free
  assign z_fire    = z_valid_i && z_ready_o;       // a reading is accepted

  logic              idx_we, idx_re;
  logic [IDX_AW-1:0] idx_waddr, idx_raddr;
  logic [IDX_W-1:0]  idx_wdata, idx_rdata;

  sectoral_ism_setup #(
    .READING_W(READING_W), .RINGS(RINGS), .BINS(BINS), .SECTORS(SECTORS), .CLASSES(CLASSES),
    .CONDITIONS(CONDITIONS), .WINDOW(WINDOW), .MAX_INDEX(MAX_INDEX), .IDX_W(IDX_W),
    .READING_FRAC(READING_FRAC), .LOG_FRAC(LOG_FRAC), .QUAD_SHIFT(QUAD_SHIFT), .LOG_W(LOG_W),
    .E_W(E_W), .SQ_W(SQ_W), .COEF_W(COEF_W), .MUL_B_W(MUL_B_W), .MUL_DIGIT_W(MUL_DIGIT_W),
    .NORM_W(NORM_W), .WEIGHT_W(WEIGHT_W), .PHI_N(PHI_N), .PHI_W(PHI_W), .PHI_AW(PHI_AW),
    .THR_W(THR_W), .BUCKET_SHIFT(BUCKET_SHIFT), .BUCKET_N(BUCKET_N), .BUCKET_W(BUCKET_W),
    .QUAD_COEF_FILE(QUAD_COEF_FILE), .LOG_NORM_FILE(LOG_NORM_FILE),
    .LOG_WEIGHT_FILE(LOG_WEIGHT_FILE), .LOG_ADD_FILE(LOG_ADD_FILE),
    .THRESHOLDS_FILE(THRESHOLDS_FILE), .BUCKET_FILE(THRESHOLD_BUCKET_FILE)
  ) i_setup (
    .clk_i, .rst_ni,
    .start_i     (z_fire),
    .z_i         (z_data_i),
    .idle_o      (setup_idle),
    .done_o      (setup_done),
    .r_lo_o      (setup_lo),
    .r_hi_o      (setup_hi),
    .below_o     (setup_below),
    .idx_we_o    (idx_we),
    .idx_waddr_o (idx_waddr),
    .idx_wdata_o (idx_wdata)
  );

  sdp_ram #(.WIDTH(IDX_W), .DEPTH(2 << IDX_AW)) i_index_ram (
    .clk_i,
    .we_i    (idx_we),
    .waddr_i ({wb_q, idx_waddr}),
    .wdata_i (idx_wdata),
    .re_i    (idx_re),
    .raddr_i ({rb_q, idx_raddr}),
    .rdata_o (idx_rdata)
  );

  sectoral_ism_stream #(.RINGS(RINGS), .BINS(BINS), .SECTORS(SECTORS), .IDX_W(IDX_W)) i_stream (
    .clk_i, .rst_ni,
    .full_i    (full_q[rb_q]),
    .r_lo_i    (lo_q[rb_q]),
    .r_hi_i    (hi_q[rb_q]),
    .below_i   (below_q[rb_q]),
    .release_o (stream_release),
    .re_o      (idx_re),
    .raddr_o   (idx_raddr),
    .rdata_i   (idx_rdata),
    .y_valid_o,
    .y_ready_i,
    .y_data_o,
    .y_last_o
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      full_q <= '0;
      wb_q   <= 1'b0;
      rb_q   <= 1'b0;
    end else begin
      if (setup_done) begin      // bank wb_q is written
        full_q[wb_q] <= 1'b1;
        wb_q         <= !wb_q;
      end
      if (stream_release) begin  // bank rb_q is read (never the bank just written)
        full_q[rb_q] <= 1'b0;
        rb_q         <= !rb_q;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (setup_done) begin
      lo_q[wb_q]    <= setup_lo;
      hi_q[wb_q]    <= setup_hi;
      below_q[wb_q] <= setup_below;
    end
  end

`ifndef SYNTHESIS
  // Checkers, simulation only (Yosys defines SYNTHESIS); Verilator needs --assert. The output
  // stream's rules are checked in i_stream and its spill register.
  // No reading is taken in reset: z_ready_o is low in every cycle after a reset edge. (The
  // checker's own flag starts at 0, so that a random initial state does not fire it.)
  bit after_reset_edge_q = 1'b0;
  always_ff @(posedge clk_i) begin
    after_reset_edge_q <= !rst_ni;
  end
  ready_low_after_reset_edge: assert property (@(posedge clk_i) after_reset_edge_q |-> !z_ready_o)
    else $error("sectoral_ism: z_ready after a reset edge");
  // The source's rule (AXI4-Stream): an offered reading stays, unchanged, until it is taken.
  z_source_holds: assert property (@(posedge clk_i) disable iff (!rst_ni)
      z_valid_i && !z_ready_o |=> z_valid_i && $stable(z_data_i))
    else $error("sectoral_ism: z changed an offered reading before it was taken");
  // Only a four-state simulator can see X here (two-state Verilator cannot).
  known_after_reset: assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown({z_ready_o, y_valid_o}) && (!y_valid_o || !$isunknown({y_last_o, y_data_o})))
    else $error("sectoral_ism: unknown output after reset");
`endif
endmodule
