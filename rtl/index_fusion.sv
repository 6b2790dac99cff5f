// Kernel 1, index fusion (S_eps): fuses two streams of occupancy-grid index beats cell by cell,
// y = sat(a + b) per lane, saturating at +-(2^(B-1) - 1). One beat per cycle (II = 1) under any
// pattern of input gaps and output back-pressure; latency 1 cycle (a beat accepted at a clock edge
// is presented on y from that edge on).
//
// Micro-architecture: a join of the two input streams (a beat moves only when both a and b are
// valid and the output buffer has room), LANES combinational saturating adders, then a
// spill_register that holds the outputs stable while y_valid_o && !y_ready_i and cuts every path
// from y_ready_i back to the inputs. The input ready depends combinationally on the input valids
// and on a register, never on y_ready_i; it is low while rst_ni is low.
//
// Data buses: lane l of a beat is bits [l*B + B-1 : l*B], lane 0 in the least significant bits,
// B-bit two's complement (the packing of hls/index_fusion.hpp).
//
// last: y_last_o carries a_last_i of the beat. b_last_i is accepted with its beat but ignored: if
// the two streams disagree on where a frame ends, the output frames follow stream a.
module index_fusion #(
  parameter int unsigned B     = 8,  // index width, 4..16
  parameter int unsigned LANES = 8   // cells per beat, 1..16
) (
  input  logic               clk_i,
  input  logic               rst_ni,  // synchronous, active low
  // input stream a
  input  logic               a_valid_i,
  output logic               a_ready_o,
  input  logic [LANES*B-1:0] a_data_i,
  input  logic               a_last_i,
  // input stream b
  input  logic               b_valid_i,
  output logic               b_ready_o,
  input  logic [LANES*B-1:0] b_data_i,
  input  logic               b_last_i,
  // output stream y
  output logic               y_valid_o,
  input  logic               y_ready_i,
  output logic [LANES*B-1:0] y_data_o,
  output logic               y_last_o
);
  if (B < 4 || B > 16) begin : gen_check_b
    $error("index_fusion: B must be 4..16");
  end
  if (LANES < 1 || LANES > 16) begin : gen_check_lanes
    $error("index_fusion: LANES must be 1..16");
  end

  logic               join_valid, join_ready, fire;
  logic [LANES*B-1:0] sum;

  assign join_valid = a_valid_i && b_valid_i;   // both halves of the next beat are present
  assign fire       = join_valid && join_ready && rst_ni; // the beat moves (never in reset): a and b consumed, sum buffered
  assign a_ready_o  = fire;                     // a is taken only together with b
  assign b_ready_o  = fire;                     // b is taken only together with a

  for (genvar l = 0; l < LANES; l++) begin : gen_lane
    saturating_add #(
      .B(B)
    ) i_saturating_add (
      .a_i(a_data_i[l*B +: B]),
      .b_i(b_data_i[l*B +: B]),
      .y_o(sum[l*B +: B])
    );
  end

  spill_register #(
    .WIDTH(LANES*B + 1)
  ) i_spill_register (
    .clk_i,
    .rst_ni,
    .valid_i(join_valid),
    .ready_o(join_ready),
    .data_i ({a_last_i, sum}),
    .valid_o(y_valid_o),
    .ready_i(y_ready_i),
    .data_o ({y_last_o, y_data_o})
  );

  // b_last_i is part of the b beat but does not shape the output frames (see the header).
  logic unused_b_last;
  assign unused_b_last = b_last_i;

`ifndef SYNTHESIS
  // Checkers, simulation only (Yosys defines SYNTHESIS); Verilator needs --assert. The output
  // stream's own rules are checked in i_spill_register.
  // Nothing is taken during reset.
  ready_low_in_reset: assert property (@(posedge clk_i) !rst_ni |-> !a_ready_o && !b_ready_o)
    else $error("index_fusion: input ready during reset");
  // The join wastes no cycle: both halves present and room in the buffer move a beat (II = 1).
  join_takes_beat: assert property (@(posedge clk_i) disable iff (!rst_ni)
      a_valid_i && b_valid_i && !i_spill_register.b_full_q |-> a_ready_o && b_ready_o)
    else $error("index_fusion: input refused with room in the output buffer");
  // The sources' rule (AXI4-Stream): an offered beat stays, unchanged, until it is taken.
  a_source_holds: assert property (@(posedge clk_i) disable iff (!rst_ni)
      a_valid_i && !a_ready_o |=> a_valid_i && $stable({a_last_i, a_data_i}))
    else $error("index_fusion: stream a changed an offered beat before it was taken");
  b_source_holds: assert property (@(posedge clk_i) disable iff (!rst_ni)
      b_valid_i && !b_ready_o |=> b_valid_i && $stable({b_last_i, b_data_i}))
    else $error("index_fusion: stream b changed an offered beat before it was taken");
  // Only a four-state simulator can see X here (two-state Verilator cannot).
  known_after_reset: assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown({a_ready_o, b_ready_o, y_valid_o}) && (!y_valid_o || !$isunknown({y_last_o, y_data_o})))
    else $error("index_fusion: unknown output after reset");
`endif
endmodule
