# cmake -DVC=<top .vc> -DHEADER=<config .hpp> -DOUT=<unit .vc> -DPARAMS=<list>
#       -P ism_unit_params.cmake
#
# Writes the Verilator parameter file of one sectoral ISM sub-module for a configuration: its
# numeric parameters from the top `sectoral_ism`'s parameter file (sectoral_ism_<cfg>.vc:
# Verilator refuses a -G that names no parameter of the top it elaborates, and the sub-modules
# name some parameters differently), and the widths the top derives as localparams from golden's
# configuration header (sectoral_ism_<cfg>_config.hpp; sectoral_ism_cosim checks that the two
# derivations agree). PARAMS lists the sub-module's parameters, comma-separated, each as NAME
# (the top's NAME), NAME=TOP_NAME, or NAME=hpp.field (the header's `field`). OUT is rewritten only
# when its text changes, so that the sub-module is Verilated again only when its parameters do.
foreach(_var VC HEADER OUT PARAMS)
  if(NOT DEFINED ${_var})
    message(FATAL_ERROR "ism_unit_params.cmake: ${_var} is not set")
  endif()
endforeach()

file(STRINGS ${VC} _lines REGEX "^-G[A-Za-z0-9_]+=")
file(STRINGS ${HEADER} _fields REGEX "static constexpr int [a-z0-9_]+ = ")
set(_text "// Verilator parameters of a sectoral ISM sub-module, from ${VC} and ${HEADER}\n")
string(REPLACE "," ";" PARAMS "${PARAMS}")
foreach(_param ${PARAMS})
  string(REPLACE "=" ";" _pair ${_param})
  list(GET _pair 0 _name)
  list(GET _pair -1 _source)
  set(_found "")
  if(_source MATCHES "^hpp\\.(.+)$")
    set(_field ${CMAKE_MATCH_1})
    foreach(_line ${_fields})
      if(_line MATCHES "static constexpr int ${_field} = (-?[0-9]+);")
        set(_found "${CMAKE_MATCH_1}")
      endif()
    endforeach()
    set(_where "${HEADER} has no field ${_field}")
  else()
    foreach(_line ${_lines})
      if(_line MATCHES "^-G${_source}=(.*)$")
        set(_found "${CMAKE_MATCH_1}")
      endif()
    endforeach()
    set(_where "${VC} sets no parameter ${_source}")
  endif()
  if(_found STREQUAL "")
    message(FATAL_ERROR "ism_unit_params.cmake: ${_where}")
  endif()
  string(APPEND _text "-G${_name}=${_found}\n")
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/../cmake/IntgridWriteIfChanged.cmake)
intgrid_write_if_changed(${OUT} "${_text}")
