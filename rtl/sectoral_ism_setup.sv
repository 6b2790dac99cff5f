// The per-reading set-up of the sectoral ISM: golden's sectoral_ism_rings (docs/algorithms.md 3)
// with the integer arithmetic of golden/kernel/src/ism_kernel.cpp, on one log-add unit, for the
// rings inside the window (|z - d_r| < WINDOW cells; every other ring's terms are log 0 and its
// indices are constants the streamer supplies), writing the index of every (ring, sector)
// of the window into the index RAM.
//
// Phases (n = rings in the window, L_A = CONDITIONS * CLASSES, ND multiplier digits):
//   init     3 + ND cycles: window [r_lo, r_hi], e = z - r_lo, e^2
//   rings    (n + 1) * L_A + 4: slot k computes ring r_lo + k's densities (density unit)
//            while the sum pipeline runs ring r_lo + k - 1: step c * V + v adds
//            density[c] * weight[v][c] to accumulator v (the classes in ascending order,
//            the V accumulators interleaved so each sees one addition every V cycles),
//            then times the ring prior: T_r (v = 0) and the 2 Ns conditioned sums
//   suffix   2 n + 2: after[r] = after[r + 1] + T[r + 1], r_hi - 1 down to r_lo - 1
//   prefix   1 + n * (3 Ns + 1) + 4: per ring, before' = before + T_r, e_j = before +
//            emptied_j, num_j = before + occupied_j, den_j = e_j + 2 after[r]; the index
//            unit turns (num_j, den_j) into the index
//   done     1
// Set-up cycles per reading: 2 with no ring in the window (z >= reach), else
//   ND + 15 + (n + 1) * L_A + 2 n + n * (3 Ns + 1).
module sectoral_ism_setup #(
  parameter int unsigned READING_W        = 16,
  parameter int unsigned RINGS            = 40,
  parameter int unsigned BINS             = 16,
  parameter int unsigned SECTORS          = 4,
  parameter int unsigned CLASSES          = 6,
  parameter int unsigned CONDITIONS       = 9,
  parameter int unsigned WINDOW           = 13,
  parameter int unsigned MAX_INDEX        = 127,
  parameter int unsigned IDX_W            = 8,
  parameter int unsigned READING_FRAC     = 8,
  parameter int unsigned LOG_FRAC         = 8,
  parameter int unsigned QUAD_SHIFT       = 24,
  parameter int unsigned LOG_W            = 20,
  parameter int unsigned E_W              = 12,
  parameter int unsigned SQ_W             = 24,
  parameter int unsigned COEF_W           = 19,
  parameter int unsigned MUL_B_W          = 19,
  parameter int unsigned MUL_DIGIT_W      = 3,
  parameter int unsigned NORM_W           = 12,
  parameter int unsigned WEIGHT_W         = 13,
  parameter int unsigned PHI_N            = 2440,
  parameter int unsigned PHI_W            = 8,
  parameter int unsigned PHI_AW           = 12,
  parameter int unsigned THR_W            = 14,
  parameter int unsigned BUCKET_SHIFT     = 6,
  parameter int unsigned BUCKET_N         = 148,
  parameter int unsigned BUCKET_W         = 7,
  parameter              QUAD_COEF_FILE   = "",
  parameter              LOG_NORM_FILE    = "",
  parameter              LOG_WEIGHT_FILE  = "",
  parameter              LOG_ADD_FILE     = "",
  parameter              THRESHOLDS_FILE  = "",
  parameter              BUCKET_FILE      = "",
  // derived (sectoral_ism_pkg)
  localparam int unsigned RING_W = sectoral_ism_pkg::ring_bits(RINGS),    // ring numbers 0..R+1
  localparam int unsigned RIDX_W = sectoral_ism_pkg::addr_bits(RINGS),    // ring indices 0..R-1
  localparam int unsigned J_W    = sectoral_ism_pkg::addr_bits(SECTORS),
  localparam int unsigned IDX_AW = RIDX_W + J_W                           // {ring index, sector}
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 start_i,  // a reading is accepted (only while idle_o)
  input  logic [READING_W-1:0] z_i,
  output logic                 idle_o,
  output logic                 done_o,   // the last set-up cycle: every index is written
  output logic [RING_W-1:0]    r_lo_o,   // the window's rings, 1-based; r_lo = R + 1 if empty
  output logic [RING_W-1:0]    r_hi_o,
  output logic [IDX_W-1:0]     below_o,  // the index of every cell before the window
  output logic                 idx_we_o,
  output logic [IDX_AW-1:0]    idx_waddr_o,
  output logic [IDX_W-1:0]     idx_wdata_o
);
  // The schedule and the words hold only for a consistent configuration.
  if (SECTORS < 1 || CONDITIONS != sectoral_ism_pkg::conditions(SECTORS)) begin : gen_check_conditions
    $error("sectoral_ism_setup: CONDITIONS must be 2 SECTORS + 1, SECTORS at least 1");
  end
  if (CLASSES < 1 || WINDOW < 1 || RINGS < 1) begin : gen_check_sizes
    $error("sectoral_ism_setup: CLASSES, WINDOW and RINGS must be at least 1");
  end
  if (MUL_DIGIT_W < 1 || MUL_DIGIT_W > MUL_B_W
      || CLASSES * sectoral_ism_pkg::digits(MUL_B_W, MUL_DIGIT_W) + 4 > CONDITIONS * CLASSES)
  begin : gen_check_schedule
    // A ring's densities must be ready by the end of the slot that sums the ring before.
    $error("sectoral_ism_setup: CLASSES * ceil(MUL_B_W / MUL_DIGIT_W) + 4 exceeds a ring slot");
  end
  if (E_W < sectoral_ism_pkg::error_bits(WINDOW, READING_FRAC)
      || SQ_W < sectoral_ism_pkg::square_bits(WINDOW, READING_FRAC)) begin : gen_check_error_w
    $error("sectoral_ism_setup: E_W or SQ_W too narrow for WINDOW << READING_FRAC");
  end
  if (MAX_INDEX < 1 || MAX_INDEX > sectoral_ism_pkg::max_index_of(IDX_W)) begin : gen_check_max_index
    $error("sectoral_ism_setup: MAX_INDEX must be 1 .. 2^(IDX_W-1) - 1");
  end
  if (LOG_W <= WEIGHT_W || LOG_W <= LOG_FRAC + 1) begin : gen_check_log_w
    $error("sectoral_ism_setup: LOG_W must exceed WEIGHT_W and LOG_FRAC + 1");
  end

  localparam int unsigned V      = CONDITIONS;
  localparam int unsigned C      = CLASSES;
  localparam int unsigned L_A    = V * C;              // cycles of a ring slot
  localparam int unsigned L_C    = 3 * SECTORS + 1;    // cycles of a prefix ring
  localparam int unsigned ND     = (MUL_B_W + MUL_DIGIT_W - 1) / MUL_DIGIT_W;
  localparam int unsigned SR_D   = V - 2;              // accumulator loop: V - 2 + 2 stages
  localparam int unsigned CJ_W   = $clog2(2 * SECTORS);  // conditioned sums per ring
  localparam int unsigned V_W    = $clog2(V);
  localparam int unsigned CLS_W  = (C > 1) ? $clog2(C) : 1;
  localparam int unsigned SEL_W  = (V_W > J_W) ? V_W : J_W;
  localparam int unsigned WAW    = $clog2(L_A);
  localparam int unsigned COEF_AW = $clog2(RINGS * C);
  localparam int unsigned CYC_MAX = (L_A > 2 * RINGS + 2) ? L_A : 2 * RINGS + 2;
  localparam int unsigned CYC_W  = $clog2(CYC_MAX + ND + 2);
  localparam int unsigned LV     = LOG_W + 1;          // {zero, value}
  localparam logic [LV-1:0] LOG_ZERO = {1'b1, {LOG_W{1'b0}}};
  localparam logic [LOG_W-1:0] LOG_ONE = LOG_W'(1) << LOG_FRAC;  // log2(2)

  // What a log-add result is for.
  localparam logic [2:0] TagNone = 3'd0, TagSum = 3'd1, TagSumLast = 3'd2, TagAfter = 3'd3,
                         TagTotal = 3'd4, TagBefore = 3'd5, TagDen = 3'd6;
  localparam int unsigned TAG_W = 3 + SEL_W + RIDX_W;

  typedef enum logic [3:0] {
    SIdle, SInit, SError, SSquare, SRings, SRingsDrain, SSuffix, SPrefixFetch, SPrefix,
    SPrefixDrain, SDone
  } state_e;

  state_e                   state_q, state_d;
  logic [CYC_W-1:0]         cyc_q, cyc_d;   // cycle within the state or slot
  logic [RING_W-1:0]        k_q, k_d;       // slot / ring counter
  logic [READING_W-1:0]     z_q;
  logic [RING_W-1:0]        r_lo_q, r_hi_q, n_win_q;
  logic [CLS_W-1:0]         sp_c_q;         // the sum pipeline's fetch step: class, condition
  logic [V_W-1:0]           sp_v_q;
  logic [LV-1:0]            before_cur_q, before_nxt_q, beyond_q, total_q;

  // ---------------------------------------------------------------- window
  // Width of the window arithmetic: cells of a reading, plus the window and the rings, signed.
  localparam int unsigned CW = READING_W - READING_FRAC + $clog2(RINGS + WINDOW + 2) + 2;
  logic signed [CW-1:0] zi, lo_raw, hi_raw, lo_clamped, hi_clamped;
  logic                 zf_zero, win_empty;
  localparam logic signed [CW-1:0] One = CW'(1);
  logic [READING_W-1:0] z_cells;
  assign z_cells    = z_q >> READING_FRAC;
  assign zi         = $signed(CW'(z_cells));
  assign zf_zero    = (z_q & READING_W'((1 << READING_FRAC) - 1)) == '0;
  assign lo_raw     = zi - $signed(CW'(WINDOW - 1));
  assign hi_raw     = zi + $signed(CW'(WINDOW)) - (zf_zero ? One : $signed(CW'(0)));
  assign lo_clamped = (lo_raw < One) ? One
                    : (lo_raw > $signed(CW'(RINGS + 1))) ? $signed(CW'(RINGS + 1)) : lo_raw;
  assign hi_clamped = (hi_raw > $signed(CW'(RINGS))) ? $signed(CW'(RINGS)) : hi_raw;
  assign win_empty  = lo_clamped > hi_clamped;

  // ---------------------------------------------------------------- density unit
  logic signed [E_W:0]  e_first;
  logic [COEF_AW-1:0]   coef_base;
  logic                 dens_slot, dens_run, dens_advance;
  logic [LOG_W-1:0]     dens;
  logic [CLS_W-1:0]     m_c_q;
  // z - r_lo * U modulo 2^(E_W+1): exact, |z - r_lo * U| < WINDOW * U.
  assign e_first   = (E_W+1)'(z_q) - (E_W+1)'(CW'(r_lo_q) << READING_FRAC);
  assign coef_base = COEF_AW'((CW'(r_lo_q) - CW'(1)) * CW'(C));
  assign dens_slot    = (state_q == SRings) && (cyc_q == '0);              // a slot begins
  assign dens_run     = k_q != n_win_q;                                     // a next ring exists
  assign dens_advance = (state_q == SRings) && (cyc_q == CYC_W'(L_A - 1)) && dens_run;

  sectoral_ism_density #(
    .RINGS(RINGS), .CLASSES(C), .READING_FRAC(READING_FRAC), .QUAD_SHIFT(QUAD_SHIFT),
    .LOG_W(LOG_W), .E_W(E_W), .SQ_W(SQ_W), .COEF_W(COEF_W), .MUL_B_W(MUL_B_W),
    .MUL_DIGIT_W(MUL_DIGIT_W), .NORM_W(NORM_W), .QUAD_COEF_FILE(QUAD_COEF_FILE),
    .LOG_NORM_FILE(LOG_NORM_FILE)
  ) i_density (
    .clk_i, .rst_ni,
    .init_i    (state_q == SError),
    .e_i       (e_first),
    .base_i    (coef_base),
    .slot_i    (dens_slot),
    .run_i     (dens_run),
    .advance_i (dens_advance),
    .cls_i     (m_c_q),
    .dens_o    (dens)
  );

  // ---------------------------------------------------------------- log-add unit
  logic              la_valid, res_valid;
  logic [LV-1:0]     la_a, la_b, res;
  logic [TAG_W-1:0]  la_tag, res_tag;
  logic [2:0]        la_kind;
  logic [SEL_W-1:0]  la_sel;
  logic [RIDX_W-1:0] la_ring;
  assign la_tag = {la_kind, la_sel, la_ring};
  logic [2:0]        res_kind;
  logic [SEL_W-1:0]  res_sel;
  logic [RIDX_W-1:0] res_ring;
  assign {res_kind, res_sel, res_ring} = res_tag;

  sectoral_ism_log_add #(
    .LOG_W(LOG_W), .PHI_N(PHI_N), .PHI_W(PHI_W), .PHI_AW(PHI_AW), .FILE(LOG_ADD_FILE),
    .TAG_W(TAG_W)
  ) i_log_add (
    .clk_i, .rst_ni,
    .valid_i (la_valid),
    .a_i     (la_a),
    .b_i     (la_b),
    .tag_i   (la_tag),
    .valid_o (res_valid),
    .res_o   (res),
    .tag_o   (res_tag)
  );

  // The result history: sr_q[SR_D - 1 - i] is the result of i + 1 cycles ago. In the ring
  // phase sr_q[0] is the accumulator of the condition now entering the log-add unit; in the
  // prefix phase it holds e_j and num_j until den_j needs them.
  logic [LV-1:0] sr_q [0:SR_D-1];
  for (genvar i = 0; i + 1 < SR_D; i++) begin : gen_history
    always_ff @(posedge clk_i) begin
      sr_q[i] <= sr_q[i+1];
    end
  end
  always_ff @(posedge clk_i) begin
    sr_q[SR_D-1] <= res;
  end
  logic [LV-1:0] e_hist, num_hist;
  if (SECTORS > 1) begin : gen_e_tap
    assign e_hist = sr_q[1];   // e_j: 2 Ns - 2 cycles old
  end else begin : gen_e_now
    assign e_hist = res;
  end
  assign num_hist = sr_q[SECTORS-1];  // num_j: Ns cycles old

  // ---------------------------------------------------------------- memories
  logic              t_we, t_re, cond_we, cond_re, after_we, after_re;
  logic [RIDX_W-1:0] t_waddr, t_raddr, after_waddr, after_raddr;
  logic [RIDX_W+CJ_W-1:0] cond_waddr, cond_raddr;
  logic [LV-1:0]     t_wdata, cond_wdata, after_wdata, t_rdata, cond_rdata, after_rdata;

  sdp_ram #(.WIDTH(LV), .DEPTH(RINGS)) i_t_ram (
    .clk_i, .we_i(t_we), .waddr_i(t_waddr), .wdata_i(t_wdata),
    .re_i(t_re), .raddr_i(t_raddr), .rdata_o(t_rdata)
  );
  sdp_ram #(.WIDTH(LV), .DEPTH(RINGS << CJ_W)) i_cond_ram (
    .clk_i, .we_i(cond_we), .waddr_i(cond_waddr), .wdata_i(cond_wdata),
    .re_i(cond_re), .raddr_i(cond_raddr), .rdata_o(cond_rdata)
  );
  sdp_ram #(.WIDTH(LV), .DEPTH(RINGS)) i_after_ram (
    .clk_i, .we_i(after_we), .waddr_i(after_waddr), .wdata_i(after_wdata),
    .re_i(after_re), .raddr_i(after_raddr), .rdata_o(after_rdata)
  );

  // ---------------------------------------------------------------- ring phase: sum pipeline
  // F: fetch weight[v][c] (class-major ROM, address = slot cycle); M: density * weight;
  // A: into the log-add unit with accumulator v (log 0 for the first class); 2 cycles later
  // the sum returns to the history, or for the last class is stored times the ring prior.
  logic [WEIGHT_W:0] weight;
  sectoral_ism_rom #(.WIDTH(WEIGHT_W + 1), .DEPTH(L_A), .FILE(LOG_WEIGHT_FILE)) i_weight_rom (
    .clk_i, .en_i(1'b1), .addr_i(WAW'(cyc_q)), .data_o(weight)
  );

  logic              f_valid;
  logic [RIDX_W-1:0] f_ring;
  assign f_valid = (state_q == SRings) && (k_q != '0);  // slot k sums ring r_lo + k - 1
  assign f_ring  = RIDX_W'(CW'(r_lo_q) + CW'(k_q) - CW'(2));

  logic              m_valid_q, m_first_q, m_last_q, a_valid_q, a_first_q, a_last_q;
  logic [V_W-1:0]    m_v_q, a_v_q;
  logic [RIDX_W-1:0] m_ring_q, a_ring_q;
  logic [LV-1:0]     a_b_q;
  logic [LOG_W-1:0]  dens_times_weight;
  logic signed [WEIGHT_W-1:0] weight_val;
  logic [LOG_W-1:0]           weight_ext;
  assign weight_val        = weight[WEIGHT_W-1:0];
  assign weight_ext        = {{(LOG_W - WEIGHT_W){weight_val[WEIGHT_W-1]}}, weight_val};
  assign dens_times_weight = dens + weight_ext;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      m_valid_q <= 1'b0;
      a_valid_q <= 1'b0;
    end else begin
      m_valid_q <= f_valid;
      a_valid_q <= m_valid_q;
    end
  end
  always_ff @(posedge clk_i) begin
    m_c_q     <= sp_c_q;
    m_v_q     <= sp_v_q;
    m_first_q <= sp_c_q == '0;
    m_last_q  <= sp_c_q == CLS_W'(C - 1);
    m_ring_q  <= f_ring;
    a_v_q     <= m_v_q;
    a_first_q <= m_first_q;
    a_last_q  <= m_last_q;
    a_ring_q  <= m_ring_q;
    a_b_q     <= weight[WEIGHT_W] ? LOG_ZERO : {1'b0, dens_times_weight};  // log 0 weight: log 0
  end

  // Store: T_r or a conditioned sum, times the prior 2^-M_r, M_r = (r - 1) * BINS.
  logic             st_we_q, st_is_t_q;
  logic [RIDX_W-1:0] st_ring_q;
  logic [CJ_W-1:0]  st_cj_q;
  logic [LV-1:0]    st_data_q;
  logic [LOG_W-1:0] prior, res_ring_ext, res_prior;
  logic [CJ_W-1:0]  res_cj;
  assign res_ring_ext = LOG_W'(res_ring);
  assign prior        = LOG_W'(0) - ((res_ring_ext * LOG_W'(BINS)) << LOG_FRAC);
  assign res_prior    = res[LOG_W-1:0] + prior;
  assign res_cj       = CJ_W'(res_sel - SEL_W'(1));
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      st_we_q <= 1'b0;
    end else begin
      st_we_q <= res_valid && (res_kind == TagSumLast);
    end
  end
  always_ff @(posedge clk_i) begin
    st_is_t_q <= res_sel == '0;
    st_ring_q <= res_ring;
    st_cj_q   <= res_cj;
    st_data_q <= res[LOG_W] ? LOG_ZERO : {1'b0, res_prior};
  end
  assign t_we       = st_we_q && st_is_t_q;
  assign t_waddr    = st_ring_q;
  assign t_wdata    = st_data_q;
  assign cond_we    = st_we_q && !st_is_t_q;
  assign cond_waddr = {st_ring_q, st_cj_q};
  assign cond_wdata = st_data_q;

  // ---------------------------------------------------------------- suffix and prefix
  logic [CYC_W-1:0]  m_step;         // suffix step
  logic              b_issue, b_fetch;
  logic [RIDX_W-1:0] p_ring;         // prefix ring index
  logic [CJ_W-1:0]   p_cj;
  assign m_step  = cyc_q >> 1;
  assign b_fetch = (state_q == SSuffix) && !cyc_q[0] && (m_step < CYC_W'(n_win_q));
  assign b_issue = (state_q == SSuffix) && cyc_q[0] && (m_step < CYC_W'(n_win_q));
  assign p_ring  = RIDX_W'(CW'(r_lo_q) - CW'(1) + CW'(k_q));
  assign p_cj    = (cyc_q < CYC_W'(SECTORS)) ? CJ_W'(cyc_q + CYC_W'(SECTORS))
                                             : CJ_W'(cyc_q - CYC_W'(SECTORS));

  logic p_last_cycle, p_last_ring;
  assign p_last_cycle = cyc_q == CYC_W'(L_C - 1);
  assign p_last_ring  = k_q == n_win_q - RING_W'(1);

  // Reads: T in the suffix (T[r_hi - m]) and for each prefix ring; after for each prefix
  // ring; conditioned sums in the prefix ring's first 2 Ns cycles.
  always_comb begin
    t_re        = 1'b0;
    t_raddr     = p_ring + RIDX_W'(1);
    after_re    = 1'b0;
    after_raddr = p_ring + RIDX_W'(1);
    if (b_fetch) begin
      t_re    = 1'b1;
      t_raddr = RIDX_W'(CW'(r_hi_q) - CW'(1) - CW'(m_step));
    end else if (state_q == SPrefixFetch) begin
      t_re        = 1'b1;
      t_raddr     = RIDX_W'(CW'(r_lo_q) - CW'(1));
      after_re    = 1'b1;
      after_raddr = RIDX_W'(CW'(r_lo_q) - CW'(1));
    end else if (state_q == SPrefix && p_last_cycle && !p_last_ring) begin
      t_re     = 1'b1;
      after_re = 1'b1;
    end
  end
  assign cond_re    = (state_q == SPrefix) && (cyc_q < CYC_W'(2 * SECTORS));
  assign cond_raddr = {p_ring, p_cj};

  // after: log 0 past the window's last ring, then the suffix sums as they return.
  always_comb begin
    after_we    = 1'b0;
    after_waddr = res_ring;
    after_wdata = res;
    if (state_q == SSuffix && cyc_q == '0) begin
      after_we    = 1'b1;
      after_waddr = RIDX_W'(CW'(r_hi_q) - CW'(1));
      after_wdata = LOG_ZERO;
    end else if (res_valid && res_kind == TagAfter) begin
      after_we = 1'b1;
    end
  end

  // The log-add unit's operands, by phase.
  logic [SEL_W-1:0] u_den;  // den_j's sector j in the prefix ring's cycles 2 Ns + 1 + j
  assign u_den = SEL_W'(cyc_q - CYC_W'(2 * SECTORS + 1));
  always_comb begin
    la_valid = 1'b0;
    la_a     = before_cur_q;
    la_b     = cond_rdata;
    la_kind  = TagNone;
    la_sel   = '0;
    la_ring  = p_ring;
    unique case (state_q)
      SRings, SRingsDrain: begin
        la_valid = a_valid_q;
        la_a     = a_first_q ? LOG_ZERO : sr_q[0];
        la_b     = a_b_q;
        la_kind  = a_last_q ? TagSumLast : TagSum;
        la_sel   = SEL_W'(a_v_q);
        la_ring  = a_ring_q;
      end
      SSuffix: begin
        la_valid = b_issue;
        la_a     = (m_step == '0) ? LOG_ZERO : res;
        la_b     = t_rdata;
        la_kind  = (m_step == CYC_W'(n_win_q) - CYC_W'(1)) ? TagTotal : TagAfter;
        la_ring  = RIDX_W'(CW'(r_hi_q) - CW'(2) - CW'(m_step));
      end
      SPrefix: begin
        la_valid = 1'b1;
        if (cyc_q == '0) begin
          la_b   = t_rdata;
          la_kind = TagBefore;
        end else if (cyc_q > CYC_W'(2 * SECTORS)) begin
          la_a   = e_hist;
          la_b   = beyond_q;
          la_kind = TagDen;
          la_sel  = u_den;
        end
      end
      default: ;
    endcase
  end

  // ---------------------------------------------------------------- index unit
  logic              idx_valid;
  logic [J_W-1:0]    res_j;
  logic [IDX_AW-1:0] idx_addr;
  assign idx_valid = res_valid && (res_kind == TagDen);
  assign res_j     = J_W'(res_sel);
  assign idx_addr  = {res_ring, res_j};
  sectoral_ism_index #(
    .LOG_W(LOG_W), .MAX_INDEX(MAX_INDEX), .IDX_W(IDX_W), .THR_W(THR_W),
    .BUCKET_SHIFT(BUCKET_SHIFT), .BUCKET_N(BUCKET_N), .BUCKET_W(BUCKET_W),
    .THRESHOLDS_FILE(THRESHOLDS_FILE), .BUCKET_FILE(BUCKET_FILE), .ADDR_W(IDX_AW)
  ) i_index (
    .clk_i, .rst_ni,
    .valid_i (idx_valid),
    .num_i   (num_hist),
    .den_i   (res),
    .waddr_i (idx_addr),
    .we_o    (idx_we_o),
    .waddr_o (idx_waddr_o),
    .wdata_o (idx_wdata_o)
  );

  logic [LOG_W-1:0] after_twice;
  assign after_twice = after_rdata[LOG_W-1:0] + LOG_ONE;

  // ---------------------------------------------------------------- control
  always_comb begin
    state_d = state_q;
    cyc_d   = cyc_q + CYC_W'(1);
    k_d     = k_q;
    unique case (state_q)
      SIdle: begin
        cyc_d = '0;
        if (start_i) state_d = SInit;
      end
      SInit: state_d = win_empty ? SDone : SError;
      SError: begin
        state_d = SSquare;
        cyc_d   = '0;
      end
      SSquare: begin
        if (cyc_q == CYC_W'(ND)) begin
          state_d = SRings;
          cyc_d   = '0;
          k_d     = '0;
        end
      end
      SRings: begin
        if (cyc_q == CYC_W'(L_A - 1)) begin
          cyc_d = '0;
          if (k_q == n_win_q) state_d = SRingsDrain;
          else k_d = k_q + RING_W'(1);
        end
      end
      SRingsDrain: begin
        if (cyc_q == CYC_W'(3)) begin
          state_d = SSuffix;
          cyc_d   = '0;
        end
      end
      SSuffix: begin
        if (cyc_q == CYC_W'(2) * CYC_W'(n_win_q) + CYC_W'(1)) begin
          state_d = SPrefixFetch;
        end
      end
      SPrefixFetch: begin
        state_d = SPrefix;
        cyc_d   = '0;
        k_d     = '0;
      end
      SPrefix: begin
        if (p_last_cycle) begin
          cyc_d = '0;
          if (p_last_ring) state_d = SPrefixDrain;
          else k_d = k_q + RING_W'(1);
        end
      end
      SPrefixDrain: begin
        if (cyc_q == CYC_W'(3)) state_d = SDone;
      end
      SDone: state_d = SIdle;
      default: state_d = SIdle;
    endcase
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      state_q <= SIdle;
    end else begin
      state_q <= state_d;
    end
  end

  always_ff @(posedge clk_i) begin
    cyc_q <= cyc_d;
    k_q   <= k_d;
    if (state_q == SError) begin  // the window is not empty here
      n_win_q <= r_hi_q - r_lo_q + RING_W'(1);
    end
    if (state_q == SIdle && start_i) begin
      z_q <= z_i;
    end
    if (state_q == SInit) begin
      r_lo_q  <= RING_W'(lo_clamped);
      r_hi_q  <= RING_W'(hi_clamped);
      total_q <= LOG_ZERO;
    end
    // The sum pipeline's fetch counters: class-major steps c * V + v.
    if (state_q != SRings || cyc_q == CYC_W'(L_A - 1)) begin
      sp_c_q <= '0;
      sp_v_q <= '0;
    end else if (sp_v_q == V_W'(V - 1)) begin
      sp_c_q <= sp_c_q + CLS_W'(1);
      sp_v_q <= '0;
    end else begin
      sp_v_q <= sp_v_q + V_W'(1);
    end
    if (res_valid && res_kind == TagTotal) begin
      total_q <= res;
    end
    if (res_valid && res_kind == TagBefore) begin
      before_nxt_q <= res;
    end
    if (state_q == SPrefixFetch) begin
      before_cur_q <= LOG_ZERO;
    end else if (state_q == SPrefix && p_last_cycle) begin
      before_cur_q <= before_nxt_q;
    end
    if (state_q == SPrefix && cyc_q == '0) begin  // 2 * after[r]
      beyond_q <= after_rdata[LOG_W] ? LOG_ZERO : {1'b0, after_twice};
    end
  end

  assign idle_o  = state_q == SIdle;
  assign done_o  = state_q == SDone;
  assign r_lo_o  = r_lo_q;
  assign r_hi_o  = r_hi_q;
  assign below_o = total_q[LOG_W] ? '0 : IDX_W'(0) - IDX_W'(MAX_INDEX);
endmodule
