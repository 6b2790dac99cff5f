// Log-odds to S_eps index, golden's kernel_index_of_log_odds: n = the number of thresholds
// at or below |num - den|, signed like num - den; +-MAX_INDEX when one side is log 0, 0
// when both are. No divider and no search: the thresholds lie at least 2^BUCKET_SHIFT
// apart, so a bucket ROM indexed by |odds| >> BUCKET_SHIFT gives the count below the
// bucket, and one threshold comparison finishes it. Three stages; the index RAM write
// (waddr_i travels along) leaves in cycle t + 3 for operands in cycle t.
module sectoral_ism_index #(
  parameter int unsigned LOG_W            = 20,
  parameter int unsigned MAX_INDEX        = 127,
  parameter int unsigned IDX_W            = 8,
  parameter int unsigned THR_W            = 14,
  parameter int unsigned BUCKET_SHIFT     = 6,
  parameter int unsigned BUCKET_N         = 148,
  parameter int unsigned BUCKET_W         = 7,
  parameter              THRESHOLDS_FILE  = "",
  parameter              BUCKET_FILE      = "",
  parameter int unsigned ADDR_W           = 8
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              valid_i,
  input  logic [LOG_W:0]    num_i,
  input  logic [LOG_W:0]    den_i,
  input  logic [ADDR_W-1:0] waddr_i,
  output logic              we_o,
  output logic [ADDR_W-1:0] waddr_o,
  output logic [IDX_W-1:0]  wdata_o
);
  // An index must hold +-MAX_INDEX, a bucket entry any count 0..MAX_INDEX.
  if (MAX_INDEX < 1 || IDX_W < 2 || MAX_INDEX >= (1 << (IDX_W - 1))) begin : gen_check_index
    $error("sectoral_ism_index: MAX_INDEX must be 1 .. 2^(IDX_W-1) - 1");
  end
  if (MAX_INDEX >= (1 << BUCKET_W) || BUCKET_N < 1 || THR_W > LOG_W + 1) begin : gen_check_bucket
    $error("sectoral_ism_index: BUCKET_W must hold MAX_INDEX, BUCKET_N be at least 1, THR_W at most LOG_W + 1");
  end

  localparam int unsigned BAW   = (BUCKET_N > 1) ? $clog2(BUCKET_N) : 1;
  localparam int unsigned TAW   = (MAX_INDEX > 1) ? $clog2(MAX_INDEX) : 1;
  localparam int unsigned MAG_W = LOG_W + 1;
  // How the index is decided: from the thresholds, or fixed by a log 0.
  localparam logic [1:0] KindOdds = 2'd0, KindZero = 2'd1, KindMin = 2'd2, KindMax = 2'd3;

  // Stage X0: the odds and their bucket.
  logic signed [LOG_W:0] odds_nd, odds_dn;
  logic                  neg;
  logic [MAG_W-1:0]      mag, bucket_full;
  logic                  over;
  logic [1:0]            kind;
  logic [LOG_W:0] num_ext, den_ext;  // sign-extended values
  assign num_ext     = {num_i[LOG_W-1], num_i[LOG_W-1:0]};
  assign den_ext     = {den_i[LOG_W-1], den_i[LOG_W-1:0]};
  assign odds_nd     = num_ext - den_ext;
  assign odds_dn     = den_ext - num_ext;
  assign neg         = odds_nd[LOG_W];
  assign mag         = neg ? odds_dn : odds_nd;
  assign bucket_full = mag >> BUCKET_SHIFT;
  assign over        = bucket_full >= MAG_W'(BUCKET_N);  // past the last threshold: MAX_INDEX
  assign kind        = (num_i[LOG_W] && den_i[LOG_W]) ? KindZero
                     : num_i[LOG_W] ? KindMin
                     : den_i[LOG_W] ? KindMax : KindOdds;

  logic [BUCKET_W-1:0] base;
  sectoral_ism_rom #(.WIDTH(BUCKET_W), .DEPTH(BUCKET_N), .FILE(BUCKET_FILE)) i_bucket_rom (
    .clk_i, .en_i(valid_i), .addr_i(over ? '0 : BAW'(bucket_full)), .data_o(base)
  );

  logic              x1_valid_q, x1_neg_q, x1_over_q;
  logic [1:0]        x1_kind_q;
  logic [MAG_W-1:0]  x1_mag_q;
  logic [ADDR_W-1:0] x1_addr_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      x1_valid_q <= 1'b0;
    end else begin
      x1_valid_q <= valid_i;
    end
  end
  always_ff @(posedge clk_i) begin
    x1_neg_q  <= neg;
    x1_over_q <= over;
    x1_kind_q <= kind;
    x1_mag_q  <= mag;
    x1_addr_q <= waddr_i;
  end

  // Stage X1: the next threshold after the bucket's count.
  logic             has_next;
  logic [THR_W-1:0] thr;
  assign has_next = base < BUCKET_W'(MAX_INDEX);  // some threshold lies above the count
  sectoral_ism_rom #(.WIDTH(THR_W), .DEPTH(MAX_INDEX), .FILE(THRESHOLDS_FILE)) i_thr_rom (
    .clk_i, .en_i(x1_valid_q), .addr_i(has_next ? TAW'(base) : '0), .data_o(thr)
  );

  logic                x2_valid_q, x2_neg_q, x2_over_q, x2_has_next_q;
  logic [1:0]          x2_kind_q;
  logic [MAG_W-1:0]    x2_mag_q;
  logic [BUCKET_W-1:0] x2_base_q;
  logic [ADDR_W-1:0]   x2_addr_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      x2_valid_q <= 1'b0;
    end else begin
      x2_valid_q <= x1_valid_q;
    end
  end
  always_ff @(posedge clk_i) begin
    x2_neg_q      <= x1_neg_q;
    x2_over_q     <= x1_over_q;
    x2_has_next_q <= has_next;
    x2_kind_q     <= x1_kind_q;
    x2_mag_q      <= x1_mag_q;
    x2_base_q     <= base;
    x2_addr_q     <= x1_addr_q;
  end

  // Stage X2: the count, its sign, the write.
  logic [IDX_W-1:0] n, index;
  assign n = x2_over_q ? IDX_W'(MAX_INDEX)
           : IDX_W'(x2_base_q) + IDX_W'(x2_has_next_q && (MAG_W'(thr) <= x2_mag_q));
  always_comb begin
    unique case (x2_kind_q)
      KindZero: index = '0;
      KindMin:  index = IDX_W'(0) - IDX_W'(MAX_INDEX);
      KindMax:  index = IDX_W'(MAX_INDEX);
      default:  index = x2_neg_q ? IDX_W'(0) - n : n;
    endcase
  end

  logic              we_q;
  logic [ADDR_W-1:0] waddr_q;
  logic [IDX_W-1:0]  wdata_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      we_q <= 1'b0;
    end else begin
      we_q <= x2_valid_q;
    end
  end
  always_ff @(posedge clk_i) begin
    waddr_q <= x2_addr_q;
    wdata_q <= index;
  end

  assign we_o    = we_q;
  assign waddr_o = waddr_q;
  assign wdata_o = wdata_q;
endmodule
