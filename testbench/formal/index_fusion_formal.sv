// Formal equivalence miter of rtl/index_fusion.sv against a reference written another way: a
// join of the two inputs, lane sums by saturating_add_model, and a two-deep FIFO held as a
// circular buffer with a count. Inputs are unconstrained (any valids, data, last and ready in
// every cycle, resets anywhere after the first cycle); every port must equal the reference's in
// every cycle: a_ready_o, b_ready_o (out of reset), y_valid_o, and y_data_o, y_last_o while
// y_valid_o.
// The proof is unbounded (k-induction): the output buffer's entries (exposed by Yosys' `expose`,
// see testbench/formal.cmake) are tied to the reference FIFO's.
module index_fusion_formal #(
  parameter int unsigned B     = 8,  // formal.cmake sets these and the RTL's to the same values
  parameter int unsigned LANES = 8
) (
  input logic               clk_i,
  input logic               rst_ni,
  input logic               a_valid_i,
  input logic [LANES*B-1:0] a_data_i,
  input logic               a_last_i,
  input logic               b_valid_i,
  input logic [LANES*B-1:0] b_data_i,
  input logic               b_last_i,
  input logic               y_ready_i
);
  logic               a_ready, b_ready, y_valid, y_last;
  logic [LANES*B-1:0] y_data;
  logic               a_full, b_full;
  logic [LANES*B:0]   a_entry, b_entry;

  // The parameters are set by chparam in formal.cmake, to the values above.
  index_fusion i_dut (
    .clk_i, .rst_ni,
    .a_valid_i, .a_ready_o(a_ready), .a_data_i, .a_last_i,
    .b_valid_i, .b_ready_o(b_ready), .b_data_i, .b_last_i,
    .y_valid_o(y_valid), .y_ready_i, .y_data_o(y_data), .y_last_o(y_last),
    // the output buffer's entries, exposed for the induction only (see formal.cmake)
    .\i_spill_register.a_full_q (a_full), .\i_spill_register.b_full_q (b_full),
    .\i_spill_register.a_data_q (a_entry), .\i_spill_register.b_data_q (b_entry)
  );

  // The reference: the fused beat of this cycle ...
  logic [LANES*B-1:0] sum;
  for (genvar l = 0; l < LANES; l++) begin : gen_lane
    saturating_add_model #(.B(B)) i_model (
      .a_i(a_data_i[l*B +: B]), .b_i(b_data_i[l*B +: B]), .y_o(sum[l*B +: B])
    );
  end

  // ... and a FIFO of two beats (data and a's last).
  logic [1:0]       count_q;
  logic             rd_q, wr_q;
  logic [LANES*B:0] entry_q [0:1];
  logic             take, give;
  assign take = a_valid_i && b_valid_i && count_q != 2'd2;  // both inputs present, room left
  assign give = count_q != 2'd0 && y_ready_i;               // the oldest beat leaves

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      count_q <= 2'd0;
      rd_q    <= 1'b0;
      wr_q    <= 1'b0;
    end else begin
      count_q <= count_q + {1'b0, take} - {1'b0, give};
      if (take) begin
        entry_q[wr_q] <= {a_last_i, sum};
        wr_q          <= !wr_q;
      end
      if (give) begin
        rd_q <= !rd_q;
      end
    end
  end

  always @* begin
    if ($initstate) begin
      assume (!rst_ni);
    end else begin
      assert (count_q != 2'd3);
      if (rst_ni) begin  // in a reset cycle the RTL's own rule decides (ready low, or nothing kept)
        assert (a_ready == take);
        assert (b_ready == take);
      end
      assert (y_valid == (count_q != 2'd0));
      if (y_valid) begin
        assert ({y_last, y_data} == entry_q[rd_q]);
      end
`ifdef FORMAL_INDUCTION
      // Induction strengthening: the pointers agree with the count, and the buffer's two
      // entries hold the reference's two beats.
      assert (wr_q == (rd_q ^ count_q[0]));
      assert (a_full == (count_q != 2'd0));
      assert (b_full == (count_q == 2'd2));
      if (count_q != 2'd0) begin
        assert (a_entry == entry_q[rd_q]);
      end
      if (count_q == 2'd2) begin
        assert (b_entry == entry_q[!rd_q]);
      end
`endif
    end
  end
endmodule
