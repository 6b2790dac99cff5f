# Builds the Cortex-M3 workload image and runs embedded_check on it. Included by the host build's
# embedded_check.cmake, which sets SOURCE_DIR, BUILD_DIR (the image's build folder), INPUTS_DIR,
# CHECK, QEMU and SIZE; REPORT and RESULTS, when defined (-D), are passed on to write the table
# (REPORT: a file of its own; RESULTS: the section between the embedded-table markers of a file).
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/testbench/cortex_m3 -B ${BUILD_DIR}
          -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/cmake/arm-none-eabi.cmake
          -DINTGRID_EMBEDDED_INPUTS_DIR=${INPUTS_DIR}
  OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
cmake_host_system_information(RESULT _cores QUERY NUMBER_OF_LOGICAL_CORES)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target workload --parallel ${_cores}
                COMMAND_ERROR_IS_FATAL ANY)
set(_write)
if(REPORT)
  list(APPEND _write --report ${REPORT})
endif()
if(RESULTS)
  list(APPEND _write --results ${RESULTS})
endif()
execute_process(COMMAND ${CHECK} --firmware ${BUILD_DIR}/workload.elf --qemu ${QEMU} --size ${SIZE}
                        ${_write}
                RESULT_VARIABLE _status)
if(NOT _status EQUAL 0)
  message(FATAL_ERROR "embedded_check failed (${_status})")
endif()
