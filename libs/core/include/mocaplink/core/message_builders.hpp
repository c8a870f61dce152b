// Message builders: pure functions BodyEstimate + context → one typed MAVLink message
// (protocols/autopilots.md §3, §12; every field, unit, frame and time base in docs/messages.md).
//
// Frames: the estimate's local NED (north = the configured mocap axis) is sent as is; the body
// frame is FRD; quaternions are w-first and rotate FRD vectors into NED. Times: `time_usec`
// arguments are host capture times in µs (sender_clock.hpp, host_time_usec). Builders never look at
// the tracking state except where a field encodes it (fix_type, yaw "unknown"); the Sender decides
// whether a message is sent at all. All functions are pure and thread-safe.
#pragma once

#include <cstdint>
#include <optional>

#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/geodesy.hpp"
#include "mocaplink/core/sender_clock.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::core {

/// MAV_FRAME_LOCAL_FRD and MAV_FRAME_BODY_FRD: the only ODOMETRY frame pair both PX4 and ArduPilot
/// accept (autopilots.md §2, §3.1).
inline constexpr std::uint8_t kMavFrameLocalFrd = 20;
inline constexpr std::uint8_t kMavFrameBodyFrd = 12;
/// MAV_ESTIMATOR_TYPE_VISION: PX4 routes MOCAP (6) away from EKF2 (§2).
inline constexpr std::uint8_t kMavEstimatorTypeVision = 2;
/// MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY: our default source component (§9).
inline constexpr std::uint8_t kVisionComponentId = 197;
/// MAV_TYPE_ONBOARD_CONTROLLER, MAV_AUTOPILOT_INVALID, MAV_STATE_ACTIVE (§3.11).
inline constexpr std::uint8_t kMavTypeOnboardController = 18;
inline constexpr std::uint8_t kMavAutopilotInvalid = 8;
inline constexpr std::uint8_t kMavStateActive = 4;
/// GPS_FIX_TYPE_NO_GPS and GPS_FIX_TYPE_3D_FIX.
inline constexpr std::uint8_t kGpsFixNone = 0;
inline constexpr std::uint8_t kGpsFix3d = 3;
/// HIL_GPS cog "unknown".
inline constexpr std::uint16_t kCogUnknown = 65535;

/// ODOMETRY.quality for a frame whose measurement was fused, and for one bridged by the prediction
/// over a gated outlier (BodyEstimate::pose_valid() is true for both).
inline constexpr std::int8_t kQualityFused = 100;
inline constexpr std::int8_t kQualityPredicted = 50;

/// Fake-GPS settings shared by HIL_GPS and GPS_INPUT (defaults documented in docs/messages.md and
/// chosen inside the ranges autopilots.md §3.5, §3.6, §12.3, §12.4 recommend).
struct GpsOptions {
  /// HIL_GPS eph / epv, cm (PX4 reads them as accuracy in cm, ArduPilot ≤ 4.5 as DOP × 100):
  /// 0.3 m passes PX4's EKF2_REQ_EPH (3 m) / EKF2_REQ_EPV (5 m) with a wide margin.
  std::uint16_t eph_cm = 30;
  std::uint16_t epv_cm = 30;
  /// satellites_visible while the body is tracked (0 while it is not): ≥ 10 per §12.3.
  std::uint8_t satellites = 12;
  /// GPS_INPUT hdop / vdop (§12.4: 0.5–1; EKF3 gate HDOP ≤ 2.5).
  float hdop = 0.5F;
  float vdop = 0.5F;
  /// GPS_INPUT accuracies are the filter's standard deviations, raised to these floors (m, m/s) so
  /// that a near-zero filter variance does not claim centimetre-free accuracy (§12.4).
  double min_horizontal_accuracy_m = 0.05;
  double min_vertical_accuracy_m = 0.05;
  double min_speed_accuracy_mps = 0.05;
  /// Horizontal speed below which HIL_GPS cog is 65535 "unknown" (§3.6, §12.3: ~0.2 m/s).
  double min_cog_speed_mps = 0.2;
};

/// Context of one fake-GPS message.
struct GpsContext {
  const LocalGeodeticFrame* origin = nullptr;  ///< required (non-null): NED → geodetic
  GpsOptions options;
  /// GPS time of the capture (GPS_INPUT only); nullopt = wall clock unknown → time_week 0,
  /// time_week_ms 0 (ArduPilot then stamps at arrival, §3.5).
  std::optional<GpsTime> gps_time;
};

/// Upper-right triangle of a symmetric 6×6 matrix, row-major, as MAVLink's 21-float covariance
/// arrays (diagonal at 0, 6, 11, 15, 18, 20; autopilots.md §2). Values as float.
[[nodiscard]] std::array<float, 21> covariance_upper_triangle(const Matrix6d& m);

/// The ODOMETRY.quality of an estimate: kQualityFused, kQualityPredicted, or 0 ("unknown") when
/// the pose is not valid (the Sender does not send it then).
[[nodiscard]] std::int8_t odometry_quality(const BodyEstimate& estimate);

/// ODOMETRY (331), autopilots.md §3.1 / §12.1: frame LOCAL_FRD, child BODY_FRD, estimator VISION;
/// x, y, z = p_ned_m; q = q_ned_frd (w, x, y, z); vx, vy, vz = velocity in body FRD (m/s);
/// rates = w_frd_radps; pose_covariance = upper triangle of pose_covariance; velocity_covariance =
/// upper triangle of velocity_covariance_frd(); reset_counter; quality = odometry_quality.
[[nodiscard]] mavlink::Odometry build_odometry(const BodyEstimate& estimate,
                                               std::uint64_t time_usec);

/// VISION_POSITION_ESTIMATE (102), §3.2: usec, x, y, z = p_ned_m; roll, pitch, yaw = Euler 3-2-1 of
/// q_ned_frd (rad); covariance = upper triangle of pose_covariance; reset_counter.
[[nodiscard]] mavlink::VisionPositionEstimate build_vision_position_estimate(
    const BodyEstimate& estimate, std::uint64_t time_usec);

/// VISION_SPEED_ESTIMATE (103), §3.3: usec; x, y, z = v_ned_mps (NED, m/s); covariance = the
/// linear-velocity 3×3 block of velocity_covariance, row-major (diagonal 0, 4, 8); reset_counter.
[[nodiscard]] mavlink::VisionSpeedEstimate build_vision_speed_estimate(const BodyEstimate& estimate,
                                                                       std::uint64_t time_usec);

/// ATT_POS_MOCAP (138), §3.4 / §12.5: time_usec; q = q_ned_frd (w, x, y, z); x, y, z = p_ned_m in
/// metres; covariance[0] = NaN ("unknown": ArduPilot ignores it), the rest 0.
[[nodiscard]] mavlink::AttPosMocap build_att_pos_mocap(const BodyEstimate& estimate,
                                                       std::uint64_t time_usec);

/// LOCAL_POSITION_NED (32), §3.8 / §12.5: time_boot_ms = ms since the bridge started (wraps at
/// 2^32); x, y, z = p_ned_m; vx, vy, vz = v_ned_mps.
[[nodiscard]] mavlink::LocalPositionNed build_local_position_ned(const BodyEstimate& estimate,
                                                                 std::uint32_t time_boot_ms);

/// HIL_GPS (113), §3.6 / §12.3. Tracked (state tracking): fix_type 3, satellites =
/// options.satellites; else fix_type 0, satellites 0, velocities 0, cog 65535 (the last position
/// is still filled in). lat/lon = geodetic position of p_ned_m in degE7, rounded half away from
/// zero; alt = altitude in mm, rounded; eph/epv = options; vn/ve/vd = v_ned_mps in cm/s, rounded,
/// saturated to int16; vel = horizontal speed in cm/s, rounded, saturated to 65534; cog =
/// atan2(ve, vn) in cdeg wrapped to [0, 35999], or 65535 below min_cog_speed_mps; id 0; yaw 0
/// (PX4 ignores HIL_GPS yaw and ArduPilot ≤ 4.5 reads none).
[[nodiscard]] mavlink::HilGps build_hil_gps(const BodyEstimate& estimate, std::uint64_t time_usec,
                                            const GpsContext& context);

/// GPS_INPUT (232), §3.5 / §12.4. Tracked: fix_type 3, satellites = options.satellites, yaw = Euler
/// yaw in cdeg with north sent as 36000 (wrapped to [1, 36000]); else fix_type 0, satellites 0,
/// yaw 0 ("unknown"), velocities 0. lat/lon degE7 rounded; alt m; hdop/vdop = options; vn/ve/vd =
/// v_ned_mps; horiz_accuracy = max(floor, sqrt(var_n + var_e)); vert_accuracy = max(floor,
/// sqrt(var_d)); speed_accuracy = max(floor, sqrt(var_vn + var_ve + var_vd)); ignore_flags 0;
/// gps_id 0; time_week / time_week_ms from context.gps_time.
[[nodiscard]] mavlink::GpsInput build_gps_input(const BodyEstimate& estimate,
                                                std::uint64_t time_usec, const GpsContext& context);

/// SET_GPS_GLOBAL_ORIGIN (48), §3.9: latitude/longitude degE7 rounded, altitude mm rounded (the
/// configured origin altitude, AMSL), target_system = the vehicle, time_usec = host µs now.
[[nodiscard]] mavlink::SetGpsGlobalOrigin build_set_gps_global_origin(
    const GeodeticPosition& origin, std::uint8_t target_system, std::uint64_t time_usec);

/// HEARTBEAT (0), §3.11: type ONBOARD_CONTROLLER 18, autopilot INVALID 8, base_mode 0,
/// custom_mode 0, system_status ACTIVE 4, mavlink_version 3.
[[nodiscard]] mavlink::Heartbeat build_heartbeat();

/// TIMESYNC (111) reply to a request (tc1 == 0), §3.10: tc1 = our steady clock in ns
/// (`now_ns`), ts1 = request.ts1, target_system / target_component = the requester's ids.
[[nodiscard]] mavlink::Timesync build_timesync_reply(const mavlink::Timesync& request,
                                                     std::uint8_t requester_sysid,
                                                     std::uint8_t requester_compid,
                                                     std::int64_t now_ns);

/// Our own TIMESYNC request: tc1 = 0, ts1 = our steady clock in ns, target = the vehicle.
[[nodiscard]] mavlink::Timesync build_timesync_request(std::int64_t now_ns,
                                                       std::uint8_t target_system,
                                                       std::uint8_t target_component);

/// COMMAND_LONG MAV_CMD_REQUEST_MESSAGE (512) asking for GPS_GLOBAL_ORIGIN (49) when the vehicle
/// has not answered our SET_GPS_GLOBAL_ORIGIN (§3.9).
[[nodiscard]] mavlink::CommandLong build_request_gps_global_origin(std::uint8_t target_system,
                                                                   std::uint8_t target_component);

/// COMMAND_LONG MAV_CMD_SET_MESSAGE_INTERVAL (511): param1 = `message_id`, param2 = `interval_us`
/// (µs between messages; common.xml: -1 stops it, 0 restores the default rate), param3..7 0,
/// `confirmation` 0 for the first transmission and incremented for each retransmission (MAVLink
/// "Command Protocol"). The agreement check asks for ATTITUDE and LOCAL_POSITION_NED with it
/// (vehicle_streams.hpp).
[[nodiscard]] mavlink::CommandLong build_set_message_interval(std::uint32_t message_id,
                                                              std::int32_t interval_us,
                                                              std::uint8_t target_system,
                                                              std::uint8_t target_component,
                                                              std::uint8_t confirmation);

/// REQUEST_DATA_STREAM (66, deprecated by common.xml but what ArduPilot's stream groups answer):
/// `stream_id` (MAV_DATA_STREAM: EXTRA1 = 10 carries ATTITUDE, POSITION = 6 LOCAL_POSITION_NED on
/// ArduPilot) at `rate_hz`, start_stop = 1. The fallback for an ArduPilot that refuses
/// SET_MESSAGE_INTERVAL (vehicle_streams.hpp).
[[nodiscard]] mavlink::RequestDataStream build_request_data_stream(std::uint8_t stream_id,
                                                                   std::uint16_t rate_hz,
                                                                   std::uint8_t target_system,
                                                                   std::uint8_t target_component);

// Field helpers, exposed for tests and docs/messages.md's worked example.

/// Degrees → degE7, rounded half away from zero (never truncated: the original truncated).
[[nodiscard]] std::int32_t deg_e7(double degrees);
/// Course over ground of a NED velocity in cdeg, [0, 35999] (atan2(ve, vn), 0 = north, 9000 =
/// east), or kCogUnknown when the horizontal speed is below `min_speed_mps`.
[[nodiscard]] std::uint16_t cog_cdeg(double vn_mps, double ve_mps, double min_speed_mps);
/// GPS_INPUT yaw of a heading in radians (0 = north, +π/2 = east): cdeg in [1, 36000], north =
/// 36000 (0 means "no yaw" on the wire).
[[nodiscard]] std::uint16_t gps_yaw_cdeg(double yaw_rad);

}  // namespace mocaplink::core
