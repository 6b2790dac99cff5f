// A read-only table loaded from a $readmemh file, read synchronously (the read data is
// registered and holds while en_i is low): Yosys maps it to iCE40 block RAM.
module sectoral_ism_rom #(
  parameter int unsigned WIDTH = 8,
  parameter int unsigned DEPTH = 256,
  parameter              FILE  = "",
  localparam int unsigned AW   = (DEPTH > 1) ? $clog2(DEPTH) : 1
) (
  input  logic             clk_i,
  input  logic             en_i,
  input  logic [AW-1:0]    addr_i,
  output logic [WIDTH-1:0] data_o
);
  if (WIDTH < 1 || DEPTH < 1) begin : gen_check_size
    $error("sectoral_ism_rom: WIDTH and DEPTH must be at least 1");
  end

  logic [WIDTH-1:0] mem_q [0:DEPTH-1];

  initial begin
    if (FILE != "") begin  // no file: the default parameters only elaborate
      $readmemh(FILE, mem_q);
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      data_o <= mem_q[addr_i];
    end
  end
endmodule
