# Kernel 2, the sectoral ISM (integer): every test here is labelled hw.
#   rtl_manifest_sectoral_ism     rtl/sectoral_ism.f, .core and Bender.yml list the build's sources
#   sectoral_ism_config_*         rtl/config/cone16 and cone12 are what `intgrid hw-config` writes
#                                 from the sensors' parameters today, byte for byte
#   sectoral_ism_defaults_cone16  the top's parameter defaults are rtl/config/cone16's
#   ism_kernel_export             writes the C++ configuration header of cone16 and cone12 into the
#                                 build tree (the RTL's files are the committed rtl/config/<name>)
#   sectoral_ism_lint*            verilator --lint-only -Wall of rtl/sectoral_ism*.sv (defaults,
#                                 cone16, cone12, a generated configuration, the broken variant)
#   sectoral_ism_illegal_*        configurations the parameter checks must refuse at elaboration
#   sectoral_ism_synth_ice40_*    rtl/synth.sh (Yosys synth_ice40) of cone16, cone12 and the
#                                 generated configuration (if yosys is found)
#   SectoralIsmHls/*              hls/sectoral_ism.hpp against golden (every reading of the port)
#   SectoralIsmHlsTop.*           the HLS top functions (compiled with __SYNTHESIS__) against golden
#   HlsWidth*                     hls/ with width checking on: no value exceeds its declared width
#   SectoralIsmRtl.*              the Verilator testbench, one Verilated model per configuration,
#                                 and the deliberately broken variant
#   sectoral_ism_cosim_*          the SystemC co-simulation (Verilated RTL beside the SystemC model),
#                                 3 seeds per configuration, and its two fault variants
#   sectoral_ism_report           measured cycles, latency and simulation speed, one JSON line each
find_package(GTest REQUIRED)
include(GoogleTest)

set(_ism_rtl_dir ${PROJECT_SOURCE_DIR}/rtl)
# The order of rtl/sectoral_ism.f (the package first); rtl_manifest_sectoral_ism holds the
# manifests to this list.
set(_ism_rtl_files sectoral_ism_pkg.sv sectoral_ism_rom.sv sdp_ram.sv spill_register.sv
    sectoral_ism_mul.sv sectoral_ism_density.sv sectoral_ism_log_add.sv sectoral_ism_index.sv
    sectoral_ism_setup.sv sectoral_ism_stream.sv sectoral_ism.sv)
list(TRANSFORM _ism_rtl_files PREPEND ${_ism_rtl_dir}/ OUTPUT_VARIABLE _ism_rtl)
set(_ism_gen ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism)
set(_ism_configs cone16 cone12)
set(_ism_roms quad_coef log_norm log_weight log_add thresholds threshold_bucket)
# Verilator's generated C++ is not ours to clean up for the project's warning flags.
set(_ism_quiet OPT_FAST -w OPT_SLOW -w OPT_GLOBAL -w)
# The RTL's assertions on, and X (explicit and initial) replaced by values the bench can randomize.
set(_ism_check --assert --x-assign unique --x-initial unique)

add_test(NAME rtl_manifest_sectoral_ism
         COMMAND ${CMAKE_COMMAND} -DRTL_DIR=${_ism_rtl_dir} -DKERNEL=sectoral_ism
                 "-DFILES=${_ism_rtl_files}" -P ${CMAKE_CURRENT_SOURCE_DIR}/check_rtl_manifests.cmake)
set_tests_properties(rtl_manifest_sectoral_ism PROPERTIES LABELS hw)

# --- The configurations: committed in rtl/config, checked against golden ------------------------
# The sensors' parameters of golden/kernel/include/intgrid/kernel/hardware_configs.hpp, as
# `intgrid hw-config` takes them.
set(_ism_args_cone16 --fov 30 --rings 40 --bins 16 --sectors 4 --cell 0.05 --sigma 0.02
    --k-d 0.05 --k-theta 0.5 --k-size 0.5 --bits 8 --eps 0.05)
set(_ism_args_cone12 --fov-rad 0.3 --rings 25 --bins 12 --sectors 3 --cell 0.1 --sigma 0.05
    --k-d 0 --k-theta 0.3 --k-size 0.2 --bits 6 --eps 0.2)
foreach(_cfg ${_ism_configs})
  add_test(NAME sectoral_ism_config_${_cfg}
           COMMAND ${CMAKE_COMMAND} -DINTGRID=$<TARGET_FILE:intgrid> -DNAME=${_cfg}
                   -DREF=${_ism_rtl_dir}/config/${_cfg} -DOUT=${_ism_gen}/regenerated/${_cfg}
                   "-DARGS=${_ism_args_${_cfg}}" -P ${CMAKE_CURRENT_SOURCE_DIR}/check_ism_config.cmake)
  set_tests_properties(sectoral_ism_config_${_cfg} PROPERTIES LABELS hw)
endforeach()

# The top's defaults are cone16, ROM files included: an instance without parameters is a kernel.
add_test(NAME sectoral_ism_defaults_cone16
         COMMAND ${CMAKE_COMMAND} -DTOP=${_ism_rtl_dir}/sectoral_ism.sv
                 -DVC=${_ism_rtl_dir}/config/cone16/sectoral_ism_cone16.vc
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/check_ism_defaults.cmake)
set_tests_properties(sectoral_ism_defaults_cone16 PROPERTIES LABELS hw)

# The C++ layers' header of each configuration, from golden at build time.
add_executable(ism_kernel_export ism_kernel_export.cpp)
target_link_libraries(ism_kernel_export PRIVATE intgrid_kernel)
set(_ism_tables "")
foreach(_cfg ${_ism_configs})
  set(_header ${_ism_gen}/sectoral_ism_${_cfg}_config.hpp)
  add_custom_command(OUTPUT ${_header}
                     COMMAND ism_kernel_export ${_cfg} ${_ism_gen}
                     DEPENDS ism_kernel_export
                     COMMENT "Sectoral ISM configuration header of ${_cfg}" VERBATIM)
  list(APPEND _ism_tables ${_header})
  # The Verilated models run in the build tree: their ROM files by absolute path, after the
  # committed parameters (which name them relative to rtl/). Later -G options win.
  set(_roms_vc ${_ism_gen}/sectoral_ism_${_cfg}_roms.vc)
  set(_text "// ${_cfg}'s ROM files for models that run outside rtl/\n")
  foreach(_rom ${_ism_roms})
    string(TOUPPER ${_rom} _key)
    string(APPEND _text "-G${_key}_FILE=\\\"${_ism_rtl_dir}/config/${_cfg}/sectoral_ism_${_cfg}_${_rom}.mem\\\"\n")
  endforeach()
  file(CONFIGURE OUTPUT ${_roms_vc} CONTENT "${_text}")
  set(_ism_vargs_${_cfg} -f ${_ism_rtl_dir}/config/${_cfg}/sectoral_ism_${_cfg}.vc -f ${_roms_vc})
endforeach()
add_custom_target(sectoral_ism_tables DEPENDS ${_ism_tables})

# A configuration from command-line parameters, generated into the build tree by the tests (a
# folder config/wide12 beside which the tools run, as they run in rtl/): a wide, coarse sensor.
set(_ism_ip_root ${_ism_gen}/generated)
add_test(NAME sectoral_ism_config_generated
         COMMAND $<TARGET_FILE:intgrid> hw-config --name wide12 --out ${_ism_ip_root}/config/wide12
                 --fov 60 --rings 24 --bins 12 --sectors 2 --cell 0.1 --sigma 0.04 --k-d 0.02
                 --k-theta 0.4 --k-size 0.3 --bits 7 --eps 0.1)
set_tests_properties(sectoral_ism_config_generated PROPERTIES LABELS hw
                     FIXTURES_SETUP sectoral_ism_generated)

# --- Lint and synthesis ----------------------------------------------------------------------
intgrid_lint_rtl(sectoral_ism_lint sectoral_ism ${_ism_rtl_files})
foreach(_cfg ${_ism_configs})
  intgrid_lint_rtl(sectoral_ism_lint_${_cfg} sectoral_ism -f sectoral_ism.f
                   -f config/${_cfg}/sectoral_ism_${_cfg}.vc)
endforeach()
set(_ism_rtl_phi ${_ism_rtl})
intgrid_testbench_fault(_ism_rtl_phi log_add_phi)
intgrid_lint_rtl(sectoral_ism_lint_broken sectoral_ism ${_ism_rtl_phi})
add_test(NAME sectoral_ism_lint_generated
         COMMAND verilator --lint-only -Wall --top-module sectoral_ism -F ${_ism_rtl_dir}/sectoral_ism.f
                 -f config/wide12/sectoral_ism_wide12.vc
         WORKING_DIRECTORY ${_ism_ip_root})
set_tests_properties(sectoral_ism_lint_generated PROPERTIES LABELS hw
                     FIXTURES_REQUIRED sectoral_ism_generated)
# Configurations the parameter checks refuse at elaboration, each with its own message: 15 bins
# in 4 sectors (would stream 12 of 15 bins a ring), a reading port too narrow for reach, a bucket
# ROM word too narrow for the count (a sub-module's own check), and a derived width set by hand.
set(_ism_illegal
    "bins|-GBINS=15|sectoral_ism|SECTORS must divide BINS"
    "reading_w|-GREADING_W=13|sectoral_ism|does not fit READING_W bits"
    "bucket_w|-GBUCKET_W=6|sectoral_ism_index|BUCKET_W must hold MAX_INDEX"
    "derived|-GE_W=16|sectoral_ism|not found in the design: E_W")
foreach(_case ${_ism_illegal})
  string(REPLACE "|" ";" _case "${_case}")
  list(GET _case 0 _name)
  list(GET _case 1 _param)
  list(GET _case 2 _top)
  list(GET _case 3 _message)
  intgrid_lint_rtl(sectoral_ism_illegal_${_name} ${_top} ${_param} -f sectoral_ism.f)
  set_tests_properties(sectoral_ism_illegal_${_name} PROPERTIES
                       PASS_REGULAR_EXPRESSION "%(Error|Warning-USERERROR)[^\n]*${_message}")
endforeach()
find_program(INTGRID_YOSYS yosys)
if(INTGRID_YOSYS AND INTGRID_HW_RTL_BENCHES)
  foreach(_cfg ${_ism_configs})
    add_test(NAME sectoral_ism_synth_ice40_${_cfg} COMMAND sh ${_ism_rtl_dir}/synth.sh ${_cfg})
    set_tests_properties(sectoral_ism_synth_ice40_${_cfg} PROPERTIES LABELS hw
                         ENVIRONMENT YOSYS=${INTGRID_YOSYS})
  endforeach()
  add_test(NAME sectoral_ism_synth_ice40_generated
           COMMAND sh ${_ism_rtl_dir}/synth.sh wide12 ${_ism_ip_root})
  set_tests_properties(sectoral_ism_synth_ice40_generated PROPERTIES LABELS hw
                       ENVIRONMENT YOSYS=${INTGRID_YOSYS} FIXTURES_REQUIRED sectoral_ism_generated)
  string(JOIN " " _ism_yosys_read ${_ism_rtl_files})
  add_test(NAME sectoral_ism_illegal_yosys
           COMMAND ${INTGRID_YOSYS} -q -p
                   "read_verilog -sv ${_ism_yosys_read}; chparam -set BINS 15 sectoral_ism; hierarchy -top sectoral_ism"
           WORKING_DIRECTORY ${_ism_rtl_dir})
  set_tests_properties(sectoral_ism_illegal_yosys PROPERTIES LABELS hw
                       PASS_REGULAR_EXPRESSION "ERROR: sectoral_ism_stream: SECTORS must divide BINS")
endif()

# --- Plain C++: the HLS function against golden ------------------------------------------------
add_executable(sectoral_ism_hls_test sectoral_ism_hls_test.cpp sectoral_ism_hls_synth.cpp
                                     hls_headers_together.cpp)
target_link_libraries(sectoral_ism_hls_test PRIVATE intgrid_hls intgrid_core intgrid_kernel GTest::gtest_main)
target_include_directories(sectoral_ism_hls_test PRIVATE ${PROJECT_SOURCE_DIR} ${_ism_gen})
add_dependencies(sectoral_ism_hls_test sectoral_ism_tables)
# sectoral_ism_hls_synth.cpp sees the header as an HLS tool does (pragmas expanded, C++17, the
# dialect HLS front ends take) and holds the top functions; hls_headers_together.cpp includes
# both kernels' headers so that, with -Werror, a second definition of the pragma macro fails.
set_source_files_properties(sectoral_ism_hls_synth.cpp hls_headers_together.cpp PROPERTIES
  COMPILE_DEFINITIONS __SYNTHESIS__ COMPILE_OPTIONS "-std=c++17;-Werror;-Wno-unknown-pragmas")
gtest_discover_tests(sectoral_ism_hls_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)

# The same kernels with width checking on (INTGRID_HLS_WIDTH_CHECK changes hls/fixed_int.hpp, so
# it is a program of its own): no value exceeds its declared width over every reading.
add_executable(hls_width_test hls_width_test.cpp)
target_link_libraries(hls_width_test PRIVATE intgrid_hls intgrid_core intgrid_kernel GTest::gtest_main)
target_include_directories(hls_width_test PRIVATE ${PROJECT_SOURCE_DIR} ${_ism_gen})
target_compile_definitions(hls_width_test PRIVATE INTGRID_HLS_WIDTH_CHECK)
add_dependencies(hls_width_test sectoral_ism_tables)
gtest_discover_tests(hls_width_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)

if(INTGRID_HW_RTL_BENCHES)
# --- The Verilated models: one per configuration, and the broken variants ----------------------
# The faults of rtl_faults.cmake: cone16_bug: Phi read one entry off (log_add_phi);
# cone16_bubble: the output stream's stage 1 waits for the spill register when empty
# (stream_bubble, a bubble at the start of a bank); cone12_ready: z_ready not held low in reset
# (ism_ready_in_reset).
add_library(sectoral_ism_vmodels STATIC)
add_dependencies(sectoral_ism_vmodels sectoral_ism_tables)
set(_ism_vdirs "")
foreach(_variant cone16 cone12 cone16_bug cone16_bubble cone12_ready)
  string(REGEX REPLACE "_.*" "" _cfg ${_variant})
  set(_args ${_ism_vargs_${_cfg}})
  set(_rtl ${_ism_rtl})
  if(_variant MATCHES "_bug$")
    intgrid_testbench_fault(_rtl log_add_phi)
  elseif(_variant MATCHES "_bubble$")
    intgrid_testbench_fault(_rtl stream_bubble)
  elseif(_variant MATCHES "_ready$")
    intgrid_testbench_fault(_rtl ism_ready_in_reset)
  endif()
  set(_vdir ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_v/${_variant})
  verilate(sectoral_ism_vmodels SOURCES ${_rtl} TOP_MODULE sectoral_ism
           PREFIX Vsectoral_ism_${_variant} DIRECTORY ${_vdir} TRACE_FST
           VERILATOR_ARGS ${_args} ${_ism_check} ${_ism_quiet})
  list(APPEND _ism_vdirs ${_vdir})
endforeach()
# The output stream alone (3 rings of 4 bins, 2 sectors), intact and with the faults that show
# its checkers live: the stream's own bubble and last flag, the spill register's overwrite and bubble.
foreach(_name none stream_bubble stream_last spill_overwrite spill_bubble)
  set(_rtl ${_ism_rtl_dir}/sectoral_ism_pkg.sv ${_ism_rtl_dir}/sectoral_ism_stream.sv
           ${_ism_rtl_dir}/spill_register.sv)
  if(NOT _name STREQUAL none)
    intgrid_testbench_fault(_rtl ${_name})
  endif()
  set(_vdir ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_v/stream_${_name})
  verilate(sectoral_ism_vmodels SOURCES ${_rtl} TOP_MODULE sectoral_ism_stream
           PREFIX Vsectoral_ism_stream_${_name} DIRECTORY ${_vdir} TRACE_FST
           VERILATOR_ARGS -GRINGS=3 -GBINS=4 -GSECTORS=2 -GIDX_W=8 ${_ism_check} ${_ism_quiet})
  list(APPEND _ism_vdirs ${_vdir})
endforeach()
# Users of the models: Verilator's headers as system headers (the project's -Wconversion is not
# for them), and the models' trace support.
function(_ism_use_vmodels target)
  target_link_libraries(${target} PRIVATE sectoral_ism_vmodels intgrid_core intgrid_kernel
                                          intgrid_tb_verilated_context)
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
endif()

# --- The SystemC co-simulation ------------------------------------------------------------------
# Verilated SystemC models of both configurations and of the broken variant, with the index RAM
# write port public (sectoral_ism_cosim.vlt) so that the co-simulation compares it every cycle.
add_library(sectoral_ism_sc_vmodels STATIC)
add_dependencies(sectoral_ism_sc_vmodels sectoral_ism_tables)
target_link_libraries(sectoral_ism_sc_vmodels PUBLIC intgrid_systemc_lib)
set(_ism_sc_vdirs "")
foreach(_variant cone16 cone12 cone16_bug)
  string(REPLACE "_bug" "" _cfg ${_variant})
  set(_args ${_ism_vargs_${_cfg}})
  set(_rtl ${_ism_rtl})
  if(_variant MATCHES "_bug$")
    intgrid_testbench_fault(_rtl log_add_phi)
  endif()
  set(_vdir ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_v/sc_${_variant})
  verilate(sectoral_ism_sc_vmodels SYSTEMC
           SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/sectoral_ism_cosim.vlt ${_rtl}
           TOP_MODULE sectoral_ism PREFIX Vsectoral_ism_sc_${_variant} DIRECTORY ${_vdir}
           VERILATOR_ARGS ${_args} ${_ism_check} ${_ism_quiet})
  list(APPEND _ism_sc_vdirs ${_vdir})
endforeach()
# The co-simulation, and a build of it whose SystemC model has a one-cycle schedule fault.
function(_ism_cosim target)
  add_executable(${target} sectoral_ism_cosim.cpp)
  target_link_libraries(${target} PRIVATE sectoral_ism_sc_vmodels intgrid_systemc intgrid_core
                                          intgrid_kernel)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR} ${_ism_gen})
  target_include_directories(${target} SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                      ${VERILATOR_ROOT}/include/vltstd ${_ism_sc_vdirs})
endfunction()
_ism_cosim(sectoral_ism_cosim)
_ism_cosim(sectoral_ism_cosim_sc_bug)
# The fault: one suffix cycle more in the model's set-up schedule.
intgrid_systemc_fault(sectoral_ism_cosim_sc_bug sc_schedule sectoral_ism_setup.hpp
  "if (o.cyc == 2 * o.n_win + 1) n.phase = Phase::PrefixFetch;"
  "if (o.cyc == 2 * o.n_win + 2) n.phase = Phase::PrefixFetch;")
# Three seeds per configuration; each fault must be caught at the cycle where it first shows.
foreach(_cfg ${_ism_configs})
  foreach(_seed 1 2 3)
    add_test(NAME sectoral_ism_cosim_${_cfg}_seed${_seed} COMMAND sectoral_ism_cosim ${_cfg} ${_seed})
    set_tests_properties(sectoral_ism_cosim_${_cfg}_seed${_seed} PROPERTIES LABELS hw)
  endforeach()
endforeach()
# Every bank starting under back-pressure: a one-cycle bubble there in either model (the SystemC
# stream stage waiting for the spill register when empty) shows as a y_valid mismatch.
add_test(NAME sectoral_ism_cosim_cone16_bank_starts
         COMMAND sectoral_ism_cosim cone16 41 --bank-starts)
set_tests_properties(sectoral_ism_cosim_cone16_bank_starts PROPERTIES LABELS hw)
add_test(NAME sectoral_ism_cosim_fault_rtl_phi
         COMMAND sectoral_ism_cosim cone16_bug_phi 1 --fault rtl_phi)
add_test(NAME sectoral_ism_cosim_fault_sc_schedule
         COMMAND sectoral_ism_cosim_sc_bug cone16 1 --fault sc_schedule)
set_tests_properties(sectoral_ism_cosim_fault_rtl_phi sectoral_ism_cosim_fault_sc_schedule
                     PROPERTIES LABELS hw)
