# The cross-windows build's dependencies, from the root scripts/windows-root builds out of Debian's
# packages (see cmake/toolchains/windows.cmake). The header-only libraries have no CMake packages
# there, so their targets are made here under the names Dependencies.cmake's find_package calls give
# on Linux; {fmt} and spdlog are used header-only. GeographicLib and GoogleTest are real packages.
set(MOCAPLINK_WINDOWS_INCLUDE ${MOCAPLINK_CROSS_ROOT}/include)
function(mocaplink_header_target name)
  add_library(${name} INTERFACE IMPORTED)
  target_include_directories(${name} SYSTEM INTERFACE ${MOCAPLINK_WINDOWS_INCLUDE})
endfunction()
mocaplink_header_target(Eigen3::Eigen)
mocaplink_header_target(tomlplusplus::tomlplusplus)
mocaplink_header_target(fmt::fmt)
target_compile_definitions(fmt::fmt INTERFACE FMT_HEADER_ONLY)
mocaplink_header_target(spdlog::spdlog)
target_compile_definitions(spdlog::spdlog INTERFACE SPDLOG_HEADER_ONLY SPDLOG_FMT_EXTERNAL)
target_link_libraries(spdlog::spdlog INTERFACE fmt::fmt)
mocaplink_header_target(nlohmann_json::nlohmann_json)
mocaplink_header_target(CLI11::CLI11)
# cpp-httplib without OpenSSL, zlib or brotli (the dashboard is plain HTTP on the lab network),
# with poll() as Debian builds it (WSAPoll here).
mocaplink_header_target(PkgConfig::HTTPLIB)
target_compile_definitions(PkgConfig::HTTPLIB INTERFACE CPPHTTPLIB_USE_POLL)
target_link_libraries(PkgConfig::HTTPLIB INTERFACE ws2_32 crypt32)
find_package(GeographicLib REQUIRED CONFIG)
