// .tlog telemetry logs (the format MAVProxy, MAVExplorer, QGroundControl and pymavlink read):
// a plain concatenation of records, each an 8-byte big-endian Unix time in microseconds followed
// by one complete MAVLink frame exactly as it went over the wire. No header, no index: a file cut
// short by a crash is readable up to its last complete record.
//
// The time is the wall clock (io::unix_now_us): a log is read against other logs and flight
// records, not fed back into the control path.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace mocaplink::io {

/// The 8 bytes that precede a frame: `unix_us` big-endian (two's complement for the never-expected
/// negative times).
[[nodiscard]] std::array<std::uint8_t, 8> tlog_time_prefix(std::int64_t unix_us) noexcept;

/// Appends records to one .tlog file through a 64 KiB user-space buffer. Not thread-safe (one
/// owner, the event loop). I/O errors do not throw: they are counted, and after the first one the
/// writer stops writing (a half-written record would corrupt every later one).
class TlogWriter {
 public:
  enum class Mode { truncate, append };
  /// Creates (truncates) `path`, or with Mode::append opens it to add records after the ones it
  /// has (created when missing). On failure returns nullptr and sets `*problem`.
  [[nodiscard]] static std::unique_ptr<TlogWriter> create(const std::filesystem::path& path,
                                                          std::string* problem,
                                                          Mode mode = Mode::truncate);
  ~TlogWriter();
  TlogWriter(const TlogWriter&) = delete;
  TlogWriter& operator=(const TlogWriter&) = delete;

  /// One record: the time prefix and `frame` (one complete MAVLink frame, ≤ 280 bytes).
  void write(std::int64_t unix_us, std::span<const std::uint8_t> frame) noexcept;
  /// Pushes buffered records to the kernel (call periodically and before exit).
  void flush() noexcept;
  /// Flushes and closes; later writes are ignored. Idempotent; the destructor calls it.
  void close() noexcept;

  [[nodiscard]] std::uint64_t records() const noexcept { return records_; }
  [[nodiscard]] std::uint64_t bytes() const noexcept { return bytes_; }
  [[nodiscard]] bool failed() const noexcept { return failed_; }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

 private:
  TlogWriter(std::FILE* file, std::filesystem::path path);

  std::FILE* file_;
  std::filesystem::path path_;
  std::unique_ptr<char[]> buffer_;
  std::uint64_t records_ = 0;
  std::uint64_t bytes_ = 0;
  bool failed_ = false;
};

}  // namespace mocaplink::io
