# The mapping engine (hls/mapping_engine.hpp): every test here is labelled hw.
#   MappingEngineHls.*         hls/mapping_engine.hpp against golden: the sine at every angle,
#                              random rays cell for cell, the packed ISM table, the bundled log's
#                              scans into a tile cell for cell
#   mapping_engine_width_test  the same with INTGRID_HLS_WIDTH_CHECK: no value leaves its width
#   mapping_engine_sc_test     the SystemC model on the bundled log against golden, gaps and
#                              back-pressure on its streams
find_package(GTest REQUIRED)
include(GoogleTest)

foreach(_me_program mapping_engine_cpp_test mapping_engine_width_test)
  add_executable(${_me_program} mapping_engine_hls_test.cpp)
  target_link_libraries(${_me_program} PRIVATE intgrid_hls intgrid_core intgrid_io
                                               intgrid_test_data_dir GTest::gtest_main)
  target_include_directories(${_me_program} PRIVATE ${PROJECT_SOURCE_DIR})
endforeach()
# mapping_engine_hls_synth.cpp sees the header as an HLS tool does (pragmas expanded, C++17).
target_sources(mapping_engine_cpp_test PRIVATE mapping_engine_hls_synth.cpp)
set_source_files_properties(mapping_engine_hls_synth.cpp PROPERTIES
  COMPILE_DEFINITIONS __SYNTHESIS__ COMPILE_OPTIONS "-std=c++17;-Werror;-Wno-unknown-pragmas")
target_compile_definitions(mapping_engine_width_test PRIVATE INTGRID_HLS_WIDTH_CHECK)
gtest_discover_tests(mapping_engine_cpp_test PROPERTIES LABELS hw DISCOVERY_TIMEOUT 60)
gtest_discover_tests(mapping_engine_width_test TEST_PREFIX Width. PROPERTIES LABELS hw
                     DISCOVERY_TIMEOUT 60)

# The SystemC model on the bundled log, random gaps and back-pressure (INTGRID_TB_SEED).
add_executable(mapping_engine_sc_test mapping_engine_sc_test.cpp)
target_link_libraries(mapping_engine_sc_test PRIVATE intgrid_systemc intgrid_core intgrid_io
                                                     intgrid_test_data_dir)
target_include_directories(mapping_engine_sc_test PRIVATE ${PROJECT_SOURCE_DIR})
add_test(NAME mapping_engine_sc_test COMMAND mapping_engine_sc_test)
set_tests_properties(mapping_engine_sc_test PROPERTIES LABELS hw)
