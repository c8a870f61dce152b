// `mocaplink run --record DIR`: what the bridge saw and said, in formats other tools open.
//   DIR/mocap.csv      every mocap frame, DESIGN.md "Recording format" (replay://DIR/mocap.csv)
//   DIR/<vehicle>.tlog everything sent to and received from that vehicle, one .tlog record per
//                      MAVLink frame (io/tlog.hpp; MAVProxy, MAVExplorer, pymavlink read it)
// DIR is created if needed; files of an earlier recording with the same names are replaced. A
// vehicle added at run time gets its .tlog then; one removed has its .tlog closed, and when a
// vehicle of that name is added again in the same recording its records are appended.
// Files are written through user-space buffers, flushed by flush() (the daemon calls it every
// second) and on close(), so a clean stop leaves complete files and a crash loses at most about a
// second. Not thread-safe (event loop only).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/io/tlog.hpp"

namespace mocaplink::app {

class Recorder {
 public:
  /// Creates DIR and opens every file; `vehicles` are the names by vehicle slot. nullptr with
  /// `*problem` set on an I/O error.
  [[nodiscard]] static std::unique_ptr<Recorder> create(const std::filesystem::path& dir,
                                                        const std::string& source_url,
                                                        const std::vector<std::string>& vehicles,
                                                        std::string* problem);
  /// Opens the .tlog of a vehicle added at run time in `slot`. False with `*problem` set when the
  /// file cannot be opened (the vehicle then goes unrecorded; failed() says so).
  bool add_vehicle(std::size_t slot, const std::string& name, std::string* problem);
  /// Closes the .tlog of the vehicle in `slot` (removed at run time).
  void remove_vehicle(std::size_t slot);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// What the bridge did with a frame (core/late_frames.hpp).
  enum class FrameFate {
    sent,        ///< tracked, and its poses sent
    late,        ///< skipped: too old when the loop took it
    superseded,  ///< skipped: a newer frame with all its bodies was already waiting
  };
  /// One mocap frame, handed over at host time `received`. The format requires time_s never to
  /// decrease: a frame after which the source's clock started again (core::source_clock_restarted,
  /// the Bridge's own rule: back by more than restart_step_back, loss_timeout_ms, or ahead of the
  /// host's clock by more than a second) is a restart, and it and the frames after
  /// it are written on the old time line, `received` minus the last frame's `received` after the
  /// last frame — the outage as the Bridge measured it, so a replay's trackers see the gap the
  /// live ones bridged (issue 41); a smaller step back (a reordered frame, which the trackers
  /// refuse) is skipped and counted. A frame the bridge did not send is written as comment lines,
  /// each row after "#" and kLateComment or kSupersededComment: kept in the file, but replay://
  /// does not deliver it, so a replay sends what the live run sent.
  void on_frame(const core::MocapFrame& frame, core::HostTime received,
                FrameFate fate = FrameFate::sent);
  /// The step back that means a restart (default 250 ms, the default loss_timeout_ms).
  void set_restart_step_back(core::Duration step) { restart_step_back_ = step; }
  static constexpr std::string_view kLateComment = " late, not sent: ";
  static constexpr std::string_view kSupersededComment = " superseded, not sent: ";
  /// One MAVLink frame sent to or received from the vehicle in slot `vehicle`, at Unix time
  /// `unix_us`.
  void on_mavlink(std::size_t vehicle, std::int64_t unix_us, std::span<const std::uint8_t> bytes);
  void flush();
  /// Flushes and closes every file (idempotent; the destructor calls it).
  void close();

  [[nodiscard]] std::uint64_t frames_written() const noexcept { return frames_written_; }
  [[nodiscard]] std::uint64_t frames_skipped() const noexcept { return frames_skipped_; }
  /// Frames written as comments because the bridge did not send them (among frames_written()).
  [[nodiscard]] std::uint64_t frames_not_sent() const noexcept { return frames_not_sent_; }
  [[nodiscard]] bool failed() const noexcept;
  [[nodiscard]] const std::filesystem::path& dir() const noexcept { return dir_; }

 private:
  Recorder(std::filesystem::path dir, std::string source_url);
  void write_header(std::optional<double> rate_hz);

  std::filesystem::path dir_;
  std::string source_url_;
  std::FILE* csv_ = nullptr;
  bool csv_failed_ = false;
  bool header_written_ = false;
  std::optional<core::SourceTime> first_capture_;
  std::optional<core::SourceTime> last_capture_;  ///< on the recording's time line
  std::optional<core::HostTime> last_received_;
  core::Duration capture_offset_{};  ///< recording time line - source clock (after restarts)
  core::Duration restart_step_back_ = std::chrono::milliseconds(250);
  std::vector<std::unique_ptr<io::TlogWriter>> tlogs_;  // by vehicle slot; nullptr: none
  std::set<std::string> opened_;                        // names whose .tlog this recording made
  bool tlog_failed_ = false;                            // a closed or unopened .tlog failed
  std::uint64_t frames_written_ = 0;
  std::uint64_t frames_skipped_ = 0;
  std::uint64_t frames_not_sent_ = 0;
};

}  // namespace mocaplink::app
