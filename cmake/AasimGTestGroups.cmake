# ctest entries that each run a group of a GoogleTest binary's tests in one process: a whole test
# suite, or MAX_CASES of its cases at a time. gtest_discover_tests gives every case a process of
# its own, so each of about 1000 cases paid the binary's start again (0.13 s under ASan) and
# every suite-level set-up again (CliRunTest's `aasim run`): docs/PERFORMANCE.md, "CI time at
# stop 25". A case that fails still names itself in the group's output.
#
#   aasim_discover_test_groups(TARGET NAME name FILTER gtest-filter MAX_CASES n TIMEOUT seconds)
#
# Like gtest_discover_tests, the cases are listed after each build of TARGET (a POST_BUILD step
# running cmake/AasimGTestGroupsList.cmake) and the entries read from the file it writes.
function(aasim_discover_test_groups target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "NAME;FILTER;MAX_CASES;TIMEOUT" "")
  set(ctest_file "${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}_groups.cmake")
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}_groups_include.cmake")
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND "${CMAKE_COMMAND}" "-DTEST_EXECUTABLE=$<TARGET_FILE:${target}>" "-DTEST_FILTER=${arg_FILTER}"
            "-DMAX_CASES=${arg_MAX_CASES}" "-DTIMEOUT=${arg_TIMEOUT}" "-DCTEST_FILE=${ctest_file}"
            -P "${PROJECT_SOURCE_DIR}/cmake/AasimGTestGroupsList.cmake"
    BYPRODUCTS "${ctest_file}"
    VERBATIM)
  file(WRITE "${include_file}"
       "if(EXISTS \"${ctest_file}\")\n  include(\"${ctest_file}\")\nelse()\n"
       "  add_test(${arg_NAME}_NOT_BUILT ${arg_NAME}_NOT_BUILT)\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
