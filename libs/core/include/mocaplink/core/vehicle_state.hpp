// VehicleState: what one vehicle tells us back, from its decoded MAVLink messages with the host
// time they arrived (DESIGN.md data flow; protocols/autopilots.md §3.9–§3.11, §10 rule 4). Pure.
//
//   heartbeat   type, autopilot, armed (base_mode bit 7), custom_mode, system_status, last seen;
//               heartbeat state silent after kVehicleSilentAfter without one. Only heartbeats
//               from the vehicle's system id that are not a GCS (type 6) or a non-autopilot
//               component (autopilot 8 INVALID) count.
//   TIMESYNC    requests (tc1 == 0) from anyone → answered at once (the caller sends the reply),
//               except what the vehicle's own clock forbids (below); responses to our own requests
//               (ts1 equal to one we sent) → RTT and clock offset.
//   clock       the vehicle's own requests measure its clock against the host's, in a
//               VehicleClockMonitor. A PX4 (or a vehicle not yet heard) is answered while that
//               clock is steady, and while it is still being measured for at most
//               kTimesyncMeasuringAnswers answers (PX4 needs 500 to converge, so it cannot converge
//               on a clock not yet judged). Once the clock is unsteady its requests are no longer
//               answered, so PX4 never converges and stamps every pose on arrival, which is never
//               in its future; the first kTimesyncResetReplies answers after that verdict are a
//               second off on purpose, which makes a PX4 that had already converged reset its
//               filter (it resets after 5 consecutive samples over 100 ms off,
//               protocols/autopilots.md §3.10). ArduPilot does not use TIMESYNC for poses: it is
//               always answered.
//   origin      not_needed → (sending ⇄ mismatch) → confirmed | conflict. While sending, the
//               Sender emits SET_GPS_GLOBAL_ORIGIN ~1 Hz. A GPS_GLOBAL_ORIGIN from the vehicle
//               matching ours (|Δlat|, |Δlon| ≤ 1e-7 deg, |Δalt| ≤ 1 cm) confirms it: sending
//               stops. A different one from an ArduPilot vehicle (autopilot 3) is a conflict: its
//               EKF3 origin cannot change until reboot (§3.9), so sending stops and the operator is
//               told. From any other autopilot a mismatch keeps us sending (PX4 accepts a new
//               origin and answers again). Sending that the vehicle never confirms stops after
//               kOriginGiveUpAfter of heartbeats (unconfirmed): PX4 1.14 without GPS stores the
//               origin but never reports it (the set-up list explains it, vehicle_setup.hpp).
//               A matching GPS_GLOBAL_ORIGIN later still confirms it.
//   agreement   the vehicle's own ATTITUDE yaw and LOCAL_POSITION_NED against the mocap estimate
//               of its body at the message's arrival: yaw offset (deg, vehicle − mocap, wrapped to
//               (−180, 180]) and position offset (m, 3-D distance). Catches a wrong axis mapping,
//               a body not created nose-forward, or another vehicle's poses, before take-off.
//               Gravity is always independent (issue 48): both autopilots compute roll and
//               pitch from their IMU whatever they fuse, so each ATTITUDE's tilt is compared
//               with mocap's tilt of the body (axis_fix.hpp: the angle between the two gravity
//               directions in the body, yaw-free); beyond kMaxTiltOffsetDeg (15°) it disagrees,
//               as the other two do (a wrong `up` or `body_up` is 90° or 180° at rest). An
//               agreement needs the tilt.
//               Never an agreement of mocap with itself (issue 48): where the vehicle's yaw or
//               position comes from mocaplink (estimate_sources.hpp: EK3_SRC1_YAW = 6,
//               EKF2_EV_CTRL bits; the Bridge passes them in from the set-up list), that
//               comparison can still disagree (the vehicle does not follow our poses) but does
//               not make an agreement, and while the deciding parameter is not known the verdict
//               stays unknown rather than agree.
//               A second heading (issue 48): where the vehicle's yaw is mocap's but it has a
//               calibrated magnetometer (ArduPilot's field in RAW_IMU, PX4's in HIGHRES_IMU:
//               sources.heading independent), each ATTITUDE also compares mocap's yaw with the
//               latest field's heading, tilt-compensated with that ATTITUDE's roll and pitch
//               plus sources.declination_rad, received within kHeadingFresh (heading offset,
//               deg, compass − mocap); beyond
//               kMaxHeadingOffsetDeg (45°: a compass indoors is 10–30° off, a nose mistake 90°
//               or 180°) it disagrees like the others, and while such a heading is wanted an
//               agreement needs it too.
//               The verdict (docs/messages.md "Agreement"):
//                 agree     at once, when the tilt, yaw and position offsets are known and
//                           within the thresholds (default 15°, 10°, 0.3 m), both sources are
//                           known, and the heading offset too where there is such a heading;
//                 disagree  only once every comparison for kAgreementHold (3 s) was beyond a
//                           threshold: a vehicle's estimate jumps while its EKF aligns or resets
//                           (a false alarm makes pilots ignore the real one); until then unknown,
//                           with disagreeing_since set;
//                 unknown   before both offsets are known, during a hold, and while the vehicle is
//                           settling: a message stamped (time_boot_ms) in its first
//                           kAgreementSettle (15 s) of uptime is not compared, and clears the
//                           offsets — right after boot the estimate is not converged (issue 31:
//                           6–10 s of false disagreement from a vehicle booted with mocaplink on),
//                           and a reboot thus restarts the check. A vehicle that stamps every
//                           message 0 is never compared (the dashboard says it settles).
//               So a real mistake (a 90° mapping) is flagged kAgreementHold after the first
//               comparison, at the earliest kAgreementSettle + kAgreementHold after boot.
// Not thread-safe (one owner); snapshot() is a copy.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "mocaplink/core/axis_fix.hpp"
#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/estimate_sources.hpp"
#include "mocaplink/core/geodesy.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/core/vehicle_clock.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::core {

/// No heartbeat for this long → the vehicle's heartbeat state is silent.
inline constexpr Duration kVehicleSilentAfter = std::chrono::seconds(3);
/// SET_GPS_GLOBAL_ORIGIN sent this long to a vehicle whose heartbeat is alive without a matching
/// GPS_GLOBAL_ORIGIN: stop (OriginState::unconfirmed). 30 s is 30 tries at ~1 Hz; a vehicle that
/// takes the origin answers within a second.
inline constexpr Duration kOriginGiveUpAfter = std::chrono::seconds(30);
/// MAV_AUTOPILOT_ARDUPILOTMEGA and MAV_AUTOPILOT_PX4.
inline constexpr std::uint8_t kMavAutopilotArdupilot = 3;
inline constexpr std::uint8_t kMavAutopilotPx4 = 12;
/// While the vehicle's clock is measured, at most this many of its TIMESYNC requests are answered:
/// below the 500 accepted samples after which PX4's filter converges (autopilots.md §3.10).
inline constexpr std::uint64_t kTimesyncMeasuringAnswers = 400;
/// PX4's time sync converges after this many accepted answers (CONVERGENCE_WINDOW, §3.10): until
/// then it stamps poses on arrival, whatever we answer.
inline constexpr std::uint64_t kPx4TimesyncConvergence = 500;
/// Answers sent a second off once a PX4's clock is unsteady: PX4 resets its filter after more than
/// 5 consecutive samples (with a round trip under 10 ms) over 100 ms from its estimate; 20 leave
/// room for requests whose round trip is too long to count.
inline constexpr std::uint64_t kTimesyncResetReplies = 20;
inline constexpr Duration kTimesyncResetOffset = std::chrono::seconds(1);
/// MAV_MODE_FLAG_SAFETY_ARMED.
inline constexpr std::uint8_t kMavModeFlagSafetyArmed = 128;

/// A decoded message from a vehicle's link, with the sender's ids from the frame header.
struct ReceivedMessage {
  std::uint8_t sysid = 0;
  std::uint8_t compid = 0;
  mavlink::Message message;
};

enum class HeartbeatState : std::uint8_t {
  waiting,  ///< no heartbeat from the vehicle yet
  alive,    ///< heartbeat within kVehicleSilentAfter
  silent,   ///< heard before, nothing for kVehicleSilentAfter
};
[[nodiscard]] std::string_view to_string(HeartbeatState state);

enum class OriginState : std::uint8_t {
  not_needed,   ///< this vehicle's profile does not set the origin (or none is configured)
  sending,      ///< SET_GPS_GLOBAL_ORIGIN ~1 Hz until the vehicle reports ours
  confirmed,    ///< the vehicle reported our origin; nothing more is sent
  conflict,     ///< ArduPilot reported another origin: cannot change until reboot; stopped
  unconfirmed,  ///< sent for kOriginGiveUpAfter, never confirmed: stopped (the list says why)
  withheld,     ///< never sent this boot: a PX4 before 1.15 (setup_rules.hpp origin_gate)
};
[[nodiscard]] std::string_view to_string(OriginState state);

/// The only verdict type: the dashboard API shows it as is (docs/api.md `agreement.verdict`).
enum class AgreementVerdict : std::uint8_t {
  unknown,   ///< not both a vehicle estimate and a tracked mocap estimate yet
  agree,     ///< within both thresholds
  disagree,  ///< yaw or position beyond its threshold (wrong axis mapping, wrong body...)
};
/// "unknown", "agree", "disagree": the API's spellings (docs/api.md).
[[nodiscard]] std::string_view to_string(AgreementVerdict verdict);

/// The vehicle's estimate in its first this much uptime (time_boot_ms) is not compared: its EKF
/// is still aligning (6–10 s of false disagreement seen after boot, issue 31; 15 s for margin).
inline constexpr Duration kAgreementSettle = std::chrono::seconds(15);
/// A disagreement becomes the verdict once it has lasted this long, every comparison beyond a
/// threshold: longer than an estimator's reset transient, short enough to be told before take-off.
inline constexpr Duration kAgreementHold = std::chrono::seconds(3);
/// A compass field (RAW_IMU, HIGHRES_IMU) older than this at an ATTITUDE is not compared (asked
/// at 2 Hz: a second is one lost; a vehicle turned by hand moves some 30° in it, inside 45°).
inline constexpr Duration kHeadingFresh = std::chrono::seconds(1);

/// Thresholds of the agreement check (documented defaults; docs/messages.md "Agreement").
struct AgreementThresholds {
  double max_yaw_offset_deg = 10.0;  ///< ArduPilot's own VisOdom pre-arm yaw check uses 10° (§7)
  double max_tilt_offset_deg = kMaxTiltOffsetDeg;  ///< axis_fix.hpp: why 15°
  double max_position_offset_m = 0.3;
  double max_heading_offset_deg = kMaxHeadingOffsetDeg;  ///< axis_fix.hpp: why 45°
};

struct VehicleStateConfig {
  std::uint8_t system_id = 1;              ///< the vehicle's sysid (messages from others ignored
                                           ///< except TIMESYNC requests)
  std::optional<GeodeticPosition> origin;  ///< set when the profile sets the origin
  AgreementThresholds agreement;
};

/// Latest heartbeat of the vehicle.
struct VehicleHeartbeat {
  std::uint8_t compid = 0;
  std::uint8_t type = 0;       ///< MAV_TYPE
  std::uint8_t autopilot = 0;  ///< MAV_AUTOPILOT (3 ArduPilot, 12 PX4)
  std::uint8_t base_mode = 0;
  std::uint32_t custom_mode = 0;
  std::uint8_t system_status = 0;
  bool armed = false;  ///< base_mode & MAV_MODE_FLAG_SAFETY_ARMED
};

/// Clock relation from our TIMESYNC requests (autopilots.md §3.10).
struct TimesyncEstimate {
  std::int64_t offset_ns = 0;  ///< vehicle clock − host clock: tc1 − (ts1 + now) / 2
  std::int64_t rtt_ns = 0;     ///< round trip of the latest answered request
  std::uint64_t samples = 0;
};

struct Agreement {
  AgreementVerdict verdict = AgreementVerdict::unknown;
  std::optional<double> yaw_offset_deg;     ///< vehicle yaw − mocap yaw, (−180, 180]
  std::optional<double> position_offset_m;  ///< |p_vehicle − p_mocap|, m
  /// Angle between the vehicle's gravity direction (ATTITUDE roll, pitch) and mocap's, deg 0–180.
  std::optional<double> tilt_offset_deg;
  std::optional<HostTime> updated;
  /// The first comparison of the current run beyond a threshold (disagree once it has lasted
  /// kAgreementHold); nullopt when the latest comparison was within both.
  std::optional<HostTime> disagreeing_since;
  /// The vehicle's latest ATTITUDE / LOCAL_POSITION_NED came in its first kAgreementSettle of
  /// uptime: not compared (verdict unknown, offsets cleared).
  bool settling = false;
  /// Where the vehicle's yaw and position come from (the Bridge's set_estimate_sources).
  EstimateSources sources;
  /// The vehicle's latest ATTITUDE roll and pitch (rad) that was compared: its gravity.
  std::optional<double> roll_rad;
  std::optional<double> pitch_rad;
  std::optional<double> yaw_rad;  ///< its yaw: a heading of its own when sources.yaw is independent
  /// The compass heading − mocap yaw (deg, (−180, 180]) where sources.heading is independent.
  std::optional<double> heading_offset_deg;
  std::optional<double> heading_rad;  ///< the compass heading compared (rad, NED)
  /// While the verdict is disagree: the axis settings that make mocap agree with the vehicle at
  /// rest (the Bridge's set_axis_fix, axis_fix.hpp); cleared with the verdict.
  std::optional<AxisFix> fix;
};

struct VehicleCounters {
  std::uint64_t messages = 0;            ///< every message offered
  std::uint64_t from_other_systems = 0;  ///< sysid ≠ the vehicle's (ignored, TIMESYNC aside)
  std::uint64_t heartbeats = 0;
  std::uint64_t timesync_requests = 0;   ///< answered (reset answers included)
  std::uint64_t timesync_withheld = 0;   ///< the vehicle's own, not answered (its clock)
  std::uint64_t timesync_resets = 0;     ///< answered a second off to reset PX4's filter
  std::uint64_t timesync_responses = 0;  ///< to our requests
  std::uint64_t origin_reports = 0;      ///< GPS_GLOBAL_ORIGIN received
  std::uint64_t origin_mismatches = 0;
};

struct VehicleSnapshot {
  HeartbeatState link = HeartbeatState::waiting;
  std::optional<VehicleHeartbeat> heartbeat;
  std::optional<HostTime> last_heartbeat;
  std::optional<HostTime> last_message;
  OriginState origin = OriginState::not_needed;
  std::optional<GeodeticPosition> reported_origin;  ///< the vehicle's latest GPS_GLOBAL_ORIGIN
  std::optional<TimesyncEstimate> timesync;
  VehicleClockFigures clock;
  /// The vehicle places our poses at their capture time: it is a PX4 that we answer on a steady
  /// clock, and have answered kPx4TimesyncConvergence times this boot (so it may have converged:
  /// a round trip over 10 ms can still keep it from it). False: it stamps them on arrival
  /// (EKF2_EV_DELAY covers the whole delay).
  bool capture_stamps = false;
  Agreement agreement;
  VehicleCounters counters;
};

/// What a message asks of the caller.
struct VehicleReaction {
  std::optional<mavlink::Timesync> timesync_reply;  ///< send at once (built with our clock)
  bool origin_changed = false;                      ///< origin state changed (event)
  bool link_changed = false;                        ///< heartbeat state changed (event)
  bool agreement_changed = false;                   ///< verdict changed (event)
  bool clock_changed = false;                       ///< VehicleClockMonitor verdict changed (event)
};

class VehicleState {
 public:
  explicit VehicleState(VehicleStateConfig config);

  /// One decoded message that arrived at `now`. `mocap` is the vehicle's body estimate at `now`
  /// (nullptr if none); used by the agreement check only while it is tracking.
  VehicleReaction on_message(const ReceivedMessage& message, HostTime now,
                             const BodyEstimate* mocap);

  /// Time passes: updates the heartbeat state (alive → silent) and gives up an origin the vehicle
  /// never confirms (link_changed, origin_changed).
  VehicleReaction on_tick(HostTime now);

  /// The vehicle restarted (VehicleStreams saw its boot clock go back): the origin it had is gone
  /// with its estimator, so ours is sent again, whether it was confirmed, in conflict (the remedy
  /// the conflict advises) or given up; the origin it reported is forgotten (origin_changed). Its
  /// clock is measured afresh, and its time sync starts from nothing (clock_changed).
  VehicleReaction on_reboot();

  /// The origin must not go to this vehicle this boot (setup_rules.hpp origin_gate): a `sending`
  /// origin becomes `withheld` (origin_changed); a report of another origin leaves it so.
  VehicleReaction withhold_origin();

  /// Where the vehicle's yaw and position come from, from its set-up list's parameters (the
  /// Bridge, on every message and tick). A change re-judges the verdict (agreement_changed).
  VehicleReaction set_estimate_sources(const EstimateSources& sources, HostTime now);

  /// The Bridge's axis fix for the current disagreement (ignored unless the verdict is disagree).
  void set_axis_fix(AxisFix fix);
  /// The vehicle's yaw is mocap's and it has a calibrated compass (RAW_IMU, HIGHRES_IMU): asked
  /// for, compared.
  [[nodiscard]] bool heading_wanted() const;

  /// We sent a TIMESYNC request with ts1 = `ts1_ns` (kept to match the response; the latest 8).
  void on_timesync_request_sent(std::int64_t ts1_ns);

  /// Whether the vehicle places our poses at their capture time (VehicleSnapshot::capture_stamps).
  [[nodiscard]] bool capture_stamps() const;
  [[nodiscard]] const VehicleClockMonitor& clock() const { return clock_; }
  /// Whether the Sender should keep sending SET_GPS_GLOBAL_ORIGIN.
  [[nodiscard]] bool wants_origin() const { return origin_ == OriginState::sending; }
  [[nodiscard]] OriginState origin_state() const { return origin_; }
  /// A heartbeat from the vehicle was heard (ever, this session).
  [[nodiscard]] bool heard() const { return heartbeat_.has_value(); }
  /// MAV_AUTOPILOT of the latest heartbeat (0 before the first).
  [[nodiscard]] std::uint8_t autopilot() const { return heartbeat_ ? heartbeat_->autopilot : 0; }
  [[nodiscard]] HeartbeatState link_state() const { return link_; }
  [[nodiscard]] const Agreement& agreement() const { return agreement_; }
  [[nodiscard]] const VehicleStateConfig& config() const { return config_; }
  [[nodiscard]] VehicleSnapshot snapshot() const;

 private:
  void on_heartbeat(const ReceivedMessage& message, HostTime now, VehicleReaction& reaction);
  void on_timesync(const ReceivedMessage& message, HostTime now, VehicleReaction& reaction);
  /// The vehicle's own TIMESYNC request, stamped `ts1_ns`, arrived at `now`: measures its clock
  /// and returns the tc1 to answer with, or nullopt when it is not to be answered (header comment).
  std::optional<std::int64_t> answer_own_request(std::int64_t ts1_ns, HostTime now,
                                                 VehicleReaction& reaction);
  /// A new boot of the vehicle: nothing of its time sync is left (the answers' counts restart).
  void forget_time_sync();
  void on_origin(const mavlink::GpsGlobalOrigin& origin, VehicleReaction& reaction);
  void update_agreement(HostTime now, VehicleReaction& reaction);
  /// A vehicle estimate stamped `time_boot_ms` arrived: false (and the check reset) while the
  /// vehicle is settling.
  bool settled(std::uint32_t time_boot_ms, HostTime now, VehicleReaction& reaction);

  VehicleStateConfig config_;
  HeartbeatState link_ = HeartbeatState::waiting;
  OriginState origin_ = OriginState::not_needed;
  std::optional<VehicleHeartbeat> heartbeat_;
  std::optional<HostTime> last_heartbeat_;
  std::optional<HostTime> last_message_;
  std::optional<GeodeticPosition> reported_origin_;
  std::optional<HostTime> origin_since_;  ///< sending to a vehicle whose heartbeat is alive since
  std::optional<TimesyncEstimate> timesync_;
  VehicleClockMonitor clock_;
  std::uint64_t answered_this_boot_ = 0;  // of the vehicle's own requests
  std::uint64_t resets_this_boot_ = 0;
  std::array<std::int64_t, 8> pending_requests_{};
  std::size_t pending_next_ = 0;
  // Agreement inputs: latest vehicle yaw / position with the mocap estimate seen with each.
  std::optional<double> vehicle_yaw_offset_deg_;
  std::optional<double> vehicle_position_offset_m_;
  std::optional<double> vehicle_tilt_offset_deg_;
  std::optional<double> vehicle_heading_offset_deg_;
  /// Its latest magnetometer field (RAW_IMU milligauss, HIGHRES_IMU gauss), received at:
  std::optional<Eigen::Vector3d> mag_frd_;
  std::optional<HostTime> mag_received_;
  Agreement agreement_;
  VehicleCounters counters_;
};

/// A sentence for the log and the dashboard on a vehicle's clock verdict and what follows from it
/// for its poses' time stamps ("clock steady (+12 ppm ...)"); `autopilot` is its MAV_AUTOPILOT.
[[nodiscard]] std::string vehicle_clock_text(const VehicleClockFigures& clock,
                                             std::uint8_t autopilot);

/// The magnetic heading (rad, NED yaw) of a body measuring `field_frd` (any unit) while rolled
/// and pitched as given: the field turned level (Ry(pitch) · Rx(roll) · field), then
/// atan2(−y, x) — Earth's field points north and down, so a nose turned ψ east of it sees its
/// horizontal part at −ψ. NaN when the field has no horizontal part.
[[nodiscard]] double magnetic_heading_rad(const Eigen::Vector3d& field_frd, double roll_rad,
                                          double pitch_rad);

/// Wraps an angle in degrees to (−180, 180].
[[nodiscard]] double wrap_deg_180(double degrees);

}  // namespace mocaplink::core
