// What the sectoral ISM's modules derive from a configuration, in one place: the widths of
// counters, addresses and words that follow from the configuration's sizes, so that no module
// takes them as parameters that could be set wrong. The same rules as golden's derive_ism_hw
// (golden/kernel/include/intgrid/kernel/hardware_configs.hpp), which the tests hold the RTL to.
// The leaf modules (ROM, RAM, multiplier, log-add, index, density) compute their few address
// widths inline, so that each compiles on its own. Constant functions only, without `return`
// (Yosys 0.23 reads only the function-name assignment).
package sectoral_ism_pkg;

  // Bits that hold the unsigned value v, at least 1 (golden's unsigned_bits).
  function automatic int unsigned unsigned_bits(input logic [63:0] v);
    unsigned_bits = (v > 64'd1) ? $clog2(v + 64'd1) : 1;
  endfunction

  // Address bits of a memory of `depth` words, at least 1.
  function automatic int unsigned addr_bits(input int unsigned depth);
    addr_bits = (depth > 1) ? $clog2(depth) : 1;
  endfunction

  // Ring numbers 0..rings+1 (0 and rings + 1 mark an empty window).
  function automatic int unsigned ring_bits(input int unsigned rings);
    ring_bits = unsigned_bits(64'(rings) + 64'd1);
  endfunction

  // |z - d_r| inside the window, in reading units: window << reading_frac - 1.
  function automatic int unsigned error_bits(input int unsigned window, input int unsigned frac);
    error_bits = unsigned_bits((64'(window) << frac) - 64'd1);
  endfunction

  // (z - d_r)^2 inside the window.
  function automatic int unsigned square_bits(input int unsigned window, input int unsigned frac);
    square_bits = unsigned_bits(((64'(window) << frac) - 64'd1) * ((64'(window) << frac) - 64'd1));
  endfunction

  // Digits of a `width`-bit operand taken `digit` bits a cycle.
  function automatic int unsigned digits(input int unsigned width, input int unsigned digit);
    digits = (width + digit - 1) / digit;
  endfunction

  // The narrowest multiplier digit whose products of a ring's `classes` densities
  // (classes * digits + 4 cycles) fit the sum pipeline's slot of conditions * classes cycles;
  // 0 if none does.
  function automatic int unsigned mul_digit_bits(input int unsigned width,
                                                 input int unsigned classes,
                                                 input int unsigned conditions);
    mul_digit_bits = 0;
    for (int unsigned k = width; k >= 1; k--) begin
      if (classes * digits(width, k) + 4 <= conditions * classes) mul_digit_bits = k;
    end
  endfunction

  // Conditions of the class sums: the prior, each sector occupied, each sector emptied.
  function automatic int unsigned conditions(input int unsigned sectors);
    conditions = 2 * sectors + 1;
  endfunction

  // The largest index magnitude an `idx_w`-bit two's-complement index can hold.
  function automatic int unsigned max_index_of(input int unsigned idx_w);
    max_index_of = (idx_w > 1) ? (32'd1 << (idx_w - 1)) - 1 : 0;
  endfunction

endpackage
