# Kernel 2, the sectoral ISM (integer): every test here is labelled hw.
#   ism_kernel_export             writes the tables of a named configuration (cone16, cone12) into
#                                 the build tree: C++ config header, $readmemh ROM files, parameters
#   sectoral_ism_lint*            verilator --lint-only -Wall of rtl/sectoral_ism*.sv (defaults,
#                                 cone16, cone12, the broken variant)
#   sectoral_ism_synth_ice40      Yosys synth_ice40 of cone16 (if yosys is found)
#   SectoralIsmHls/*              hls/sectoral_ism.hpp against golden (every reading of the port)
#   SectoralIsmRtl.*              the Verilator testbench, one Verilated model per configuration,
#                                 and the deliberately broken variant
#   sectoral_ism_cosim            the SystemC co-simulation (Verilated RTL beside the SystemC model)
#   sectoral_ism_report           measured cycles, latency and simulation speed, one JSON line each
find_package(GTest REQUIRED)
include(GoogleTest)

set(_ism_rtl_dir ${PROJECT_SOURCE_DIR}/rtl)
set(_ism_rtl_files sectoral_ism.sv sectoral_ism_setup.sv sectoral_ism_density.sv
    sectoral_ism_mul.sv sectoral_ism_log_add.sv sectoral_ism_index.sv sectoral_ism_stream.sv
    sectoral_ism_rom.sv sectoral_ism_ram.sv spill_register.sv)
list(TRANSFORM _ism_rtl_files PREPEND ${_ism_rtl_dir}/ OUTPUT_VARIABLE _ism_rtl)
set(_ism_gen ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism)
set(_ism_configs cone16 cone12)
# Verilator's generated C++ is not ours to clean up for the project's warning flags.
set(_ism_quiet OPT_FAST -w OPT_SLOW -w OPT_GLOBAL -w)
# The RTL's assertions on, and X (explicit and initial) replaced by values the bench can randomize.
set(_ism_check --assert --x-assign unique --x-initial unique)

# --- Tables, generated at build time from golden ---------------------------------------------
# The text of every file is golden's (intgrid/kernel/table_export.hpp); the program writes it.
add_executable(ism_kernel_export ism_kernel_export.cpp)
target_link_libraries(ism_kernel_export PRIVATE intgrid_kernel)
set(_ism_tables "")
foreach(_cfg ${_ism_configs})
  set(_out ${_ism_gen}/sectoral_ism_${_cfg})
  set(_files ${_out}_config.hpp ${_out}.vc ${_out}.svh ${_out}.ys)
  foreach(_rom quad_coef log_norm log_weight log_add thresholds threshold_bucket)
    list(APPEND _files ${_out}_${_rom}.mem)
  endforeach()
  add_custom_command(OUTPUT ${_files}
                     COMMAND ism_kernel_export ${_cfg} ${_ism_gen}
                     DEPENDS ism_kernel_export
                     COMMENT "Sectoral ISM tables of ${_cfg}" VERBATIM)
  list(APPEND _ism_tables ${_files})
  # verilate() runs Verilator once at configure time, before any table exists: it then sees an
  # empty parameter file (the RTL's defaults). The build writes the real one, and Verilator runs
  # again because the file is among its dependencies.
  if(NOT EXISTS ${_out}.vc)
    file(WRITE ${_out}.vc "// replaced at build time by ism_kernel_export\n")
  endif()
endforeach()
add_custom_target(sectoral_ism_tables DEPENDS ${_ism_tables})

# --- Lint and synthesis ----------------------------------------------------------------------
intgrid_lint_rtl(sectoral_ism_lint sectoral_ism ${_ism_rtl_files})
intgrid_lint_rtl(sectoral_ism_lint_cone16 sectoral_ism -f ${_ism_gen}/sectoral_ism_cone16.vc
                 ${_ism_rtl_files})
intgrid_lint_rtl(sectoral_ism_lint_cone12 sectoral_ism -f ${_ism_gen}/sectoral_ism_cone12.vc
                 ${_ism_rtl_files})
intgrid_lint_rtl(sectoral_ism_lint_broken sectoral_ism -DSECTORAL_ISM_BUG_PHI ${_ism_rtl_files})
find_program(INTGRID_YOSYS yosys)
if(INTGRID_YOSYS)
  string(JOIN " " _ism_yosys_read ${_ism_rtl_files})
  add_test(NAME sectoral_ism_synth_ice40
           COMMAND ${INTGRID_YOSYS} -q -p
                   "read_verilog -sv ${_ism_yosys_read}; script ${_ism_gen}/sectoral_ism_cone16.ys; synth_ice40 -top sectoral_ism; check -assert"
           WORKING_DIRECTORY ${_ism_rtl_dir})
  set_tests_properties(sectoral_ism_synth_ice40 PROPERTIES LABELS hw)
endif()

# --- Plain C++: the HLS function against golden ------------------------------------------------
add_executable(sectoral_ism_hls_test sectoral_ism_hls_test.cpp sectoral_ism_hls_synth.cpp)
target_link_libraries(sectoral_ism_hls_test PRIVATE intgrid_hls intgrid_core intgrid_kernel GTest::gtest_main)
target_include_directories(sectoral_ism_hls_test PRIVATE ${PROJECT_SOURCE_DIR} ${_ism_gen})
add_dependencies(sectoral_ism_hls_test sectoral_ism_tables)
# sectoral_ism_hls_synth.cpp sees the header as an HLS tool does, pragmas expanded.
set_source_files_properties(sectoral_ism_hls_synth.cpp PROPERTIES
  COMPILE_DEFINITIONS __SYNTHESIS__ COMPILE_OPTIONS -Wno-unknown-pragmas)
gtest_discover_tests(sectoral_ism_hls_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)

# --- The Verilated models: one per configuration, and the broken variants ----------------------
# cone16_bug: Phi read one entry off; cone16_bubble: the output stream's stage 1 waits for the
# spill register when empty (INTGRID_FAULT_STREAM_BUBBLE, a bubble at the start of a bank);
# cone12_ready: z_ready not held low in reset (INTGRID_FAULT_READY_IN_RESET).
add_library(sectoral_ism_vmodels STATIC)
add_dependencies(sectoral_ism_vmodels sectoral_ism_tables)
set(_ism_vdirs "")
foreach(_variant cone16 cone12 cone16_bug cone16_bubble cone12_ready)
  string(REGEX REPLACE "_.*" "" _cfg ${_variant})
  set(_args -f ${_ism_gen}/sectoral_ism_${_cfg}.vc)
  if(_variant MATCHES "_bug$")
    list(APPEND _args -DSECTORAL_ISM_BUG_PHI)
  elseif(_variant MATCHES "_bubble$")
    list(APPEND _args -DINTGRID_FAULT_STREAM_BUBBLE)
  elseif(_variant MATCHES "_ready$")
    list(APPEND _args -DINTGRID_FAULT_READY_IN_RESET)
  endif()
  set(_vdir ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_v/${_variant})
  verilate(sectoral_ism_vmodels SOURCES ${_ism_rtl} TOP_MODULE sectoral_ism
           PREFIX Vsectoral_ism_${_variant} DIRECTORY ${_vdir} TRACE_FST
           VERILATOR_ARGS ${_args} ${_ism_check} ${_ism_quiet})
  list(APPEND _ism_vdirs ${_vdir})
endforeach()
# The output stream alone (3 rings of 4 bins, 2 sectors), intact and with the faults that show
# its checkers live: the stream's own bubble and last flag, the spill register's overwrite and bubble.
foreach(_fault none STREAM_BUBBLE STREAM_LAST SPILL_OVERWRITE SPILL_BUBBLE)
  string(TOLOWER ${_fault} _name)
  set(_args -GRINGS=3 -GBINS=4 -GSECTORS=2 -GIDX_W=8)
  if(NOT _fault STREQUAL none)
    list(APPEND _args -DINTGRID_FAULT_${_fault})
  endif()
  set(_vdir ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_v/stream_${_name})
  verilate(sectoral_ism_vmodels SOURCES ${_ism_rtl_dir}/sectoral_ism_stream.sv
           ${_ism_rtl_dir}/spill_register.sv TOP_MODULE sectoral_ism_stream
           PREFIX Vsectoral_ism_stream_${_name} DIRECTORY ${_vdir} TRACE_FST
           VERILATOR_ARGS ${_args} ${_ism_check} ${_ism_quiet})
  list(APPEND _ism_vdirs ${_vdir})
endforeach()
# Users of the models: Verilator's headers as system headers (the project's -Wconversion is not
# for them), and the models' trace support.
function(_ism_use_vmodels target)
  target_link_libraries(${target} PRIVATE sectoral_ism_vmodels intgrid_core intgrid_kernel)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR} ${_ism_gen})
  target_include_directories(${target} SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                      ${VERILATOR_ROOT}/include/vltstd ${_ism_vdirs})
  target_compile_definitions(${target} PRIVATE VM_TRACE=1 VM_TRACE_FST=1)
endfunction()

add_executable(sectoral_ism_rtl_test sectoral_ism_rtl_test.cpp)
_ism_use_vmodels(sectoral_ism_rtl_test)
target_link_libraries(sectoral_ism_rtl_test PRIVATE GTest::gtest_main)
gtest_discover_tests(sectoral_ism_rtl_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)

add_executable(sectoral_ism_report sectoral_ism_report.cpp)
_ism_use_vmodels(sectoral_ism_report)
add_test(NAME sectoral_ism_report COMMAND sectoral_ism_report 300)
set_tests_properties(sectoral_ism_report PROPERTIES LABELS hw)

# --- The SystemC co-simulation ------------------------------------------------------------------
add_executable(sectoral_ism_cosim sectoral_ism_cosim.cpp)
add_dependencies(sectoral_ism_cosim sectoral_ism_tables)
target_link_libraries(sectoral_ism_cosim PRIVATE intgrid_systemc intgrid_core intgrid_kernel)
target_include_directories(sectoral_ism_cosim PRIVATE ${PROJECT_SOURCE_DIR} ${_ism_gen})
target_include_directories(sectoral_ism_cosim SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                             ${VERILATOR_ROOT}/include/vltstd)
foreach(_cfg ${_ism_configs})
  verilate(sectoral_ism_cosim SYSTEMC SOURCES ${_ism_rtl} TOP_MODULE sectoral_ism
           PREFIX Vsectoral_ism_sc_${_cfg} DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_v/sc_${_cfg}
           VERILATOR_ARGS -f ${_ism_gen}/sectoral_ism_${_cfg}.vc ${_ism_check} ${_ism_quiet})
endforeach()
add_test(NAME sectoral_ism_cosim COMMAND sectoral_ism_cosim)
set_tests_properties(sectoral_ism_cosim PROPERTIES LABELS hw)
