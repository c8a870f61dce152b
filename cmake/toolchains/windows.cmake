# x86-64 Windows with Debian's MinGW-w64 toolchain (g++-mingw-w64-x86-64-posix: the posix thread
# model, which std::thread and std::mutex need): preset cross-windows. Libraries: the root that
# scripts/windows-root builds in $MOCAPLINK_CROSS_ROOT/windows (default /opt/mocaplink-cross/windows)
# from Debian's packages — header-only libraries as Debian ships them, GeographicLib and GoogleTest
# compiled from Debian's source packages with this same toolchain. Everything links statically, so
# mocaplink.exe is one file with no MinGW DLLs beside it. Tests run under Wine
# (CMAKE_CROSSCOMPILING_EMULATOR).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(MOCAPLINK_TRIPLET x86_64-w64-mingw32)
set(CMAKE_C_COMPILER ${MOCAPLINK_TRIPLET}-gcc-posix)
set(CMAKE_CXX_COMPILER ${MOCAPLINK_TRIPLET}-g++-posix)
set(CMAKE_RC_COMPILER ${MOCAPLINK_TRIPLET}-windres)

if(DEFINED ENV{MOCAPLINK_CROSS_ROOT})
  set(MOCAPLINK_CROSS_ROOT $ENV{MOCAPLINK_CROSS_ROOT}/windows)
else()
  set(MOCAPLINK_CROSS_ROOT /opt/mocaplink-cross/windows)
endif()
# scripts/windows-root itself uses this file (with MOCAPLINK_BUILDING_ROOT set in the environment,
# which CMake's try_compile projects see too) before the root exists.
if(NOT DEFINED ENV{MOCAPLINK_BUILDING_ROOT} AND NOT EXISTS ${MOCAPLINK_CROSS_ROOT}/.stamp)
  message(FATAL_ERROR "No Windows root at ${MOCAPLINK_CROSS_ROOT}: run scripts/setup --cross")
endif()
set(CMAKE_FIND_ROOT_PATH ${MOCAPLINK_CROSS_ROOT} /usr/${MOCAPLINK_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# Windows 10 and later; static C++ runtime and winpthreads.
set(CMAKE_C_FLAGS_INIT "-D_WIN32_WINNT=0x0A00")
set(CMAKE_CXX_FLAGS_INIT "-D_WIN32_WINNT=0x0A00")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")

# Wine without its diagnostics (WINEDEBUG) and without a desktop (no display in CI).
find_program(MOCAPLINK_WINE wine REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR /usr/bin/env WINEDEBUG=-all DISPLAY= ${MOCAPLINK_WINE})
