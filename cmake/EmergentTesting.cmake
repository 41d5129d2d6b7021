# SPDX-License-Identifier: MIT
# emergent_add_test(NAME SOURCES a.cpp b.cpp [RANKS 1 2 4] [LABELS l...] [TIMEOUT s])
# Builds one GoogleTest executable and registers it once per rank count; counts above 1 run
# through mpirun (oversubscribed, allowed as root, as CI runs). Tests named *RankCount* compare
# the run's ranks with one rank and are left out of the 1-rank variant.
find_program(EMERGENT_MPIRUN NAMES mpirun mpiexec REQUIRED)

function(emergent_add_test name)
  cmake_parse_arguments(T "" "TIMEOUT" "SOURCES;RANKS;LABELS" ${ARGN})
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  add_executable(${name} ${T_SOURCES} ${PROJECT_SOURCE_DIR}/tests/mpi_main.cpp)
  target_link_libraries(${name} PRIVATE emergent_problems emergent_core GTest::gtest)
  foreach(n IN LISTS T_RANKS)
    set(test_name ${name}_np${n})
    if(n EQUAL 1)
      # Tests that compare the ranks of the run with one rank (*RankCount*) would compare a
      # run with itself here: they run only on several ranks.
      add_test(NAME ${test_name} COMMAND ${name} --gtest_filter=-*RankCount*)
    else()
      add_test(NAME ${test_name}
               COMMAND ${EMERGENT_MPIRUN} --allow-run-as-root --oversubscribe -np ${n}
                       $<TARGET_FILE:${name}>)
    endif()
    # 77: every selected test skipped itself (tests/mpi_main.cpp), counted as a skip.
    set_tests_properties(${test_name} PROPERTIES LABELS "${T_LABELS};np${n}" TIMEOUT ${T_TIMEOUT}
                         PROCESSORS ${n} SKIP_RETURN_CODE 77)
  endforeach()
endfunction()
