# cmake -DVC=<top .vc> -DOUT=<unit .vc> -DPARAMS=<list> -P ism_unit_params.cmake
#
# Writes the Verilator parameter file of one sectoral ISM sub-module from the parameter file of
# the top `sectoral_ism` of a configuration (sectoral_ism_<cfg>.vc): Verilator refuses a -G that
# names no parameter of the top it elaborates, and the sub-modules name some parameters
# differently. PARAMS lists the sub-module's parameters, comma-separated, each as NAME (the
# top's NAME) or NAME=TOP_NAME. OUT is rewritten only when its text changes, so that the sub-module is
# Verilated again only when its parameters do.
foreach(_var VC OUT PARAMS)
  if(NOT DEFINED ${_var})
    message(FATAL_ERROR "ism_unit_params.cmake: ${_var} is not set")
  endif()
endforeach()

file(STRINGS ${VC} _lines REGEX "^-G[A-Za-z0-9_]+=")
set(_text "// Verilator parameters of a sectoral ISM sub-module, from ${VC}\n")
string(REPLACE "," ";" PARAMS "${PARAMS}")
foreach(_param ${PARAMS})
  string(REPLACE "=" ";" _pair ${_param})
  list(GET _pair 0 _name)
  list(GET _pair -1 _top)
  set(_found "")
  foreach(_line ${_lines})
    if(_line MATCHES "^-G${_top}=(.*)$")
      set(_found "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  if(_found STREQUAL "")
    message(FATAL_ERROR "ism_unit_params.cmake: ${VC} sets no parameter ${_top}")
  endif()
  string(APPEND _text "-G${_name}=${_found}\n")
endforeach()

set(_old "")
if(EXISTS ${OUT})
  file(READ ${OUT} _old)
endif()
if(NOT _old STREQUAL _text)
  file(WRITE ${OUT} "${_text}")
endif()
