# Kernel 1, index fusion (S_eps): every test here is labelled hw.
#   index_fusion_lint*        verilator --lint-only -Wall of rtl/index_fusion.sv (three parameter sets)
#   index_fusion_synth_ice40  Yosys synth_ice40 of the default configuration (if yosys is found)
#   IndexFusionHls.*          hls/index_fusion.hpp against golden, all widths; the accumulate variant
#   IndexFusionChecker.*      the scoreboard on a C++ model of the RTL, intact and with protocol faults
#   IndexFusionRtl.*          the Verilator testbench, one Verilated model per (B, LANES) below
#   IndexFusionRtlFault.*     the checker's self-test on a deliberately broken RTL
#   index_fusion_cosim        the SystemC co-simulation (Verilated RTL beside the SystemC model)
#   rtl_manifest_index_fusion rtl/index_fusion.f, .core and Bender.yml list the build's sources
# `index_fusion_rtl_test --report` prints the measured cycles, latency and simulation speed.
find_package(GTest REQUIRED)
include(GoogleTest)

set(_if_rtl_dir ${PROJECT_SOURCE_DIR}/rtl)
set(_if_rtl_files saturating_add.sv spill_register.sv index_fusion.sv)
list(TRANSFORM _if_rtl_files PREPEND ${_if_rtl_dir}/ OUTPUT_VARIABLE _if_rtl)
add_test(NAME rtl_manifest_index_fusion
         COMMAND ${CMAKE_COMMAND} -DRTL_DIR=${_if_rtl_dir} -DKERNEL=index_fusion
                 "-DFILES=${_if_rtl_files}" -P ${CMAKE_CURRENT_SOURCE_DIR}/check_rtl_manifests.cmake)
set_tests_properties(rtl_manifest_index_fusion PROPERTIES LABELS hw)
# Verilator's generated C++ is not ours to clean up for the project's warning flags.
set(_if_quiet OPT_FAST -w OPT_SLOW -w OPT_GLOBAL -w)
# The RTL's assertions on, and X (explicit and initial) replaced by values the bench can randomize.
set(_if_check --assert --x-assign unique --x-initial unique)

# --- Lint and synthesis ----------------------------------------------------------------------
intgrid_lint_rtl(index_fusion_lint index_fusion ${_if_rtl_files})
intgrid_lint_rtl(index_fusion_lint_b4_l1 index_fusion -GB=4 -GLANES=1 ${_if_rtl_files})
intgrid_lint_rtl(index_fusion_lint_b16_l16 index_fusion -GB=16 -GLANES=16 ${_if_rtl_files})
find_program(INTGRID_YOSYS yosys)
if(INTGRID_YOSYS AND INTGRID_HW_RTL_BENCHES)
  string(JOIN " " _if_yosys_read ${_if_rtl_files})
  add_test(NAME index_fusion_synth_ice40
           COMMAND ${INTGRID_YOSYS} -q -p
                   "read_verilog -sv ${_if_yosys_read}; synth_ice40 -top index_fusion; check -assert"
           WORKING_DIRECTORY ${_if_rtl_dir})
  set_tests_properties(index_fusion_synth_ice40 PROPERTIES LABELS hw)
endif()

# --- Plain C++: the HLS function against golden, and the checker's self-test ------------------
add_executable(index_fusion_cpp_test index_fusion_hls_test.cpp index_fusion_hls_synth.cpp
                                     index_fusion_checker_test.cpp)
target_link_libraries(index_fusion_cpp_test PRIVATE intgrid_hls intgrid_core intgrid_kernel GTest::gtest_main)
# index_fusion_hls_synth.cpp sees the header as an HLS tool does (pragmas expanded, C++17) and
# holds the top function.
set_source_files_properties(index_fusion_hls_synth.cpp PROPERTIES
  COMPILE_DEFINITIONS __SYNTHESIS__ COMPILE_OPTIONS "-std=c++17;-Werror;-Wno-unknown-pragmas")
gtest_discover_tests(index_fusion_cpp_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)

if(INTGRID_HW_RTL_BENCHES)
# --- The Verilator testbench of the RTL --------------------------------------------------------
# B:LANES of the Verilated models: B = 8 at every power-of-two LANES (exhaustive, 65,536 pairs in
# every lane), then the other widths on buses that make lanes straddle 32- and 64-bit words.
set(INTGRID_INDEX_FUSION_CONFIGS 8:1 8:2 8:4 8:8 8:16 4:16 6:16 10:7 12:8 16:1 16:16)
add_executable(index_fusion_rtl_test index_fusion_rtl_test.cpp)
target_link_libraries(index_fusion_rtl_test PRIVATE intgrid_core intgrid_kernel intgrid_tb_verilated_context
                                                    GTest::gtest)
target_include_directories(index_fusion_rtl_test PRIVATE ${PROJECT_SOURCE_DIR}
                                                         ${CMAKE_CURRENT_BINARY_DIR})
# Verilator's runtime headers, as system headers: the project's -Wconversion is not for them.
target_include_directories(index_fusion_rtl_test SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                                ${VERILATOR_ROOT}/include/vltstd)
set(_if_includes "")
set(_if_xmacro "")
foreach(_cfg ${INTGRID_INDEX_FUSION_CONFIGS})
  string(REPLACE ":" ";" _cfg ${_cfg})
  list(GET _cfg 0 _b)
  list(GET _cfg 1 _l)
  set(_prefix Vindex_fusion_b${_b}_l${_l})
  verilate(index_fusion_rtl_test SOURCES ${_if_rtl} TOP_MODULE index_fusion PREFIX ${_prefix}
           TRACE_FST VERILATOR_ARGS -GB=${_b} -GLANES=${_l} ${_if_check} ${_if_quiet})
  string(APPEND _if_includes "#include \"${_prefix}.h\"\n")
  string(APPEND _if_xmacro "  X(${_prefix}, ${_b}, ${_l}) \\\n")
endforeach()
# The deliberately broken RTL (rtl_faults.cmake, saturation_bound).
set(_if_fault_rtl ${_if_rtl})
intgrid_testbench_fault(_if_fault_rtl saturation_bound)
verilate(index_fusion_rtl_test SOURCES ${_if_fault_rtl} TOP_MODULE index_fusion
         PREFIX Vindex_fusion_fault_b8_l8 TRACE_FST
         VERILATOR_ARGS -GB=8 -GLANES=8 ${_if_check} ${_if_quiet})
string(APPEND _if_includes "#include \"Vindex_fusion_fault_b8_l8.h\"\n")
# Protocol faults that show the checkers live: ready during reset, and a spill register that
# refuses a beat while its entry b is free.
set(_if_fault_rtl ${_if_rtl})
intgrid_testbench_fault(_if_fault_rtl fusion_ready_in_reset)
intgrid_testbench_fault(_if_fault_rtl spill_refuse)
verilate(index_fusion_rtl_test SOURCES ${_if_fault_rtl} TOP_MODULE index_fusion
         PREFIX Vindex_fusion_fault_protocol_b4_l1 TRACE_FST
         VERILATOR_ARGS -GB=4 -GLANES=1 ${_if_check} ${_if_quiet})
string(APPEND _if_includes "#include \"Vindex_fusion_fault_protocol_b4_l1.h\"\n")
file(CONFIGURE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/index_fusion_configs.hpp CONTENT
"// Generated by testbench/index_fusion.cmake: the Verilated models of rtl/index_fusion.sv.
#pragma once
${_if_includes}
// X(model, B, LANES) for every configuration tested.
#define INTGRID_INDEX_FUSION_CONFIGS(X) \\
${_if_xmacro}
" @ONLY)
gtest_discover_tests(index_fusion_rtl_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)
endif()

# --- The SystemC co-simulation ------------------------------------------------------------------
add_executable(index_fusion_cosim index_fusion_cosim.cpp)
target_link_libraries(index_fusion_cosim PRIVATE intgrid_systemc intgrid_core intgrid_kernel)
target_include_directories(index_fusion_cosim PRIVATE ${PROJECT_SOURCE_DIR})
target_include_directories(index_fusion_cosim SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                             ${VERILATOR_ROOT}/include/vltstd)
foreach(_cfg 8:8 12:6)
  string(REPLACE ":" ";" _cfg ${_cfg})
  list(GET _cfg 0 _b)
  list(GET _cfg 1 _l)
  verilate(index_fusion_cosim SYSTEMC SOURCES ${_if_rtl} TOP_MODULE index_fusion
           PREFIX Vindex_fusion_sc_b${_b}_l${_l}
           VERILATOR_ARGS -GB=${_b} -GLANES=${_l} ${_if_check} ${_if_quiet})
endforeach()
add_test(NAME index_fusion_cosim COMMAND index_fusion_cosim)
set_tests_properties(index_fusion_cosim PROPERTIES LABELS hw SKIP_RETURN_CODE 77)
