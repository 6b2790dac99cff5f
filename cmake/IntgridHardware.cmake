# The hardware toolchain: SystemC (pkg-config, built for C++17 on Debian 12) and Verilator.
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
