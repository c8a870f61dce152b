// What the dashboard shows: a plain-value snapshot of the Station, its bodies and every vehicle's
// Sender, as GET /api/status and every /api/events message carry it (docs/api.md documents the
// JSON; status_json.hpp converts). The daemon fills one from its core snapshots (core_views.hpp
// helps with the Station part); the server adds the alerts (alerts.hpp).
//
// Units and frames are in the names. Optional fields are JSON null when unknown. Plain value types:
// copy them between threads freely.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/vehicle_state.hpp"

namespace mocaplink::web {

/// One rigid body as the Station and its Tracker see it.
struct BodyView {
  std::string name{};
  /// unseen / tracking / lost (core Tracker; LOST after loss_timeout_ms without a valid sample).
  core::TrackingState state = core::TrackingState::unseen;
  bool tracked = false;  ///< tracked in the latest mocap frame
  /// Untracked in the latest frame because the source's rotation was a reflection (a left-handed
  /// matrix): a mirrored frame no axis setting can fix (core StationBody::mirrored).
  bool mirrored = false;
  /// Last tracked position in the source's world frame (m), as `mocaplink bodies` prints it;
  /// null until the body was tracked once.
  std::optional<std::array<double, 3>> p_m{};
  /// Last tracked attitude (w, x, y, z), source world frame; null until tracked once.
  std::optional<std::array<double, 4>> q_wxyz{};
  std::uint64_t frames_tracked = 0;
  /// Samples the Tracker refused: gated outliers plus invalid input (NaN, non-unit quaternion,
  /// time going backwards). Cumulative.
  std::uint64_t rejected = 0;
  std::uint64_t resets = 0;  ///< pose jumps (ODOMETRY reset_counter increments)
};

/// The bridge's latency figures (ms): the latest frame's and percentiles of the latest frames.
struct BridgeLatencyView {
  double last = 0.0;
  double p50 = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};

/// The mocap source and its figures (core StationSnapshot).
struct StationView {
  std::string source{};        ///< source URL as configured ("sim://", "vicon://192.168.1.3")
  bool connected = false;      ///< frames are arriving / the connection is up
  std::string error{};         ///< last connection problem ("" when none), shown while disconnected
  double frame_rate_hz = 0.0;  ///< measured arrival rate over the last second
  std::optional<double> nominal_rate_hz{};  ///< the rate the source says it runs at
  std::optional<double> latency_ms{};       ///< latency reported by the source, when it reports one
  std::optional<double> jitter_ms{};        ///< std. dev. of receive − capture time
  std::uint64_t frames = 0;                 ///< frames received, cumulative
  std::uint64_t dropped = 0;                ///< frames missing from frame-number gaps, cumulative
  bool drops_counted = true;  ///< false: the source has no frame numbers (VRPN); `dropped` is null
  std::vector<BodyView> bodies{};  ///< in order of first appearance
  /// The bridge's own latency (a frame received → the last datagram it caused sent), over the
  /// latest frames (core::LatencyWindow); null until a frame was bridged.
  std::optional<BridgeLatencyView> bridge_latency_ms{};
  /// Frames the bridge reached more than 250 ms after they arrived, skipped rather than sent
  /// (core::LateFrames; an overloaded machine), cumulative.
  std::uint64_t late_frames_skipped = 0;
  /// Frames the bridge skipped because a newer frame with all their bodies was already waiting
  /// (core::LateFrames; a loop that is behind, short of CPU), cumulative.
  std::uint64_t superseded_frames = 0;
  /// Packets the source dropped unread (malformed, or from another sender than configured),
  /// cumulative, and why the latest was ("" if none, or the source does not say).
  std::uint64_t rejected = 0;
  std::string rejected_reason{};
};

/// How the bridge hears from a vehicle over its link, as the dashboard shows it (docs/api.md
/// `link.state`). Not a copy of a core type: it combines two owners' states — the vehicle's
/// heartbeat state (core::HeartbeatState waiting / alive / silent: alive → up, otherwise silent)
/// and the socket's (io::TransportState down or closed → down), which the core cannot know.
enum class LinkHealth {
  up,      ///< a message arrived within the last few seconds (the daemon's silence timeout)
  silent,  ///< sending, but nothing heard back (yet, or for longer than the timeout)
  down,    ///< the link cannot send (serial port gone, TCP disconnected, socket error)
};
[[nodiscard]] std::string_view to_string(LinkHealth state);

/// TIMESYNC with the vehicle (the vehicle's boot clock estimate).
enum class TimesyncState {
  off,      ///< the profile does not use TIMESYNC
  waiting,  ///< no exchange completed yet
  synced,   ///< offset estimated
};
[[nodiscard]] std::string_view to_string(TimesyncState state);

/// SET_GPS_GLOBAL_ORIGIN handshake: the core's state as is (not_needed, sending, confirmed,
/// conflict; core::to_string spells it for the JSON).
using OriginState = core::OriginState;

/// The agreement check: the vehicle's own ATTITUDE / LOCAL_POSITION_NED against the mocap estimate
/// (the core's verdict; core::to_string gives the API spelling).
using AgreementVerdict = core::AgreementVerdict;

/// The vehicle's HEARTBEAT as last received.
struct HeartbeatView {
  std::string type{};       ///< MAV_TYPE, readable ("quadrotor", or the number when unknown)
  std::string autopilot{};  ///< MAV_AUTOPILOT, readable ("px4", "ardupilotmega")
  bool armed = false;       ///< base_mode has MAV_MODE_FLAG_SAFETY_ARMED
  std::string mode{};       ///< flight mode, readable where the daemon can decode it
  double age_s = 0.0;       ///< seconds since it arrived, ≥ 0
};

struct TimesyncView {
  TimesyncState state = TimesyncState::off;
  std::optional<double> offset_ms{};  ///< vehicle clock − host clock
  std::optional<double> rtt_ms{};     ///< last round trip
};

/// The vehicle's clock against the host's (core::VehicleClockMonitor) and what PX4 does with our
/// poses' time stamps because of it.
struct ClockView {
  /// nullopt: not measured on this link (PX4 over uXRCE-DDS carries no TIMESYNC).
  std::optional<core::VehicleClockVerdict> verdict = core::VehicleClockVerdict::measuring;
  std::optional<double> rate_ppm{};     ///< vehicle rate − host rate, ppm
  std::optional<double> residual_ms{};  ///< largest window minimum off the fitted line
  /// PX4 only: "capture" (its time sync converts our capture times) or "arrival" (it stamps
  /// poses when they arrive: its clock is unsteady or still being measured); nullopt otherwise.
  std::optional<std::string> pose_stamps{};
  std::uint64_t withheld = 0;       ///< its TIMESYNC requests not answered
  std::uint64_t reset_answers = 0;  ///< answered a second off to reset PX4's filter
  std::string text;                 ///< core::vehicle_clock_text
};

/// The axis settings that make mocap agree with a disagreeing vehicle at rest (core::AxisFix).
struct AxisFixView {
  std::string kind;                            ///< "agrees", "fix", "mirror", "no_fit"
  std::vector<std::string> lines;              ///< `[mocap] up = "+z"`, ...
  std::vector<std::string> alternative_lines;  ///< an equally small other choice, if any
  double tilt_residual_deg = 0.0;
  std::optional<double> heading_residual_deg{};
  std::string text;
};

struct AgreementView {
  AgreementVerdict verdict = AgreementVerdict::unknown;
  std::optional<double> yaw_offset_deg{};  ///< vehicle yaw − mocap yaw, wrapped to (−180, 180]
  std::optional<double> position_offset_m{};  ///< |vehicle position − mocap position|, NED
  /// While the verdict is unknown: why, one sentence ("no ATTITUDE from the vehicle after
  /// asking: is this port's MAVLink enabled?"); null once there is a verdict.
  std::optional<std::string> reason{};
  /// Angle between the vehicle's gravity direction (its IMU's roll and pitch) and mocap's, deg.
  std::optional<double> tilt_offset_deg{};
  /// While the verdict is disagree: the fix (docs/api.md `agreement.fix`); null otherwise.
  std::optional<AxisFixView> fix{};
  /// The compass heading (ArduPilot's RAW_IMU, PX4's HIGHRES_IMU) − mocap yaw, where the vehicle's
  /// yaw is mocap's and it has a compass (estimate_sources.hpp); null otherwise.
  std::optional<double> heading_offset_deg{};
  /// What the comparison measured against something of the vehicle's own, in this order:
  /// "tilt" (always), "yaw", "position", "compass" (once compared); what came from mocap is
  /// missing.
  std::vector<std::string> checked{};
};

/// The vehicle's autopilot (core::VehicleSetup): "px4", "ardupilot", "other" or "unknown", and
/// its firmware version from AUTOPILOT_VERSION ("1.14.3"; null until it answers).
struct AutopilotView {
  std::string name = "unknown";
  std::optional<std::string> version{};
  std::string profile_in_effect{};  ///< the profile whose set-up rules apply
};

/// One line of the set-up check list (docs/api.md `setup.items`).
struct SetupItemView {
  std::string parameter{};  ///< "EKF2_EV_CTRL", or "profile"
  std::optional<double> current{};
  std::string needed{};    ///< as the operator reads it ("15 (horizontal ...)")
  std::string severity{};  ///< blocks | degrades | advice
  std::string status{};    ///< ok | wrong | missing | unread | unmeasured
  std::string why{};
  std::optional<double> fix{};  ///< what Apply writes (wrong items with a fix only)
  bool reboot = false;          ///< takes effect after a reboot
  std::string apply = "none";   ///< none | pending | confirmed | failed
  std::string apply_note{};
};

struct SetupView {
  /// waiting | identifying | reading | ready | blocked | no answer | unsupported | unavailable
  std::string state = "waiting";
  std::vector<SetupItemView> items{};
  std::vector<std::string> reboot_for{};  ///< confirmed changes waiting for a reboot
  std::string last_refusal{};
  std::string note{};  ///< why the list cannot be read on this link ("" if it can)
};

struct StatusTextView {
  std::string severity{};  ///< emergency ... debug
  std::string text{};
  double age_s = 0.0;
};

struct EstimatorView {
  std::string source{};  ///< EKF_STATUS_REPORT | ESTIMATOR_STATUS
  std::vector<std::string> good{};
  std::vector<std::string> problems{};
  double age_s = 0.0;
};

/// The delay recommendation (docs/api.md `delay_ms`).
struct DelayView {
  std::optional<double> measured{};
  std::optional<double> recommended{};
  std::string parameter{};
  std::optional<double> current{};
  std::string basis{};
};

/// One vehicle: its Sender (what we send) and its VehicleState (what it tells us).
/// A ground-station endpoint serving the vehicle (issue 38; docs/api.md "Ground stations").
struct GcsEndpointView {
  std::string url{};      ///< the endpoint, canonical ("udpin://:14550")
  std::string state{};    ///< its socket: connecting | up | down | closed (io::TransportState)
  std::size_t peers = 0;  ///< ground stations (system/component ids) heard within 5 s
  std::uint64_t frames_to_gcs = 0;    ///< vehicle frames sent to it, cumulative
  std::uint64_t frames_from_gcs = 0;  ///< frames its ground stations sent, cumulative
  std::uint64_t dropped = 0;   ///< frames toward it dropped (its socket down or backlog full)
  std::uint64_t no_route = 0;  ///< its frames addressed to no vehicle behind it, dropped
  /// its ground stations' TIMESYNC answers, never passed to a vehicle (core::GcsRouter)
  std::uint64_t timesync_answers = 0;
  std::uint64_t bad_frames = 0;  ///< bad CRC / flags / cut-off frames from it, dropped
};

/// The vehicle's link as shared by mocaplink's own traffic and its ground stations' (poses
/// first). Rates are bytes per second toward the vehicle over the last second or so.
struct LinkShareView {
  std::optional<double>
      capacity_bytes_per_s{};           ///< what the link carries (serial: baud / 10); else null
  double own_bytes_per_s = 0.0;         ///< mocaplink's own frames (poses, heartbeat, ...)
  double forwarded_bytes_per_s = 0.0;   ///< ground stations' frames
  std::uint64_t forwarded = 0;          ///< ground-station frames written, cumulative
  std::uint64_t forwarded_dropped = 0;  ///< ground-station frames dropped, cumulative
  std::size_t queued_bytes = 0;         ///< ground-station bytes waiting for their turn
};

struct VehicleView {
  std::string name{};
  std::string body{};          ///< mocap rigid body it follows
  std::string link{};          ///< link URL, canonical form
  std::uint8_t system_id = 1;  ///< 1..255
  std::string profile{};       ///< px4 | ardupilot | px4-gps | ardupilot-gps | classic | custom
  /// Pose messages being sent now (config spelling: "odometry", "hil_gps", ...).
  std::vector<std::string> messages{};
  /// Pose messages the dashboard offers as check boxes for this vehicle (at least `messages`).
  std::vector<std::string> available_messages{};
  double rate_hz = 0.0;  ///< configured pose rate, 0 < rate ≤ 500
  bool paused = false;   ///< true: no pose messages are sent (heartbeat continues)
  LinkHealth link_state = LinkHealth::silent;
  std::optional<double> last_heard_s{};  ///< seconds since anything arrived from the vehicle
  std::uint64_t sent_total = 0;          ///< every MAVLink frame sent to it, cumulative
  /// Frames sent per message name (MAVLink names, "ODOMETRY", "HEARTBEAT", ...), cumulative.
  std::map<std::string, std::uint64_t> sent{};
  /// Due pose sends per second (one per rate_hz slot, whatever messages it holds) over the last
  /// second, measured by the core (core::SenderSnapshot::send_rate_hz), comparable with rate_hz.
  double send_rate_hz = 0.0;
  std::optional<HeartbeatView> heartbeat{};  ///< null until the vehicle's first HEARTBEAT
  TimesyncView timesync{};
  ClockView clock{};
  OriginState origin = OriginState::not_needed;
  AgreementView agreement{};
  /// What the agreement check asked of the vehicle, per message it needs ("ATTITUDE",
  /// "LOCAL_POSITION_NED") → core::StreamState's spelling ("idle", "asking", "arriving", ...).
  std::map<std::string, std::string> streams{};
  /// Why the origin was never confirmed, once it is given up (origin state "unconfirmed").
  std::optional<std::string> origin_advice{};
  AutopilotView autopilot{};
  SetupView setup{};
  std::vector<StatusTextView> statustext{};  ///< the vehicle's last few, oldest first
  std::optional<EstimatorView> estimator{};
  DelayView delay_ms{};
  std::vector<GcsEndpointView> gcs{};  ///< its ground-station endpoints (empty: none configured)
  LinkShareView link_share{};
};

enum class AlertLevel { warning, error };
[[nodiscard]] std::string_view to_string(AlertLevel level);

/// A condition the operator should look at (see alerts.hpp for the rules).
struct Alert {
  AlertLevel level = AlertLevel::warning;
  /// body_lost | body_mirrored | vehicle_silent | link_down | origin_not_confirmed |
  /// origin_conflict | agreement_failing | drops_rising | source_disconnected | (daemon's own)
  std::string kind{};
  std::string subject{};  ///< the body or vehicle name, or "station"
  std::string message{};  ///< one readable sentence
};

/// The dashboard server's own connections (the server fills them in, not the daemon).
struct ConnectionsView {
  std::size_t open = 0;  ///< connections being served now (event streams included)
  /// Connections closed unread because their client address already held
  /// max_connections_per_client, cumulative.
  std::uint64_t refused = 0;
  /// Requests answered 408: not complete within the request deadline, cumulative.
  std::uint64_t timed_out = 0;
  /// Requests answered 403 because their Host is not a name of this dashboard (DNS rebinding,
  /// DashboardServerConfig::allowed_hosts), cumulative.
  std::uint64_t host_refused = 0;
};

/// One ROS 2 topic mocaplink publishes (docs/ros2.md).
struct Ros2TopicView {
  std::string name{};             ///< "/mocap/Quad1/pose"
  std::string type{};             ///< "geometry_msgs/msg/PoseStamped"
  std::uint32_t subscribers = 0;  ///< readers matched now
  std::uint64_t published = 0;    ///< samples written, cumulative
};

/// The [ros2] side: the participant and its topics.
struct Ros2View {
  bool running = false;  ///< the participant is up
  std::string error{};   ///< why not, or the latest write problem; "" when fine
  std::uint32_t domain_id = 0;
  std::string network_interface{};  ///< "all", "loopback" or an address
  std::string ns{};                 ///< the namespace of the body topics ("" = none)
  std::string frame_id{};           ///< the world frame
  std::string axes{};               ///< "enu_flu" or "mocap"
  std::string implementation{};     ///< "Fast DDS 2.9.1"
  std::vector<Ros2TopicView> topics{};
  std::uint64_t frames_published = 0;
  std::uint64_t frames_dropped = 0;  ///< the publishing thread was behind
  std::uint64_t write_errors = 0;
  std::vector<std::string> unnamed{};  ///< bodies with nothing to make a ROS name of
  std::vector<std::string> clashes{};  ///< "A (as B)": bodies whose ROS name another body has
};

/// Everything GET /api/status returns.
struct StatusView {
  double uptime_s = 0.0;  ///< seconds since the daemon started
  StationView station{};
  std::vector<VehicleView> vehicles{};
  std::vector<Alert> alerts{};     ///< the daemon's own; the server appends the derived ones
  ConnectionsView http{};          ///< the server's
  std::optional<Ros2View> ros2{};  ///< null without [ros2]
};

}  // namespace mocaplink::web
