# The faults that show the hardware checkers live: each one a known-bad edit of one RTL file, which
# a self-test builds and must see caught (a scoreboard mismatch, a protocol assertion, a formal
# counterexample). The shipped RTL holds no switch for them (cmake/IntgridHardware.cmake,
# intgrid_rtl_fault, writes the faulty copies into the build tree).

# intgrid_testbench_fault(SOURCES FAULT): in the list of RTL paths SOURCES, the file FAULT breaks
# replaced by its faulty copy.
function(intgrid_testbench_fault sources fault)
  if(fault STREQUAL saturation_bound)
    # The negative bound -2^(B-1) (two's complement's own minimum) instead of -(2^(B-1) - 1): a
    # sum of exactly -2^(B-1) comes out unsaturated.
    intgrid_rtl_fault(${sources} ${fault} saturating_add.sv
      "assign below  = sum[B] && (!sum[B-1] || at_min);"
      "assign below  = sum[B] && !sum[B-1];\n  logic unused_at_min;\n  assign unused_at_min = at_min;")
  elseif(fault STREQUAL fusion_ready_in_reset)
    # Index fusion takes beats during reset.
    intgrid_rtl_fault(${sources} ${fault} index_fusion.sv
      "assign fire       = join_valid && join_ready && rst_ni;"
      "assign fire       = join_valid && join_ready;")
  elseif(fault STREQUAL ism_ready_in_reset)
    # The ISM kernel's z_ready_o high during reset.
    intgrid_rtl_fault(${sources} ${fault} sectoral_ism.sv
      "assign z_ready_o = out_of_reset_q && setup_idle && !full_q[wb_q];"
      "assign z_ready_o = setup_idle && !full_q[wb_q];\n  logic unused_out_of_reset;\n  assign unused_out_of_reset = out_of_reset_q;")
  elseif(fault STREQUAL spill_refuse)
    # The spill register refuses a beat while its entry a is full, though b is free.
    intgrid_rtl_fault(${sources} ${fault} spill_register.sv
      "assign ready_o = !b_full_q;" "assign ready_o = !a_full_q;")
  elseif(fault STREQUAL spill_overwrite)
    # A beat stalled in entry a is overwritten by the next.
    intgrid_rtl_fault(${sources} ${fault} spill_register.sv
      "assign a_fill  = valid_i && ready_o && (!a_full_q || a_drain) && !b_full_q;"
      "assign a_fill  = valid_i && ready_o && !b_full_q;")
  elseif(fault STREQUAL spill_bubble)
    # Entry b waits a cycle after a drains before it moves up: a bubble, and with a full a, a
    # stall.
    intgrid_rtl_fault(${sources} ${fault} spill_register.sv
      "assign b_drain = b_full_q && (!a_full_q || a_drain);"
      "assign b_drain = b_full_q && !a_full_q;")
  elseif(fault STREQUAL stream_bubble)
    # The output stream's stage 1, when empty, waits for the spill register: a bubble at the
    # start of a bank.
    intgrid_rtl_fault(${sources} ${fault} sectoral_ism_stream.sv
      "assign s1_advance = !s1_valid_q || sp_ready;" "assign s1_advance = sp_ready;")
  elseif(fault STREQUAL stream_last)
    # last on every bin of the last sector, not on its last bin alone.
    intgrid_rtl_fault(${sources} ${fault} sectoral_ism_stream.sv
      "s1_last_q      <= last_cell;"
      "s1_last_q      <= (ring_q == RIDX_W'(RINGS - 1)) && (sec_q == J_W'(SECTORS - 1));")
  elseif(fault STREQUAL log_add_phi)
    # The log-add reads Phi(d + 1) instead of Phi(d).
    intgrid_rtl_fault(${sources} ${fault} sectoral_ism_log_add.sv
      "assign phi_addr = distance[PHI_AW-1:0];"
      "assign phi_addr = distance[PHI_AW-1:0] + PHI_AW'(1);")
  elseif(fault STREQUAL engine_threshold_tie)
    # The mapping engine's line-of-sight cell counts a threshold only once d has passed it, not
    # when d lands on it: k one short at exact ties, which a real log's rays seldom reach.
    intgrid_rtl_fault(${sources} ${fault} mapping_engine.sv
      "if (d_step >= next_q) begin" "if (d_step > next_q) begin")
  else()
    message(FATAL_ERROR "intgrid_testbench_fault: no fault named ${fault}")
  endif()
  set(${sources} ${${sources}} PARENT_SCOPE)
endfunction()
