# Target-scoped warnings. MOCAPLINK_WERROR turns them into errors (CI presets set it).
option(MOCAPLINK_WERROR "Treat warnings as errors" OFF)

function(mocaplink_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wnon-virtual-dtor
    -Wold-style-cast -Woverloaded-virtual -Wdouble-promotion -Wformat=2
    -Wimplicit-fallthrough)
  if(MOCAPLINK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# MOCAPLINK_TEST_CXX_FLAGS: compile flags for the tests' own code only (the test executables; the
# libraries and the program they test are built as the build type says). The CI and cross presets
# set "-O1 -g0": GoogleTest's macros make test code the bigger half of the compile, and at -O1
# without debug information it compiles in half the time of -O2 -g (measured on the biggest
# test, 49 s vs 100 s of CPU) while still running Eigen-heavy tests at a useful speed under
# qemu-user. Use mocaplink_test_flags(TARGET) for a test executable not made by mocaplink_gtest.
set(MOCAPLINK_TEST_CXX_FLAGS "" CACHE STRING "Compile flags for the test executables' own code")

function(mocaplink_test_flags target)
  separate_arguments(flags NATIVE_COMMAND "${MOCAPLINK_TEST_CXX_FLAGS}")
  if(flags)
    target_compile_options(${target} PRIVATE ${flags})
  endif()
endfunction()

# A test executable: GoogleTest, discovered into CTest with a label (unit, integration,
# conformance, fuzz-replay).
function(mocaplink_gtest name label)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE GTest::gtest GTest::gmock GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  mocaplink_warnings(${name})
  mocaplink_test_flags(${name})
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES LABELS ${label}
    DISCOVERY_TIMEOUT 60)
endfunction()
