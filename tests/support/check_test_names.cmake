# Fails if a Catch2 test name would be mangled by catch_discover_tests: CMake splits names at
# ';' (they travel as a CMake list) and Catch parses a name starting with '-' as an option,
# so such a test would be registered under a truncated name that matches nothing and
# "passes" without running. Usage: cmake -DTEST_ROOT=<tests dir> -P check_test_names.cmake
file(GLOB_RECURSE sources "${TEST_ROOT}/*.cpp")
set(bad "")
foreach(source IN LISTS sources)
  file(READ "${source}" text)
  # A TEST_CASE( followed by one or more adjacent string literals.
  string(REGEX MATCHALL "TEST_CASE\\([ \t\r\n]*(\"[^\"]*\"[ \t\r\n]*)+" cases "${text}")
  foreach(case IN LISTS cases)
    if(case MATCHES "\\\\;" OR case MATCHES "TEST_CASE\\([ \t\r\n]*\"-")
      list(APPEND bad "${source}: ${case}")
    endif()
  endforeach()
  # MATCHALL already split at ';' inside names: a fragment without TEST_CASE is one.
  string(REGEX MATCHALL "TEST_CASE\\([ \t\r\n]*\"[^\"]*;[^\"]*\"" semicolon "${text}")
  if(semicolon)
    list(APPEND bad "${source}: a test name contains ';'")
  endif()
endforeach()
if(bad)
  message(FATAL_ERROR "test names that catch_discover_tests would mangle:\n${bad}")
endif()
message(STATUS "test names: ${TEST_ROOT} ok")
