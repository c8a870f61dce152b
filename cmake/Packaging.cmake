# Install rules and the Debian package (issue 14): `cmake --workflow --preset package` for this
# machine's architecture, the cross-arm64 / cross-armhf workflows for the Raspberry Pi. The .deb
# holds /usr/bin/mocaplink, /etc/mocaplink/mocaplink.toml (docs/examples/px4-quad.toml, a
# conffile), the systemd unit packaging/mocaplink.service and the README.
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
    "libc6, libstdc++6, libgcc-s1, libfmt9, libspdlog1.10, libtomlplusplus3, libcpp-httplib0.11, libgeographiclib23")
if(NOT CMAKE_CROSSCOMPILING)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
endif()
include(CPack)
