# The mapping engine (hls/mapping_engine.hpp): every test here is labelled hw.
#   MappingEngineHls.*         hls/mapping_engine.hpp against golden: the sine at every angle,
#                              random rays cell for cell, the packed ISM table, the bundled log's
#                              scans into a tile cell for cell
#   mapping_engine_width_test  the same with INTGRID_HLS_WIDTH_CHECK: no value leaves its width
#   mapping_engine_lint*       verilator --lint-only -Wall of rtl/mapping_engine.sv (two sets)
#   rtl_manifest_mapping_engine  rtl/mapping_engine.f, .core and Bender.yml list the sources
#   mapping_engine_cosim       the Verilated RTL beside the SystemC model on the bundled log, each
#                              against golden and against each other every cycle
#   mapping_engine_cosim_catches_fault  the same on a deliberately broken RTL must see it differ
find_package(GTest REQUIRED)
# The bundled log's ISM table's bins (testbench/mapping_engine_log.hpp: 30 m in 6 mm bins).
set(INTGRID_MAPPING_ENGINE_LOG_BINS 5002)
include(GoogleTest)

foreach(_me_program mapping_engine_cpp_test mapping_engine_width_test)
  add_executable(${_me_program} mapping_engine_hls_test.cpp)
  target_link_libraries(${_me_program} PRIVATE intgrid_hls intgrid_core intgrid_io
                                               intgrid_test_data_dir GTest::gtest_main)
  target_include_directories(${_me_program} PRIVATE ${PROJECT_SOURCE_DIR})
endforeach()
# mapping_engine_hls_synth.cpp sees the header as an HLS tool does (pragmas expanded, C++17).
target_sources(mapping_engine_cpp_test PRIVATE mapping_engine_hls_synth.cpp)
set_source_files_properties(mapping_engine_hls_synth.cpp PROPERTIES
  COMPILE_DEFINITIONS __SYNTHESIS__ COMPILE_OPTIONS "-std=c++17;-Werror;-Wno-unknown-pragmas")
target_compile_definitions(mapping_engine_width_test PRIVATE INTGRID_HLS_WIDTH_CHECK)
gtest_discover_tests(mapping_engine_cpp_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)
gtest_discover_tests(mapping_engine_width_test TEST_PREFIX Width. PROPERTIES LABELS hw
                     DISCOVERY_TIMEOUT 60)

# --- The RTL: lint, manifests ------------------------------------------------------------------
set(_me_rtl_dir ${PROJECT_SOURCE_DIR}/rtl)
set(_me_rtl_files saturating_add.sv sdp_ram.sv mapping_engine_divider.sv mapping_engine_sine.sv
                  mapping_engine.sv)
list(TRANSFORM _me_rtl_files PREPEND ${_me_rtl_dir}/ OUTPUT_VARIABLE _me_rtl)
intgrid_lint_rtl(mapping_engine_lint mapping_engine ${_me_rtl_files})
intgrid_lint_rtl(mapping_engine_lint_b12_t4 mapping_engine -GB=12 -GTILE_BITS=4 -GBINS=300
                 -GTAIL_CELLS=64 ${_me_rtl_files})
add_test(NAME rtl_manifest_mapping_engine
         COMMAND ${CMAKE_COMMAND} -DRTL_DIR=${_me_rtl_dir} -DKERNEL=mapping_engine
                 "-DFILES=${_me_rtl_files}" -P ${CMAKE_CURRENT_SOURCE_DIR}/check_rtl_manifests.cmake)
set_tests_properties(rtl_manifest_mapping_engine PROPERTIES LABELS hw)

# --- The co-simulation: the Verilated RTL beside the SystemC model on the bundled log, random
# gaps and back-pressure (INTGRID_TB_SEED) -------------------------------------------------------
# One co-simulation program on the given RTL sources.
function(_mapping_engine_cosim target)
  add_executable(${target} mapping_engine_cosim.cpp)
  target_link_libraries(${target} PRIVATE intgrid_systemc intgrid_core intgrid_io
                                          intgrid_test_data_dir)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_include_directories(${target} SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                      ${VERILATOR_ROOT}/include/vltstd)
  verilate(${target} SYSTEMC SOURCES ${ARGN} TOP_MODULE mapping_engine PREFIX Vmapping_engine_sc
           VERILATOR_ARGS -GBINS=${INTGRID_MAPPING_ENGINE_LOG_BINS} -GTAIL_CELLS=1024 --assert
                          --x-assign unique --x-initial unique OPT_FAST -w OPT_SLOW -w
                          OPT_GLOBAL -w)
endfunction()

_mapping_engine_cosim(mapping_engine_cosim ${_me_rtl})
add_test(NAME mapping_engine_cosim COMMAND mapping_engine_cosim)
set_tests_properties(mapping_engine_cosim PROPERTIES LABELS hw)

# The co-simulation's self-test: the same program on the RTL with engine_threshold_tie
# (rtl_faults.cmake) must report cycles where the RTL and the model differ, on the ties.
set(_me_fault_rtl ${_me_rtl})
intgrid_testbench_fault(_me_fault_rtl engine_threshold_tie)
_mapping_engine_cosim(mapping_engine_cosim_fault ${_me_fault_rtl})
add_test(NAME mapping_engine_cosim_catches_fault COMMAND mapping_engine_cosim_fault)
set_tests_properties(mapping_engine_cosim_catches_fault PROPERTIES LABELS hw
  PASS_REGULAR_EXPRESSION "\"stimulus\": \"ties\"[^}]*\"rtl_model_cycle_mismatches\": [1-9]")
