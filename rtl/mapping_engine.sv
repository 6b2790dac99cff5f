// The mapping engine: a scan's readings laid along integer rays, each line-of-sight cell given its
// reading's narrow-ISM index and fused into a tile of S_eps cells with kernel 1's saturating
// adder; bit for bit golden's insert_scan_along_rays, cycle for cycle the SystemC model
// (systemc/mapping_engine_module.hpp, whose header states the schedule; hls/mapping_engine.hpp
// the arithmetic and the widths).
//
// Micro-architecture: a one-beat command slot; a restoring divider for a used reading's range bin
// (19 cycles, overlapped with the walk before it) and a cycle to read the bin's entry, during
// which one shared multiplier forms the ray's six direction products, one a cycle; one start
// cycle that sets the ray up (one multiplication left, the bin's length); then one cell a
// cycle: the cell's tile and tail entries are read at the edge that steps the ray, and the
// fused index is written at the next edge (the write stage), so the tile is a simple dual-port
// RAM. A reset clears the tile, a cell a cycle; the load port fills the settings and memories;
// the read port serves the tile while the engine is idle, its result held by a skid register
// under back-pressure.
module mapping_engine #(
  parameter int unsigned B          = 8,     // index width, 4..16
  parameter int unsigned TILE_BITS  = 8,     // the tile is 2^TILE_BITS cells square, 2..10
  parameter int unsigned BINS       = 5002,  // range bins of the ISM table
  parameter int unsigned TAIL_CELLS = 1024,  // entries of the tail memory
  localparam int unsigned TILE_AW   = 2 * TILE_BITS
) (
  input  logic               clk_i,
  input  logic               rst_ni,  // synchronous, active low
  // command stream: a scan pose (in_pose_i) or a reading
  input  logic               in_valid_i,
  output logic               in_ready_o,
  input  logic               in_pose_i,
  input  logic [25:0]        in_cx_i,     // sensor cell (two's complement)
  input  logic [25:0]        in_cy_i,
  input  logic [14:0]        in_px_i,     // mm from the cell's centre (two's complement)
  input  logic [14:0]        in_py_i,
  input  logic [15:0]        in_angle_i,  // a pose's heading, a reading's bearing (2^-16 turn)
  input  logic [17:0]        in_range_i,  // mm, 0 for none
  // tile read port
  input  logic               rd_valid_i,
  output logic               rd_ready_o,
  input  logic [TILE_AW-1:0] rd_addr_i,   // y * 2^TILE_BITS + x
  output logic               rd_valid_o,
  input  logic               rd_ready_i,
  output logic [B-1:0]       rd_data_o,
  output logic               idle_o,
  // load port
  input  logic               ld_valid_i,
  input  logic [2:0]         ld_target_i,  // 0 settings, 1 sine coarse, 2 sine steps, 3 bin, 4 tail
  input  logic [15:0]        ld_addr_i,
  input  logic [63:0]        ld_data_i
);
  localparam int unsigned RangeBits  = 18;
  localparam int unsigned CellBits   = 14;
  localparam int unsigned CountBits  = RangeBits + 1;
  localparam int unsigned WalkBits   = RangeBits + 21;
  localparam int unsigned CoordBits  = 26;
  localparam int unsigned Quarter    = 16384;
  localparam int unsigned TailBits   = $clog2(TAIL_CELLS + 1);
  localparam int unsigned BinBits    = 2 * CountBits + B + TailBits;
  localparam int unsigned BinAw      = $clog2(BINS);
  localparam int unsigned TailAw     = $clog2(TAIL_CELLS);
  localparam int unsigned Side       = 1 << TILE_BITS;
  localparam int unsigned SetupCycles = RangeBits + 2;  // the divider's 19, the bin's entry 1

  if (B < 4 || B > 16) begin : gen_check_b
    $error("mapping_engine: B must be 4..16");
  end
  if (TILE_BITS < 2 || TILE_BITS > 10) begin : gen_check_tile
    $error("mapping_engine: TILE_BITS must be 2..10");
  end
  if (BINS < 2 || BINS > 65536 || TAIL_CELLS < 2 || TAIL_CELLS > 65536) begin : gen_check_memories
    $error("mapping_engine: BINS and TAIL_CELLS must be 2..65536");
  end
  if (BinBits > 64) begin : gen_check_bin
    $error("mapping_engine: a bin's entry must fit the 64-bit load bus");
  end

  typedef logic signed [WalkBits-1:0] walk_t;

  // ---- settings and loads ----------------------------------------------------------------------
  logic [CellBits-1:0]  cell_q;
  logic [RangeBits-1:0] z_step_q, max_range_q;
  logic                 load_sine_coarse, load_sine_steps, load_bin, load_tail;

  assign load_sine_coarse = ld_valid_i && ld_target_i == 3'd1 && ld_addr_i < 16'd1025;
  assign load_sine_steps  = ld_valid_i && ld_target_i == 3'd2 && ld_addr_i < 16'd1024;
  assign load_bin         = ld_valid_i && ld_target_i == 3'd3 && 32'(ld_addr_i) < BINS;
  assign load_tail        = ld_valid_i && ld_target_i == 3'd4 && 32'(ld_addr_i) < TAIL_CELLS;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      cell_q      <= '0;
      z_step_q    <= '0;
      max_range_q <= '0;
    end else if (ld_valid_i && ld_target_i == 3'd0) begin
      if (ld_addr_i == 16'd0) cell_q <= ld_data_i[CellBits-1:0];
      if (ld_addr_i == 16'd1) z_step_q <= ld_data_i[RangeBits-1:0];
      if (ld_addr_i == 16'd2) max_range_q <= ld_data_i[RangeBits-1:0];
    end
  end

  // ---- the command slot ------------------------------------------------------------------------
  logic                        slot_full_q, slot_pose_q;
  logic signed [CoordBits-1:0] slot_cx_q, slot_cy_q;
  logic signed [CellBits:0]    slot_px_q, slot_py_q;
  logic [15:0]                 slot_angle_q;
  logic [RangeBits-1:0]        slot_range_q;
  logic [4:0]                  countdown_q;  // set-up cycles left before the slot may start
  logic [TILE_AW:0]            clearing_q;   // tile cells left to clear
  logic                        walking_q, draining_q;
  logic                        in_fire, in_used, start;

  assign in_ready_o = rst_ni && clearing_q == '0 && !slot_full_q;
  assign in_fire    = in_valid_i && in_ready_o;
  assign in_used    = in_range_i != '0 && in_range_i < max_range_q;
  assign start      = slot_full_q && countdown_q == '0 && !walking_q;
  assign idle_o     = rst_ni && clearing_q == '0 && !slot_full_q && !walking_q && !draining_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      slot_full_q  <= 1'b0;
      slot_pose_q  <= 1'b0;
      slot_cx_q    <= '0;
      slot_cy_q    <= '0;
      slot_px_q    <= '0;
      slot_py_q    <= '0;
      slot_angle_q <= '0;
      slot_range_q <= '0;
      countdown_q  <= '0;
    end else begin
      if (start) slot_full_q <= 1'b0;
      if (slot_full_q && countdown_q != '0) countdown_q <= countdown_q - 1'b1;
      if (in_fire) begin
        slot_full_q  <= 1'b1;
        slot_pose_q  <= in_pose_i;
        slot_cx_q    <= in_cx_i;
        slot_cy_q    <= in_cy_i;
        slot_px_q    <= in_px_i;
        slot_py_q    <= in_py_i;
        slot_angle_q <= in_angle_i;
        slot_range_q <= in_range_i;
        countdown_q  <= (!in_pose_i && in_used) ? 5'(SetupCycles) : '0;
      end
    end
  end

  // ---- set-up: the range bin, the bin's entry, the direction -----------------------------------
  logic [CountBits-1:0] bin;
  logic [BinBits-1:0]   bin_entry;
  logic [15:0]          angle;
  logic [14:0]          sin_entry, cos_entry;
  logic [16:0]          sin_magnitude, cos_magnitude;

  mapping_engine_divider #(
    .W(CountBits)
  ) i_divider (
    .clk_i,
    .rst_ni,
    .start_i   (in_fire && !in_pose_i && in_used),
    .dividend_i(CountBits'(in_range_i) + CountBits'(z_step_q[RangeBits-1:1])),
    .divisor_i (CountBits'(z_step_q)),
    .quotient_o(bin)
  );

  sdp_ram #(
    .WIDTH(BinBits),
    .DEPTH(BINS)
  ) i_bins (
    .clk_i,
    .we_i   (load_bin),
    .waddr_i(ld_addr_i[BinAw-1:0]),
    .wdata_i(ld_data_i[BinBits-1:0]),
    .re_i   (slot_full_q && countdown_q == 5'd1),
    .raddr_i(bin[BinAw-1:0]),
    .rdata_o(bin_entry)
  );

  // The quarter-wave sine, looked up twice in the set-up: sin at its first cycle, cos at its
  // second, each magnitude kept from the cycle after its lookup.
  // Quadrant q of angle a: sin a = (q < 2 ? +1 : -1) S[q odd ? 2^14 - w : w], w = a mod 2^14.
  assign angle     = heading_q + slot_angle_q;
  assign sin_entry = angle[14] ? 15'(Quarter) - 15'(angle[13:0]) : 15'(angle[13:0]);
  logic [15:0] cos_angle;
  assign cos_angle = angle + 16'(Quarter);
  assign cos_entry = cos_angle[14] ? 15'(Quarter) - 15'(cos_angle[13:0]) : 15'(cos_angle[13:0]);

  logic [16:0] sine_magnitude;
  logic        sin_lookup, cos_lookup;
  assign sin_lookup = slot_full_q && countdown_q == 5'(SetupCycles);
  assign cos_lookup = slot_full_q && countdown_q == 5'(SetupCycles - 1);

  mapping_engine_sine i_sine (
    .clk_i,
    .we_coarse_i(load_sine_coarse),
    .we_steps_i (load_sine_steps),
    .waddr_i    (ld_addr_i[10:0]),
    .wdata_i    (ld_data_i[44:0]),
    .re_i       (sin_lookup || cos_lookup),
    .entry_i    (sin_lookup ? sin_entry : cos_entry),
    .magnitude_o(sine_magnitude)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      sin_magnitude <= '0;
      cos_magnitude <= '0;
    end else begin
      if (cos_lookup) sin_magnitude <= sine_magnitude;  // sin's result, the cycle after its lookup
      if (slot_full_q && countdown_q == 5'(SetupCycles - 2)) cos_magnitude <= sine_magnitude;
    end
  end

  // ---- the scan's pose -------------------------------------------------------------------------
  logic signed [CoordBits-1:0] cx_q, cy_q;
  logic signed [CellBits:0]    px_q, py_q;
  logic [15:0]                 heading_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      cx_q      <= '0;
      cy_q      <= '0;
      px_q      <= '0;
      py_q      <= '0;
      heading_q <= '0;
    end else if (start && slot_pose_q) begin
      cx_q      <= slot_cx_q;
      cy_q      <= slot_cy_q;
      px_q      <= slot_px_q;
      py_q      <= slot_py_q;
      heading_q <= slot_angle_q;
    end
  end

  // ---- the ray's set-up (the start cycle) ------------------------------------------------------
  // The sine table's angle is that of the slot's reading, read when it entered the set-up; the
  // quadrant bits are still those of `angle` here (the pose cannot change before the start).
  logic signed [17:0]          cs, sn;
  logic [16:0]                 acs, asn;
  logic [CountBits-1:0]        bin_cells, bin_core;
  logic [B-1:0]                bin_constant;
  logic [TailBits-1:0]         bin_tail;
  logic signed [CellBits+2:0]  x0, y0;         // doubled mm from the sensor cell's corner
  logic signed [1:0]           ix0, iy0;       // the cell holding the sensor, -1..1
  logic signed [CellBits+2:0]  bx, by;         // doubled mm to the next boundary
  logic signed [CellBits+2:0]  ox, oy;         // doubled mm from the sensor to (ix0, iy0)'s centre
  logic [CellBits:0]           c2;
  logic [CountBits-1:0]        limit;          // mm; wraps as the model's uint<19> does
  walk_t                       d0, next0, cell_q17, end0;
  logic                        used_slot, starts_walk;

  // The direction products, one a cycle at countdowns FirstProduct .. FirstProduct - 5 (sin and
  // cos are both held from countdown SetupCycles - 3 on), on one 18 x 18 signed multiplier:
  // ox cos, oy sin (d0's two terms), bx |sin|, by |cos| (tx, ty), 2c |cos|, 2c |sin|.
  localparam int unsigned FirstProduct = SetupCycles - 4;
  logic signed [17:0] mul_a, mul_b;
  logic signed [35:0] product_q[6];
  logic [4:0]         product_slot;
  assign product_slot = 5'(FirstProduct) - countdown_q;
  always_comb begin
    unique case (product_slot)
      5'd0:    begin mul_a = 18'(ox); mul_b = cs; end
      5'd1:    begin mul_a = 18'(oy); mul_b = sn; end
      5'd2:    begin mul_a = 18'(bx); mul_b = $signed({1'b0, asn}); end
      5'd3:    begin mul_a = 18'(by); mul_b = $signed({1'b0, acs}); end
      5'd4:    begin mul_a = $signed(18'(c2)); mul_b = $signed({1'b0, acs}); end
      default: begin mul_a = $signed(18'(c2)); mul_b = $signed({1'b0, asn}); end
    endcase
  end
  for (genvar i = 0; i < 6; i++) begin : gen_product
    always_ff @(posedge clk_i) begin
      if (!rst_ni) product_q[i] <= '0;
      else if (slot_full_q && countdown_q != '0 && product_slot == 5'(i))
        product_q[i] <= mul_a * mul_b;
    end
  end

  assign cs = cos_angle[15] ? -$signed({1'b0, cos_magnitude}) : $signed({1'b0, cos_magnitude});
  assign sn = angle[15] ? -$signed({1'b0, sin_magnitude}) : $signed({1'b0, sin_magnitude});
  assign acs = cos_magnitude;
  assign asn = sin_magnitude;
  assign {bin_tail, bin_constant, bin_core, bin_cells} = bin_entry;

  // c and 2c as signed words of the doubled-millimetre width; c / 2.
  logic signed [CellBits+2:0] c_s, c2_s, ic2_x, ic2_y;
  logic [CellBits-2:0]        half_cell;
  assign c2        = {cell_q, 1'b0};
  assign c_s       = $signed({3'b0, cell_q});
  assign c2_s      = $signed({2'b0, c2});
  assign half_cell = cell_q[CellBits-1:1];
  assign x0 = (CellBits+3)'($signed({px_q, 1'b0})) + c_s;
  assign y0 = (CellBits+3)'($signed({py_q, 1'b0})) + c_s;
  assign ix0 = x0 < 0 ? -2'sd1 : (x0 >= c2_s ? 2'sd1 : 2'sd0);
  assign iy0 = y0 < 0 ? -2'sd1 : (y0 >= c2_s ? 2'sd1 : 2'sd0);
  // i c2; (i + 1) c2 - x forward, x - i c2 backward; i c2 + c - x to the centre.
  assign ic2_x = ix0 == 2'sd1 ? c2_s : (ix0 == -2'sd1 ? -c2_s : '0);
  assign ic2_y = iy0 == 2'sd1 ? c2_s : (iy0 == -2'sd1 ? -c2_s : '0);
  assign bx    = cs > 0 ? ic2_x + c2_s - x0 : x0 - ic2_x;
  assign by    = sn > 0 ? ic2_y + c2_s - y0 : y0 - ic2_y;
  assign ox    = ic2_x + c_s - x0;
  assign oy    = ic2_y + c_s - y0;
  assign limit = CountBits'(bin_cells * CountBits'(cell_q) + CountBits'(half_cell));
  assign d0       = $signed(WalkBits'(product_q[0])) + $signed(WalkBits'(product_q[1]));
  assign cell_q17 = $signed(WalkBits'({cell_q, 17'b0}));
  assign next0    = $signed(WalkBits'({CellBits'(cell_q - CellBits'(half_cell)), 17'b0}));
  assign end0     = $signed(WalkBits'({CountBits'(limit) + 20'd1, 17'b0}));
  assign used_slot   = slot_range_q != '0 && slot_range_q < max_range_q;
  assign starts_walk = start && !slot_pose_q && used_slot;

  // ---- the walk --------------------------------------------------------------------------------
  logic signed [CoordBits-1:0] ix_q, iy_q;
  logic [CountBits-1:0]        k_q, cells_q, core_q;
  logic [B-1:0]                constant_q;
  logic [TailBits-1:0]         tail_q;
  walk_t                       tx_q, ty_q, d_q, next_q, c2_cos_q, c2_sin_q, end_q;
  logic                        forward_x_q, forward_y_q;
  // The step's next state, and the ray's first (k counted once, as advance does).
  logic                        along_x;
  walk_t                       d_step, d_first;
  logic signed [CoordBits-1:0] ix_step, iy_step;

  assign along_x = tx_q < ty_q;
  assign d_step  = d_q + (along_x ? c2_cos_q : c2_sin_q);
  assign ix_step = along_x ? (forward_x_q ? ix_q + 1 : ix_q - 1) : ix_q;
  assign iy_step = along_x ? iy_q : (forward_y_q ? iy_q + 1 : iy_q - 1);
  assign d_first = d0;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      walking_q   <= 1'b0;
      draining_q  <= 1'b0;
      ix_q        <= '0;
      iy_q        <= '0;
      k_q         <= '0;
      cells_q     <= '0;
      core_q      <= '0;
      constant_q  <= '0;
      tail_q      <= '0;
      tx_q        <= '0;
      ty_q        <= '0;
      d_q         <= '0;
      next_q      <= '0;
      c2_cos_q    <= '0;
      c2_sin_q    <= '0;
      end_q       <= '0;
      forward_x_q <= 1'b0;
      forward_y_q <= 1'b0;
    end else begin
      draining_q <= walking_q;  // the cell walked at this edge is written at the next
      if (walking_q) begin
        ix_q <= ix_step;
        iy_q <= iy_step;
        if (along_x) tx_q <= tx_q + c2_sin_q;
        else ty_q <= ty_q + c2_cos_q;
        d_q <= d_step;
        if (d_step >= next_q) begin
          k_q    <= k_q + 1'b1;
          next_q <= next_q + cell_q17;
        end
        walking_q <= d_step < end_q;
      end else if (starts_walk) begin
        cells_q     <= bin_cells;
        core_q      <= bin_core;
        constant_q  <= bin_constant;
        tail_q      <= bin_tail;
        forward_x_q <= cs > 0;
        forward_y_q <= sn > 0;
        ix_q        <= CoordBits'(ix0);
        iy_q        <= CoordBits'(iy0);
        tx_q        <= $signed(WalkBits'(product_q[2]));
        ty_q        <= $signed(WalkBits'(product_q[3]));
        c2_cos_q    <= $signed(WalkBits'(product_q[4]));
        c2_sin_q    <= $signed(WalkBits'(product_q[5]));
        d_q         <= d_first;
        end_q       <= end0;
        if (d_first >= next0) begin
          k_q    <= CountBits'(1);
          next_q <= next0 + cell_q17;
        end else begin
          k_q    <= '0;
          next_q <= next0;
        end
        walking_q <= d_first < end0;
      end
    end
  end

  // ---- the tile: read at the step, written at the next edge ------------------------------------
  logic signed [CoordBits:0] cell_x, cell_y, side_s;
  logic                      in_tile, k_in_ism, fuse;
  logic [TILE_AW-1:0]        cell_addr, tile_raddr, tile_waddr, wr_addr_q, clear_addr;
  logic [B-1:0]              tile_rdata, tail_rdata, tile_wdata, fused, value;
  logic [TailAw-1:0]         tail_raddr;
  logic                      wr_valid_q, wr_core_q, rd_fire, rd_valid_q, rd_hold_q;
  logic [B-1:0]              rd_data_q;

  assign side_s     = (CoordBits+1)'(Side);
  assign cell_x     = cx_q + ix_q;
  assign cell_y     = cy_q + iy_q;
  assign in_tile   = cell_x >= 0 && cell_x < side_s && cell_y >= 0 && cell_y < side_s;
  assign k_in_ism   = k_q != '0 && k_q <= cells_q;
  assign fuse       = walking_q && in_tile && k_in_ism;
  assign cell_addr  = {cell_y[TILE_BITS-1:0], cell_x[TILE_BITS-1:0]};
  // Cell k of the tail: tail + k - core - 1 (read for every cell, used past the core).
  assign tail_raddr = TailAw'(CountBits'(tail_q) + k_q - core_q - 1'b1);
  assign value      = wr_core_q ? constant_q : tail_rdata;
  assign clear_addr = '0 - clearing_q[TILE_AW-1:0];  // 2^TILE_AW - clearing_q, from 0 up
  assign tile_raddr = walking_q ? cell_addr : rd_addr_i;
  assign tile_waddr = clearing_q != '0 ? clear_addr : wr_addr_q;
  assign tile_wdata = clearing_q != '0 ? '0 : fused;

  saturating_add #(
    .B(B)
  ) i_fuse (
    .a_i(tile_rdata),
    .b_i(value),
    .y_o(fused)
  );

  sdp_ram #(
    .WIDTH(B),
    .DEPTH(TAIL_CELLS)
  ) i_tail (
    .clk_i,
    .we_i   (load_tail),
    .waddr_i(ld_addr_i[TailAw-1:0]),
    .wdata_i(ld_data_i[B-1:0]),
    .re_i   (walking_q),
    .raddr_i(tail_raddr),
    .rdata_o(tail_rdata)
  );

  sdp_ram #(
    .WIDTH(B),
    .DEPTH(1 << TILE_AW)
  ) i_tile (
    .clk_i,
    .we_i   (clearing_q != '0 || wr_valid_q),
    .waddr_i(tile_waddr),
    .wdata_i(tile_wdata),
    .re_i   (walking_q || rd_fire),
    .raddr_i(tile_raddr),
    .rdata_o(tile_rdata)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      clearing_q <= (TILE_AW + 1)'(1 << TILE_AW);
      wr_valid_q <= 1'b0;
      wr_core_q  <= 1'b0;
      wr_addr_q  <= '0;
    end else begin
      if (clearing_q != '0) clearing_q <= clearing_q - 1'b1;
      wr_valid_q <= fuse;
      wr_core_q  <= (k_q <= core_q);
      wr_addr_q  <= cell_addr;
    end
  end

  // ---- the read port ---------------------------------------------------------------------------
  assign rd_ready_o = idle_o && (!rd_valid_q || rd_ready_i);
  assign rd_fire    = rd_valid_i && rd_ready_o;
  assign rd_valid_o = rd_valid_q;
  assign rd_data_o  = rd_hold_q ? rd_data_q : tile_rdata;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      rd_valid_q <= 1'b0;
      rd_hold_q  <= 1'b0;
      rd_data_q  <= '0;
    end else begin
      rd_valid_q <= rd_fire || (rd_valid_q && !rd_ready_i);
      // A result still offered is kept apart from the RAM, whose output the next walk reuses.
      if (rd_valid_q && !rd_ready_i && !rd_hold_q) begin
        rd_data_q <= tile_rdata;
        rd_hold_q <= 1'b1;
      end else if (rd_fire || !rd_valid_q || rd_ready_i) begin
        rd_hold_q <= 1'b0;
      end
    end
  end

  // The load bus's bits past a bin's entry are not used.
  if (BinBits < 64) begin : gen_unused_load_bits
    logic unused_load_bits;
    assign unused_load_bits = ^ld_data_i[63:BinBits];
  end

`ifndef SYNTHESIS
  // Nothing is taken during reset or while the tile clears.
  ready_low_while_clearing: assert property (@(posedge clk_i)
      !rst_ni || clearing_q != '0 |-> !in_ready_o && !rd_ready_o)
    else $error("mapping_engine: ready while in reset or clearing");
  // The sources' rule: an offered beat stays, unchanged, until it is taken.
  in_source_holds: assert property (@(posedge clk_i) disable iff (!rst_ni)
      in_valid_i && !in_ready_o |=> in_valid_i &&
      $stable({in_pose_i, in_cx_i, in_cy_i, in_px_i, in_py_i, in_angle_i, in_range_i}))
    else $error("mapping_engine: the command stream changed an offered beat before it was taken");
  // The read result stays until it is taken.
  read_result_holds: assert property (@(posedge clk_i) disable iff (!rst_ni)
      rd_valid_o && !rd_ready_i |=> rd_valid_o && $stable(rd_data_o))
    else $error("mapping_engine: the read result changed before it was taken");
  // The walk's successive cells differ (the write stage never writes the cell being read).
  write_not_read: assert property (@(posedge clk_i) disable iff (!rst_ni)
      wr_valid_q && walking_q |-> wr_addr_q != cell_addr || !in_tile)
    else $error("mapping_engine: a cell read while its previous value is being written");
  // The host loaded a table that holds every bin a used reading can need.
  bin_in_table: assert property (@(posedge clk_i) disable iff (!rst_ni)
      slot_full_q && countdown_q == 5'd1 |-> 32'(bin) < BINS)
    else $error("mapping_engine: a range bin past the ISM table");
`endif
endmodule
