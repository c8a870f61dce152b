# Shared by the Debian cross toolchains (arm64.cmake, armhf.cmake), which set MOCAPLINK_TRIPLET,
# MOCAPLINK_DEB_ARCH and MOCAPLINK_QEMU_NAME first. Compilers: Debian's crossbuild-essential-<arch>.
# Libraries: Debian's <arch> packages unpacked by scripts/cross-sysroot into
# $MOCAPLINK_CROSS_ROOT/<arch> (default /opt/mocaplink-cross/<arch>), searched before anything of
# the build machine's. Tests run under qemu-user (CMAKE_CROSSCOMPILING_EMULATOR, with that root as
# the guest's library root): ctest, add_test and gtest_discover_tests use it for every target
# executable, in whatever folder it is.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_C_COMPILER ${MOCAPLINK_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${MOCAPLINK_TRIPLET}-g++)
set(CMAKE_LIBRARY_ARCHITECTURE ${MOCAPLINK_TRIPLET})

if(DEFINED ENV{MOCAPLINK_CROSS_ROOT})
  set(MOCAPLINK_CROSS_ROOT $ENV{MOCAPLINK_CROSS_ROOT}/${MOCAPLINK_DEB_ARCH})
else()
  set(MOCAPLINK_CROSS_ROOT /opt/mocaplink-cross/${MOCAPLINK_DEB_ARCH})
endif()
if(NOT EXISTS ${MOCAPLINK_CROSS_ROOT}/.stamp)
  message(FATAL_ERROR "No ${MOCAPLINK_DEB_ARCH} root at ${MOCAPLINK_CROSS_ROOT}: run scripts/setup --cross")
endif()
set(CMAKE_FIND_ROOT_PATH ${MOCAPLINK_CROSS_ROOT})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# The root's headers before the build machine's /usr/include (which the Debian cross compilers
# also search); its libraries for the linker's transitive look-ups.
set(root_includes
    "-isystem ${MOCAPLINK_CROSS_ROOT}/usr/include/${MOCAPLINK_TRIPLET} -isystem ${MOCAPLINK_CROSS_ROOT}/usr/include")
set(CMAKE_C_FLAGS_INIT "${root_includes}")
set(CMAKE_CXX_FLAGS_INIT "${root_includes}")
foreach(kind EXE SHARED MODULE)
  set(CMAKE_${kind}_LINKER_FLAGS_INIT
      "-Wl,-rpath-link,${MOCAPLINK_CROSS_ROOT}/usr/lib/${MOCAPLINK_TRIPLET} -Wl,-rpath-link,${MOCAPLINK_CROSS_ROOT}/lib/${MOCAPLINK_TRIPLET}")
endforeach()
set(ENV{PKG_CONFIG_SYSROOT_DIR} ${MOCAPLINK_CROSS_ROOT})
set(ENV{PKG_CONFIG_LIBDIR}
    "${MOCAPLINK_CROSS_ROOT}/usr/lib/${MOCAPLINK_TRIPLET}/pkgconfig:${MOCAPLINK_CROSS_ROOT}/usr/share/pkgconfig")

find_program(MOCAPLINK_QEMU ${MOCAPLINK_QEMU_NAME} REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR ${MOCAPLINK_QEMU} -L ${MOCAPLINK_CROSS_ROOT})
