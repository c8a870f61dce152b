// Tracker behaviour with injected source time (DESIGN.md "Behaviour under faults").
#include "mocaplink/core/tracker.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const Eigen::Quaterniond kLevel = Eigen::Quaterniond::Identity();

SourceTime ms(double t_ms) {
  return source_time_from_ns(static_cast<std::int64_t>(std::llround(t_ms * 1e6)));
}

// Feeds a body moving at constant velocity v from p0, every 10 ms (100 Hz) from t0 for n frames.
void fly(Tracker& tracker, double t0_ms, int n, const Eigen::Vector3d& p0,
         const Eigen::Vector3d& v) {
  for (int k = 0; k < n; ++k) {
    const double t = t0_ms + 10.0 * k;
    tracker.on_pose_ned(ms(t), p0 + v * (t * 1e-3), kLevel);
  }
}

TEST(TrackerConfig, DefaultsAreValidAndRangesChecked) {
  EXPECT_FALSE(validate(TrackerConfig{}).has_value());
  auto expect_field = [](TrackerConfig c, const char* field) {
    const auto e = validate(c);
    ASSERT_TRUE(e.has_value()) << field;
    EXPECT_EQ(e->field, field);
  };
  TrackerConfig c;
  c.loss_timeout_ms = 0;
  expect_field(c, "loss_timeout_ms");
  c = {};
  c.reset_after_ms = 100;  // < loss_timeout_ms 250
  expect_field(c, "reset_after_ms");
  c = {};
  c.position_noise_m = kNaN;
  expect_field(c, "position_noise_m");
  c = {};
  c.attitude_noise_rad = -1;
  expect_field(c, "attitude_noise_rad");
  c = {};
  c.accel_noise_mps2 = 0;
  expect_field(c, "accel_noise_mps2");
  c = {};
  c.angular_accel_noise_radps2 = std::numeric_limits<double>::infinity();
  expect_field(c, "angular_accel_noise_radps2");
  c = {};
  c.gate_sigma = 0;
  expect_field(c, "gate_sigma");
  c = {};
  c.gate_min_m = -0.01;
  expect_field(c, "gate_min_m");
  c = {};
  c.jump_confirm_frames = 0;
  expect_field(c, "jump_confirm_frames");
  c = {};
  c.gate_min_m = 0;  // allowed: no floor
  EXPECT_FALSE(validate(c).has_value());
}

TEST(Tracker, UnseenUntilTheFirstSample) {
  Tracker t;
  EXPECT_EQ(t.estimate().state, TrackingState::unseen);
  EXPECT_FALSE(t.estimate().pose_valid());
  EXPECT_EQ(t.on_missing(ms(0)), SampleOutcome::untracked);
  EXPECT_EQ(t.estimate().state, TrackingState::unseen);
  EXPECT_EQ(t.on_pose_ned(ms(10), {1, 2, -3}, kLevel), SampleOutcome::initialised);
  const BodyEstimate& e = t.estimate();
  EXPECT_EQ(e.state, TrackingState::tracking);
  EXPECT_TRUE(e.pose_valid());
  EXPECT_EQ(e.p_ned_m, Eigen::Vector3d(1, 2, -3));
  EXPECT_EQ(e.v_ned_mps, Eigen::Vector3d::Zero());
  EXPECT_EQ(e.capture_time, ms(10));
  EXPECT_EQ(e.reset_counter, 0);
  EXPECT_EQ(e.counters.samples, 1u);
  EXPECT_EQ(e.counters.accepted, 1u);
  EXPECT_EQ(e.counters.untracked, 1u);
  // Initial covariances: position variance = position_noise_m^2; velocity 2 m/s sigma.
  EXPECT_NEAR(e.pose_covariance(0, 0), 0.0005 * 0.0005, 1e-18);
  EXPECT_NEAR(e.velocity_covariance(0, 0), 4.0, 1e-12);
}

TEST(Tracker, MapsViconSamplesToNed) {
  const auto mapping = AxisMapping::parse("+z", "+x");
  ASSERT_TRUE(mapping.has_value());
  Tracker t(TrackerConfig{}, *mapping);
  BodySample s;
  s.tracked = true;
  s.p_world_m = {1.0, 2.0, 0.5};  // 0.5 m above the floor
  s.q_world_body = Eigen::Quaterniond(std::sqrt(0.5), 0, 0, std::sqrt(0.5));  // nose on mocap +y
  EXPECT_EQ(t.on_sample(ms(0), s), SampleOutcome::initialised);
  EXPECT_NEAR((t.estimate().p_ned_m - Eigen::Vector3d(1.0, -2.0, -0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(euler_321_from_quaternion(t.estimate().q_ned_frd).yaw_rad, -kPi / 2, 1e-12);
  // The mapping gives (-a, 0, 0, a) here; the Tracker starts in the w >= 0 hemisphere.
  EXPECT_NEAR(t.estimate().q_ned_frd.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(t.estimate().q_ned_frd.z(), -std::sqrt(0.5), 1e-12);
  s.tracked = false;
  EXPECT_EQ(t.on_sample(ms(10), s), SampleOutcome::untracked);
  EXPECT_FALSE(t.estimate().pose_valid());
}

TEST(Tracker, EstimatesVelocityFromCaptureTimestamps) {
  Tracker t;
  const Eigen::Vector3d v(2.0, -1.0, 0.5);
  fly(t, 0, 100, {0, 0, -1}, v);
  EXPECT_NEAR((t.estimate().v_ned_mps - v).norm(), 0.0, 1e-6);
  // Irregular intervals (dropped frames): dt comes from the timestamps, not the frame count.
  Tracker u;
  const double times[] = {0, 10, 20, 50, 60, 61, 90, 120, 200, 210, 215, 300, 310, 320, 330};
  for (double tm : times) u.on_pose_ned(ms(tm), v * (tm * 1e-3), kLevel);
  EXPECT_NEAR((u.estimate().v_ned_mps - v).norm(), 0.0, 0.01);
  EXPECT_EQ(u.estimate().counters.rejected_outliers, 0u);
}

TEST(Tracker, EstimatesBodyRates) {
  Tracker t;
  // 1 rad/s about body z (yaw rate), 100 Hz, through +-180 deg.
  for (int k = 0; k <= 400; ++k) {
    const double a = 0.01 * k;
    t.on_pose_ned(ms(10.0 * k), {0, 0, 0},
                  Eigen::Quaterniond(std::cos(a / 2), 0, 0, std::sin(a / 2)));
  }
  EXPECT_NEAR((t.estimate().w_frd_radps - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-4);
  EXPECT_EQ(t.estimate().counters.rejected_outliers, 0u);
  EXPECT_NEAR(euler_321_from_quaternion(t.estimate().q_ned_frd).yaw_rad, 4.0 - 2 * kPi, 1e-6);
}

TEST(Tracker, SignOfTheInputQuaternionDoesNotMatter) {
  Tracker t;
  const Eigen::Quaterniond q(std::cos(0.3), 0, std::sin(0.3), 0);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Quaterniond in = (k % 2 == 0) ? q : Eigen::Quaterniond(-q.coeffs());
    EXPECT_NE(t.on_pose_ned(ms(10.0 * k), {0, 0, 0}, in), SampleOutcome::rejected_outlier);
    EXPECT_GT(t.estimate().q_ned_frd.dot(q), 0.9999);  // continuous: same sign every frame
  }
  EXPECT_NEAR(t.estimate().w_frd_radps.norm(), 0.0, 1e-9);
}

TEST(Tracker, SingleOutlierNeverReachesTheOutput) {
  Tracker t;
  const Eigen::Vector3d v(1.0, 0.0, 0.0);
  fly(t, 0, 50, {0, 0, 0}, v);  // t = 0..490 ms
  // 10 cm jump for one frame at 500 ms.
  EXPECT_EQ(t.on_pose_ned(ms(500), v * 0.5 + Eigen::Vector3d(0, 0.1, 0), kLevel),
            SampleOutcome::rejected_outlier);
  EXPECT_NEAR((t.estimate().p_ned_m - v * 0.5).norm(), 0.0, 1e-6);  // the prediction
  EXPECT_TRUE(t.estimate().pose_valid());
  EXPECT_EQ(t.on_pose_ned(ms(510), v * 0.51, kLevel), SampleOutcome::accepted);
  EXPECT_NEAR((t.estimate().p_ned_m - v * 0.51).norm(), 0.0, 1e-6);
  EXPECT_NEAR((t.estimate().v_ned_mps - v).norm(), 0.0, 1e-4);
  EXPECT_EQ(t.estimate().counters.rejected_outliers, 1u);
  EXPECT_EQ(t.estimate().reset_counter, 0);
}

TEST(Tracker, AttitudeOutlierIsRejectedToo) {
  Tracker t;
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  // A marker swap flips the body 120 deg about z for one frame; position unchanged.
  EXPECT_EQ(t.on_pose_ned(ms(300), {0, 0, 0},
                          Eigen::Quaterniond(std::cos(kPi / 3), 0, 0, std::sin(kPi / 3))),
            SampleOutcome::rejected_outlier);
  EXPECT_NEAR(std::abs(t.estimate().q_ned_frd.w()), 1.0, 1e-9);
}

TEST(Tracker, PersistentJumpBecomesAReset) {
  TrackerConfig config;
  config.jump_confirm_frames = 3;
  Tracker t(config);
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  const Eigen::Vector3d moved(0.1, 0, 0);
  EXPECT_EQ(t.on_pose_ned(ms(300), moved, kLevel), SampleOutcome::rejected_outlier);
  EXPECT_EQ(t.on_pose_ned(ms(310), moved, kLevel), SampleOutcome::rejected_outlier);
  EXPECT_NEAR(t.estimate().p_ned_m.norm(), 0.0, 1e-9);
  EXPECT_EQ(t.on_pose_ned(ms(320), moved, kLevel), SampleOutcome::reset);
  EXPECT_EQ(t.estimate().p_ned_m, moved);
  EXPECT_EQ(t.estimate().reset_counter, 1);
  EXPECT_EQ(t.estimate().counters.resets, 1u);
  EXPECT_EQ(t.estimate().counters.rejected_outliers, 2u);
  EXPECT_EQ(t.on_pose_ned(ms(330), moved, kLevel), SampleOutcome::accepted);
}

TEST(Tracker, InconsistentOutliersDoNotConfirmAJump) {
  TrackerConfig config;
  config.jump_confirm_frames = 2;
  Tracker t(config);
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  EXPECT_EQ(t.on_pose_ned(ms(300), {0.1, 0, 0}, kLevel), SampleOutcome::rejected_outlier);
  EXPECT_EQ(t.on_pose_ned(ms(310), {-0.1, 0, 0}, kLevel), SampleOutcome::rejected_outlier);
  EXPECT_EQ(t.on_pose_ned(ms(320), {0, 0.1, 0}, kLevel), SampleOutcome::rejected_outlier);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_EQ(t.on_pose_ned(ms(330), {0, 0, 0}, kLevel), SampleOutcome::accepted);
}

TEST(Tracker, GatingFloorAcceptsSmallSurprises) {
  // A 1.5 cm step is many sigma with 0.5 mm noise, but under gate_min_m = 2 cm: accepted.
  Tracker t;
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  EXPECT_EQ(t.on_pose_ned(ms(300), {0.015, 0, 0}, kLevel), SampleOutcome::accepted);
  TrackerConfig no_floor;
  no_floor.gate_min_m = 0.0;
  Tracker u(no_floor);
  fly(u, 0, 30, {0, 0, 0}, {0, 0, 0});
  EXPECT_EQ(u.on_pose_ned(ms(300), {0.015, 0, 0}, kLevel), SampleOutcome::rejected_outlier);
}

TEST(Tracker, LostAfterTimeoutAndBackNearbyWithoutReset) {
  Tracker t;                            // loss_timeout_ms 250, reset_after_ms 1000
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});  // last sample at 290 ms
  for (double tm = 300; tm <= 540; tm += 10) {
    EXPECT_EQ(t.on_missing(ms(tm)), SampleOutcome::untracked);
    EXPECT_EQ(t.estimate().state, TrackingState::tracking) << tm;  // 250 ms not yet exceeded
    EXPECT_FALSE(t.estimate().pose_valid());
  }
  t.on_missing(ms(550));  // 260 ms without a sample
  EXPECT_EQ(t.estimate().state, TrackingState::lost);
  EXPECT_FALSE(t.estimate().pose_valid());
  EXPECT_EQ(t.on_pose_ned(ms(700), {0.001, 0, 0}, kLevel), SampleOutcome::accepted);
  EXPECT_EQ(t.estimate().state, TrackingState::tracking);
  EXPECT_EQ(t.estimate().reset_counter, 0);
}

TEST(Tracker, BackFarFromPredictionAfterLossResetsAtOnce) {
  Tracker t;
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  t.on_missing(ms(600));
  ASSERT_EQ(t.estimate().state, TrackingState::lost);
  EXPECT_EQ(t.on_pose_ned(ms(700), {2, 0, 0}, kLevel), SampleOutcome::reset);
  EXPECT_EQ(t.estimate().p_ned_m, Eigen::Vector3d(2, 0, 0));
  EXPECT_EQ(t.estimate().v_ned_mps, Eigen::Vector3d::Zero());
  EXPECT_EQ(t.estimate().reset_counter, 1);
}

TEST(Tracker, LongGapResetsEvenInPlace) {
  Tracker t;
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  // 290 ms -> 1300 ms: 1010 ms > reset_after_ms, no frames in between (very large dt).
  EXPECT_EQ(t.on_pose_ned(ms(1300), {0, 0, 0}, kLevel), SampleOutcome::reset);
  EXPECT_EQ(t.estimate().reset_counter, 1);
  // A whole hour later.
  EXPECT_EQ(t.on_pose_ned(ms(3.6e6), {0, 0, 0}, kLevel), SampleOutcome::reset);
  EXPECT_EQ(t.estimate().reset_counter, 2);
  EXPECT_TRUE(t.estimate().p_ned_m.allFinite());
  EXPECT_TRUE(t.estimate().pose_covariance.allFinite());
}

TEST(Tracker, ResetCounterWrapsAt256) {
  Tracker t;
  t.on_pose_ned(ms(0), {0, 0, 0}, kLevel);
  for (int i = 1; i <= 256; ++i) {
    ASSERT_EQ(t.on_pose_ned(ms(2000.0 * i), {0, 0, 0}, kLevel), SampleOutcome::reset);
  }
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_EQ(t.estimate().counters.resets, 256u);
}

TEST(Tracker, RefusesNonIncreasingTime) {
  Tracker t;
  fly(t, 0, 10, {0, 0, 0}, {1, 0, 0});  // last at 90 ms
  const BodyEstimate before = t.estimate();
  EXPECT_EQ(t.on_pose_ned(ms(90), {5, 5, 5}, kLevel), SampleOutcome::invalid_input);
  EXPECT_EQ(t.on_pose_ned(ms(50), {5, 5, 5}, kLevel), SampleOutcome::invalid_input);
  EXPECT_EQ(t.on_missing(ms(80)), SampleOutcome::invalid_input);
  EXPECT_EQ(t.estimate().p_ned_m, before.p_ned_m);
  EXPECT_EQ(t.estimate().capture_time, ms(90));
  EXPECT_EQ(t.estimate().counters.invalid(InvalidInput::time_not_increasing), 3u);
  EXPECT_EQ(t.on_pose_ned(ms(100), {0.1, 0, 0}, kLevel), SampleOutcome::accepted);
}

TEST(Tracker, SourceClockRestartResetsInsteadOfRefusingForever) {
  Tracker t;
  fly(t, 0, 300, {0, 0, 0}, {0, 0, 0});  // last at 2990 ms
  // 500 ms back (< reset_after_ms 1000): a late frame, refused.
  EXPECT_EQ(t.on_pose_ned(ms(2490), {0, 0, 0}, kLevel), SampleOutcome::invalid_input);
  // The server restarted: its clock is back near zero. Lost at once, reset at the next sample.
  EXPECT_EQ(t.on_missing(ms(5)), SampleOutcome::untracked);
  EXPECT_EQ(t.estimate().state, TrackingState::lost);
  EXPECT_FALSE(t.estimate().pose_valid());
  EXPECT_EQ(t.on_pose_ned(ms(15), {0.5, 0, 0}, kLevel), SampleOutcome::reset);
  EXPECT_EQ(t.estimate().reset_counter, 1);
  EXPECT_EQ(t.estimate().state, TrackingState::tracking);
  EXPECT_EQ(t.on_pose_ned(ms(25), {0.5, 0, 0}, kLevel), SampleOutcome::accepted);
  EXPECT_EQ(t.estimate().counters.invalid(InvalidInput::time_not_increasing), 1u);
}

TEST(Tracker, RefusesNonFiniteAndNonUnitInputWithReasons) {
  Tracker t;
  fly(t, 0, 10, {0, 0, 0}, {0, 0, 0});
  EXPECT_EQ(t.on_pose_ned(ms(100), {kNaN, 0, 0}, kLevel), SampleOutcome::invalid_input);
  EXPECT_EQ(t.on_pose_ned(ms(110), {0, 0, 0}, Eigen::Quaterniond(kNaN, 0, 0, 0)),
            SampleOutcome::invalid_input);
  EXPECT_EQ(t.on_pose_ned(ms(120), {0, 0, 0}, Eigen::Quaterniond(0.9, 0, 0, 0)),
            SampleOutcome::invalid_input);
  EXPECT_EQ(t.on_pose_ned(ms(130), {0, 0, 0}, Eigen::Quaterniond(0, 0, 0, 0)),
            SampleOutcome::invalid_input);
  EXPECT_FALSE(t.estimate().pose_valid());
  const TrackerCounters& c = t.estimate().counters;
  EXPECT_EQ(c.invalid(InvalidInput::non_finite_position), 1u);
  EXPECT_EQ(c.invalid(InvalidInput::non_finite_quaternion), 1u);
  EXPECT_EQ(c.invalid(InvalidInput::non_unit_quaternion), 2u);
  EXPECT_EQ(c.invalid_total(), 4u);
  EXPECT_TRUE(t.estimate().p_ned_m.allFinite());
  EXPECT_TRUE(t.estimate().q_ned_frd.coeffs().allFinite());
  // Mapped input: NaN in the mocap frame stays NaN after the mapping.
  BodySample s;
  s.tracked = true;
  s.p_world_m = {0, kNaN, 0};
  EXPECT_EQ(t.on_sample(ms(140), s), SampleOutcome::invalid_input);
  EXPECT_EQ(t.on_pose_ned(ms(150), {0, 0, 0}, kLevel), SampleOutcome::accepted);
}

TEST(Tracker, OnlyInvalidInputEventuallyMeansLost) {
  Tracker t;
  fly(t, 0, 10, {0, 0, 0}, {0, 0, 0});
  for (double tm = 100; tm <= 400; tm += 10) t.on_pose_ned(ms(tm), {kNaN, 0, 0}, kLevel);
  EXPECT_EQ(t.estimate().state, TrackingState::lost);
}

TEST(Tracker, CovariancesAreSymmetricAndShrinkWithData) {
  Tracker t;
  fly(t, 0, 100, {0, 0, 0}, {0.5, 0, 0});
  const BodyEstimate& e = t.estimate();
  EXPECT_NEAR((e.pose_covariance - e.pose_covariance.transpose()).norm(), 0.0, 1e-18);
  EXPECT_NEAR((e.velocity_covariance - e.velocity_covariance.transpose()).norm(), 0.0, 1e-15);
  for (int i = 0; i < 6; ++i) {
    EXPECT_GT(e.pose_covariance(i, i), 0.0);
    EXPECT_GT(e.velocity_covariance(i, i), 0.0);
  }
  // Filtered position is better than one measurement; velocity far better than the 2 m/s prior.
  EXPECT_LT(e.pose_covariance(0, 0), 0.0005 * 0.0005);
  EXPECT_LT(e.velocity_covariance(0, 0), 0.01);
  EXPECT_EQ(e.pose_covariance(0, 3), 0.0);  // position and attitude are independent
}

}  // namespace
}  // namespace mocaplink::core
