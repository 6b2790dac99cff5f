// Formal harness of rtl/spill_register.sv against an abstract FIFO of depth 2.
//
// The reference is a queue of at most two beats (q0 the oldest), written as a shift register
// with a count. The proof shows, for every input sequence and every reset pattern:
// - valid_o, ready_o and data_o are functions of the reference's registers alone: valid_o =
//   count > 0, ready_o = count < 2, data_o = the oldest beat. So no beat is lost, duplicated or
//   reordered, and ready_o is registered-only (it cannot depend on this cycle's valid_i, data_i
//   or ready_i, since the reference's registers do not);
// - data_o and valid_o hold while valid_o && !ready_i;
// - throughput: a cycle with ready_i leaves room for a beat in the next one, and a beat taken
//   is offered in the next cycle, so with valid_i and ready_i high one beat moves every cycle;
// - reset empties the buffer.
// The internal entries (exposed by Yosys' `expose`, see testbench/formal.cmake) are tied to the
// reference so that k-induction closes: the proof is unbounded.
module spill_register_formal #(
  parameter int unsigned WIDTH = 4  // formal.cmake sets this and the RTL's to the same value
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic [WIDTH-1:0] data_i,
  input logic             ready_i
);
  logic             ready_o, valid_o;
  logic [WIDTH-1:0] data_o;
  logic             a_full_q, b_full_q;
  logic [WIDTH-1:0] a_data_q, b_data_q;

  spill_register i_dut (
    .clk_i, .rst_ni, .valid_i, .ready_o, .data_i, .valid_o, .ready_i, .data_o,
    .a_full_q, .b_full_q, .a_data_q, .b_data_q  // exposed internals, for the induction only
  );

  // The reference FIFO.
  logic [1:0]       count_q;
  logic [WIDTH-1:0] q0_q, q1_q;
  logic             push, pop;
  assign push = valid_i && ready_o;  // a beat enters
  assign pop  = valid_o && ready_i;  // a beat leaves

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      count_q <= 2'd0;
    end else begin
      count_q <= count_q + {1'b0, push} - {1'b0, pop};
      if (pop) begin
        q0_q <= (count_q == 2'd1) ? data_i : q1_q;  // with count 1 a pop is only kept by a push
        if (push && count_q == 2'd2) begin
          q1_q <= data_i;
        end
      end else if (push) begin
        if (count_q == 2'd0) begin
          q0_q <= data_i;
        end else begin
          q1_q <= data_i;
        end
      end
    end
  end

  // Last cycle's values, for the properties that span a clock edge (registers here, so that
  // every check is an immediate one on the current step).
  logic             past_rst_n_q, past_stall_q, past_ready_q, past_push_q;
  logic [WIDTH-1:0] past_data_q;
  always_ff @(posedge clk_i) begin
    past_rst_n_q <= rst_ni;
    past_stall_q <= valid_o && !ready_i;
    past_ready_q <= ready_i;
    past_push_q  <= push;
    past_data_q  <= data_o;
  end

  always @* begin
    if ($initstate) begin
      assume (!rst_ni);  // start from reset; later resets are arbitrary
    end else begin
      assert (count_q <= 2'd2);
      assert (valid_o == (count_q != 2'd0));
      assert (ready_o == (count_q != 2'd2));
      if (count_q != 2'd0) begin
        assert (data_o == q0_q);
      end
      if (!past_rst_n_q) begin
        assert (!valid_o && ready_o);  // reset empties both entries
      end else begin
        if (past_stall_q) begin
          assert (valid_o && data_o == past_data_q);  // a stalled beat holds
        end
        if (past_ready_q) begin
          assert (ready_o);  // no wasted ready cycle: the consumer's take frees room at once
        end
        if (past_push_q) begin
          assert (valid_o);  // a beat taken is offered in the next cycle
        end
        if (past_ready_q && past_push_q && valid_i && ready_i) begin
          assert (push && pop);  // so both sides held high move one beat a cycle through it
        end
      end
`ifdef FORMAL_INDUCTION
      // Induction strengthening: the two entries are the reference's two beats.
      assert (a_full_q == (count_q != 2'd0));
      assert (b_full_q == (count_q == 2'd2));
      if (count_q == 2'd2) begin
        assert (b_data_q == q1_q);
      end
`endif
    end
  end
endmodule
