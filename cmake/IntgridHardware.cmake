# The hardware toolchain: SystemC (pkg-config, built for C++17 on Debian 12) and Verilator.
include(${CMAKE_CURRENT_LIST_DIR}/IntgridWriteIfChanged.cmake)
find_package(PkgConfig REQUIRED)
pkg_check_modules(SYSTEMC REQUIRED IMPORTED_TARGET systemc)
find_package(verilator 5 REQUIRED HINTS /usr/share/verilator)

# Debian's libsystemc-dev 2.3.4 is built for C++17: a C++20 translation unit that includes
# SystemC links only if it declares the library's language version.
add_library(intgrid_systemc_lib INTERFACE)
target_link_libraries(intgrid_systemc_lib INTERFACE PkgConfig::SYSTEMC)
target_compile_definitions(intgrid_systemc_lib INTERFACE SC_CPLUSPLUS=201703L)
# SystemC's headers trip the project's stricter warnings; they are not ours to fix.
target_compile_options(intgrid_systemc_lib INTERFACE -Wno-conversion -Wno-shadow -Wno-pedantic)

# intgrid_lint_rtl(NAME TOP SOURCES...): a ctest (label hw) running verilator --lint-only -Wall.
function(intgrid_lint_rtl name top)
  add_test(NAME ${name}
           COMMAND verilator --lint-only -Wall --top-module ${top} ${ARGN}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/rtl)
  set_tests_properties(${name} PROPERTIES LABELS hw)
endfunction()

# _intgrid_fault_copy(SOURCE OUT NAME FROM TO): writes to OUT a copy of SOURCE in which FROM
# (found exactly once) becomes TO. Configuration fails if FROM is not found exactly once, so that
# an edit of the source never silently turns a fault into the intact source.
function(_intgrid_fault_copy src out name from to)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${src})
  file(READ ${src} text)
  string(FIND "${text}" "${from}" first)
  string(FIND "${text}" "${from}" last REVERSE)
  file(RELATIVE_PATH shown ${PROJECT_SOURCE_DIR} ${src})
  if(first EQUAL -1 OR NOT first EQUAL last)
    message(FATAL_ERROR "fault ${name}: `${from}` is not found exactly once in ${shown}")
  endif()
  string(REPLACE "${from}" "${to}" text "${text}")
  intgrid_write_if_changed(${out} "${text}")
endfunction()

# intgrid_rtl_fault(SOURCES NAME FILE FROM TO): a fault for a checker's self-test. In the list of
# RTL paths held by the variable SOURCES, rtl/FILE is replaced by a copy in which FROM (found
# exactly once) becomes TO, written to <build>/rtl_faults/NAME/FILE. The shipped RTL holds no
# fault switches: each fault lives here, in the testbench, beside the test that must catch it.
# Call it again on the same list for a fault across files.
function(intgrid_rtl_fault sources name file from to)
  set(src ${PROJECT_SOURCE_DIR}/rtl/${file})
  set(out ${CMAKE_BINARY_DIR}/rtl_faults/${name}/${file})
  _intgrid_fault_copy(${src} ${out} ${name} "${from}" "${to}")
  set(list ${${sources}})
  list(FIND list ${src} at)
  if(at EQUAL -1)
    message(FATAL_ERROR "fault ${name}: rtl/${file} is not among its sources")
  endif()
  list(REMOVE_AT list ${at})
  list(INSERT list ${at} ${out})
  set(${sources} ${list} PARENT_SCOPE)
endfunction()

# intgrid_systemc_fault(TARGET NAME FILE FROM TO): the same for a SystemC model, whose headers
# are included as "systemc/FILE": TARGET finds a copy of systemc/FILE with the edit, written to
# <build>/systemc_faults/NAME/systemc/FILE, before the shipped one.
function(intgrid_systemc_fault target name file from to)
  set(root ${CMAKE_BINARY_DIR}/systemc_faults/${name})
  _intgrid_fault_copy(${PROJECT_SOURCE_DIR}/systemc/${file} ${root}/systemc/${file} ${name}
                      "${from}" "${to}")
  target_include_directories(${target} BEFORE PRIVATE ${root})
endfunction()
