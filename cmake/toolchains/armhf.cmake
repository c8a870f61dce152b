# Debian armhf (Raspberry Pi OS 32-bit, ARMv7 hard float): presets cross-armhf. See
# linux-cross.cmake. Built with the same 32-bit time_t ABI as Debian 12's armhf libraries it links
# (cpp-httplib's API takes time_t): mocaplink's own time values are std::chrono 64-bit counts, and
# tests/platform checks that none of them is narrowed on this target.
set(CMAKE_SYSTEM_PROCESSOR arm)
set(MOCAPLINK_TRIPLET arm-linux-gnueabihf)
set(MOCAPLINK_DEB_ARCH armhf)
set(MOCAPLINK_QEMU_NAME qemu-arm-static)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
# GCC notes on armhf that passing some std:: iterators "changed in GCC 7.1" (-Wpsabi): everything
# here is built by one compiler, GCC 12, so the note concerns no one and only buries real messages.
string(APPEND CMAKE_CXX_FLAGS_INIT " -Wno-psabi")
