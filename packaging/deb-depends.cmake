# cpack runs this (CPACK_PROJECT_CONFIG_FILE, set by cmake/Packaging.cmake) before it makes the
# .deb: Depends is what dpkg-shlibdeps computes for the binary, each library's package once, with
# the lowest version whose symbols the binary uses (from the packages' symbols files, else their
# shlibs files). The same command for every architecture; only where it finds the libraries'
# packages differs:
# - native (package preset): this machine's installed packages, through dpkg's database;
# - cross (cross-arm64, cross-armhf): CPACK_MOCAPLINK_TARGET_PACKAGES, where scripts/cross-sysroot
#   unpacked each of the target's library packages with its control files (dpkg-deb -R), given to
#   dpkg-shlibdeps as package build trees (-S); DEB_HOST_ARCH makes it read the target's ELF
#   files with the target's objdump and search the target's multiarch directories.
if(NOT CPACK_GENERATOR STREQUAL "DEB")
  return()
endif()
set(work ${CPACK_PACKAGE_DIRECTORY}/shlibdeps)
file(REMOVE_RECURSE ${work})
file(WRITE ${work}/debian/control "")  # dpkg-shlibdeps reads it; an empty one will do
# The binary where dpkg-shlibdeps expects it: in a package build tree (a folder with DEBIAN/).
file(MAKE_DIRECTORY ${work}/tree/DEBIAN)
file(COPY ${CPACK_MOCAPLINK_BINARY} DESTINATION ${work}/tree/usr/bin)
get_filename_component(binary ${CPACK_MOCAPLINK_BINARY} NAME)
set(options -O)
set(env LC_ALL=C)
if(CPACK_MOCAPLINK_TARGET_PACKAGES)
  list(APPEND env DEB_HOST_ARCH=${CPACK_DEBIAN_PACKAGE_ARCHITECTURE})
  file(GLOB trees LIST_DIRECTORIES true ${CPACK_MOCAPLINK_TARGET_PACKAGES}/*)
  if(NOT trees)
    message(FATAL_ERROR "No target packages in ${CPACK_MOCAPLINK_TARGET_PACKAGES}: run "
                        "scripts/setup --cross")
  endif()
  foreach(tree IN LISTS trees)
    list(APPEND options -S${tree})
  endforeach()
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env ${env} dpkg-shlibdeps ${options} tree/usr/bin/${binary}
  WORKING_DIRECTORY ${work}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT status EQUAL 0 OR NOT out MATCHES "^shlibs:Depends=(.+)$")
  message(FATAL_ERROR "dpkg-shlibdeps ${options} ${CPACK_MOCAPLINK_BINARY} failed (${status}):\n"
                      "${err}${out}")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${CMAKE_MATCH_1}")
if(err)
  message(WARNING "dpkg-shlibdeps: ${err}")
endif()
message(STATUS "Depends: ${CPACK_DEBIAN_PACKAGE_DEPENDS}")
file(REMOVE_RECURSE ${work})
