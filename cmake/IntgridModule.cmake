# intgrid_add_module(NAME SOURCES... [DEPENDS module...] [LIBS target...] [PRIVATE_LIBS target...])
#
# One library of the project, intgrid_NAME (intgrid::NAME), built from NAME/src and exporting the
# headers of NAME/include/intgrid/NAME. It sees only the headers of the modules it depends on, so
# a dependency that is not declared is a compile error. Installed headers go under
# include/intgrid/NAME/, the library into the exported package intgrid.
function(intgrid_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPENDS;LIBS;PRIVATE_LIBS" ${ARGN})
  set(target intgrid_${name})
  list(TRANSFORM ARG_UNPARSED_ARGUMENTS PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/${name}/src/)
  add_library(${target} STATIC ${ARG_UNPARSED_ARGUMENTS})
  add_library(intgrid::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/${name}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  list(TRANSFORM ARG_DEPENDS PREPEND intgrid_)
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS} ${ARG_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  install(TARGETS ${target} EXPORT intgridTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/${name}/include/intgrid/${name}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/intgrid)
endfunction()
