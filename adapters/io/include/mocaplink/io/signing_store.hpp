// Persistence of each link's outgoing MAVLink signing timestamp (mavlink-wire.md §7.3): a
// receiver rejects a frame whose timestamp is not newer than the last one it accepted from that
// stream, so after a restart (or a wall-clock step backwards) the bridge must continue above the
// last value it used. One small text file per vehicle under a state directory, replaced
// atomically (write to a temporary file, fsync, rename), so a crash mid-write leaves the previous
// value intact.
//
// File format (UTF-8 text, one line, at most kMaxSigningFileBytes):
//   mocaplink-signing-timestamp 1 <decimal 10-µs units since 2015-01-01 UTC>\n
//
// Restoring: OutgoingSigner(key, link_id, stored) signs its first frame at max(now, stored + 1).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace mocaplink::io {

inline constexpr std::size_t kMaxSigningFileBytes = 128;

/// The file text for `timestamp_10us` (≤ 48 bits).
[[nodiscard]] std::string format_signing_timestamp(std::uint64_t timestamp_10us);

/// Parses a signing-timestamp file. nullopt (never throws) for anything but exactly the format
/// above with a value ≤ 2^48 − 1; a missing final newline is accepted. Pure; thread-safe.
[[nodiscard]] std::optional<std::uint64_t> parse_signing_timestamp(std::string_view text);

/// The default state directory: $MOCAPLINK_STATE_DIR if set, else $STATE_DIRECTORY (systemd's
/// StateDirectory=), else $XDG_STATE_HOME/mocaplink, else $HOME/.local/state/mocaplink, else
/// ".mocaplink-state" in the working directory.
[[nodiscard]] std::filesystem::path default_state_dir();

/// Loads and saves per-vehicle timestamps under one directory (created on first save).
/// Not thread-safe: one owner (the event loop).
class SigningStore {
 public:
  explicit SigningStore(std::filesystem::path dir) : dir_(std::move(dir)) {}

  /// The stored timestamp of `vehicle` (a config vehicle name, [A-Za-z0-9_.-]); nullopt when
  /// there is none. A file that exists but does not parse is reported in `*problem` (if given)
  /// and treated as absent.
  [[nodiscard]] std::optional<std::uint64_t> load(std::string_view vehicle,
                                                  std::string* problem = nullptr) const;

  /// Stores `timestamp_10us` for `vehicle`, atomically. False with `*problem` set on I/O errors.
  [[nodiscard]] bool save(std::string_view vehicle, std::uint64_t timestamp_10us,
                          std::string* problem = nullptr) const;

  [[nodiscard]] std::filesystem::path path_for(std::string_view vehicle) const;
  [[nodiscard]] const std::filesystem::path& dir() const noexcept { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace mocaplink::io
