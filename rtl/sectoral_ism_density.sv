// The class densities of one ring, log2 p(z | d_r, c) = -((e^2 * quad_coef) >> QUAD_SHIFT)
// - log_norm, e = z - r * 2^READING_FRAC, for the rings inside the window. One digit-serial
// multiplier; e^2 follows from ring to ring by additions only,
//   (e - U)^2 = e^2 - 2 U e + U^2,  U = 2^READING_FRAC,
// after one multiplication e * e at the start of a reading.
//
// Schedule (cycles relative to the setup FSM):
//   init_i in cycle I: e_i loaded, e^2 ready for a slot that starts in cycle I + ND + 2;
//   slot_i in a slot's cycle 0: dens_o switches to the densities computed in the slot
//   before (after this cycle); if run_i, the C densities of the next ring are computed,
//   product c starting in slot cycle 2 + c * ND, its density stored by cycle C * ND + 5;
//   advance_i in a computing slot's last cycle steps e, e^2 and the ROM index to the next
//   ring.
module sectoral_ism_density #(
  parameter int unsigned RINGS          = 40,
  parameter int unsigned CLASSES        = 6,
  parameter int unsigned READING_FRAC   = 8,
  parameter int unsigned QUAD_SHIFT     = 24,
  parameter int unsigned LOG_W          = 20,
  parameter int unsigned E_W            = 12,
  parameter int unsigned SQ_W           = 24,
  parameter int unsigned COEF_W         = 19,
  parameter int unsigned MUL_B_W        = 19,
  parameter int unsigned MUL_DIGIT_W    = 3,
  parameter int unsigned NORM_W         = 12,
  parameter              QUAD_COEF_FILE = "",
  parameter              LOG_NORM_FILE  = "",
  localparam int unsigned COEF_AW = (RINGS * CLASSES > 1) ? $clog2(RINGS * CLASSES) : 1,
  localparam int unsigned CLS_W   = (CLASSES > 1) ? $clog2(CLASSES) : 1
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    init_i,
  input  logic signed [E_W:0]     e_i,      // z - r_lo * U, |e| < window
  input  logic [COEF_AW-1:0]      base_i,   // (r_lo - 1) * CLASSES
  input  logic                    slot_i,
  input  logic                    run_i,
  input  logic                    advance_i,
  input  logic [CLS_W-1:0]        cls_i,
  output logic [LOG_W-1:0]        dens_o
);
  // e and e^2 are sign-extended into wider words, the coefficient into the multiplier's.
  if (SQ_W < E_W + 2 || MUL_B_W < COEF_W || MUL_B_W < E_W) begin : gen_check_words
    $error("sectoral_ism_density: SQ_W must exceed E_W + 1, MUL_B_W hold COEF_W and E_W");
  end
  if (LOG_W <= NORM_W || QUAD_SHIFT >= SQ_W + MUL_B_W) begin : gen_check_density_w
    $error("sectoral_ism_density: LOG_W must exceed NORM_W, QUAD_SHIFT be below the product");
  end

  localparam int unsigned ND    = (MUL_B_W + MUL_DIGIT_W - 1) / MUL_DIGIT_W;
  localparam int unsigned T_W   = (ND > 1) ? $clog2(ND) : 1;
  localparam int unsigned P_W   = SQ_W + MUL_B_W;
  localparam int unsigned TAG_W = 1 + CLS_W + NORM_W;  // {is e^2, class, log_norm}

  logic signed [E_W:0]   e_q;
  logic [E_W-1:0]        neg_e;  // -e modulo 2^E_W: |e| itself when e < 0
  assign neg_e = E_W'(0) - e_i[E_W-1:0];
  logic [E_W-1:0]        abs_e_q;
  logic                  init_q;
  logic [SQ_W-1:0]       sq_q;
  logic [COEF_AW-1:0]    base_q;
  logic                  active_q;
  logic [CLS_W-1:0]      c_q, issue_c_q;
  logic [T_W-1:0]        t_q;
  logic                  issue_q;
  logic [LOG_W-1:0]      dens_next_q [0:CLASSES-1];
  logic [LOG_W-1:0]      dens_cur_q  [0:CLASSES-1];

  logic                  rom_en;
  logic [COEF_AW-1:0]    rom_addr;
  logic [COEF_W-1:0]     coef;
  logic [NORM_W-1:0]     norm;
  assign rom_en   = active_q && (t_q == '0);  // fetch class c_q's coefficient and normalization
  assign rom_addr = base_q + COEF_AW'(c_q);

  sectoral_ism_rom #(.WIDTH(COEF_W), .DEPTH(RINGS * CLASSES), .FILE(QUAD_COEF_FILE)) i_coef_rom (
    .clk_i, .en_i(rom_en), .addr_i(rom_addr), .data_o(coef)
  );
  sectoral_ism_rom #(.WIDTH(NORM_W), .DEPTH(RINGS * CLASSES), .FILE(LOG_NORM_FILE)) i_norm_rom (
    .clk_i, .en_i(rom_en), .addr_i(rom_addr), .data_o(norm)
  );

  logic                  mul_start, mul_done;
  logic [SQ_W-1:0]       mul_a;
  logic [MUL_B_W-1:0]    mul_b;
  logic [TAG_W-1:0]      mul_tag, done_tag;
  logic [P_W-1:0]        product;
  assign mul_start = init_q || issue_q;  // e * e after init, or one class density
  assign mul_a     = init_q ? SQ_W'(abs_e_q) : sq_q;
  assign mul_b     = init_q ? MUL_B_W'(abs_e_q) : MUL_B_W'(coef);
  assign mul_tag   = {init_q, issue_c_q, norm};

  sectoral_ism_mul #(.A_W(SQ_W), .B_W(MUL_B_W), .K(MUL_DIGIT_W), .TAG_W(TAG_W)) i_mul (
    .clk_i, .rst_ni,
    .start_i (mul_start),
    .a_i     (mul_a),
    .b_i     (mul_b),
    .tag_i   (mul_tag),
    .done_o  (mul_done),
    .p_o     (product),
    .tag_o   (done_tag)
  );

  // The finished density: -(quad) - log_norm, both inside +-2^(LOG_W-1) by construction.
  logic                     done_is_sq;
  logic [CLS_W-1:0]         done_cls;
  logic signed [NORM_W-1:0] done_norm;
  logic [LOG_W-1:0]         quad, dens_new;
  assign {done_is_sq, done_cls, done_norm} = done_tag;
  assign quad      = LOG_W'(product >> QUAD_SHIFT);
  logic [LOG_W-1:0] norm_ext;
  assign norm_ext  = {{(LOG_W - NORM_W){done_norm[NORM_W-1]}}, done_norm};
  assign dens_new  = LOG_W'(0) - quad - norm_ext;

  // e^2 of the next ring, modulo 2^SQ_W (exact: the true value fits).
  localparam logic [SQ_W-1:0] U2 = SQ_W'(1) << (2 * READING_FRAC);
  logic [SQ_W-1:0] sq_next, e_ext;
  assign e_ext   = {{(SQ_W - E_W - 1){e_q[E_W]}}, e_q};
  assign sq_next = sq_q - (e_ext << (READING_FRAC + 1)) + U2;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      init_q   <= 1'b0;
      active_q <= 1'b0;
      issue_q  <= 1'b0;
    end else begin
      init_q  <= init_i;
      issue_q <= rom_en;
      if (slot_i && run_i) begin
        active_q <= 1'b1;
      end else if (active_q && t_q == T_W'(ND - 1) && c_q == CLS_W'(CLASSES - 1)) begin
        active_q <= 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (init_i) begin
      e_q     <= e_i;
      abs_e_q <= e_i[E_W] ? neg_e : e_i[E_W-1:0];
      base_q  <= base_i;
    end else if (advance_i) begin
      e_q    <= e_q - (E_W+1)'(1 << READING_FRAC);
      base_q <= base_q + COEF_AW'(CLASSES);
    end
    if (advance_i) begin
      sq_q <= sq_next;
    end else if (mul_done && done_is_sq) begin
      sq_q <= SQ_W'(product);
    end
    if (slot_i && run_i) begin
      c_q <= '0;
      t_q <= '0;
    end else if (active_q) begin
      if (t_q == T_W'(ND - 1)) begin
        t_q <= '0;
        c_q <= c_q + CLS_W'(1);
      end else begin
        t_q <= t_q + T_W'(1);
      end
    end
    issue_c_q <= c_q;
    if (mul_done && !done_is_sq) begin
      dens_next_q[done_cls] <= dens_new;
    end
  end

  for (genvar c = 0; c < CLASSES; c++) begin : gen_dens_cur
    always_ff @(posedge clk_i) begin
      if (slot_i) begin
        dens_cur_q[c] <= dens_next_q[c];
      end
    end
  end

  assign dens_o = dens_cur_q[cls_i];
endmodule
