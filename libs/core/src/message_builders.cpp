// Message builders (message_builders.hpp). Field-by-field sources are in docs/messages.md; the
// autopilot facts behind each choice are cited from protocols/autopilots.md.
#include "mocaplink/core/message_builders.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

/// Rounds half away from zero and saturates into [lo, hi] (NaN → 0).
template <typename Int>
Int round_saturated(double value, double lo, double hi) {
  if (std::isnan(value)) return Int{0};
  return static_cast<Int>(std::clamp(std::round(value), lo, hi));
}

std::int16_t cm_per_s(double mps) {
  return round_saturated<std::int16_t>(mps * 100.0, std::numeric_limits<std::int16_t>::min(),
                                       std::numeric_limits<std::int16_t>::max());
}

/// Standard deviation from a variance, raised to `floor` (non-finite variances give the floor).
float accuracy(double variance, double floor) {
  const double sd = std::isfinite(variance) && variance > 0.0 ? std::sqrt(variance) : 0.0;
  return static_cast<float>(std::max(sd, floor));
}

/// x, y, z of a pose message from a vector (m or m/s), as float.
template <typename M>
void set_xyz(M& m, const Eigen::Vector3d& v) {
  m.x = static_cast<float>(v.x());
  m.y = static_cast<float>(v.y());
  m.z = static_cast<float>(v.z());
}

/// (w, x, y, z): MAVLink's quaternion order.
std::array<float, 4> wxyz(const Eigen::Quaterniond& q) {
  return {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
          static_cast<float>(q.z())};
}

struct GeoFields {
  std::int32_t lat_e7 = 0;
  std::int32_t lon_e7 = 0;
  double alt_m = 0.0;
};

GeoFields geodetic_fields(const BodyEstimate& estimate, const GpsContext& context) {
  assert(context.origin != nullptr && "GPS builders need an origin");
  const GeodeticPosition geo = context.origin->geodetic_from_ned(estimate.p_ned_m);
  return {deg_e7(geo.latitude_deg), deg_e7(geo.longitude_deg), geo.altitude_m};
}

}  // namespace

std::int32_t deg_e7(double degrees) {
  // ±180° × 1e7 = ±1.8e9 fits int32 (±2.147e9); anything beyond is saturated.
  return round_saturated<std::int32_t>(degrees * 1e7, std::numeric_limits<std::int32_t>::min(),
                                       std::numeric_limits<std::int32_t>::max());
}

std::uint16_t cog_cdeg(double vn_mps, double ve_mps, double min_speed_mps) {
  const double speed = std::hypot(vn_mps, ve_mps);
  if (!(speed >= min_speed_mps) || speed == 0.0) return kCogUnknown;
  const double cdeg = std::round(std::atan2(ve_mps, vn_mps) * kRadToDeg * 100.0);
  // atan2 ∈ [−180°, 180°]; wrap into [0, 36000) so that 359.996° rounds to 0, never 36000.
  const auto wrapped = std::fmod(std::fmod(cdeg, 36000.0) + 36000.0, 36000.0);
  return static_cast<std::uint16_t>(wrapped);
}

std::uint16_t gps_yaw_cdeg(double yaw_rad) {
  if (!std::isfinite(yaw_rad)) return 0;
  const double cdeg = std::round(yaw_rad * kRadToDeg * 100.0);
  const double wrapped = std::fmod(std::fmod(cdeg, 36000.0) + 36000.0, 36000.0);
  // GPS_INPUT yaw 0 means "no yaw": north is sent as 36000 (autopilots.md §3.5).
  return wrapped == 0.0 ? std::uint16_t{36000} : static_cast<std::uint16_t>(wrapped);
}

std::array<float, 21> covariance_upper_triangle(const Matrix6d& m) {
  std::array<float, 21> out{};
  std::size_t k = 0;
  for (Eigen::Index row = 0; row < 6; ++row) {
    for (Eigen::Index col = row; col < 6; ++col) out[k++] = static_cast<float>(m(row, col));
  }
  return out;
}

std::int8_t odometry_quality(const BodyEstimate& estimate) {
  if (!estimate.pose_valid()) return 0;
  return estimate.last_outcome == SampleOutcome::rejected_outlier ? kQualityPredicted
                                                                  : kQualityFused;
}

mavlink::Odometry build_odometry(const BodyEstimate& estimate, std::uint64_t time_usec) {
  mavlink::Odometry m;
  m.time_usec = time_usec;
  set_xyz(m, estimate.p_ned_m);
  m.q = wxyz(estimate.q_ned_frd);
  // child_frame_id BODY_FRD: the velocity is expressed in body axes (§3.1; ArduPilot rotates it
  // back to NED with q).
  const Eigen::Vector3d v_frd = estimate.v_frd_mps();
  m.vx = static_cast<float>(v_frd.x());
  m.vy = static_cast<float>(v_frd.y());
  m.vz = static_cast<float>(v_frd.z());
  m.rollspeed = static_cast<float>(estimate.w_frd_radps.x());
  m.pitchspeed = static_cast<float>(estimate.w_frd_radps.y());
  m.yawspeed = static_cast<float>(estimate.w_frd_radps.z());
  m.pose_covariance = covariance_upper_triangle(estimate.pose_covariance);
  m.velocity_covariance = covariance_upper_triangle(estimate.velocity_covariance_frd());
  m.frame_id = kMavFrameLocalFrd;
  m.child_frame_id = kMavFrameBodyFrd;
  m.reset_counter = estimate.reset_counter;
  m.estimator_type = kMavEstimatorTypeVision;
  m.quality = odometry_quality(estimate);
  return m;
}

mavlink::VisionPositionEstimate build_vision_position_estimate(const BodyEstimate& estimate,
                                                               std::uint64_t time_usec) {
  mavlink::VisionPositionEstimate m;
  m.usec = time_usec;
  set_xyz(m, estimate.p_ned_m);
  const Euler321 e = euler_321_from_quaternion(estimate.q_ned_frd);
  m.roll = static_cast<float>(e.roll_rad);
  m.pitch = static_cast<float>(e.pitch_rad);
  m.yaw = static_cast<float>(e.yaw_rad);
  m.covariance = covariance_upper_triangle(estimate.pose_covariance);
  m.reset_counter = estimate.reset_counter;
  return m;
}

mavlink::VisionSpeedEstimate build_vision_speed_estimate(const BodyEstimate& estimate,
                                                         std::uint64_t time_usec) {
  mavlink::VisionSpeedEstimate m;
  m.usec = time_usec;
  set_xyz(m, estimate.v_ned_mps);
  std::size_t k = 0;
  for (Eigen::Index row = 0; row < 3; ++row) {
    for (Eigen::Index col = 0; col < 3; ++col) {
      m.covariance[k++] = static_cast<float>(estimate.velocity_covariance(row, col));
    }
  }
  m.reset_counter = estimate.reset_counter;
  return m;
}

mavlink::AttPosMocap build_att_pos_mocap(const BodyEstimate& estimate, std::uint64_t time_usec) {
  mavlink::AttPosMocap m;
  m.time_usec = time_usec;
  // w first (the original copied an x-first quaternion into these slots, §12.5).
  m.q = wxyz(estimate.q_ned_frd);
  set_xyz(m, estimate.p_ned_m);  // metres (the original sent millimetres)
  m.covariance.fill(0.0F);
  m.covariance[0] = std::numeric_limits<float>::quiet_NaN();  // "unknown" (§2)
  return m;
}

mavlink::LocalPositionNed build_local_position_ned(const BodyEstimate& estimate,
                                                   std::uint32_t time_boot_ms) {
  mavlink::LocalPositionNed m;
  m.time_boot_ms = time_boot_ms;
  set_xyz(m, estimate.p_ned_m);
  m.vx = static_cast<float>(estimate.v_ned_mps.x());
  m.vy = static_cast<float>(estimate.v_ned_mps.y());
  m.vz = static_cast<float>(estimate.v_ned_mps.z());
  return m;
}

mavlink::HilGps build_hil_gps(const BodyEstimate& estimate, std::uint64_t time_usec,
                              const GpsContext& context) {
  const GeoFields geo = geodetic_fields(estimate, context);
  mavlink::HilGps m;
  m.time_usec = time_usec;
  m.lat = geo.lat_e7;
  m.lon = geo.lon_e7;
  m.alt =
      round_saturated<std::int32_t>(geo.alt_m * 1000.0, std::numeric_limits<std::int32_t>::min(),
                                    std::numeric_limits<std::int32_t>::max());
  m.eph = context.options.eph_cm;
  m.epv = context.options.epv_cm;
  m.id = 0;
  m.yaw = 0;  // PX4 ignores HIL_GPS yaw, ArduPilot ≤ 4.5 reads none (§3.6)
  if (estimate.state == TrackingState::tracking) {
    const Eigen::Vector3d& v = estimate.v_ned_mps;
    m.vn = cm_per_s(v.x());
    m.ve = cm_per_s(v.y());
    m.vd = cm_per_s(v.z());
    m.vel = round_saturated<std::uint16_t>(std::hypot(v.x(), v.y()) * 100.0, 0.0, 65534.0);
    m.cog = cog_cdeg(v.x(), v.y(), context.options.min_cog_speed_mps);
    m.fix_type = kGpsFix3d;
    m.satellites_visible = context.options.satellites;
  } else {
    m.vel = 0;
    m.cog = kCogUnknown;
    m.fix_type = kGpsFixNone;
    m.satellites_visible = 0;
  }
  return m;
}

mavlink::GpsInput build_gps_input(const BodyEstimate& estimate, std::uint64_t time_usec,
                                  const GpsContext& context) {
  const GeoFields geo = geodetic_fields(estimate, context);
  mavlink::GpsInput m;
  m.time_usec = time_usec;
  if (context.gps_time) {
    m.time_week = context.gps_time->week;
    m.time_week_ms = context.gps_time->week_ms;
  }
  m.lat = geo.lat_e7;
  m.lon = geo.lon_e7;
  m.alt = static_cast<float>(geo.alt_m);
  m.hdop = context.options.hdop;
  m.vdop = context.options.vdop;
  const Matrix6d& p = estimate.pose_covariance;
  const Matrix6d& v = estimate.velocity_covariance;
  m.horiz_accuracy = accuracy(p(0, 0) + p(1, 1), context.options.min_horizontal_accuracy_m);
  m.vert_accuracy = accuracy(p(2, 2), context.options.min_vertical_accuracy_m);
  m.speed_accuracy = accuracy(v(0, 0) + v(1, 1) + v(2, 2), context.options.min_speed_accuracy_mps);
  m.ignore_flags = 0;  // every field is meaningful (§3.5)
  m.gps_id = 0;        // must equal the GPS instance: GPS1 (§3.5)
  if (estimate.state == TrackingState::tracking) {
    m.vn = static_cast<float>(estimate.v_ned_mps.x());
    m.ve = static_cast<float>(estimate.v_ned_mps.y());
    m.vd = static_cast<float>(estimate.v_ned_mps.z());
    m.fix_type = kGpsFix3d;
    m.satellites_visible = context.options.satellites;
    m.yaw = gps_yaw_cdeg(euler_321_from_quaternion(estimate.q_ned_frd).yaw_rad);
  } else {
    m.fix_type = kGpsFixNone;
    m.satellites_visible = 0;
    m.yaw = 0;  // unknown
  }
  return m;
}

mavlink::SetGpsGlobalOrigin build_set_gps_global_origin(const GeodeticPosition& origin,
                                                        std::uint8_t target_system,
                                                        std::uint64_t time_usec) {
  mavlink::SetGpsGlobalOrigin m;
  m.latitude = deg_e7(origin.latitude_deg);
  m.longitude = deg_e7(origin.longitude_deg);
  m.altitude = round_saturated<std::int32_t>(origin.altitude_m * 1000.0,
                                             std::numeric_limits<std::int32_t>::min(),
                                             std::numeric_limits<std::int32_t>::max());
  m.target_system = target_system;
  m.time_usec = time_usec;
  return m;
}

mavlink::Heartbeat build_heartbeat() {
  mavlink::Heartbeat m;
  m.type = kMavTypeOnboardController;  // never GCS: PX4 would count us as its GCS (§3.11)
  m.autopilot = kMavAutopilotInvalid;
  m.base_mode = 0;
  m.custom_mode = 0;
  m.system_status = kMavStateActive;
  m.mavlink_version = 3;
  return m;
}

mavlink::Timesync build_timesync_reply(const mavlink::Timesync& request,
                                       std::uint8_t requester_sysid, std::uint8_t requester_compid,
                                       std::int64_t now_ns) {
  mavlink::Timesync m;
  m.tc1 = now_ns;  // the same steady clock as every time_usec we send (§4.3)
  m.ts1 = request.ts1;
  m.target_system = requester_sysid;
  m.target_component = requester_compid;
  return m;
}

mavlink::Timesync build_timesync_request(std::int64_t now_ns, std::uint8_t target_system,
                                         std::uint8_t target_component) {
  mavlink::Timesync m;
  m.tc1 = 0;
  m.ts1 = now_ns;
  m.target_system = target_system;
  m.target_component = target_component;
  return m;
}

mavlink::CommandLong build_request_gps_global_origin(std::uint8_t target_system,
                                                     std::uint8_t target_component) {
  mavlink::CommandLong m;
  m.command = 512;  // MAV_CMD_REQUEST_MESSAGE
  m.param1 = static_cast<float>(mavlink::GpsGlobalOrigin::kId);
  m.target_system = target_system;
  m.target_component = target_component;
  m.confirmation = 0;
  return m;
}

mavlink::CommandLong build_set_message_interval(std::uint32_t message_id, std::int32_t interval_us,
                                                std::uint8_t target_system,
                                                std::uint8_t target_component,
                                                std::uint8_t confirmation) {
  mavlink::CommandLong m;
  m.command = 511;  // MAV_CMD_SET_MESSAGE_INTERVAL
  m.param1 = static_cast<float>(message_id);
  m.param2 = static_cast<float>(interval_us);  // exact: |interval_us| < 2^24 for any rate ≥ 0.06 Hz
  m.target_system = target_system;
  m.target_component = target_component;
  m.confirmation = confirmation;
  return m;
}

mavlink::RequestDataStream build_request_data_stream(std::uint8_t stream_id, std::uint16_t rate_hz,
                                                     std::uint8_t target_system,
                                                     std::uint8_t target_component) {
  mavlink::RequestDataStream m;
  m.req_message_rate = rate_hz;
  m.target_system = target_system;
  m.target_component = target_component;
  m.req_stream_id = stream_id;
  m.start_stop = 1;
  return m;
}

}  // namespace mocaplink::core
