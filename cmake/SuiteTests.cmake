# add_suite_tests(<name> <suite.toml>): registers each case of a suite as a CTest test
# suite.<name>.<case id> (label `suite`), so `ctest -R`, `ctest -L suite` and `ctest -j` work
# per case. The cases are listed by `aosuite check --list` when ctest runs, as
# gtest_discover_tests does, so editing the suite needs no re-configure.
function(add_suite_tests name suite)
  set(bin "$<TARGET_FILE:aosuite>")
  set(reports "${CMAKE_CURRENT_BINARY_DIR}/suite-reports")
  set(script "${CMAKE_CURRENT_BINARY_DIR}/${name}_suite_tests.cmake")
  file(GENERATE OUTPUT "${script}" CONTENT "
execute_process(COMMAND \"${bin}\" check \"${suite}\" --list
                OUTPUT_VARIABLE ids ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  # Keep the failure visible as a test rather than silently registering nothing.
  add_test(suite.${name}.list \"${bin}\" check \"${suite}\" --list)
  set_tests_properties(suite.${name}.list PROPERTIES LABELS suite)
  return()
endif()
string(REPLACE \"\\n\" \";\" ids \"\${ids}\")
foreach(id IN LISTS ids)
  if(id)
    add_test(suite.${name}.\${id} \"${bin}\" check \"${suite}\" --filter \"^\${id}$\"
             --report \"${reports}/\${id}\")
    set_tests_properties(suite.${name}.\${id} PROPERTIES LABELS suite)
  endif()
endforeach()
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${script}")
endfunction()
