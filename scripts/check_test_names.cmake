# ctest registers each doctest case by name (doctest_discover_tests) and CMake splits a name at
# ';': such a case is registered as one that matches nothing and "passes" without running.
# Run as `cmake -DEXECUTABLES=a,b -P check_test_names.cmake`; fails naming the case.
string(REPLACE "," ";" executables "${EXECUTABLES}")
foreach(exe IN LISTS executables)
  execute_process(COMMAND "${exe}" --list-test-cases --no-version
                  OUTPUT_VARIABLE listing RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${exe} --list-test-cases failed (exit ${status})")
  endif()
  string(REGEX MATCHALL "[^\n]*;[^\n]*" offending "${listing}")
  if(offending)
    string(REPLACE ";" "<;>" shown "${offending}")
    message(FATAL_ERROR "${exe}: a test case name holds ';' (shown <;>), which ctest would "
                        "never run: ${shown}")
  endif()
endforeach()
