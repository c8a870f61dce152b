// VehicleStreams: asks a vehicle for the two messages the agreement check compares, ATTITUDE (30)
// and LOCAL_POSITION_NED (32), when they do not arrive by themselves (issue 31), and for its
// estimator's health, which the set-up list shows in words (issue 28): EKF_STATUS_REPORT (193)
// from ArduPilot, ESTIMATOR_STATUS (230) from PX4, at 1 Hz; the estimator's is never asked of
// another autopilot. And, of a vehicle whose yaw comes from mocap but which has a compass, its
// magnetometer field: RAW_IMU (27) of ArduPilot, HIGHRES_IMU (105) of PX4 —
// the one reference for the nose left (estimate_sources.hpp, issue 48), at 2 Hz, asked only
// while the Bridge says it is wanted (StreamTarget::want_heading).
// Pure: time is passed in; one per vehicle, owned by the Bridge.
//
// Why: ArduCopter's default stream rates for EXTRA1 (ATTITUDE), POSITION (LOCAL_POSITION_NED) and
// EXTRA3 (EKF_STATUS_REPORT) are 0 on every port; it sends them on a link only when asked on that
// link. PX4's onboard mode streams ATTITUDE, not always LOCAL_POSITION_NED. Without them the
// agreement check never runs, and "PreArm: ... waiting for external nav" has no estimator flags
// beside it.
//
// Per message, per boot of the vehicle (states are StreamState):
//   idle      not asked. Nothing is asked before the vehicle's HEARTBEAT is heard (its sysid and
//             autopilot component are the target). A message that arrives within kStreamGrace
//             of the first heartbeat of this boot is never asked for: something (the vehicle's
//             defaults, a ground station) already set its rate, and we leave it alone.
//   asking    COMMAND_LONG MAV_CMD_SET_MESSAGE_INTERVAL(id, interval_us) to the autopilot,
//             every kCommandRetryPeriod until a COMMAND_ACK, at most kCommandAttempts times, with
//             confirmation 0, 1, 2, 3 (MAVLink "Command Protocol"). One such command in flight at
//             a time, ATTITUDE first: COMMAND_ACK does not say which message it is about.
//             ACK ACCEPTED → accepted. TEMPORARILY_REJECTED, IN_PROGRESS → the next attempt as
//             scheduled. Any other result (DENIED, UNSUPPORTED, FAILED...), or no ACK after the
//             last attempt → fallback on ArduPilot (autopilot 3), refused on anything else.
//   accepted  waiting for the message, at most kStreamAnswerTimeout.
//   fallback  REQUEST_DATA_STREAM (EXTRA1 for ATTITUDE, POSITION for LOCAL_POSITION_NED, EXTRA3
//             for EKF_STATUS_REPORT, RAW_SENSORS for RAW_IMU — the group's rate is the one asked
//             last) at the
//             message's rate, start_stop 1, sent kDataStreamAttempts
//             times kCommandRetryPeriod apart (it has no ACK) unless the message arrives; then
//             waiting kStreamAnswerTimeout.
//   arriving  the message arrives (whether asked or not).
//   refused   a vehicle that is not ArduPilot refused or never answered: not asked again this boot.
//   silent    asked (accepted, or fallback sent) but none arrived within kStreamAnswerTimeout: not
//             asked again this boot (the dashboard says why the agreement is unknown).
// A message that was arriving and stops for kStreamStaleAfter while the heartbeat is alive is
// asked for again (a new round).
//
// Reboot: rates set by SET_MESSAGE_INTERVAL or REQUEST_DATA_STREAM are lost when the vehicle
// restarts. Its boot clock going back by more than kRebootStepBack — time_boot_ms of ATTITUDE /
// LOCAL_POSITION_NED, or the vehicle's clock in TIMESYNC (tc1 of an answer, ts1 of its own
// request), each compared with its own kind, from the autopilot's component — means it rebooted:
// every message goes back to idle (a new grace period from then, then asked again). A HEARTBEAT
// carries no boot time, and its frame sequence wraps every 256 frames, so neither is used.
// (time_boot_ms wraps after 49.7 days of uptime: taken for a reboot, it costs one more round.)
//
// Never asked: any other message, any other rate (5 Hz for the agreement's two, 1 Hz for the
// estimator's). The events (log lines, in `notes`) are one per
// change of a round — asked, accepted, refused and what next, arriving after asking, silent,
// rebooted — never one per retransmission.
// Not thread-safe (one owner).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/core/time.hpp"
#include "mocaplink/core/vehicle_state.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::core {

/// The messages asked for.
enum class VehicleStream : std::uint8_t {
  attitude,            ///< ATTITUDE (30): yaw, for the agreement check
  local_position_ned,  ///< LOCAL_POSITION_NED (32): position, for the agreement check
  estimator,           ///< EKF_STATUS_REPORT (193, ArduPilot) / ESTIMATOR_STATUS (230, PX4)
  heading,  ///< RAW_IMU (27, ArduPilot) / HIGHRES_IMU (105, PX4): its compass, yaw from mocap
};
inline constexpr std::size_t kVehicleStreamCount = 4;
inline constexpr std::array<VehicleStream, kVehicleStreamCount> kVehicleStreams{
    VehicleStream::attitude, VehicleStream::local_position_ned, VehicleStream::estimator,
    VehicleStream::heading};
/// The two the agreement check compares (its reason names what is missing of them).
inline constexpr std::array<VehicleStream, 2> kAgreementStreams{VehicleStream::attitude,
                                                                VehicleStream::local_position_ned};
/// "ATTITUDE", "LOCAL_POSITION_NED"; the estimator's is "EKF_STATUS_REPORT" on ArduPilot
/// (`autopilot` 3), "ESTIMATOR_STATUS" on anything else; the heading's "HIGHRES_IMU" on PX4 (12),
/// "RAW_IMU" on anything else.
[[nodiscard]] std::string_view mavlink_name(VehicleStream stream, std::uint8_t autopilot = 0);
/// 30, 32; the estimator's 193 on ArduPilot, 230 on anything else; the heading's 105 on PX4, 27
/// on anything else.
[[nodiscard]] std::uint32_t message_id(VehicleStream stream, std::uint8_t autopilot = 0);
/// ArduPilot's stream group carrying it (MAV_DATA_STREAM): EXTRA1 = 10, POSITION = 6, EXTRA3 = 12,
/// RAW_SENSORS = 1.
[[nodiscard]] std::uint8_t data_stream_id(VehicleStream stream);
/// "EXTRA1", "POSITION", "EXTRA3" (the estimator's), "RAW_SENSORS" (RAW_IMU).
[[nodiscard]] std::string_view data_stream_name(VehicleStream stream);
/// Whether it is asked of this autopilot: the estimator's only of ArduPilot (3) and PX4 (12),
/// the heading's of both (and then only when wanted).
[[nodiscard]] bool asked_of(VehicleStream stream, std::uint8_t autopilot);

/// 5 Hz: a yaw or position check before take-off needs a fresh value, not a fast one (the
/// vehicle stands still); 5 Hz gives a verdict within 0.2 s of a change and costs 400 bytes/s
/// from the vehicle (2 × 40-byte frames), 7 % of a 57600-baud radio. ArduPilot's own GCS default
/// for these groups (MAVProxy, Mission Planner) is 4 Hz or more.
inline constexpr double kStreamRateHz = 5.0;
/// 1 Hz for the estimator's health: its flags change on a scale of seconds, and 1 Hz costs
/// 34 bytes/s (EKF_STATUS_REPORT) to 54 bytes/s (ESTIMATOR_STATUS), under 1 % of a 57600-baud
/// radio. ArduPilot's GCS defaults for EXTRA3 are 1-2 Hz, PX4's for ESTIMATOR_STATUS 0.5-1 Hz.
inline constexpr double kEstimatorRateHz = 1.0;
/// 2 Hz for the compass field (RAW_IMU, HIGHRES_IMU): a nose 90° off is a constant offset, and
/// two samples a second keep one within kHeadingFresh of every ATTITUDE with one lost; HIGHRES_IMU
/// is 75 bytes a frame, 150 bytes/s at 2 Hz (2.6 % of a 57600-baud radio; 375 at 5 Hz pushed a
/// px4 vehicle at 20 Hz over that radio's budget).
inline constexpr double kHeadingRateHz = 2.0;
/// kStreamRateHz, kEstimatorRateHz for the estimator's, kHeadingRateHz for the heading's.
[[nodiscard]] double rate_hz(VehicleStream stream);
/// SET_MESSAGE_INTERVAL's interval for rate_hz (µs, rounded): 200000, 1000000, 500000.
[[nodiscard]] std::int32_t interval_us(VehicleStream stream);
/// After the first heartbeat of a boot: a message arriving by then is not asked for.
inline constexpr Duration kStreamGrace = std::chrono::seconds(3);
/// A message that was arriving and has not for this long (heartbeat alive) is asked for again.
inline constexpr Duration kStreamStaleAfter = std::chrono::seconds(3);
/// Between retransmissions of SET_MESSAGE_INTERVAL (and of REQUEST_DATA_STREAM).
inline constexpr Duration kCommandRetryPeriod = std::chrono::seconds(1);
/// SET_MESSAGE_INTERVAL transmissions per round: confirmation 0..3.
inline constexpr std::uint8_t kCommandAttempts = 4;
/// REQUEST_DATA_STREAM transmissions per fallback (no ACK exists; a datagram may be lost).
inline constexpr std::uint8_t kDataStreamAttempts = 3;
/// After ACCEPTED or the last REQUEST_DATA_STREAM: the message must arrive within this.
inline constexpr Duration kStreamAnswerTimeout = std::chrono::seconds(5);
/// A boot clock going back more than this is a reboot (a reordered datagram is never this late).
inline constexpr Duration kRebootStepBack = std::chrono::seconds(2);

enum class StreamState : std::uint8_t {
  idle,      ///< not asked (no heartbeat yet, or within the grace period)
  asking,    ///< SET_MESSAGE_INTERVAL sent, waiting for its COMMAND_ACK
  accepted,  ///< the vehicle ACKed ACCEPTED; waiting for the message
  fallback,  ///< ArduPilot refused or never answered: REQUEST_DATA_STREAM sent
  arriving,  ///< the message arrives
  refused,   ///< refused or never answered (not ArduPilot): not asked again this boot
  silent,    ///< asked, accepted or fallen back, and still nothing: not asked again this boot
};
/// The API's spellings: "idle", "asking", "accepted", "fallback", "arriving", "refused", "silent".
[[nodiscard]] std::string_view to_string(StreamState state);

/// One message's request, as the dashboard shows it.
struct StreamStatus {
  StreamState state = StreamState::idle;
  bool asked = false;                      ///< asked for since the vehicle's (re)boot
  std::optional<std::uint8_t> ack_result;  ///< MAV_RESULT of the latest COMMAND_ACK this round
  std::uint8_t attempts = 0;               ///< SET_MESSAGE_INTERVAL sent this round
  std::uint8_t data_stream_requests = 0;   ///< REQUEST_DATA_STREAM sent this round
  std::optional<HostTime> last_seen;       ///< latest arrival of the message
};

/// Why a message asked for is not arriving, as one sentence for the dashboard and the log ("no
/// ATTITUDE from the vehicle after asking: is this port's MAVLink enabled?"); nullopt when it
/// arrives. `autopilot` names the estimator's message.
[[nodiscard]] std::optional<std::string> describe_missing(VehicleStream stream,
                                                          const StreamStatus& status,
                                                          std::uint8_t autopilot = 0);

struct VehicleStreamsSnapshot {
  std::array<StreamStatus, kVehicleStreamCount> streams{};  ///< by VehicleStream
  std::uint64_t reboots = 0;  ///< reboots detected (boot clock went back)
  [[nodiscard]] const StreamStatus& operator[](VehicleStream s) const {
    return streams[static_cast<std::size_t>(s)];
  }
};

/// The vehicle as its heartbeat describes it (from VehicleState), given on every tick.
struct StreamTarget {
  bool alive = false;          ///< a heartbeat from the vehicle within kVehicleSilentAfter
  std::uint8_t autopilot = 0;  ///< MAV_AUTOPILOT of that heartbeat (3 ArduPilot: fallback)
  std::uint8_t compid = 1;     ///< the heartbeat's component: the commands' target component
  /// The compass is wanted: the vehicle's yaw is mocap's and it has a calibrated compass (the
  /// agreement's sources). While false it is not asked for, and an unanswered request is not
  /// repeated.
  bool want_heading = false;
};

class VehicleStreams {
 public:
  /// `system_id`: the vehicle's (messages from others are ignored; it is also our source sysid);
  /// `component_id`: ours (a COMMAND_ACK addressed to another component is not ours).
  VehicleStreams(std::uint8_t system_id, std::uint8_t component_id);

  /// A message from the vehicle's link that arrived at `now`. Appends log lines to `notes`.
  void on_message(const ReceivedMessage& message, HostTime now, std::vector<std::string>& notes);

  /// Time passes (call about every 100 ms): appends what to send now (CommandLong,
  /// RequestDataStream) to `out` and log lines to `notes`.
  void on_tick(HostTime now, const StreamTarget& target, std::vector<mavlink::Message>& out,
               std::vector<std::string>& notes);

  [[nodiscard]] const StreamStatus& status(VehicleStream stream) const {
    return streams_[static_cast<std::size_t>(stream)].status;
  }
  [[nodiscard]] VehicleStreamsSnapshot snapshot() const;

 private:
  struct Stream {
    StreamStatus status;
    std::optional<HostTime> next_send;  ///< next SET_MESSAGE_INTERVAL / REQUEST_DATA_STREAM
    std::optional<HostTime> deadline;   ///< accepted / fallback: the message must arrive by then
  };
  Stream& at(VehicleStream s) { return streams_[static_cast<std::size_t>(s)]; }
  void arrived(VehicleStream s, HostTime now, std::vector<std::string>& notes);
  void on_ack(const mavlink::CommandAck& ack, HostTime now, std::vector<std::string>& notes);
  void give_up(VehicleStream s, HostTime now, std::vector<std::string>& notes);
  void boot_clock(std::optional<std::int64_t>& last_ms, std::int64_t now_ms, HostTime now,
                  std::vector<std::string>& notes);
  void tick_stream(VehicleStream s, HostTime now, std::vector<mavlink::Message>& out,
                   std::vector<std::string>& notes);
  void tick_command(HostTime now, std::vector<mavlink::Message>& out,
                    std::vector<std::string>& notes);

  std::uint8_t system_id_;
  std::uint8_t component_id_;
  StreamTarget target_{};
  std::optional<HostTime> alive_since_;     ///< first heartbeat of this boot (or since silence)
  std::optional<VehicleStream> in_flight_;  ///< the SET_MESSAGE_INTERVAL awaiting its ACK
  std::array<Stream, kVehicleStreamCount> streams_{};
  std::optional<std::int64_t> last_boot_ms_;      ///< time_boot_ms of ATTITUDE / LPN
  std::optional<std::int64_t> last_timesync_ms_;  ///< the vehicle's TIMESYNC clock
  std::uint64_t reboots_ = 0;
};

}  // namespace mocaplink::core
