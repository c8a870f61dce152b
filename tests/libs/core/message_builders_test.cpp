// Message builders against hand-derived values (every field), golden frames from the reference
// implementations (/work/shared/mavlink/golden-vectors.json, copied below) and the wire layouts of
// mavlink-wire.md §6 (read back at the documented byte offsets, independently of our pack code).
#include "mocaplink/core/message_builders.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::core {
namespace {

constexpr double kPi = std::numbers::pi;

std::string hex(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (const auto b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0xF];
  }
  return out;
}

/// Little-endian value at `offset` of a MAVLink 2 frame's payload; bytes past the (truncated)
/// payload read as zero (mavlink-wire.md §3).
template <typename T>
T payload_at(const mavlink::Frame& frame, std::size_t offset) {
  const auto bytes = frame.bytes();
  const std::size_t len = bytes[1];
  std::array<std::uint8_t, sizeof(T)> raw{};
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    if (offset + i < len) raw[i] = bytes[10 + offset + i];
  }
  T value;
  std::memcpy(&value, raw.data(), sizeof(T));
  return value;
}

/// Nose east (yaw +90°), level: q = (cos 45°, 0, 0, sin 45°).
BodyEstimate sample_estimate() {
  BodyEstimate e;
  e.state = TrackingState::tracking;
  e.last_outcome = SampleOutcome::accepted;
  e.p_ned_m = {1.5, -2.25, -0.75};
  e.v_ned_mps = {0.3, 0.4, -0.1};
  e.q_ned_frd = Eigen::Quaterniond(std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5));
  e.w_frd_radps = {0.01, -0.02, 0.5};
  e.pose_covariance.diagonal() << 1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6;
  e.pose_covariance(0, 1) = e.pose_covariance(1, 0) = 1e-7;
  e.velocity_covariance.diagonal() << 1e-4, 2e-4, 3e-4, 0.01, 0.02, 0.03;
  e.reset_counter = 7;
  return e;
}

const GeodeticPosition kZurich{47.3977418, 8.5455938, 488.0};

// --- ODOMETRY -------------------------------------------------------------------------------

TEST(BuildersOdometry, EveryFieldHandDerived) {
  const auto m = build_odometry(sample_estimate(), 1'234'567);
  EXPECT_EQ(m.time_usec, 1'234'567U);
  EXPECT_EQ(m.x, 1.5F);
  EXPECT_EQ(m.y, -2.25F);
  EXPECT_EQ(m.z, -0.75F);
  EXPECT_FLOAT_EQ(m.q[0], 0.70710678F);  // w first
  EXPECT_EQ(m.q[1], 0.0F);
  EXPECT_EQ(m.q[2], 0.0F);
  EXPECT_FLOAT_EQ(m.q[3], 0.70710678F);
  // Nose east: forward = east (0.4 m/s), right = south (−north = −0.3 m/s), down = down.
  EXPECT_NEAR(m.vx, 0.4F, 1e-6F);
  EXPECT_NEAR(m.vy, -0.3F, 1e-6F);
  EXPECT_NEAR(m.vz, -0.1F, 1e-6F);
  EXPECT_FLOAT_EQ(m.rollspeed, 0.01F);
  EXPECT_FLOAT_EQ(m.pitchspeed, -0.02F);
  EXPECT_FLOAT_EQ(m.yawspeed, 0.5F);
  // Upper triangle, row-major: diagonal at 0, 6, 11, 15, 18, 20; (0,1) at index 1.
  const std::array<float, 21> pose{1e-6F, 1e-7F, 0, 0, 0,     0, 2e-6F, 0,     0, 0,    0,
                                   3e-6F, 0,     0, 0, 4e-6F, 0, 0,     5e-6F, 0, 6e-6F};
  for (std::size_t i = 0; i < 21; ++i) EXPECT_FLOAT_EQ(m.pose_covariance[i], pose[i]) << i;
  // Velocity covariance in body axes: forward = east (2e-4), right = south (1e-4), down (3e-4);
  // rates unchanged.
  EXPECT_NEAR(m.velocity_covariance[0], 2e-4F, 1e-10F);
  EXPECT_NEAR(m.velocity_covariance[6], 1e-4F, 1e-10F);
  EXPECT_NEAR(m.velocity_covariance[11], 3e-4F, 1e-10F);
  EXPECT_FLOAT_EQ(m.velocity_covariance[15], 0.01F);
  EXPECT_FLOAT_EQ(m.velocity_covariance[18], 0.02F);
  EXPECT_FLOAT_EQ(m.velocity_covariance[20], 0.03F);
  EXPECT_NEAR(m.velocity_covariance[1], 0.0F, 1e-12F);
  EXPECT_EQ(m.frame_id, 20);        // MAV_FRAME_LOCAL_FRD
  EXPECT_EQ(m.child_frame_id, 12);  // MAV_FRAME_BODY_FRD
  EXPECT_EQ(m.estimator_type, 2);   // MAV_ESTIMATOR_TYPE_VISION
  EXPECT_EQ(m.reset_counter, 7);
  EXPECT_EQ(m.quality, 100);
}

TEST(BuildersOdometry, QualityFollowsTheLastOutcome) {
  auto e = sample_estimate();
  e.last_outcome = SampleOutcome::rejected_outlier;  // prediction bridged an outlier
  EXPECT_EQ(build_odometry(e, 0).quality, 50);
  e.last_outcome = SampleOutcome::untracked;  // not valid: would not be sent; 0 = unknown
  EXPECT_EQ(build_odometry(e, 0).quality, 0);
}

TEST(BuildersOdometry, WireLayoutAtDocumentedOffsets) {
  const auto m = build_odometry(sample_estimate(), 0x0102030405060708ULL);
  const auto frame = mavlink::encode(m, {.seq = 3, .sysid = 1, .compid = 197});
  const auto b = frame.bytes();
  EXPECT_EQ(b[0], 0xFD);
  EXPECT_EQ(b[4], 3);    // seq
  EXPECT_EQ(b[5], 1);    // sysid
  EXPECT_EQ(b[6], 197);  // compid
  EXPECT_EQ(b[7] | (b[8] << 8) | (b[9] << 16), 331);
  EXPECT_EQ(payload_at<std::uint64_t>(frame, 0), 0x0102030405060708ULL);
  EXPECT_EQ(payload_at<float>(frame, 8), 1.5F);
  EXPECT_EQ(payload_at<float>(frame, 12), -2.25F);
  EXPECT_EQ(payload_at<float>(frame, 16), -0.75F);
  EXPECT_FLOAT_EQ(payload_at<float>(frame, 20), 0.70710678F);  // q[0] = w
  EXPECT_FLOAT_EQ(payload_at<float>(frame, 32), 0.70710678F);  // q[3] = z
  EXPECT_NEAR(payload_at<float>(frame, 36), 0.4F, 1e-6F);      // vx (FRD)
  EXPECT_FLOAT_EQ(payload_at<float>(frame, 56), 0.5F);         // yawspeed
  EXPECT_FLOAT_EQ(payload_at<float>(frame, 60), 1e-6F);        // pose_covariance[0]
  EXPECT_FLOAT_EQ(payload_at<float>(frame, 60 + 4 * 20), 6e-6F);
  EXPECT_EQ(payload_at<std::uint8_t>(frame, 228), 20);
  EXPECT_EQ(payload_at<std::uint8_t>(frame, 229), 12);
  EXPECT_EQ(payload_at<std::uint8_t>(frame, 230), 7);
  EXPECT_EQ(payload_at<std::uint8_t>(frame, 231), 2);
  EXPECT_EQ(payload_at<std::int8_t>(frame, 232), 100);
}

// --- VISION_POSITION_ESTIMATE / VISION_SPEED_ESTIMATE / ATT_POS_MOCAP / LOCAL_POSITION_NED
// --------

TEST(BuildersVisionPositionEstimate, EulerAnglesAndCovariance) {
  const auto m = build_vision_position_estimate(sample_estimate(), 42);
  EXPECT_EQ(m.usec, 42U);
  EXPECT_EQ(m.x, 1.5F);
  EXPECT_EQ(m.y, -2.25F);
  EXPECT_EQ(m.z, -0.75F);
  EXPECT_NEAR(m.roll, 0.0F, 1e-7F);
  EXPECT_NEAR(m.pitch, 0.0F, 1e-7F);
  EXPECT_FLOAT_EQ(m.yaw, static_cast<float>(kPi / 2));
  EXPECT_FLOAT_EQ(m.covariance[0], 1e-6F);
  EXPECT_FLOAT_EQ(m.covariance[20], 6e-6F);
  EXPECT_EQ(m.reset_counter, 7);
}

TEST(BuildersVisionPositionEstimate, YawAtPlusMinus180IsPi) {
  auto e = sample_estimate();
  e.q_ned_frd = Eigen::Quaterniond(0.0, 0.0, 0.0, 1.0);  // nose south
  EXPECT_FLOAT_EQ(build_vision_position_estimate(e, 0).yaw, static_cast<float>(kPi));
  e.q_ned_frd = Eigen::Quaterniond(0.0, 0.0, 0.0, -1.0);  // the same rotation, −q
  EXPECT_FLOAT_EQ(build_vision_position_estimate(e, 0).yaw, static_cast<float>(kPi));
}

TEST(BuildersVisionSpeedEstimate, NedVelocityAndThreeByThreeCovariance) {
  const auto m = build_vision_speed_estimate(sample_estimate(), 43);
  EXPECT_EQ(m.usec, 43U);
  EXPECT_FLOAT_EQ(m.x, 0.3F);
  EXPECT_FLOAT_EQ(m.y, 0.4F);
  EXPECT_FLOAT_EQ(m.z, -0.1F);
  const std::array<float, 9> cov{1e-4F, 0, 0, 0, 2e-4F, 0, 0, 0, 3e-4F};
  for (std::size_t i = 0; i < 9; ++i) EXPECT_FLOAT_EQ(m.covariance[i], cov[i]) << i;
  EXPECT_EQ(m.reset_counter, 7);
}

TEST(BuildersAttPosMocap, MetresAndWFirstQuaternion) {
  const auto m = build_att_pos_mocap(sample_estimate(), 44);
  EXPECT_EQ(m.time_usec, 44U);
  EXPECT_FLOAT_EQ(m.q[0], 0.70710678F);  // w
  EXPECT_EQ(m.q[1], 0.0F);
  EXPECT_EQ(m.q[2], 0.0F);
  EXPECT_FLOAT_EQ(m.q[3], 0.70710678F);
  EXPECT_EQ(m.x, 1.5F);  // metres, not the original's millimetres
  EXPECT_EQ(m.y, -2.25F);
  EXPECT_EQ(m.z, -0.75F);
  EXPECT_TRUE(std::isnan(m.covariance[0]));
  for (std::size_t i = 1; i < 21; ++i) EXPECT_EQ(m.covariance[i], 0.0F);
  // Wire: q at offset 8 (w first), x at 24.
  const auto frame = mavlink::encode(m, {.seq = 0, .sysid = 1, .compid = 197});
  EXPECT_FLOAT_EQ(payload_at<float>(frame, 8), 0.70710678F);
  EXPECT_EQ(payload_at<float>(frame, 24), 1.5F);
  EXPECT_TRUE(std::isnan(payload_at<float>(frame, 36)));
}

TEST(BuildersLocalPositionNed, TimeBootAndNedState) {
  const auto m = build_local_position_ned(sample_estimate(), 123'456);
  EXPECT_EQ(m.time_boot_ms, 123'456U);
  EXPECT_EQ(m.x, 1.5F);
  EXPECT_EQ(m.y, -2.25F);
  EXPECT_EQ(m.z, -0.75F);
  EXPECT_FLOAT_EQ(m.vx, 0.3F);
  EXPECT_FLOAT_EQ(m.vy, 0.4F);
  EXPECT_FLOAT_EQ(m.vz, -0.1F);
}

// --- Field helpers ----------------------------------------------------------------------------

TEST(BuildersFieldHelpers, DegE7RoundsInsteadOfTruncating) {
  EXPECT_EQ(deg_e7(47.39774187), 473977419);  // .7 rounds up (truncation gave ...418)
  EXPECT_EQ(deg_e7(47.39774182), 473977418);  // .2 rounds down
  EXPECT_EQ(deg_e7(-8.54559387), -85455939);  // away from zero for negatives
  EXPECT_EQ(deg_e7(-8.54559382), -85455938);
  EXPECT_EQ(deg_e7(0.0), 0);
  EXPECT_EQ(deg_e7(-0.0), 0);
  EXPECT_EQ(deg_e7(180.0), 1'800'000'000);
  EXPECT_EQ(deg_e7(-180.0), -1'800'000'000);
}

TEST(BuildersFieldHelpers, CourseOverGround) {
  EXPECT_EQ(cog_cdeg(0.3, 0.4, 0.2), 5313);     // atan2(0.4, 0.3) = 53.130°
  EXPECT_EQ(cog_cdeg(1.0, 0.0, 0.2), 0);        // north
  EXPECT_EQ(cog_cdeg(0.0, 1.0, 0.2), 9000);     // east
  EXPECT_EQ(cog_cdeg(0.0, -1.0, 0.2), 27000);   // west
  EXPECT_EQ(cog_cdeg(-1.0, 0.0, 0.2), 18000);   // south, +0 east
  EXPECT_EQ(cog_cdeg(-1.0, -0.0, 0.2), 18000);  // south, −0 east: atan2 gives −180°
  // 359.99°: ve = tan(−0.01°) → −1 cdeg → wraps to 35999.
  EXPECT_EQ(cog_cdeg(1.0, std::tan(-0.01 * kPi / 180.0), 0.2), 35999);
  // 359.996° rounds to 36000 cdeg, which is 0, never 36000.
  EXPECT_EQ(cog_cdeg(1.0, std::tan(-0.004 * kPi / 180.0), 0.2), 0);
  EXPECT_EQ(cog_cdeg(0.1, 0.1, 0.2), 65535);  // 0.14 m/s: nearly still → unknown
  EXPECT_EQ(cog_cdeg(0.0, 0.0, 0.2), 65535);
  EXPECT_EQ(cog_cdeg(0.0, 0.0, 0.0), 65535);  // no direction at all
}

TEST(BuildersFieldHelpers, GpsInputYawNorthIs36000) {
  EXPECT_EQ(gps_yaw_cdeg(0.0), 36000);
  EXPECT_EQ(gps_yaw_cdeg(-0.0), 36000);
  EXPECT_EQ(gps_yaw_cdeg(kPi / 2), 9000);
  EXPECT_EQ(gps_yaw_cdeg(-kPi / 2), 27000);
  EXPECT_EQ(gps_yaw_cdeg(kPi), 18000);
  EXPECT_EQ(gps_yaw_cdeg(-kPi), 18000);
  EXPECT_EQ(gps_yaw_cdeg(-0.004 * kPi / 180.0), 36000);  // rounds to north
  EXPECT_EQ(gps_yaw_cdeg(-0.01 * kPi / 180.0), 35999);
  EXPECT_EQ(gps_yaw_cdeg(0.01 * kPi / 180.0), 1);
  EXPECT_EQ(gps_yaw_cdeg(std::numeric_limits<double>::quiet_NaN()), 0);  // unknown
}

TEST(BuildersFieldHelpers, CovarianceUpperTriangleIndices) {
  Matrix6d m;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) m(r, c) = 10 * r + c;
  }
  const auto t = covariance_upper_triangle(m);
  const std::array<float, 21> expected{0,  1,  2,  3,  4,  5,  11, 12, 13, 14, 15,
                                       22, 23, 24, 25, 33, 34, 35, 44, 45, 55};
  EXPECT_EQ(t, expected);
}

// --- HIL_GPS / GPS_INPUT ----------------------------------------------------------------------

/// Independent small-offset geodesy (WGS84 radii of curvature), good to < 1e-9 deg over 10 m.
struct Expected {
  double lat_deg;
  double lon_deg;
};
Expected offset_geodetic(const GeodeticPosition& o, double north_m, double east_m) {
  const double a = 6378137.0;
  const double f = 1.0 / 298.257223563;
  const double e2 = f * (2 - f);
  const double phi = o.latitude_deg * kPi / 180.0;
  const double s = std::sin(phi);
  const double w = std::sqrt(1 - e2 * s * s);
  const double meridian = a * (1 - e2) / (w * w * w);
  const double normal = a / w;
  return {o.latitude_deg + north_m / meridian * 180.0 / kPi,
          o.longitude_deg + east_m / (normal * std::cos(phi)) * 180.0 / kPi};
}

GpsContext gps_context(const LocalGeodeticFrame& frame) {
  GpsContext c;
  c.origin = &frame;
  return c;
}

TEST(BuildersHilGps, EveryFieldHandDerived) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.p_ned_m = {3.0, -4.0, -1.2347};
  const auto m = build_hil_gps(e, 99, gps_context(*frame));
  const Expected x = offset_geodetic(kZurich, 3.0, -4.0);
  EXPECT_EQ(m.time_usec, 99U);
  EXPECT_EQ(m.lat, std::lround(x.lat_deg * 1e7));
  EXPECT_EQ(m.lon, std::lround(x.lon_deg * 1e7));
  EXPECT_EQ(m.alt, 489235);  // 488 m + 1.2347 m (+ 2 µm of curvature) in mm, rounded
  EXPECT_EQ(m.eph, 30);
  EXPECT_EQ(m.epv, 30);
  EXPECT_EQ(m.vel, 50);  // |(0.3, 0.4)| = 0.5 m/s
  EXPECT_EQ(m.vn, 30);
  EXPECT_EQ(m.ve, 40);
  EXPECT_EQ(m.vd, -10);
  EXPECT_EQ(m.cog, 5313);
  EXPECT_EQ(m.fix_type, 3);
  EXPECT_EQ(m.satellites_visible, 12);
  EXPECT_EQ(m.id, 0);
  EXPECT_EQ(m.yaw, 0);
}

TEST(BuildersHilGps, AtTheOriginMatchesTheGoldenVectorsPosition) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.p_ned_m.setZero();
  const auto m = build_hil_gps(e, 0, gps_context(*frame));
  EXPECT_EQ(m.lat, 473977418);  // golden vector hil_gps
  EXPECT_EQ(m.lon, 85455938);
  EXPECT_EQ(m.alt, 488000);
}

TEST(BuildersHilGps, LostBodyHasNoFix) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.state = TrackingState::lost;
  const auto m = build_hil_gps(e, 0, gps_context(*frame));
  EXPECT_EQ(m.fix_type, 0);
  EXPECT_EQ(m.satellites_visible, 0);
  EXPECT_EQ(m.cog, 65535);
  EXPECT_EQ(m.vel, 0);
  EXPECT_EQ(m.vn, 0);
  EXPECT_EQ(m.ve, 0);
  EXPECT_EQ(m.vd, 0);
}

TEST(BuildersHilGps, SlowAndSaturatedVelocities) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.v_ned_mps = {0.05, -0.1, 0.0};  // 0.11 m/s
  auto m = build_hil_gps(e, 0, gps_context(*frame));
  EXPECT_EQ(m.cog, 65535);
  EXPECT_EQ(m.vel, 11);
  EXPECT_EQ(m.vn, 5);
  EXPECT_EQ(m.ve, -10);
  e.v_ned_mps = {400.0, -400.0, 0.0};  // beyond int16 cm/s
  m = build_hil_gps(e, 0, gps_context(*frame));
  EXPECT_EQ(m.vn, 32767);
  EXPECT_EQ(m.ve, -32768);
  EXPECT_EQ(m.vel, 56569);
  EXPECT_EQ(m.cog, 31500);
}

TEST(BuildersGpsTimeTest, UnixToGpsWeek) {
  // 2023-11-14 22:13:20 UTC: GPS seconds 1 700 000 000 − 315 964 800 + 18 = 1 384 035 218 =
  // week 2288 (× 604 800 = 1 383 782 400) + 252 818 s.
  const auto t = gps_time_from_unix_us(1'700'000'000'000'000);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->week, 2288);
  EXPECT_EQ(t->week_ms, 252'818'000U);
  const auto epoch = gps_time_from_unix_us((315'964'800 - 18) * 1'000'000LL);
  ASSERT_TRUE(epoch);
  EXPECT_EQ(epoch->week, 0);
  EXPECT_EQ(epoch->week_ms, 0U);
  EXPECT_FALSE(gps_time_from_unix_us(0));
}

TEST(BuildersGpsInput, EveryFieldHandDerived) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.p_ned_m = {3.0, -4.0, -1.2347};
  e.pose_covariance.diagonal().head<3>() << 0.01, 0.03, 0.04;
  e.velocity_covariance.diagonal().head<3>() << 0.01, 0.02, 0.06;
  GpsContext c = gps_context(*frame);
  c.gps_time = GpsTime{2288, 252'818'000};
  const auto m = build_gps_input(e, 1'700'000'000'000'000, c);
  const Expected x = offset_geodetic(kZurich, 3.0, -4.0);
  EXPECT_EQ(m.time_usec, 1'700'000'000'000'000U);
  EXPECT_EQ(m.time_week, 2288);
  EXPECT_EQ(m.time_week_ms, 252'818'000U);
  EXPECT_EQ(m.lat, std::lround(x.lat_deg * 1e7));
  EXPECT_EQ(m.lon, std::lround(x.lon_deg * 1e7));
  EXPECT_NEAR(m.alt, 489.2347F, 1e-4F);
  EXPECT_FLOAT_EQ(m.hdop, 0.5F);
  EXPECT_FLOAT_EQ(m.vdop, 0.5F);
  EXPECT_FLOAT_EQ(m.vn, 0.3F);
  EXPECT_FLOAT_EQ(m.ve, 0.4F);
  EXPECT_FLOAT_EQ(m.vd, -0.1F);
  EXPECT_FLOAT_EQ(m.horiz_accuracy, 0.2F);  // sqrt(0.01 + 0.03)
  EXPECT_FLOAT_EQ(m.vert_accuracy, 0.2F);   // sqrt(0.04)
  EXPECT_FLOAT_EQ(m.speed_accuracy, 0.3F);  // sqrt(0.01 + 0.02 + 0.06)
  EXPECT_EQ(m.ignore_flags, 0);
  EXPECT_EQ(m.gps_id, 0);
  EXPECT_EQ(m.fix_type, 3);
  EXPECT_EQ(m.satellites_visible, 12);
  EXPECT_EQ(m.yaw, 9000);  // nose east
}

TEST(BuildersGpsInput, FloorsNorthYawAndLoss) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.q_ned_frd = Eigen::Quaterniond::Identity();  // nose north
  auto m = build_gps_input(e, 0, gps_context(*frame));
  EXPECT_EQ(m.yaw, 36000);    // north is 36000; 0 would mean "no yaw"
  EXPECT_EQ(m.time_week, 0);  // wall clock unknown
  EXPECT_EQ(m.time_week_ms, 0U);
  EXPECT_FLOAT_EQ(m.horiz_accuracy, 0.05F);  // tiny filter variance → floor
  EXPECT_FLOAT_EQ(m.vert_accuracy, 0.05F);
  EXPECT_FLOAT_EQ(m.speed_accuracy, 0.05F);
  e.q_ned_frd = Eigen::Quaterniond(0.0, 0.0, 0.0, 1.0);  // nose south: ±180°
  EXPECT_EQ(build_gps_input(e, 0, gps_context(*frame)).yaw, 18000);
  e.state = TrackingState::lost;
  m = build_gps_input(e, 0, gps_context(*frame));
  EXPECT_EQ(m.fix_type, 0);
  EXPECT_EQ(m.satellites_visible, 0);
  EXPECT_EQ(m.yaw, 0);
  EXPECT_EQ(m.vn, 0.0F);
}

TEST(BuildersGpsInput, YawExtensionOnTheWire) {
  const auto frame = LocalGeodeticFrame::make(kZurich);
  ASSERT_TRUE(frame);
  auto e = sample_estimate();
  e.p_ned_m.setZero();
  e.q_ned_frd = Eigen::Quaterniond::Identity();
  const auto f = mavlink::encode(build_gps_input(e, 0, gps_context(*frame)),
                                 {.seq = 0, .sysid = 1, .compid = 197});
  EXPECT_EQ(f.bytes()[1], 65);  // extension present: MAVLink 2 length with yaw
  EXPECT_EQ(payload_at<std::uint16_t>(f, 63), 36000);
  EXPECT_EQ(payload_at<std::int32_t>(f, 12), 473977418);
  EXPECT_EQ(payload_at<std::uint8_t>(f, 61), 3);
}

// --- Golden frames: byte-exact against the reference implementations -----------------------

TEST(BuildersGolden, Heartbeat) {
  const auto f = mavlink::encode(build_heartbeat(), {.seq = 0, .sysid = 1, .compid = 197});
  EXPECT_EQ(hex(f.bytes()), "fd0900000001c50000000000000012080004031ee4");
}

TEST(BuildersGolden, SetGpsGlobalOrigin) {
  const auto m = build_set_gps_global_origin(kZurich, 1, 1'700'000'000'000'000);
  EXPECT_EQ(m.latitude, 473977418);
  EXPECT_EQ(m.longitude, 85455938);
  EXPECT_EQ(m.altitude, 488000);
  EXPECT_EQ(m.target_system, 1);
  const auto f = mavlink::encode(m, {.seq = 8, .sysid = 1, .compid = 197});
  EXPECT_EQ(hex(f.bytes()), "fd1400000801c53000004a52401c42f41705407207000100401e18240a06c7a7");
}

TEST(BuildersGolden, TimesyncRequest) {
  const auto m = build_timesync_request(1'700'000'000'123'456'789, 1, 1);
  const auto f = mavlink::encode(m, {.seq = 9, .sysid = 1, .compid = 197});
  EXPECT_EQ(hex(f.bytes()), "fd1200000901c56f0000000000000000000015cd853dfe9c97170101051c");
}

TEST(BuildersTimesync, ReplyMirrorsTs1AndAddressesTheRequester) {
  mavlink::Timesync request;
  request.tc1 = 0;
  request.ts1 = 123'456'789'000;
  request.target_system = 0;
  const auto m = build_timesync_reply(request, 1, 1, 987'654'321'000);
  EXPECT_EQ(m.tc1, 987'654'321'000);
  EXPECT_EQ(m.ts1, 123'456'789'000);
  EXPECT_EQ(m.target_system, 1);
  EXPECT_EQ(m.target_component, 1);
}

TEST(BuildersHeartbeat, Fields) {
  const auto m = build_heartbeat();
  EXPECT_EQ(m.type, 18);
  EXPECT_EQ(m.autopilot, 8);
  EXPECT_EQ(m.base_mode, 0);
  EXPECT_EQ(m.custom_mode, 0U);
  EXPECT_EQ(m.system_status, 4);
  EXPECT_EQ(m.mavlink_version, 3);
}

TEST(BuildersRequestOrigin, CommandLongFields) {
  const auto m = build_request_gps_global_origin(3, 1);
  EXPECT_EQ(m.command, 512);
  EXPECT_EQ(m.param1, 49.0F);
  EXPECT_EQ(m.target_system, 3);
  EXPECT_EQ(m.target_component, 1);
}

TEST(BuildersStreamRequests, SetMessageIntervalAndRequestDataStreamOnTheWire) {
  // Issue 31. Oracle: node-mavlink 2.3.0 (an independent implementation; mavlink-wire.md §9, none
  // of its deviations apply here), serialize() of the same fields from sysid 1, compid 197:
  //   CommandLong{targetSystem 1, targetComponent 1, command 511, confirmation 2, _param1 30,
  //               _param2 200000}, seq 5;
  //   RequestDataStream{targetSystem 1, targetComponent 1, reqStreamId 10, reqMessageRate 5,
  //                     startStop 1}, seq 6.
  const mavlink::CommandLong c = build_set_message_interval(30, 200'000, 1, 1, 2);
  EXPECT_EQ(c.command, 511);
  EXPECT_EQ(c.param1, 30.0F);
  EXPECT_EQ(c.param2, 200'000.0F);
  EXPECT_EQ(c.param3, 0.0F);
  EXPECT_EQ(c.confirmation, 2);
  EXPECT_EQ(hex(mavlink::encode(c, {.seq = 5, .sysid = 1, .compid = 197}).bytes()),
            "fd2100000501c54c00000000f041005043480000000000000000000000000000000000000000ff01010102"
            "6457");
  const mavlink::RequestDataStream r = build_request_data_stream(10, 5, 1, 1);
  EXPECT_EQ(r.start_stop, 1);
  EXPECT_EQ(hex(mavlink::encode(r, {.seq = 6, .sysid = 1, .compid = 197}).bytes()),
            "fd0600000601c5420000050001010a0102f6");
}

}  // namespace
}  // namespace mocaplink::core
