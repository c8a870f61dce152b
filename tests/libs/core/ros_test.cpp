// ROS names and a body's state in ROS's frames. The expected values are worked by hand from
// REP 103 (ENU world, FLU body, yaw 0 facing east) and the estimate's NED/FRD, not computed with
// the code under test.
#include "mocaplink/core/ros.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Quaterniond about(const Eigen::Vector3d& axis, double deg) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(deg * kPi / 180.0, axis.normalized()));
}

/// Same rotation (q and −q are one).
void expect_same_rotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  EXPECT_NEAR(std::abs(a.coeffs().dot(b.coeffs())), 1.0, 1e-12)
      << a.coeffs().transpose() << " vs " << b.coeffs().transpose();
}

TEST(RosNames, BodyNamesBecomeTokens) {
  EXPECT_EQ(ros_name_token("Quad1"), "Quad1");
  EXPECT_EQ(ros_name_token("Rigid Body 1"), "Rigid_Body_1");
  EXPECT_EQ(ros_name_token("cf-2.3"), "cf_2_3");
  EXPECT_EQ(ros_name_token("  a  --  b  "), "a_b");  // no "__", no '_' at the ends
  EXPECT_EQ(ros_name_token("1 quad"), "_1_quad");    // a token may not start with a digit
  EXPECT_EQ(ros_name_token("drone_"), "drone");
  EXPECT_EQ(ros_name_token("__x__"), "x");
  EXPECT_EQ(ros_name_token("Körper"), "K_rper");  // UTF-8 bytes are not token characters
  EXPECT_EQ(ros_name_token("???"), "");
  EXPECT_EQ(ros_name_token(""), "");
}

TEST(RosNames, NamespacesAndFrameIds) {
  EXPECT_FALSE(ros_namespace_problem(""));
  EXPECT_FALSE(ros_namespace_problem("mocap"));
  EXPECT_FALSE(ros_namespace_problem("/lab_1/mocap"));
  EXPECT_TRUE(ros_namespace_problem("lab/"));
  EXPECT_TRUE(ros_namespace_problem("a//b"));
  EXPECT_TRUE(ros_namespace_problem("a/1b"));
  EXPECT_TRUE(ros_namespace_problem("a__b"));
  EXPECT_TRUE(ros_namespace_problem("a-b"));
  EXPECT_FALSE(ros_frame_id_problem("world"));
  EXPECT_FALSE(ros_frame_id_problem("lab/world"));
  EXPECT_TRUE(ros_frame_id_problem(""));
  EXPECT_TRUE(ros_frame_id_problem("/world"));
  EXPECT_EQ(ros_body_topic("mocap", "Quad1", "pose"), "/mocap/Quad1/pose");
  EXPECT_EQ(ros_body_topic("/lab/mocap", "Quad1", "odom"), "/lab/mocap/Quad1/odom");
  EXPECT_EQ(ros_body_topic("", "Quad1", "pose"), "/Quad1/pose");
}

BodyEstimate facing_east() {
  BodyEstimate e;
  e.state = TrackingState::tracking;
  e.p_ned_m = {1.0, 2.0, -3.0};                         // 1 m north, 2 m east, 3 m up
  e.v_ned_mps = {0.5, 0.0, 0.0};                        // flying north
  e.q_ned_frd = about(Eigen::Vector3d::UnitZ(), 90.0);  // yaw 90° in NED: nose east
  e.w_frd_radps = {0.1, 0.2, 0.3};                      // roll, pitch, yaw rates
  e.pose_covariance.diagonal() << 1e-6, 2e-6, 3e-6, 4e-4, 5e-4, 6e-4;
  e.velocity_covariance.diagonal() << 1e-2, 2e-2, 3e-2, 4e-2, 5e-2, 6e-2;
  return e;
}

TEST(RosBodyState, EnuWorldAndFluBody) {
  const RosBodyState s =
      ros_body_state(facing_east(), RosAxes::enu_flu, WorldAxisMapping(), BodyAxisMapping());
  // ENU = (east, north, up).
  EXPECT_TRUE(s.position_m.isApprox(Eigen::Vector3d(2.0, 1.0, 3.0), 1e-12));
  // Nose east is yaw 0 in REP 103: the identity.
  expect_same_rotation(s.orientation, Eigen::Quaterniond::Identity());
  // Flying north with the nose east: north is to the body's left, +y in FLU.
  EXPECT_TRUE(s.linear_velocity_mps.isApprox(Eigen::Vector3d(0.0, 0.5, 0.0), 1e-12))
      << s.linear_velocity_mps.transpose();
  // FRD rates (p, q, r) → FLU (p, −q, −r).
  EXPECT_TRUE(s.angular_velocity_radps.isApprox(Eigen::Vector3d(0.1, -0.2, -0.3), 1e-12));
  // Position variances N, E, D → E, N, U.
  EXPECT_NEAR(s.pose_covariance(0, 0), 2e-6, 1e-18);
  EXPECT_NEAR(s.pose_covariance(1, 1), 1e-6, 1e-18);
  EXPECT_NEAR(s.pose_covariance(2, 2), 3e-6, 1e-18);
  // Nose east: the body's roll axis is the world's x (east), pitch axis ∓y, yaw axis ∓z — the
  // variances keep their order about the world's fixed axes.
  EXPECT_NEAR(s.pose_covariance(3, 3), 4e-4, 1e-15);
  EXPECT_NEAR(s.pose_covariance(4, 4), 5e-4, 1e-15);
  EXPECT_NEAR(s.pose_covariance(5, 5), 6e-4, 1e-15);
  // Twist covariance in the body (FLU): signs of axes do not change variances.
  EXPECT_NEAR(s.twist_covariance(3, 3), 4e-2, 1e-15);
  EXPECT_NEAR(s.twist_covariance(5, 5), 6e-2, 1e-15);
  // The body-frame linear velocity variances: north was NED x (1e-2); in the body it is ±y.
  EXPECT_NEAR(s.twist_covariance(1, 1), 1e-2, 1e-15);
  EXPECT_NEAR(s.twist_covariance(0, 0), 2e-2, 1e-15);
}

TEST(RosBodyState, CovariancesStayExactlySymmetricThroughTheRotations) {
  // A strict subscriber checks Σ == Σᵀ element by element: the rotations R Σ Rᵀ must not leave
  // rounding differences between (i, j) and (j, i) (seen on a real body: 1e-19 apart).
  BodyEstimate e = facing_east();
  e.q_ned_frd = (about(Eigen::Vector3d::UnitZ(), 37.0) * about(Eigen::Vector3d::UnitX(), 11.0) *
                 about(Eigen::Vector3d::UnitY(), -23.0))
                    .normalized();
  Matrix6d a;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) a(i, j) = 1e-3 * std::sin(1.0 + 7.0 * i + 3.0 * j);
  }
  e.pose_covariance = a * a.transpose() + 1e-6 * Matrix6d::Identity();
  e.velocity_covariance = a.transpose() * a + 1e-4 * Matrix6d::Identity();
  for (const RosAxes axes : {RosAxes::enu_flu, RosAxes::mocap}) {
    const RosBodyState s = ros_body_state(e, axes, WorldAxisMapping(), BodyAxisMapping());
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < i; ++j) {
        EXPECT_EQ(s.pose_covariance(i, j), s.pose_covariance(j, i)) << i << "," << j;
        EXPECT_EQ(s.twist_covariance(i, j), s.twist_covariance(j, i)) << i << "," << j;
      }
    }
  }
}

TEST(RosBodyState, AttitudeVariancesFollowTheNoseAboutWorldAxes) {
  BodyEstimate e = facing_east();
  e.q_ned_frd = Eigen::Quaterniond::Identity();  // nose north
  const RosBodyState s = ros_body_state(e, RosAxes::enu_flu, WorldAxisMapping(), BodyAxisMapping());
  // Nose north = yaw 90° in ENU.
  expect_same_rotation(s.orientation, about(Eigen::Vector3d::UnitZ(), 90.0));
  // The roll axis now points north (world y), the pitch axis east (world x).
  EXPECT_NEAR(s.pose_covariance(3, 3), 5e-4, 1e-15);
  EXPECT_NEAR(s.pose_covariance(4, 4), 4e-4, 1e-15);
  EXPECT_NEAR(s.pose_covariance(5, 5), 6e-4, 1e-15);
}

TEST(RosBodyState, TiltedBodyInEnu) {
  BodyEstimate e = facing_east();
  // Nose north, rolled 30° right wing down (about the FRD x axis).
  e.q_ned_frd = about(Eigen::Vector3d::UnitX(), 30.0);
  const RosBodyState s = ros_body_state(e, RosAxes::enu_flu, WorldAxisMapping(), BodyAxisMapping());
  // The body's up (FLU +z) in the world: right wing down tilts the top to the right, i.e. east
  // for a nose pointing north: (sin 30°, 0, cos 30°) in ENU.
  const Eigen::Vector3d up = s.orientation * Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(up.isApprox(Eigen::Vector3d(0.5, 0.0, std::sqrt(3.0) / 2.0), 1e-12))
      << up.transpose();
  const Eigen::Vector3d nose = s.orientation * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(nose.isApprox(Eigen::Vector3d(0.0, 1.0, 0.0), 1e-12)) << nose.transpose();
}

TEST(RosBodyState, TheMocapSystemsOwnAxesComeBack) {
  // Motive: Y up, north = +x (so east = +z: z = x × y), body forward −z, body up +y (a rigid
  // body made so).
  const auto world = WorldAxisMapping::make(axis::pos_y, axis::pos_x);
  const auto body = BodyAxisMapping::make(axis::neg_z, axis::pos_y);
  ASSERT_TRUE(world && body);
  const Eigen::Vector3d p_mocap(0.4, 1.2, -2.0);  // 0.4 m north, 1.2 m up, 2 m west
  const Eigen::Quaterniond q_mocap = about(Eigen::Vector3d(0.3, 1.0, -0.2), 40.0);
  const AxisMapping mapping(*world, *body);
  BodyEstimate e = facing_east();
  e.p_ned_m = mapping.position_ned(p_mocap);
  e.q_ned_frd = mapping.attitude_ned_frd(q_mocap);
  // By hand: NED of that position is (0.4, −2.0, −1.2).
  EXPECT_TRUE(e.p_ned_m.isApprox(Eigen::Vector3d(0.4, -2.0, -1.2), 1e-12));
  const RosBodyState s = ros_body_state(e, RosAxes::mocap, *world, *body);
  EXPECT_TRUE(s.position_m.isApprox(p_mocap, 1e-12));
  expect_same_rotation(s.orientation, q_mocap);
  // And in ENU: (east, north, up) = (−2.0, 0.4, 1.2).
  const RosBodyState enu = ros_body_state(e, RosAxes::enu_flu, *world, *body);
  EXPECT_TRUE(enu.position_m.isApprox(Eigen::Vector3d(-2.0, 0.4, 1.2), 1e-12));
}

TEST(RosBodyState, KeepsTheTrackersSign) {
  BodyEstimate e = facing_east();
  e.q_ned_frd.coeffs() = -e.q_ned_frd.coeffs();  // w < 0: the tracker keeps its sign continuous
  const RosBodyState s = ros_body_state(e, RosAxes::enu_flu, WorldAxisMapping(), BodyAxisMapping());
  const RosBodyState t =
      ros_body_state(facing_east(), RosAxes::enu_flu, WorldAxisMapping(), BodyAxisMapping());
  EXPECT_TRUE(s.orientation.coeffs().isApprox(-t.orientation.coeffs(), 1e-12));
}

}  // namespace
}  // namespace mocaplink::core
