# Debian arm64 (Raspberry Pi OS 64-bit): presets cross-arm64. See linux-cross.cmake.
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(MOCAPLINK_TRIPLET aarch64-linux-gnu)
set(MOCAPLINK_DEB_ARCH arm64)
set(MOCAPLINK_QEMU_NAME qemu-aarch64-static)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
