// A text file that never grows past a size: when the next write would take it over `max_bytes`, it
// is renamed NAME.1.EXT (NAME.1 to NAME.2, …, up to `keep` old files; the oldest is deleted) and a
// new one is started. The daemon's log file on Windows (docs/daemon.md "Logs"), where there is no
// journal to keep what a closed console window loses. Paths go through io::open_file (UTF-16 on
// Windows) and std::filesystem, so any user name in %LOCALAPPDATA% works.
// Not thread-safe: one writer (the log sink serialises).
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace mocaplink::io {

class RotatingFile {
 public:
  /// Opens (creating its directory) `path` for appending. On failure ok() is false, error() says
  /// why, and write() does nothing.
  RotatingFile(std::filesystem::path path, std::size_t max_bytes, std::size_t keep);
  ~RotatingFile();
  RotatingFile(const RotatingFile&) = delete;
  RotatingFile& operator=(const RotatingFile&) = delete;

  [[nodiscard]] bool ok() const noexcept { return file_ != nullptr; }
  [[nodiscard]] const std::string& error() const noexcept { return error_; }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  /// The k-th older file (k ≥ 1): "mocaplink.log" → "mocaplink.1.log".
  [[nodiscard]] std::filesystem::path older(std::size_t k) const;

  /// Appends `text` (a whole line or more), rotating first when it would not fit. A line longer
  /// than max_bytes is written whole into a new file.
  void write(std::string_view text);
  void flush();

 private:
  void open(const char* mode);
  void rotate();

  std::filesystem::path path_;
  std::size_t max_bytes_;
  std::size_t keep_;
  std::FILE* file_ = nullptr;
  std::size_t size_ = 0;
  std::string error_;
};

}  // namespace mocaplink::io
