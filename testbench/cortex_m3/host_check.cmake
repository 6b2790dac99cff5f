# The embedded target's host side (ctest label embedded): the inputs generated from the bundled
# data, the host check (the same workload built for the host), and the test that builds the
# Cortex-M3 image, runs it under QEMU and compares. The image is a cross-compiled project of its
# own (testbench/cortex_m3/CMakeLists.txt): one CMake project has one C++ compiler.
find_program(INTGRID_ARM_GXX arm-none-eabi-g++)
find_program(INTGRID_ARM_SIZE arm-none-eabi-size)
find_program(INTGRID_QEMU_ARM qemu-system-arm)
if(NOT INTGRID_ARM_GXX OR NOT INTGRID_ARM_SIZE OR NOT INTGRID_QEMU_ARM)
  message(FATAL_ERROR "The embedded target needs gcc-arm-none-eabi, libstdc++-arm-none-eabi-newlib "
                      "and qemu-system-arm (bash scripts/setup.sh installs them); "
                      "-DINTGRID_BUILD_EMBEDDED=OFF leaves it out")
endif()

set(_dir ${PROJECT_SOURCE_DIR}/testbench/cortex_m3)
set(INTGRID_EMBEDDED_INPUTS_DIR ${PROJECT_BINARY_DIR}/embedded_inputs)
add_executable(make_embedded_inputs ${_dir}/make_embedded_inputs.cpp)
target_link_libraries(make_embedded_inputs PRIVATE intgrid_io intgrid_slam intgrid_localization)
# Both programs include "testbench/cortex_m3/...", from the repository's root.
target_include_directories(make_embedded_inputs PRIVATE ${PROJECT_SOURCE_DIR})
set(_log ${INTGRID_DATA_DIR}/malaga_telecom_loop.log)
set(_map ${INTGRID_DATA_DIR}/malaga_room_map.yaml)
add_custom_command(
  OUTPUT ${INTGRID_EMBEDDED_INPUTS_DIR}/embedded_inputs.hpp
  COMMAND ${CMAKE_COMMAND} -E make_directory ${INTGRID_EMBEDDED_INPUTS_DIR}
  COMMAND make_embedded_inputs ${_log} ${_map} ${INTGRID_EMBEDDED_INPUTS_DIR}/embedded_inputs.hpp
  DEPENDS make_embedded_inputs ${_log} ${_map} ${INTGRID_DATA_DIR}/malaga_room_map.pgm
  COMMENT "Embedded inputs from the bundled data")

add_executable(embedded_check ${_dir}/embedded_check.cpp ${_dir}/workload.cpp
                              ${INTGRID_EMBEDDED_INPUTS_DIR}/embedded_inputs.hpp)
target_include_directories(embedded_check PRIVATE ${PROJECT_SOURCE_DIR} ${INTGRID_EMBEDDED_INPUTS_DIR})
target_link_libraries(embedded_check PRIVATE intgrid_io intgrid_slam intgrid_localization)

# The check as one script, which the test runs and scripts/embedded.sh runs with -DREPORT and
# -DRESULTS to write the table (docs/embedded.md, and its section in docs/results.md).
set(INTGRID_EMBEDDED_CHECK_SCRIPT ${PROJECT_BINARY_DIR}/embedded_check.cmake)
file(GENERATE OUTPUT ${INTGRID_EMBEDDED_CHECK_SCRIPT} CONTENT "\
set(SOURCE_DIR ${PROJECT_SOURCE_DIR})
set(BUILD_DIR ${PROJECT_BINARY_DIR}/cortex_m3)
set(INPUTS_DIR ${INTGRID_EMBEDDED_INPUTS_DIR})
set(CHECK $<TARGET_FILE:embedded_check>)
set(QEMU ${INTGRID_QEMU_ARM})
set(SIZE ${INTGRID_ARM_SIZE})
include(${_dir}/run_check.cmake)
")
add_test(NAME EmbeddedCortexM3.IntegerResultsAreTheHostsBitForBit
         COMMAND ${CMAKE_COMMAND} -P ${INTGRID_EMBEDDED_CHECK_SCRIPT})
set_tests_properties(EmbeddedCortexM3.IntegerResultsAreTheHostsBitForBit
                     PROPERTIES LABELS embedded TIMEOUT 1800)
