# Formal proofs of the RTL with Yosys and yosys-smtbmc (z3), label formal: each harness in
# testbench/formal/ proved by testbench/formal/prove.sh, plus one negative test a harness family
# (an injected fault in a copy of the RTL, or the RTL's own fault switch) that must give a
# counterexample, so that every harness is shown to be live. Registered only when yosys,
# yosys-smtbmc and z3 are all found.
#   formal_saturating_add        rtl/saturating_add.sv = an integer reference, B = 4, 8, 16, all inputs
#   formal_spill_register        rtl/spill_register.sv = a 2-deep FIFO; stability, throughput, reset
#   formal_index_fusion          rtl/index_fusion.sv = join + reference adders + 2-deep FIFO, B 8, LANES 8
#   formal_sectoral_ism_stream   rtl/sectoral_ism_stream.sv: reads, release, throughput, y handshake,
#                                and its cells = a ring-major reference, RINGS 3, BINS 4, SECTORS 2
#   formal_sectoral_ism_stream_r5_b6_s3  the same for RINGS 5, BINS 6, SECTORS 3
# All but the adder's (combinational: one step is complete) are k-induction proofs, unbounded.
# A proof's files are in <build>/testbench/formal/<test>/: yosys.log, smtbmc.log, model.smt2, and
# a counterexample in trace.vcd (induction.vcd for a failed induction step).
find_program(INTGRID_YOSYS yosys)
find_program(INTGRID_YOSYS_SMTBMC yosys-smtbmc)
find_program(INTGRID_Z3 z3)
if(NOT (INTGRID_YOSYS AND INTGRID_YOSYS_SMTBMC AND INTGRID_Z3))
  message(STATUS "intgrid: formal proofs off (needs yosys, yosys-smtbmc and z3)")
  return()
endif()

set(_fv_dir ${CMAKE_CURRENT_SOURCE_DIR}/formal)
set(_fv_rtl ${PROJECT_SOURCE_DIR}/rtl)
set(_fv_out ${CMAKE_CURRENT_BINARY_DIR}/formal)
# The RTL's packages, read before its modules by every proof.
file(GLOB _fv_packages CONFIGURE_DEPENDS ${_fv_rtl}/*_pkg.sv)

# intgrid_formal(NAME TOP top DEPTH k [INDUCTION] [COUNTEREXAMPLE] [PREPARE "yosys cmd"...]
#                [PARAMS "-set P V ..."] RTL files... HARNESS files...)
# PREPARE runs on the RTL before the harness is read: chparam to the proof's parameters, and
# expose of the registers that the induction ties to the reference.
function(intgrid_formal name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "INDUCTION;COUNTEREXAMPLE" "TOP;DEPTH;PARAMS"
                        "PREPARE;RTL;HARNESS")
  set(opts --dir ${_fv_out}/${name} --top ${arg_TOP} --depth ${arg_DEPTH})
  if(arg_INDUCTION)
    list(APPEND opts --induction)
  endif()
  if(arg_COUNTEREXAMPLE)
    list(APPEND opts --counterexample)
  endif()
  foreach(cmd ${arg_PREPARE})
    list(APPEND opts --prepare "${cmd}")
  endforeach()
  if(arg_PARAMS)
    list(APPEND opts --params "${arg_PARAMS}")
  endif()
  add_test(NAME ${name}
           COMMAND bash ${_fv_dir}/prove.sh ${opts} --rtl ${_fv_packages} ${arg_RTL}
                   --harness ${arg_HARNESS})
  set_tests_properties(${name} PROPERTIES LABELS formal TIMEOUT 300)
endfunction()

# A negative test: NAME must give a counterexample with rtl/FILE faulty, FROM replaced by TO
# (intgrid_rtl_fault). ARGN as for intgrid_formal.
function(intgrid_formal_negative name fault_file from to)
  cmake_parse_arguments(PARSE_ARGV 4 arg "" "" "RTL")
  set(rtl ${arg_RTL})
  intgrid_rtl_fault(rtl ${name} ${fault_file} "${from}" "${to}")
  intgrid_formal(${name} COUNTEREXAMPLE ${arg_UNPARSED_ARGUMENTS} RTL ${rtl})
endfunction()

# --- rtl/saturating_add.sv: all input pairs for B = 4, 8, 16 -----------------------------------
set(_fv_sat TOP saturating_add_formal DEPTH 1
            HARNESS ${_fv_dir}/saturating_add_model.sv ${_fv_dir}/saturating_add_formal.sv)
intgrid_formal(formal_saturating_add ${_fv_sat} RTL ${_fv_rtl}/saturating_add.sv)
# The negative bound -2^(B-1) (rtl_faults.cmake) must be caught.
set(_fv_sat_fault ${_fv_rtl}/saturating_add.sv)
intgrid_testbench_fault(_fv_sat_fault saturation_bound)
intgrid_formal(formal_saturating_add_fault_bound COUNTEREXAMPLE ${_fv_sat} RTL ${_fv_sat_fault})

# --- rtl/spill_register.sv: a 2-deep FIFO, unbounded ----------------------------------------------
set(_fv_spill_expose a_full_q b_full_q a_data_q b_data_q)
list(TRANSFORM _fv_spill_expose PREPEND spill_register/)
string(JOIN " " _fv_spill_expose ${_fv_spill_expose})
set(_fv_spill TOP spill_register_formal PARAMS "-set WIDTH 4"
              PREPARE "chparam -set WIDTH 4 spill_register" proc "expose ${_fv_spill_expose}"
              HARNESS ${_fv_dir}/spill_register_formal.sv)
intgrid_formal(formal_spill_register INDUCTION DEPTH 4 ${_fv_spill} RTL ${_fv_rtl}/spill_register.sv)
# Entry b no longer moves up while a's beat leaves: beats stall and ready is lost (the
# spill_bubble fault of rtl_faults.cmake, which the simulations catch too).
set(_fv_spill_fault ${_fv_rtl}/spill_register.sv)
intgrid_testbench_fault(_fv_spill_fault spill_bubble)
intgrid_formal(formal_spill_register_fault_b_drain COUNTEREXAMPLE DEPTH 10 ${_fv_spill}
               RTL ${_fv_spill_fault})

# --- rtl/index_fusion.sv against a reference, B 8, LANES 8 (the default), unbounded -------------
set(_fv_if_expose a_full_q b_full_q a_data_q b_data_q)
list(TRANSFORM _fv_if_expose PREPEND w:i_spill_register.)
string(JOIN " " _fv_if_expose ${_fv_if_expose})
set(_fv_if_params "-set B 8 -set LANES 8")
set(_fv_if TOP index_fusion_formal PARAMS ${_fv_if_params}
           PREPARE "chparam ${_fv_if_params} index_fusion" "hierarchy -top index_fusion" proc flatten
                   "expose ${_fv_if_expose}"
           HARNESS ${_fv_dir}/saturating_add_model.sv ${_fv_dir}/index_fusion_formal.sv
           RTL ${_fv_rtl}/saturating_add.sv ${_fv_rtl}/spill_register.sv ${_fv_rtl}/index_fusion.sv)
intgrid_formal(formal_index_fusion INDUCTION DEPTH 3 ${_fv_if})
# y_last taken from stream b instead of a.
intgrid_formal_negative(formal_index_fusion_fault_last index_fusion.sv
  ".data_i ({a_last_i, sum})" ".data_i ({b_last_i, sum})" DEPTH 6 ${_fv_if})

# --- rtl/sectoral_ism_stream.sv, unbounded ------------------------------------------------------
# RINGS:BINS:SECTORS:IDX_W: the small set, then one with bins and sectors not powers of two (the
# address {ring, sector} has holes). Both back to back over banks of 12 and 30 cells.
set(_fv_ism_expose ring_q sec_q bin_q s1_valid_q s1_last_q s1_const_q s1_const_idx_q
                   i_spill.a_full_q i_spill.b_full_q i_spill.a_data_q i_spill.b_data_q)
list(TRANSFORM _fv_ism_expose PREPEND w:)
string(JOIN " " _fv_ism_expose ${_fv_ism_expose})
foreach(_cfg 3:4:2:4 5:6:3:4)
  string(REPLACE ":" ";" _p ${_cfg})
  list(GET _p 0 _r)
  list(GET _p 1 _b)
  list(GET _p 2 _s)
  list(GET _p 3 _w)
  set(_params "-set RINGS ${_r} -set BINS ${_b} -set SECTORS ${_s} -set IDX_W ${_w}")
  set(_fv_ism_${_r}_${_b}_${_s} TOP sectoral_ism_stream_formal PARAMS ${_params}
      PREPARE "chparam ${_params} sectoral_ism_stream"
              "hierarchy -top sectoral_ism_stream" proc flatten "expose ${_fv_ism_expose}"
      HARNESS ${_fv_dir}/sectoral_ism_stream_formal.sv
      RTL ${_fv_rtl}/spill_register.sv ${_fv_rtl}/sectoral_ism_stream.sv)
endforeach()
intgrid_formal(formal_sectoral_ism_stream INDUCTION DEPTH 4 ${_fv_ism_3_4_2})
intgrid_formal(formal_sectoral_ism_stream_r5_b6_s3 INDUCTION DEPTH 4 ${_fv_ism_5_6_3})
# Stage 1 waits for its cell to leave before the next read: a bubble every other cycle.
intgrid_formal_negative(formal_sectoral_ism_stream_fault_bubble sectoral_ism_stream.sv
  "assign s1_advance = !s1_valid_q || sp_ready;" "assign s1_advance = !s1_valid_q;"
  DEPTH 8 ${_fv_ism_3_4_2})
# The window's first ring taken as before it: that ring's cells get the below index.
intgrid_formal_negative(formal_sectoral_ism_stream_fault_window sectoral_ism_stream.sv
  "RING_W'(ring_q) + RING_W'(1) < r_lo_i" "RING_W'(ring_q) + RING_W'(1) <= r_lo_i"
  DEPTH 8 ${_fv_ism_3_4_2})
