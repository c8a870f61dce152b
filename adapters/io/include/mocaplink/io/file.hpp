// std::fopen for a std::filesystem::path on every platform (Windows paths are UTF-16: a narrow
// fopen would mangle names outside the ANSI code page).
#pragma once

#include <cstdio>
#include <filesystem>

namespace mocaplink::io {

/// fopen(path, mode); mode is ASCII ("wb", "ab", "rb"). nullptr with errno set on failure.
[[nodiscard]] std::FILE* open_file(const std::filesystem::path& path, const char* mode);

}  // namespace mocaplink::io
