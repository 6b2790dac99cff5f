# Installs BUILD_DIR into WORK_DIR/prefix, builds CONSUMER_DIR against it and runs the consumer,
# which uses intgrid::core and intgrid::io and the installed command and data.
cmake_minimum_required(VERSION 3.25)
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f include/intgrid/core/seps.hpp include/intgrid/io/log_io.hpp bin/intgrid
          share/intgrid/data/malaga_telecom_map.yaml share/intgrid/hardware_report.json
          lib/cmake/intgrid/intgridConfig.cmake)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

set(flags "")
if(SANITIZE)
  set(flags "-fsanitize=address,undefined")
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/consumer -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} "-DCMAKE_CXX_FLAGS=${flags}"
    "-DCMAKE_EXE_LINKER_FLAGS=${flags}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
run(${WORK_DIR}/consumer/consumer ${prefix}/share/intgrid/data/malaga_room_map.yaml)
message(STATUS "consumer: ${run_output}")

# The installed command, moved away from the build tree, finds its data beside itself.
file(RENAME ${prefix} ${WORK_DIR}/moved)
run(${WORK_DIR}/moved/bin/intgrid map --log ${WORK_DIR}/moved/share/intgrid/data/malaga_telecom_loop_reference.log
    --out ${WORK_DIR}/map --cell 0.2)
if(NOT EXISTS ${WORK_DIR}/map/map.yaml)
  message(FATAL_ERROR "the moved command wrote no map")
endif()
