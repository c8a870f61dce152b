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
# the cross-arm64 / cross-armhf workflows for the Raspberry Pi. The .deb holds /usr/bin/mocaplink,
# /etc/mocaplink/mocaplink.toml (docs/examples/px4-quad.toml, a conffile), the systemd unit
# packaging/mocaplink.service and the README.
install(TARGETS mocaplink RUNTIME DESTINATION bin)
install(FILES ${PROJECT_SOURCE_DIR}/docs/examples/px4-quad.toml DESTINATION /etc/mocaplink
        RENAME mocaplink.toml)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/mocaplink.service DESTINATION lib/systemd/system)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/mocaplink)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME mocaplink)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "mocaplink maintainers <mocaplink@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/packages)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
if(MOCAPLINK_DEB_ARCH)  # set by cmake/toolchains/*.cmake
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${MOCAPLINK_DEB_ARCH})
endif()
# The Debian 12 packages of the shared libraries mocaplink links, on every architecture.
# scripts/check-deb compares this list with the binary's NEEDED entries; natively dpkg-shlibdeps
# adds the version constraints too.
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libc6, libstdc++6, libgcc-s1, libssl3, libfmt9, libspdlog1.10, libtomlplusplus3, libcpp-httplib0.11, libgeographiclib23")
if(NOT CMAKE_CROSSCOMPILING)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
endif()
include(CPack)
