// The receiving side of a VRPN connection, pure (vrpn.md §4, §6, §8): the server's id tables and
// the grouping of tracker reports into MocapFrames.
//
// ClientTables translates one connection's messages: sender (−1) and type (−2) descriptions fill
// `remote id → name` tables (ids are per connection: make a new one per connection); a message of
// the type named "vrpn_Tracker Pos_Quat" from a described sender becomes a Report. Every other
// message is ignored. At most kMaxIds names per table are kept, so a server cannot grow memory.
//
// FrameAssembler turns reports into frames, since VRPN has no frame number and no tracking flag:
//   - A round is the reports since the last frame. A report of a (tracker, sensor) already in the
//     round closes it (the next update has begun); so does a drained socket once the round holds
//     every key of the previous round. A round that lacks some of them when the socket drains (a
//     tracker reporting at a lower rate, a body no longer reported, a server stalled mid-round)
//     is closed `settle_after` after its last report if nothing more came: not held back until
//     the next update (one report period), nor until `lost_after`. Frames are numbered 1, 2, …
//     by the assembler (host-time frames; MocapFrame::frame_step = 0 tells the Station that gaps
//     mean nothing).
//   - Each frame comes with `received`: the host arrival time of its round's last report (for
//     the loss frame, the time it was made), so whoever judges a frame's age (the daemon's
//     core::LateFrames) sees how old its data is, however late the round was closed.
//   - capture_time is the host arrival time of the round's first report (as a SourceTime with the
//     host clock's epoch), smoothed by ArrivalClock with the step between the rounds' header
//     times (the server's wall clock), so that reports read in one burst keep their spacing.
//   - A body is in a frame when its tracker reported in the round; it is untracked when its pose
//     has been bit-identical for `frozen_after` (a real body never holds six doubles still).
//   - After `lost_after` without any report, one frame with every known body untracked goes out
//     (loss after silence), then nothing until reports resume.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/wire/arrival_clock.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace mocaplink::wire::vrpn {

/// Names kept per table (senders, types) and per connection.
inline constexpr std::size_t kMaxIds = 4096;

/// A Pos_Quat from a named tracker.
struct Report {
  std::string tracker;
  PosQuat pose;
  Timeval time;  ///< the server's wall clock (diagnostics only)
};

/// What one message did.
struct MessageOutcome {
  std::optional<Report> report;
  bool described = false;   ///< a sender or type description was stored
  bool over_limit = false;  ///< a description beyond kMaxIds, dropped
  bool unknown_id = false;  ///< a user message whose sender or type was never described
  std::string new_sender;   ///< a sender name described for the first time ("" if none)
};

class ClientTables {
 public:
  /// One message (header + unpadded payload). An error: a malformed description or Pos_Quat.
  [[nodiscard]] Result<MessageOutcome> apply(const Header& header,
                                             std::span<const std::byte> payload);
  /// Every sender name described so far, in order of description.
  [[nodiscard]] const std::vector<std::string>& senders() const { return sender_order_; }

 private:
  std::unordered_map<std::int32_t, std::string> senders_;
  std::unordered_map<std::int32_t, std::string> types_;
  std::vector<std::string> sender_order_;
};

/// The body name of a (tracker, sensor): the tracker's name for sensor 0, "NAME:N" for sensor N.
[[nodiscard]] std::string body_name(const std::string& tracker, std::int32_t sensor);

struct AssemblerConfig {
  core::Duration lost_after = std::chrono::milliseconds(500);
  /// An incomplete round found when the socket drained closes this long after its last report
  /// unless more reports came: a VRPN server writes one update's reports together (one
  /// send_pending_reports per mainloop), so a gap this long inside one update means a stalled
  /// or split write, not more of the round on the way.
  core::Duration settle_after = std::chrono::milliseconds(2);
  core::Duration frozen_after = std::chrono::milliseconds(0);  ///< 0: never
  std::size_t max_bodies = 1024;  ///< further (tracker, sensor) keys are ignored (counted)
};

/// A frame and the host time its data arrived (the FrameSink's `received`).
struct AssembledFrame {
  core::MocapFrame frame;
  core::HostTime received{};  ///< arrival of the round's last report; the loss frame: when made
};

class FrameAssembler {
 public:
  explicit FrameAssembler(AssemblerConfig config = {}) : config_(config) {}

  /// A report arrived at `arrival`; returns the frame its arrival closed, if any.
  [[nodiscard]] std::optional<AssembledFrame> on_report(const Report& report,
                                                        core::HostTime arrival);
  /// Every byte received so far has been read: returns the round as a frame if it is complete,
  /// else arms the settle deadline (idle_deadline).
  [[nodiscard]] std::optional<AssembledFrame> on_drained();
  /// Closes the round unconditionally (end of a connection): its frame, if it has reports.
  [[nodiscard]] std::optional<AssembledFrame> flush();
  /// A new connection: forgets the round, the bodies and their poses (frame numbers and the
  /// capture clock go on).
  void reset();
  /// Time passes without reports: the incomplete round `settle_after` after its last report
  /// (once the socket drained), and the all-untracked frame after `lost_after` of silence (once).
  [[nodiscard]] std::optional<AssembledFrame> on_idle(core::HostTime now);
  /// When on_idle should next be asked (nullopt: nothing pending).
  [[nodiscard]] std::optional<core::HostTime> idle_deadline() const;

  [[nodiscard]] std::uint64_t ignored_bodies() const { return ignored_bodies_; }
  [[nodiscard]] std::uint64_t frozen_samples() const { return frozen_samples_; }

 private:
  struct Known {
    std::string name;
    Eigen::Vector3d p_m;
    Eigen::Quaterniond q;
    core::HostTime changed{};  ///< last arrival with a different pose
  };
  struct Pending {
    std::size_t key = 0;
    bool tracked = true;
  };
  using Key = std::pair<std::string, std::int32_t>;
  AssembledFrame close_round();
  core::SourceTime next_capture(core::HostTime host, std::optional<Timeval> stamp);

  AssemblerConfig config_;
  std::map<Key, std::size_t> index_;
  std::vector<Known> known_;
  std::vector<Pending> round_;
  std::set<std::size_t> in_round_;
  std::set<std::size_t> previous_round_;
  std::optional<core::HostTime> round_start_;
  core::HostTime round_last_{};         // arrival of the round's last report
  bool settling_ = false;               // the socket drained with the round incomplete
  std::optional<Timeval> round_stamp_;  // header time of the round's first report
  std::optional<Timeval> last_stamp_;   // ... of the last frame's
  ArrivalClock clock_;
  std::optional<core::HostTime> last_report_;
  bool lost_sent_ = true;  ///< nothing to report lost until a report came
  std::uint64_t next_frame_ = 1;
  std::uint64_t ignored_bodies_ = 0;
  std::uint64_t frozen_samples_ = 0;
};

}  // namespace mocaplink::wire::vrpn
