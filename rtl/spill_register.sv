// A two-entry stream buffer that cuts every combinational path between its ports: data,
// valid and ready are all driven from registers, and it still moves one beat per cycle.
// After common_cells' spill_register (pulp-platform).
module spill_register #(
  parameter int unsigned WIDTH = 8
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  output logic             ready_o,
  input  logic [WIDTH-1:0] data_i,
  output logic             valid_o,
  input  logic             ready_i,
  output logic [WIDTH-1:0] data_o
);
  // Entry a faces the output; entry b catches a beat that arrives while a is stalled.
  logic             a_full_q, b_full_q;
  logic [WIDTH-1:0] a_data_q, b_data_q;

  logic a_fill, a_drain, b_fill, b_drain;
  assign a_fill  = valid_i && ready_o && (!a_full_q || a_drain) && !b_full_q;  // input goes straight to a
  assign a_drain = a_full_q && ready_i;                                        // a's beat leaves
  assign b_fill  = valid_i && ready_o && a_full_q && !a_drain;                 // a stalls: input parks in b
  assign b_drain = b_full_q && (!a_full_q || a_drain);                         // b moves up into a

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      a_full_q <= 1'b0;
      b_full_q <= 1'b0;
      a_data_q <= '0;
      b_data_q <= '0;
    end else begin
      if (b_drain) begin
        a_data_q <= b_data_q;
      end else if (a_fill) begin
        a_data_q <= data_i;
      end
      a_full_q <= b_drain || a_fill || (a_full_q && !a_drain);
      if (b_fill) begin
        b_data_q <= data_i;
      end
      b_full_q <= b_fill || (b_full_q && !b_drain);
    end
  end

  assign ready_o = !b_full_q;  // registered: room for one more beat whatever the output does
  assign valid_o = a_full_q;
  assign data_o  = a_data_q;

`ifndef SYNTHESIS
  // Checkers, simulation only (Yosys defines SYNTHESIS); Verilator needs --assert. A failure
  // reports through $error, which stops the simulation.
  // The output holds while it is stalled (AXI4-Stream).
  output_stable: assert property (@(posedge clk_i) disable iff (!rst_ni)
      valid_o && !ready_i |=> valid_o && $stable(data_o))
    else $error("spill_register: output changed while valid_o && !ready_i");
  // Entry b only ever waits behind a full entry a, so ready_o is low only with both entries full.
  entry_order: assert property (@(posedge clk_i) disable iff (!rst_ni) b_full_q |-> a_full_q)
    else $error("spill_register: entry b full while entry a is empty");
  // No bubble: a beat taken at an edge, or parked in b, is on the output in the next cycle.
  no_bubble: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (valid_i && ready_o) || b_full_q |=> valid_o)
    else $error("spill_register: a held beat is not on the output (bubble)");
  // Only a four-state simulator can see X here (two-state Verilator cannot).
  known_after_reset: assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown({valid_o, ready_o}) && (!valid_o || !$isunknown(data_o)))
    else $error("spill_register: unknown output after reset");
`endif
endmodule
