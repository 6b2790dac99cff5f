# cmake -DINTGRID=<intgrid> -DNAME=<name> -DREF=<rtl/config/name> -DOUT=<dir> -DARGS=<a;b;...>
#       -P check_ism_config.cmake
# A committed configuration folder of the sectoral ISM cannot drift from golden: `intgrid
# hw-config --name NAME ARGS --out OUT` (the sensor's parameters on the command line) must write
# exactly the files of REF, byte for byte, and no other.
cmake_minimum_required(VERSION 3.20)

file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${INTGRID} hw-config --name ${NAME} ${ARGS} --out ${OUT}
                RESULT_VARIABLE _status OUTPUT_QUIET)
if(NOT _status EQUAL 0)
  message(FATAL_ERROR "intgrid hw-config ${ARGS} failed (${_status})")
endif()

file(GLOB _written RELATIVE ${OUT} ${OUT}/*)
file(GLOB _committed RELATIVE ${REF} ${REF}/*)
list(SORT _written)
list(SORT _committed)
if(NOT "${_written}" STREQUAL "${_committed}")
  message(FATAL_ERROR "${REF} holds\n  ${_committed}\nintgrid hw-config writes\n  ${_written}")
endif()
set(_differ "")
foreach(_f ${_committed})
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${REF}/${_f} ${OUT}/${_f}
                  RESULT_VARIABLE _same)
  if(NOT _same EQUAL 0)
    list(APPEND _differ ${_f})
  endif()
endforeach()
string(REPLACE ";" " " ARGS "${ARGS}")
if(_differ)
  message(FATAL_ERROR "${REF} is not what golden writes today: ${_differ} differ; regenerate "
                      "with intgrid hw-config --name ${NAME} ${ARGS} --out ${REF}")
endif()
list(LENGTH _committed _n)
message(STATUS "${REF}: all ${_n} files are golden's")
