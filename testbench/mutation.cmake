# The mutation catalogue against the tree (label hw): every mutant of testbench/mutants.txt must
# find its snippet exactly once, so that edits to rtl/, hls/ and systemc/ cannot leave the
# catalogue silently stale. The campaign itself is scripts/mutation_test.py (docs/hardware.md,
# "Mutation testing"); it leaves this test out (-E ^mutation_), which would fail on every mutant.
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  add_test(NAME mutation_catalogue
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/mutation_test.py --list
                   --source ${PROJECT_SOURCE_DIR})
  set_tests_properties(mutation_catalogue PROPERTIES LABELS hw)
endif()
