// BodyEstimate helpers and names.
#include "mocaplink/core/body_estimate.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

TEST(BodyEstimate, BodyFrameVelocityOfABodyFacingEast) {
  BodyEstimate e;
  const double a = std::sqrt(0.5);
  e.q_ned_frd = Eigen::Quaterniond(a, 0, 0, a);  // yaw +90 deg: nose east
  e.v_ned_mps = {0, 2, 0.5};                     // moving east and descending
  // Forward = east, right = south, down = down: v_frd = (2, 0, 0.5).
  EXPECT_NEAR((e.v_frd_mps() - Eigen::Vector3d(2, 0, 0.5)).norm(), 0.0, 1e-15);
  e.velocity_covariance.setZero();
  e.velocity_covariance(0, 0) = 4.0;  // north variance
  e.velocity_covariance(1, 1) = 1.0;  // east variance
  e.velocity_covariance(5, 5) = 0.3;
  const Matrix6d frd = e.velocity_covariance_frd();
  EXPECT_NEAR(frd(0, 0), 1.0, 1e-14);  // forward = east
  EXPECT_NEAR(frd(1, 1), 4.0, 1e-14);  // right = south
  EXPECT_NEAR(frd(5, 5), 0.3, 1e-15);
}

TEST(BodyEstimate, PoseValidOnlyWhenTrackingWithFreshData) {
  BodyEstimate e;
  EXPECT_FALSE(e.pose_valid());
  e.state = TrackingState::tracking;
  for (auto o : {SampleOutcome::accepted, SampleOutcome::initialised, SampleOutcome::reset,
                 SampleOutcome::rejected_outlier}) {
    e.last_outcome = o;
    EXPECT_TRUE(e.pose_valid()) << to_string(o);
  }
  for (auto o : {SampleOutcome::untracked, SampleOutcome::invalid_input}) {
    e.last_outcome = o;
    EXPECT_FALSE(e.pose_valid()) << to_string(o);
  }
  e.state = TrackingState::lost;
  e.last_outcome = SampleOutcome::accepted;
  EXPECT_FALSE(e.pose_valid());
}

TEST(BodyEstimate, Names) {
  EXPECT_EQ(to_string(TrackingState::lost), "lost");
  EXPECT_EQ(to_string(SampleOutcome::rejected_outlier), "rejected_outlier");
  EXPECT_EQ(to_string(InvalidInput::time_not_increasing), "time_not_increasing");
  TrackerCounters c;
  c.invalid_input[static_cast<std::size_t>(InvalidInput::non_unit_quaternion)] = 3;
  EXPECT_EQ(c.invalid(InvalidInput::non_unit_quaternion), 3u);
  EXPECT_EQ(c.invalid_total(), 3u);
}

}  // namespace
}  // namespace mocaplink::core
