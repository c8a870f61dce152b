// Tracker behaviour with injected source time (DESIGN.md "Behaviour under faults").
#include "mocaplink/core/tracker.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

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
  c.reset_jump_m = 0;
  expect_field(c, "reset_jump_m");
  c = {};
  c.reset_jump_rad = kNaN;
  expect_field(c, "reset_jump_rad");
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

TEST(Tracker, BackWithinReachAfterLossIsNoJump) {
  // 40 cm off after 410 ms unseen: within reset_jump_m, the autopilot is not told of a jump
  // (fused, or restarted there when outside the filter's gate).
  Tracker t;
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  t.on_missing(ms(600));
  ASSERT_EQ(t.estimate().state, TrackingState::lost);
  const SampleOutcome o = t.on_pose_ned(ms(700), {0.4, 0, 0}, kLevel);
  EXPECT_TRUE(o == SampleOutcome::accepted || o == SampleOutcome::resumed) << to_string(o);
  EXPECT_NEAR(t.estimate().p_ned_m.x(), 0.4, 0.01);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_TRUE(t.estimate().pose_valid());
}

TEST(Tracker, LongGapInPlaceResumesWithItsVelocityUnknown) {
  Tracker t;
  fly(t, 0, 30, {0, 0, 0}, {0, 0, 0});
  const double settled_var = t.estimate().velocity_covariance(0, 0);
  // 290 ms -> 1300 ms: 1010 ms > reset_after_ms, no frames in between (very large dt).
  EXPECT_EQ(t.on_pose_ned(ms(1300), {0, 0, 0}, kLevel), SampleOutcome::resumed);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  // The velocity was re-initialised and the published covariance says so (ODOMETRY).
  EXPECT_EQ(t.estimate().v_ned_mps, Eigen::Vector3d::Zero());
  EXPECT_GT(t.estimate().velocity_covariance(0, 0), 100 * settled_var);
  EXPECT_NEAR(t.estimate().velocity_covariance(0, 0), 4.0, 1e-9);
  // A whole hour later, still in place.
  EXPECT_EQ(t.on_pose_ned(ms(3.6e6), {0, 0, 0}, kLevel), SampleOutcome::resumed);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_EQ(t.estimate().counters.resumed, 2u);
  EXPECT_TRUE(t.estimate().p_ned_m.allFinite());
  EXPECT_TRUE(t.estimate().pose_covariance.allFinite());
}

TEST(Tracker, ResumedVelocitySettlesWithoutRinging) {
  // A body cruising at 5 cm/s with uniform +-0.5 mm noise (std::mt19937: the same numbers on
  // every platform), lost for 1.06 s (a server restart) and back where it could have got to.
  // Over the half second after its return, the velocity error (RMS over 20 seeds, from the second
  // sample on: the first carries the velocity unknown) against the same filter's in steady state:
  // 4.3x when a return restarted with a multirotor's acceleration envelope (10 m/s^2), 3.1x now.
  // A filterless difference of the same samples is 13.6x.
  double steady = 0;
  double resumed = 0;
  int steady_n = 0;
  int resumed_n = 0;
  const double v = 0.05;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    const auto noise = [&rng] { return (static_cast<double>(rng()) / 4294967296.0 - 0.5) * 1e-3; };
    Tracker t;
    int k = 0;
    for (; k < 300; ++k) {
      t.on_pose_ned(ms(10.0 * k), {v * k * 0.01 + noise(), 0, -1}, kLevel);
      if (k >= 250) {
        steady += std::pow(t.estimate().v_ned_mps.x() - v, 2);
        ++steady_n;
      }
    }
    k += 106;
    for (int j = 0; j < 50; ++j, ++k) {
      const SampleOutcome o = t.on_pose_ned(ms(10.0 * k), {v * k * 0.01 + noise(), 0, -1}, kLevel);
      if (j == 0) {
        EXPECT_EQ(o, SampleOutcome::resumed);
      }
      if (j >= 1) {
        resumed += std::pow(t.estimate().v_ned_mps.x() - v, 2);
        ++resumed_n;
      }
    }
    EXPECT_EQ(t.estimate().reset_counter, 0);
  }
  const double ratio = std::sqrt(resumed / resumed_n) / std::sqrt(steady / steady_n);
  EXPECT_LT(ratio, 3.6);
  EXPECT_GT(ratio, 1.0);  // a filter that had learnt nothing before the gap would not be slower
}

TEST(Tracker, ResetCounterWrapsAt256) {
  Tracker t;
  t.on_pose_ned(ms(0), {0, 0, 0}, kLevel);
  for (int i = 1; i <= 256; ++i) {
    // Back after 2 s, 2 m from where it was lost each time: a jump.
    ASSERT_EQ(t.on_pose_ned(ms(2000.0 * i), {2.0 * (i % 2), 0, 0}, kLevel), SampleOutcome::reset);
  }
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_EQ(t.estimate().counters.resets, 256u);
}

// The reset rule (issue 41): after a gap, the first pose continues the stream when it lies where
// the body could have got to; reset_counter counts only jumps. One row per case, time injected.
struct GapCase {
  const char* name;
  Eigen::Vector3d velocity_mps;   // the body's velocity before the gap (flown 1 s at 100 Hz)
  double gap_ms;                  // from the last sample before the gap to the first after it
  Eigen::Vector3d back_offset_m;  // where it is back, relative to its path continued
  double back_yaw_rad;            // its heading back, relative to before
  int frames_after;               // frames fed after the return, at 100 Hz, at the same offset
  SampleOutcome first_outcome;
  int resets;  // reset_counter at the end
};

class TrackerGapRule : public ::testing::TestWithParam<GapCase> {};

TEST_P(TrackerGapRule, ResetCounterCountsOnlyJumps) {
  const GapCase& c = GetParam();
  Tracker t;
  const Eigen::Vector3d p0(1, 2, -1.5);
  fly(t, 0, 100, p0, c.velocity_mps);  // last sample at 990 ms
  // Occluded (the server still sends frames) for the gap, every 10 ms.
  const double back_ms = 990 + c.gap_ms;
  for (double tm = 1000; tm < back_ms - 1; tm += 10) t.on_missing(ms(tm));
  const auto q_back =
      Eigen::Quaterniond(Eigen::AngleAxisd(c.back_yaw_rad, Eigen::Vector3d::UnitZ()));
  SampleOutcome first = SampleOutcome::untracked;
  for (int k = 0; k <= c.frames_after; ++k) {
    const double tm = back_ms + 10.0 * k;
    const Eigen::Vector3d truth = p0 + c.velocity_mps * (tm * 1e-3);
    const SampleOutcome o = t.on_pose_ned(ms(tm), truth + c.back_offset_m, q_back);
    if (k == 0) first = o;
  }
  EXPECT_EQ(first, c.first_outcome) << to_string(first);
  EXPECT_EQ(t.estimate().reset_counter, c.resets);
  EXPECT_EQ(t.estimate().counters.resets, static_cast<std::uint64_t>(c.resets));
  EXPECT_EQ(t.estimate().state, TrackingState::tracking);
}

const Eigen::Vector3d kStill = Eigen::Vector3d::Zero();
const Eigen::Vector3d kHere = Eigen::Vector3d::Zero();

INSTANTIATE_TEST_SUITE_P(
    Issue41, TrackerGapRule,
    ::testing::Values(
        // A 1 s server restart, the hovering body back in place: no jump.
        GapCase{"restart_1s_in_place", kStill, 1010, kHere, 0, 20, SampleOutcome::resumed, 0},
        // ... with the drift a blind hover accumulates (2 cm, the issue's SITL figure x 1): none.
        GapCase{"restart_1s_drifted_2cm",
                kStill,
                1010,
                {0.02, 0.01, 0},
                0,
                20,
                SampleOutcome::resumed,
                0},
        // 0.3 s occluded in place: within the gate, fused as usual.
        GapCase{"occluded_300ms_in_place", kStill, 300, kHere, 0, 20, SampleOutcome::accepted, 0},
        // 5 s occluded in place: none.
        GapCase{"occluded_5s_in_place", kStill, 5000, kHere, 0, 20, SampleOutcome::resumed, 0},
        // Moving at 0.5 m/s and back where it would be after 2 s: none.
        GapCase{
            "moving_back_on_its_path", {0.5, 0, 0}, 2000, kHere, 0, 20, SampleOutcome::resumed, 0},
        // Moved (or its rigid body re-defined) 1 m while unseen for 1 s: one.
        GapCase{"moved_1m_while_unseen", kStill, 1010, {1, 0, 0}, 0, 20, SampleOutcome::reset, 1},
        // ... also after 5 s (the reach widens with the gap but is capped).
        GapCase{"moved_1m_in_5s", kStill, 5000, {0, 1, 0}, 0, 20, SampleOutcome::reset, 1},
        // ... and after shorter occlusions, where the filter's own gate is wider than a metre.
        GapCase{"moved_1m_in_300ms", kStill, 300, {0, 0, 1}, 0, 20, SampleOutcome::reset, 1},
        GapCase{"moved_1m_in_900ms", kStill, 900, {1, 0, 0}, 0, 20, SampleOutcome::reset, 1},
        GapCase{"moved_60cm_in_600ms", kStill, 600, {0, 0.6, 0}, 0, 20, SampleOutcome::reset, 1},
        // Back in place but turned by 90 degrees (a symmetric marker set re-identified): one.
        GapCase{"turned_90deg_while_unseen", kStill, 1010, kHere, kPi / 2, 20, SampleOutcome::reset,
                1},
        // A marker swap that persists (no gap: 0.2 m off from one frame to the next, and
        // stays): one, once jump_confirm_frames agree.
        GapCase{
            "persisting_swap", kStill, 10, {0.2, 0, 0}, 0, 20, SampleOutcome::rejected_outlier, 1},
        // A swap that persists with a flipped heading: one.
        GapCase{"persisting_swap_flipped",
                kStill,
                10,
                {0.05, 0, 0},
                kPi,
                20,
                SampleOutcome::rejected_outlier,
                1},
        // A 3-frame swap (reflection) that goes away: none.
        GapCase{
            "three_frame_swap", kStill, 10, {0.2, 0, 0}, 0, 2, SampleOutcome::rejected_outlier, 0}),
    [](const ::testing::TestParamInfo<GapCase>& row) { return std::string(row.param.name); });

TEST(Tracker, ThreeFrameSwapThenBackIsNoJump) {
  Tracker t;
  fly(t, 0, 100, {0, 0, 0}, kStill);
  for (double tm : {1000.0, 1010.0, 1020.0}) {
    EXPECT_EQ(t.on_pose_ned(ms(tm), {0.2, 0, 0}, kLevel), SampleOutcome::rejected_outlier);
  }
  EXPECT_EQ(t.on_pose_ned(ms(1030), {0, 0, 0}, kLevel), SampleOutcome::accepted);
  EXPECT_EQ(t.estimate().reset_counter, 0);
}

TEST(Tracker, JumpThresholdsComeFromTheConfig) {
  // 30 cm off after a 1 s gap: within the default 0.5 m, beyond a 0.1 m threshold (an autopilot
  // whose vision noise floor was lowered to 2 cm).
  for (const double jump_m : {0.5, 0.1}) {
    TrackerConfig config;
    config.reset_jump_m = jump_m;
    Tracker t(config);
    fly(t, 0, 100, {0, 0, 0}, kStill);
    const SampleOutcome o = t.on_pose_ned(ms(2000), {0.3, 0, 0}, kLevel);
    EXPECT_EQ(o, jump_m > 0.3 ? SampleOutcome::resumed : SampleOutcome::reset) << jump_m;
    EXPECT_EQ(t.estimate().reset_counter, jump_m > 0.3 ? 0 : 1) << jump_m;
  }
}

TEST(Tracker, ReachWidensWithTheGapForAnUnsettledVelocity) {
  // A body seen for one frame only (velocity unknown, 2 m/s 1 sigma) and back 0.8 m away after
  // 1.1 s: it could have got there (0.5 m + min(3 x 2 m/s x 1.1 s, 0.5 m) = 1 m): no jump. The
  // same from a settled hover (velocity known to a few mm/s) is one.
  Tracker fresh;
  fresh.on_pose_ned(ms(0), {0, 0, 0}, kLevel);
  EXPECT_EQ(fresh.on_pose_ned(ms(1100), {0.8, 0, 0}, kLevel), SampleOutcome::resumed);
  EXPECT_EQ(fresh.estimate().reset_counter, 0);
  Tracker settled;
  fly(settled, 0, 100, {0, 0, 0}, kStill);  // last at 990 ms
  EXPECT_EQ(settled.on_pose_ned(ms(2090), {0.8, 0, 0}, kLevel), SampleOutcome::reset);
  EXPECT_EQ(settled.estimate().reset_counter, 1);
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

TEST(Tracker, SourceClockRestartIsJudgedLikeAGap) {
  Tracker t;
  fly(t, 0, 300, {0, 0, 0}, {0, 0, 0});  // last at 2990 ms
  // 500 ms back (< reset_after_ms 1000): a late frame, refused.
  EXPECT_EQ(t.on_pose_ned(ms(2490), {0, 0, 0}, kLevel), SampleOutcome::invalid_input);
  // The server restarted: its clock is back near zero. Lost at once; the body is back in place:
  // the stream continues.
  EXPECT_EQ(t.on_missing(ms(5)), SampleOutcome::untracked);
  EXPECT_EQ(t.estimate().state, TrackingState::lost);
  EXPECT_FALSE(t.estimate().pose_valid());
  EXPECT_EQ(t.on_pose_ned(ms(15), {0.001, 0, 0}, kLevel), SampleOutcome::resumed);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_EQ(t.estimate().state, TrackingState::tracking);
  EXPECT_EQ(t.on_pose_ned(ms(25), {0.001, 0, 0}, kLevel), SampleOutcome::accepted);
  EXPECT_EQ(t.estimate().counters.invalid(InvalidInput::time_not_increasing), 1u);
  // Restarted again after a second of hover, and the body is 1 m away now: a jump.
  fly(t, 35, 100, {0.001, 0, 0}, {0, 0, 0});  // last at 1025 ms
  EXPECT_EQ(t.on_pose_ned(ms(1), {1.0, 0, 0}, kLevel), SampleOutcome::reset);
  EXPECT_EQ(t.estimate().reset_counter, 1);
}

TEST(Tracker, ClockRestartWithTheOutageLengthKeepsTheIntervals) {
  // The Bridge tells the Tracker the outage lasted 200 ms (host time): the body back in place is
  // a return after 200 ms + the frames since the last valid one, fused without a restart.
  Tracker t;
  fly(t, 0, 100, {0, 0, 0}, kStill);  // last at 990 ms
  t.on_clock_restart(ms(7), std::chrono::milliseconds(200));
  EXPECT_EQ(t.estimate().state, TrackingState::lost);
  EXPECT_EQ(t.on_pose_ned(ms(7), {0.001, 0, 0}, kLevel), SampleOutcome::accepted);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  EXPECT_EQ(t.estimate().capture_time, ms(7));
  // The same with 2 s: a long gap, resumed (velocity re-initialised), still no jump.
  t.on_clock_restart(ms(3), std::chrono::seconds(2));
  EXPECT_EQ(t.on_pose_ned(ms(3), {0.001, 0, 0}, kLevel), SampleOutcome::resumed);
  EXPECT_EQ(t.estimate().reset_counter, 0);
  // Nothing seen yet: nothing to move.
  Tracker fresh;
  fresh.on_clock_restart(ms(3), std::chrono::seconds(2));
  EXPECT_EQ(fresh.on_pose_ned(ms(3), {0, 0, 0}, kLevel), SampleOutcome::initialised);
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
