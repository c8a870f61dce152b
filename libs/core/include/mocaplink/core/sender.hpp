// Sender: one per vehicle. Turns the vehicle's BodyEstimate on every mocap frame into the profile's
// messages at rate_hz, and emits the clock-driven ones (HEARTBEAT 1 Hz, SET_GPS_GLOBAL_ORIGIN ~1 Hz
// while the origin is unconfirmed, our TIMESYNC requests 1 Hz) on ticks. Pure: time is passed in.
//
// Decimation (DESIGN.md: sending is driven by mocap frames, decimated per vehicle to rate_hz,
// independent of the mocap rate): slots lie every 1/rate_hz on the source clock from the first
// frame; each frame claims the slot nearest to it (it may be up to half a source frame interval
// early, never more than half a period), so the output rate is min(rate_hz, source rate) exactly
// whatever the source's jitter or timestamp rounding (240 Hz from a 240 Hz source stamped in µs
// is 240 Hz, not every other frame). Slots advance by whole periods: a frame dropped by the source,
// a gap, or a mocap rate below rate_hz skips slots without a burst and without shifting the phase
// (50 Hz from 240 Hz frames: 500 sends in 10 s, with or without dropped frames). A source clock
// going backwards restarts the schedule at that frame; a rate change counts the new period from
// the last send and so takes effect on the next frame.
//
// What is sent when due (autopilots.md §12 "Common": never a stale pose):
//   pose messages (ODOMETRY, VISION_*, ATT_POS_MOCAP, LOCAL_POSITION_NED): only while
//     BodyEstimate::pose_valid() (tracking, and this frame measured or a bridged outlier);
//   GPS messages (HIL_GPS, GPS_INPUT): always, with fix_type 0 unless the body is tracking.
// Paused: no pose/GPS messages; HEARTBEAT, TIMESYNC and the origin continue.
//
// Every frame is MAVLink 2 from (system_id, component_id), with this Sender's own sequence counter
// (mavlink-wire.md §5) and signed when a key is configured (the signing timestamp comes from the
// caller: 10 µs units since 2015-01-01 UTC, mavlink-wire.md §7). Not thread-safe (one owner).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/frame_interval.hpp"
#include "mocaplink/core/geodesy.hpp"
#include "mocaplink/core/message_builders.hpp"
#include "mocaplink/core/message_table.hpp"
#include "mocaplink/core/profile.hpp"
#include "mocaplink/core/rate_window.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/messages.hpp"
#include "mocaplink/mavlink/sequence.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::core {

/// Largest accepted rate_hz: the one bound of every rate_hz check (config file, command line,
/// dashboard API, Bridge, Sender); their messages print this number.
inline constexpr double kMaxSenderRateHz = 500.0;
/// kMaxSenderRateHz as the messages print it ("500").
[[nodiscard]] std::string max_rate_text();
/// HEARTBEAT, SET_GPS_GLOBAL_ORIGIN and TIMESYNC request period (autopilots.md §3.9–§3.11).
inline constexpr Duration kHeartbeatPeriod = std::chrono::seconds(1);
inline constexpr Duration kOriginPeriod = std::chrono::seconds(1);
inline constexpr Duration kTimesyncRequestPeriod = std::chrono::seconds(1);
/// The window SenderSnapshot::send_rate_hz is measured over (the Station's frame rate uses 1 s
/// too).
inline constexpr Duration kSendRateWindow = std::chrono::seconds(1);

/// A due estimate with a non-finite value, a position beyond this (m) or a speed beyond
/// kMaxPlausibleSpeedMps is not sent at all (counted in SenderCounters::implausible): no mocap
/// arena is 1000 km wide, and it keeps every float/integer field conversion well defined.
inline constexpr double kMaxPlausiblePositionM = 1e6;
inline constexpr double kMaxPlausibleSpeedMps = 1e4;

/// One message ready for a vehicle's link: the typed message (for logs, the dashboard and tests)
/// and its encoded MAVLink 2 frame (what goes on the wire).
struct OutgoingMessage {
  std::size_t vehicle = 0;  ///< index of the vehicle (BridgeConfig::vehicles order)
  HostTime time{};          ///< host time the message was produced for (input time)
  mavlink::Message message;
  mavlink::Frame frame;
};

/// Static settings of a Sender.
struct SenderConfig {
  std::size_t vehicle = 0;                         ///< index stamped into OutgoingMessage
  std::uint8_t system_id = 1;                      ///< source sysid = the vehicle's (§9); 1..255
  std::uint8_t component_id = kVisionComponentId;  ///< 2..255 (never 1, the autopilot)
  MessageSet messages;                             ///< messages_for(profile, custom)
  double rate_hz = 50.0;                           ///< (0, kMaxSenderRateHz]
  std::optional<std::array<std::uint8_t, 32>> signing_key;  ///< MAVLink 2 signing secret
  std::uint8_t signing_link_id = 0;
};

/// Inputs of one due send besides the estimate.
struct SendContext {
  HostTime now{};                              ///< host time of the input (receive time)
  HostTime capture{};                          ///< host capture time of the estimate
  HostTime start{};                            ///< bridge start (LOCAL_POSITION_NED time_boot_ms)
  const LocalGeodeticFrame* origin = nullptr;  ///< required for HIL_GPS / GPS_INPUT
  GpsOptions gps;
  std::optional<GpsTime> gps_time;     ///< GPS time of `capture`, if the wall clock is known
  std::uint64_t signing_now_10us = 0;  ///< signing timestamp source (0 = unknown)
};

/// Counters since creation.
struct SenderCounters {
  std::array<std::uint64_t, kMessageKindCount> sent{};  ///< per MessageKind
  /// Due sends that sent something (one per rate_hz slot, however many messages the profile puts
  /// in it): what send_rate_hz counts, comparable with rate_hz.
  std::uint64_t poses = 0;
  std::uint64_t heartbeats = 0;
  std::uint64_t origins = 0;               ///< SET_GPS_GLOBAL_ORIGIN sent
  std::uint64_t origin_requests = 0;       ///< REQUEST_MESSAGE(GPS_GLOBAL_ORIGIN) sent
  std::uint64_t interval_requests = 0;     ///< SET_MESSAGE_INTERVAL sent (vehicle_streams.hpp)
  std::uint64_t data_stream_requests = 0;  ///< REQUEST_DATA_STREAM sent (vehicle_streams.hpp)
  std::uint64_t timesync_replies = 0;
  std::uint64_t timesync_requests = 0;
  std::uint64_t due_without_pose = 0;  ///< due slots skipped: pose not valid (lost, occluded)
  std::uint64_t implausible = 0;       ///< due slots skipped: non-finite or absurd state
  std::uint64_t frames = 0;            ///< frames encoded in total
  std::uint64_t bytes = 0;             ///< bytes encoded in total
};

/// Immutable view for the dashboard.
struct SenderSnapshot {
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  MessageSet messages;
  double rate_hz = 0.0;
  bool paused = false;
  bool signing = false;
  std::optional<HostTime> last_pose_sent;  ///< host time of the latest due send with a message
  /// Due sends with a message (SenderCounters::poses) per second over the kSendRateWindow before
  /// the snapshot's time (rate_window.hpp): the actual pose rate, whoever asks and whenever.
  double send_rate_hz = 0.0;
  SenderCounters counters;
};

class Sender {
 public:
  /// `config` must be valid (rate in range, component_id ≠ 0): a programming error aborts.
  explicit Sender(const SenderConfig& config);

  /// Called on every mocap frame with this vehicle's body estimate (after the Tracker ran). If a
  /// send is due, appends the due messages to `out`.
  void on_estimate(const BodyEstimate& estimate, const SendContext& context,
                   std::vector<OutgoingMessage>& out);

  /// Clock-driven messages at host time `now`: HEARTBEAT when due (the first tick sends at once);
  /// SET_GPS_GLOBAL_ORIGIN to `origin_target` when `origin` is non-null and due (every 3rd one is
  /// followed by a REQUEST_MESSAGE for GPS_GLOBAL_ORIGIN); a TIMESYNC request when
  /// `timesync_request` is true and due. Each once a second, in a phase of the second that
  /// follows the vehicle's slot (SenderConfig::vehicle; slot 0 at the first tick's phase): a
  /// thousand vehicles' heartbeats and requests spread over the second instead of leaving in
  /// one tick that holds every pose behind it (issue 50). The second of each comes up to a
  /// period later than one period after the first; after a stall, one at once and the next in
  /// phase at least a period later, never a burst.
  void on_tick(HostTime now, std::uint64_t signing_now_10us, const GeodeticPosition* origin,
               bool timesync_request, std::vector<OutgoingMessage>& out);

  /// Encodes any message with this Sender's identity and sequence (TIMESYNC replies, the
  /// requests of VehicleStreams, tests), counting TIMESYNC, SET_MESSAGE_INTERVAL and
  /// REQUEST_DATA_STREAM.
  void send(const mavlink::Message& message, HostTime now, std::uint64_t signing_now_10us,
            std::vector<OutgoingMessage>& out);

  /// Raises the signing timestamp so the next signed frame uses at least `timestamp_10us` + 1: a
  /// persisted value at start, or the timestamp of a correctly signed incoming frame
  /// (mavlink-wire.md §7.3). No effect without a signing key.
  void raise_signing_timestamp(std::uint64_t timestamp_10us) {
    if (signer_) signer_->observe(timestamp_10us);
  }

  // Runtime changes (the dashboard's controls). Take effect at the next frame.
  /// New rate in (0, kMaxSenderRateHz]; false (unchanged) otherwise. The next slot is one new
  /// period after the last send.
  bool set_rate_hz(double rate_hz);
  void set_messages(const MessageSet& messages) { config_.messages = messages; }
  void set_paused(bool paused) { paused_ = paused; }

  [[nodiscard]] const SenderConfig& config() const { return config_; }
  [[nodiscard]] bool paused() const { return paused_; }
  /// The figures as of host time `now` (send_rate_hz is measured up to it).
  [[nodiscard]] SenderSnapshot snapshot(HostTime now) const;
  /// The sequence number the next frame will carry.
  [[nodiscard]] std::uint8_t next_seq() const { return sequence_.peek_seq(); }

 private:
  bool due(SourceTime capture);
  void emit(const mavlink::Message& message, HostTime now, std::uint64_t signing_now_10us,
            std::vector<OutgoingMessage>& out);
  void emit_kind(MessageKind kind, const BodyEstimate& estimate, const SendContext& context,
                 std::vector<OutgoingMessage>& out);

  SenderConfig config_;
  Duration period_{};
  Duration phase_{};  ///< of the clock-driven messages in their period (on_tick)
  bool paused_ = false;
  mavlink::SequenceCounter sequence_;
  std::optional<mavlink::OutgoingSigner> signer_;
  std::optional<SourceTime> next_due_;
  std::optional<SourceTime> last_due_capture_;  ///< of the latest frame that claimed a slot
  FrameInterval frame_interval_;                ///< the source's, as observed; its latest frame
  std::optional<HostTime> next_heartbeat_;
  std::optional<HostTime> next_origin_;
  std::optional<HostTime> next_timesync_;
  std::optional<HostTime> last_pose_sent_;
  RateWindow pose_sends_{kSendRateWindow};  // host times of the due sends with a message
  SenderCounters counters_;
};

}  // namespace mocaplink::core
