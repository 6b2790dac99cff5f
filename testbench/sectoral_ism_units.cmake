# Unit tests of the RTL sub-modules (every test here is labelled hw), each Verilated as its own
# top and driven at its ports by testbench/sectoral_ism_units_test.cpp:
#   IsmUnits.*          sectoral_ism_log_add, _index, _density and _mul with the parameters and ROMs
#                       of cone16 and cone12 (and the multiplier at small widths, exhaustively);
#                       spill_register and saturating_add
#   IsmUnitsFault.*     the same checks on sub-modules with one injected fault each: they must fail
# Included after sectoral_ism.cmake, whose tables it uses.

# --- The configurations' files ------------------------------------------------------------------
# _units_table(<cfg> <suffix> <var>): the file sectoral_ism_<cfg><suffix> of a configuration:
# .vc (the top's parameters) and _<rom>.mem (its ROMs), committed in rtl/config/<cfg>; and
# _config.hpp (golden's configuration header, with the derived widths), which
# _units_tables_target writes in the build tree.
function(_units_table cfg suffix out_var)
  if(suffix STREQUAL "_config.hpp")
    set(${out_var} ${_ism_gen}/sectoral_ism_${cfg}${suffix} PARENT_SCOPE)
  else()
    set(${out_var} ${_ism_rtl_dir}/config/${cfg}/sectoral_ism_${cfg}${suffix} PARENT_SCOPE)
  endif()
endfunction()
set(_units_tables_target sectoral_ism_tables)

set(_units_dir ${CMAKE_CURRENT_BINARY_DIR}/sectoral_ism_units)
file(MAKE_DIRECTORY ${_units_dir})
set(_units_tag_w 5)   # width of the tags the log-add unit and the multiplier carry
set(_units_addr_w 7)  # width of the index unit's write address
set(_units_rtl_log_add sectoral_ism_log_add.sv sectoral_ism_rom.sv)
set(_units_rtl_index sectoral_ism_index.sv sectoral_ism_rom.sv)
set(_units_rtl_density sectoral_ism_density.sv sectoral_ism_mul.sv sectoral_ism_rom.sv)
set(_units_rtl_mul sectoral_ism_mul.sv)
# Each sub-module's numeric parameters: the top's NAME, or NAME=TOP_NAME where they differ, or
# NAME=hpp.field for a width the top derives (a localparam), from golden's configuration header.
set(_units_params_log_add LOG_W PHI_N PHI_W PHI_AW=hpp.phi_addr_bits)
set(_units_params_index LOG_W MAX_INDEX=hpp.max_index IDX_W THR_W BUCKET_SHIFT BUCKET_N
    BUCKET_W=hpp.bucket_bits)
set(_units_params_density RINGS CLASSES READING_FRAC QUAD_SHIFT LOG_W E_W=hpp.e_bits
    SQ_W=hpp.sq_bits COEF_W MUL_B_W=hpp.mul_b_bits MUL_DIGIT_W=hpp.mul_digit_bits NORM_W)
set(_units_params_mul A_W=hpp.sq_bits B_W=hpp.mul_b_bits K=hpp.mul_digit_bits)
# Its ROM file parameters, PARAM=rom: on the command line, not in the generated parameter file,
# so that the configure-time Verilator run already sees them (and lists the files the build
# compiles).
set(_units_roms_log_add FILE=log_add)
set(_units_roms_index THRESHOLDS_FILE=thresholds BUCKET_FILE=threshold_bucket)
set(_units_roms_density QUAD_COEF_FILE=quad_coef LOG_NORM_FILE=log_norm)
set(_units_roms_mul "")
set(_units_args_log_add -GTAG_W=${_units_tag_w})
set(_units_args_index -GADDR_W=${_units_addr_w})
set(_units_args_density "")
set(_units_args_mul -GTAG_W=${_units_tag_w})
# _units_args(<unit> <cfg> <var>): the Verilator arguments of a sub-module for a configuration.
function(_units_args unit cfg out_var)
  set(_args -f ${_units_dir}/${unit}_${cfg}.vc ${_units_args_${unit}})
  foreach(_rom ${_units_roms_${unit}})
    string(REPLACE "=" ";" _pair ${_rom})
    list(GET _pair 0 _param)
    list(GET _pair 1 _name)
    _units_table(${cfg} _${_name}.mem _file)
    list(APPEND _args "-G${_param}=\"${_file}\"")
  endforeach()
  set(${out_var} ${_args} PARENT_SCOPE)
endfunction()

add_executable(sectoral_ism_units_test sectoral_ism_units_test.cpp)
add_dependencies(sectoral_ism_units_test ${_units_tables_target})
target_link_libraries(sectoral_ism_units_test PRIVATE intgrid_tb_verilated_context intgrid_hls intgrid_core intgrid_kernel
                                                      GTest::gtest_main)
target_include_directories(sectoral_ism_units_test PRIVATE ${PROJECT_SOURCE_DIR})
foreach(_cfg ${_ism_configs})
  _units_table(${_cfg} _config.hpp _header)
  get_filename_component(_header_dir ${_header} DIRECTORY)
  target_include_directories(sectoral_ism_units_test PRIVATE ${_header_dir})
endforeach()
target_include_directories(sectoral_ism_units_test SYSTEM PRIVATE ${VERILATOR_ROOT}/include
                                                                  ${VERILATOR_ROOT}/include/vltstd)
target_compile_definitions(sectoral_ism_units_test PRIVATE INTGRID_UNIT_TAG_W=${_units_tag_w}
                                                           INTGRID_UNIT_ADDR_W=${_units_addr_w})

# _units_verilate(PREFIX TOP SOURCES... ARGS args...): one Verilated model of the test.
function(_units_verilate prefix top)
  cmake_parse_arguments(PARSE_ARGV 2 _u "" "" "SOURCES;ARGS")
  verilate(sectoral_ism_units_test SOURCES ${_u_SOURCES} TOP_MODULE ${top} PREFIX ${prefix}
           DIRECTORY ${_units_dir}/${prefix} VERILATOR_ARGS ${_u_ARGS} ${_ism_quiet})
endfunction()

# A sub-module's parameter file per configuration, written at build time (golden's header is a
# build product). verilate() runs once at configure time on an empty file (the sub-module's
# defaults: the file list is the same), and again when the build writes the real one.
function(_units_params unit cfg)
  set(_vc ${_units_dir}/${unit}_${cfg}.vc)
  _units_table(${cfg} .vc _top_vc)
  _units_table(${cfg} _config.hpp _header)
  string(JOIN "," _params ${_units_params_${unit}})
  set(_write ${CMAKE_COMMAND} -DVC=${_top_vc} -DHEADER=${_header} -DOUT=${_vc}
             -DPARAMS=${_params} -P ${CMAKE_CURRENT_SOURCE_DIR}/ism_unit_params.cmake)
  add_custom_command(OUTPUT ${_vc} COMMAND ${_write}
                     DEPENDS ${_top_vc} ${_header}
                             ${CMAKE_CURRENT_SOURCE_DIR}/ism_unit_params.cmake
                     COMMENT "Parameters of sectoral_ism_${unit} for ${cfg}" VERBATIM)
  if(NOT EXISTS ${_vc})
    file(WRITE ${_vc} "// replaced at build time from ${_top_vc}\n")
  endif()
endfunction()

# The four ISM sub-modules for each configuration: V<unit>_<cfg>.
foreach(_cfg ${_ism_configs})
  foreach(_unit log_add index density mul)
    _units_params(${_unit} ${_cfg})
    _units_args(${_unit} ${_cfg} _args)
    set(_src ${_units_rtl_${_unit}})
    list(TRANSFORM _src PREPEND ${_ism_rtl_dir}/)
    _units_verilate(V${_unit}_${_cfg} sectoral_ism_${_unit} SOURCES ${_src} ARGS ${_args})
  endforeach()
endforeach()

# The multiplier at small widths, where every operand pair is tried: A_W:B_W:K (ND = 1, a digit
# width that does not divide B_W, one bit a digit).
foreach(_shape 6:5:2 5:7:7 4:6:1)
  string(REPLACE ":" ";" _s ${_shape})
  list(GET _s 0 _a)
  list(GET _s 1 _b)
  list(GET _s 2 _k)
  _units_verilate(Vmul_a${_a}_b${_b}_k${_k} sectoral_ism_mul SOURCES ${_ism_rtl_dir}/sectoral_ism_mul.sv
                  ARGS -GA_W=${_a} -GB_W=${_b} -GK=${_k} -GTAG_W=${_units_tag_w})
endforeach()

# Shared with index fusion.
_units_verilate(Vspill_register_w8 spill_register SOURCES ${_ism_rtl_dir}/spill_register.sv
                ARGS -GWIDTH=8)
foreach(_b 4 8 16)
  _units_verilate(Vsaturating_add_b${_b} saturating_add SOURCES ${_ism_rtl_dir}/saturating_add.sv
                  ARGS -GB=${_b})
endforeach()

# --- Injected faults -----------------------------------------------------------------------------
# _units_fault(NAME UNIT FROM TO): rtl/sectoral_ism_<UNIT>.sv with the one occurrence of FROM
# replaced by TO (intgrid_rtl_fault), Verilated for cone16 as V<unit>_fault_<NAME>.
function(_units_fault name unit from to)
  set(_src ${_units_rtl_${unit}})
  list(TRANSFORM _src PREPEND ${_ism_rtl_dir}/)
  intgrid_rtl_fault(_src ${unit}_${name} sectoral_ism_${unit}.sv "${from}" "${to}")
  _units_args(${unit} cone16 _args)
  _units_verilate(V${unit}_fault_${name} sectoral_ism_${unit} SOURCES ${_src} ARGS ${_args})
endfunction()
# log 0 + log 0 computed as a finite sum (the bypass only when exactly one side is log 0).
_units_fault(both_zero log_add "a_i[LOG_W] || b_i[LOG_W]" "a_i[LOG_W] ^ b_i[LOG_W]")
# a's log-0 test read as false: x + log 0 returns log 0 instead of x.
_units_fault(pass_a log_add "a_i[LOG_W] ? b_i : a_i" "1'b0 ? b_i : a_i")
# a log-0 denominator not seen: the odds are read from its value bits.
_units_fault(den_zero index "den_i[LOG_W] ? KindMax" "1'b0 ? KindMax")
# a log-0 numerator gives +MAX_INDEX instead of -MAX_INDEX.
_units_fault(num_zero index "num_i[LOG_W] ? KindMin" "num_i[LOG_W] ? KindMax")
# log 0 / log 0 not recognized: -MAX_INDEX instead of 0.
_units_fault(both_zero index "(num_i[LOG_W] && den_i[LOG_W]) ? KindZero"
             "1'b0 ? KindZero")
# The saturating adder with its negative bound one off (rtl_faults.cmake).
set(_units_sat_fault ${_ism_rtl_dir}/saturating_add.sv)
intgrid_testbench_fault(_units_sat_fault saturation_bound)
_units_verilate(Vsaturating_add_fault_b8 saturating_add SOURCES ${_units_sat_fault} ARGS -GB=8)

gtest_discover_tests(sectoral_ism_units_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)
