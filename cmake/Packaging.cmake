# Install rules and the packages (issue 14).
#
# Windows (cross-windows): a .zip with mocaplink.exe (static: no DLLs beside it), the README, the
# example configuration as mocaplink.toml, packaging/windows/START-HERE.txt and the licences of the
# libraries linked into the executable.
if(WIN32)
  install(TARGETS mocaplink RUNTIME DESTINATION .)
  install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/packaging/windows/START-HERE.txt
          DESTINATION .)
  install(FILES ${PROJECT_SOURCE_DIR}/docs/examples/px4-quad.toml DESTINATION . RENAME mocaplink.toml)
  file(GLOB licences ${MOCAPLINK_CROSS_ROOT}/share/licenses/*.copyright)
  list(FILTER licences EXCLUDE REGEX "googletest")  # the tests' framework, not in mocaplink.exe
  install(FILES ${licences} DESTINATION licenses)
  install(FILES /usr/share/doc/mingw-w64-x86-64-dev/copyright DESTINATION licenses
          RENAME mingw-w64-runtime.copyright)
  # mocaplink.exe without its symbol table (8.7 MB -> 4.3 MB): CMAKE_STRIP is MinGW-w64's strip.
  set(CPACK_STRIP_FILES ON)
  set(CPACK_GENERATOR ZIP)
  set(CPACK_PACKAGE_NAME mocaplink)
  set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
  set(CPACK_PACKAGE_FILE_NAME mocaplink-${PROJECT_VERSION}-windows-x86_64)
  set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/packages)
  set(CPACK_INCLUDE_TOPLEVEL_DIRECTORY ON)
  include(CPack)
  return()
endif()

# Linux: the Debian package, `cmake --workflow --preset package` for this machine's architecture,
# the cross-arm64 / cross-armhf workflows for the Raspberry Pi, made the same way for all three
# (issue 29: lintian of Debian 12 finds no error or warning; scripts/check-deb runs it). The .deb
# holds /usr/bin/mocaplink (stripped; no -dbgsym package: the release build has no debug
# information to keep), /etc/mocaplink/mocaplink.toml (docs/examples/px4-quad.toml, a conffile),
# the systemd unit packaging/mocaplink.service, the man page, and in /usr/share/doc/mocaplink the
# README, the copyright file and the changelog.
install(TARGETS mocaplink RUNTIME DESTINATION bin)
install(FILES ${PROJECT_SOURCE_DIR}/docs/examples/px4-quad.toml DESTINATION /etc/mocaplink
        RENAME mocaplink.toml)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/mocaplink.service DESTINATION lib/systemd/system)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/packaging/copyright
        DESTINATION share/doc/mocaplink)

# The man page, from the binary's own --help (packaging/manpage.cmake), run under the emulator
# (qemu-user) when cross-compiling.
set(man_page ${CMAKE_BINARY_DIR}/packaging/mocaplink.1.gz)
set(run "")
if(CMAKE_CROSSCOMPILING_EMULATOR)
  list(JOIN CMAKE_CROSSCOMPILING_EMULATOR "|" run)
  string(APPEND run "|")
endif()
add_custom_command(
  OUTPUT ${man_page}
  COMMAND ${CMAKE_COMMAND} "-DMOCAPLINK_RUN=${run}$<TARGET_FILE:mocaplink>"
          -DTEMPLATE=${PROJECT_SOURCE_DIR}/packaging/mocaplink.1.in -DVERSION=${PROJECT_VERSION}
          -DOUTPUT=${man_page} -P ${PROJECT_SOURCE_DIR}/packaging/manpage.cmake
  DEPENDS mocaplink ${PROJECT_SOURCE_DIR}/packaging/mocaplink.1.in
          ${PROJECT_SOURCE_DIR}/packaging/manpage.cmake ${PROJECT_SOURCE_DIR}/cmake/CliHelp.cmake
  COMMENT "Man page mocaplink.1 from mocaplink --help"
  VERBATIM)
add_custom_target(mocaplink_man_page ALL DEPENDS ${man_page})
install(FILES ${man_page} DESTINATION share/man/man1)

# The changelog: packaging/changelog in Debian's format, its newest entry this version. A package
# whose version has no Debian revision is a native one, whose changelog is changelog.gz (lintian:
# wrong-name-for-changelog-of-native-package for changelog.Debian.gz).
file(STRINGS ${PROJECT_SOURCE_DIR}/packaging/changelog changelog_top LIMIT_COUNT 1)
if(NOT changelog_top MATCHES "^mocaplink \\(${PROJECT_VERSION}\\) ")
  message(FATAL_ERROR "packaging/changelog starts with \"${changelog_top}\", not version "
                      "${PROJECT_VERSION}: add an entry for it")
endif()
set(changelog ${CMAKE_BINARY_DIR}/packaging/changelog.gz)
find_program(MOCAPLINK_GZIP gzip REQUIRED)
add_custom_command(
  OUTPUT ${changelog}
  COMMAND ${MOCAPLINK_GZIP} -9nc ${PROJECT_SOURCE_DIR}/packaging/changelog > ${changelog}
  DEPENDS ${PROJECT_SOURCE_DIR}/packaging/changelog
  COMMENT "changelog.gz")
add_custom_target(mocaplink_changelog ALL DEPENDS ${changelog})
install(FILES ${changelog} DESTINATION share/doc/mocaplink)

# Who makes the packages: a team address, not a person's. Whoever builds and distributes their own
# packages sets theirs (-DMOCAPLINK_DEB_MAINTAINER="Name <address>"). docs/packaging.md.
set(MOCAPLINK_DEB_MAINTAINER "mocaplink maintainers <maintainers@mocaplink.org>"
    CACHE STRING "Maintainer of the .deb: NAME <ADDRESS>")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME mocaplink)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
# The long description: lines of at most 79 characters (lintian), as Debian's policy wants them.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "mocaplink gives indoor PX4 and ArduPilot vehicles their position from a
motion-capture system. It reads poses from Vicon DataStream, Vicon Tracker's
UDP object stream, OptiTrack NatNet, Qualisys QTM RT and VRPN servers with its
own protocol clients (no vendor SDK), runs a Kalman filter per rigid body, and
sends each vehicle the MAVLink messages its autopilot fuses (ODOMETRY, or a
simulated GPS) over that vehicle's own UDP, TCP or serial link, with MAVLink 2
signing if configured.

The package runs it as a hardened systemd service with a web dashboard
(mocaplink.service, not started until enabled). It also records and replays
sessions, simulates a mocap system and emulates each protocol's server, so
everything can be tried without hardware.")
set(CPACK_PACKAGE_CONTACT "${MOCAPLINK_DEB_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/packages)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# /usr/bin/mocaplink without its symbol table; CMAKE_STRIP is the target's strip.
set(CPACK_STRIP_FILES ON)
if(MOCAPLINK_DEB_ARCH)  # set by cmake/toolchains/*.cmake
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${MOCAPLINK_DEB_ARCH})
endif()
# Depends: dpkg-shlibdeps on the binary, at cpack time (packaging/deb-depends.cmake), natively
# against this machine's installed libraries, cross against the target's packages that
# scripts/cross-sysroot laid out for it. CPack's own CPACK_DEBIAN_PACKAGE_SHLIBDEPS is not used:
# it knows no target packages, and passes --ignore-missing-info, which would drop a library
# silently.
set(CPACK_PROJECT_CONFIG_FILE ${PROJECT_SOURCE_DIR}/packaging/deb-depends.cmake)
set(CPACK_MOCAPLINK_BINARY ${CMAKE_BINARY_DIR}/mocaplink)  # apps/mocaplink puts it there
if(CMAKE_CROSSCOMPILING)
  set(CPACK_MOCAPLINK_TARGET_PACKAGES ${MOCAPLINK_CROSS_ROOT}/.debian)
endif()
include(CPack)
