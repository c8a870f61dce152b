# Every dependency comes from a Debian package (scripts/setup installs them). Nothing is downloaded.
find_package(Threads REQUIRED)
if(WIN32)
  include(${CMAKE_CURRENT_LIST_DIR}/WindowsDependencies.cmake)
else()
  find_package(Eigen3 3.4 REQUIRED NO_MODULE)
  list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
  find_package(GeographicLib REQUIRED)
  if(NOT TARGET GeographicLib::GeographicLib)
    add_library(GeographicLib::GeographicLib INTERFACE IMPORTED)
    set_target_properties(GeographicLib::GeographicLib PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${GeographicLib_INCLUDE_DIRS}"
      INTERFACE_LINK_LIBRARIES "${GeographicLib_LIBRARIES}")
  endif()
  find_package(tomlplusplus 3 REQUIRED)
  find_package(fmt REQUIRED)
  find_package(spdlog REQUIRED)
  find_package(nlohmann_json 3 REQUIRED)
  find_package(CLI11 REQUIRED)
  find_package(OpenSSL REQUIRED COMPONENTS Crypto)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)
endif()

# ROS 2 over DDS (adapters/ros2): Fast DDS 2.x from Debian, in native Linux builds and in the
# arm64 and armhf cross builds (scripts/cross-sysroot unpacks Debian's packages of it). Debian has
# no Windows package, so that build leaves it out (`check` says so when [ros2] asks).
if(WIN32)
  set(ros2_default OFF)
else()
  set(ros2_default ON)
endif()
option(MOCAPLINK_ROS2 "Publish to ROS 2 over Fast DDS (adapters/ros2)" ${ros2_default})
if(MOCAPLINK_ROS2)
  find_package(fastrtps 2 QUIET)
  if(NOT fastrtps_FOUND)
    message(FATAL_ERROR "Fast DDS 2.x (Debian's libfastrtps-dev) not found: run scripts/setup, or "
                        "configure with -DMOCAPLINK_ROS2=OFF to build without ROS 2")
  endif()
endif()

# Standalone Asio is header-only and ships no CMake package.
find_path(ASIO_INCLUDE_DIR asio.hpp REQUIRED)
add_library(mocaplink_asio INTERFACE)
target_include_directories(mocaplink_asio SYSTEM INTERFACE ${ASIO_INCLUDE_DIR})
target_compile_definitions(mocaplink_asio INTERFACE ASIO_STANDALONE ASIO_NO_DEPRECATED)
target_link_libraries(mocaplink_asio INTERFACE Threads::Threads)
if(WIN32)
  target_link_libraries(mocaplink_asio INTERFACE ws2_32 mswsock)
endif()
add_library(mocaplink::asio ALIAS mocaplink_asio)

if(BUILD_TESTING)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()

# Tests that need tools from outside CMake (node, chromium, npm ci) are left out with a note when
# those are missing, unless MOCAPLINK_ALL_TESTS (the ci preset) demands every test: then a missing
# tool fails the configuration, so CI can never pass by dropping tests.
function(mocaplink_tests_unavailable message)
  if(MOCAPLINK_ALL_TESTS)
    message(FATAL_ERROR "${message} (run scripts/setup)")
  endif()
  message(STATUS "${message}")
endfunction()
if(MOCAPLINK_BENCH)
  find_package(benchmark REQUIRED)
endif()
