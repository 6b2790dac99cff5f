// A restoring divider, one quotient bit a cycle: start_i loads the dividend and the divisor, then
// each of the next W cycles decides one bit, most significant first; quotient_o is floor(dividend
// / divisor) from the W-th cycle after start_i on, and holds until the next start. The mapping
// engine's range bin, (z + z_step / 2) / z_step, overlapped with the walk before it.
module mapping_engine_divider #(
  parameter int unsigned W = 19  // bits of the dividend, the divisor and the quotient
) (
  input  logic         clk_i,
  input  logic         rst_ni,  // synchronous, active low
  input  logic         start_i,
  input  logic [W-1:0] dividend_i,
  input  logic [W-1:0] divisor_i,  // not 0
  output logic [W-1:0] quotient_o
);
  if (W < 2 || W > 31) begin : gen_check_w
    $error("mapping_engine_divider: W must be 2..31");
  end

  localparam int unsigned CW = $clog2(W + 1);

  logic [W-1:0]  dividend_q, divisor_q, remainder_q;
  logic [CW-1:0] steps_q;  // quotient bits still to decide
  logic [W:0]    shifted, trial;

  // The remainder with the dividend's next bit shifted in, and whether the divisor goes into it.
  assign shifted = {remainder_q, dividend_q[W-1]};
  assign trial   = shifted - {1'b0, divisor_q};

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      dividend_q  <= '0;
      divisor_q   <= '0;
      remainder_q <= '0;
      quotient_o  <= '0;
      steps_q     <= '0;
    end else if (start_i) begin
      dividend_q  <= dividend_i;
      divisor_q   <= divisor_i;
      remainder_q <= '0;
      quotient_o  <= '0;
      steps_q     <= CW'(W);
    end else if (steps_q != '0) begin
      steps_q    <= steps_q - 1'b1;
      dividend_q <= {dividend_q[W-2:0], 1'b0};
      if (!trial[W]) begin  // shifted >= divisor: the bit is 1
        remainder_q <= trial[W-1:0];
        quotient_o  <= {quotient_o[W-2:0], 1'b1};
      end else begin
        remainder_q <= shifted[W-1:0];
        quotient_o  <= {quotient_o[W-2:0], 1'b0};
      end
    end
  end

`ifndef SYNTHESIS
  divisor_not_zero: assert property (@(posedge clk_i) disable iff (!rst_ni)
      start_i |-> divisor_i != '0)
    else $error("mapping_engine_divider: division by 0");
`endif
endmodule
