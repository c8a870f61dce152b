// The agreement's gravity comparison and the axis fix (axis_fix.hpp), for the mistakes a lab
// makes with each source's axis convention. Every raw orientation below is written by hand from
// where the rigid body's axes point in the mocap world (columns: body x, y, z in world
// coordinates), and every expected fix from what the lab did wrong; the code under test maps
// them, the test never does.
#include "mocaplink/core/axis_fix.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRad = kPi / 180.0;

/// A matrix from its columns: where the body's x, y, z axes point in the mocap world.
Eigen::Matrix3d columns(Eigen::Vector3d x, Eigen::Vector3d y, Eigen::Vector3d z) {
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kY = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();

AxisSettings settings(SignedAxis up, SignedAxis north, SignedAxis forward, SignedAxis body_up) {
  return AxisSettings{up, north, forward, body_up};
}

const VehicleAtRest kLevel{0.0, 0.0, std::nullopt};

TEST(Tilt, IsTheAngleBetweenGravityDirectionsAndIgnoresYaw) {
  // Level mocap at any yaw against a level vehicle: 0.
  for (double yaw_deg : {0.0, 37.0, 90.0, -150.0}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw_deg * kRad, Eigen::Vector3d::UnitZ()));
    EXPECT_NEAR(tilt_offset_deg(q, 0.0, 0.0), 0.0, 1e-9) << yaw_deg;
  }
  // Mocap rolled 90° (its body down is its right, as with a Y-up mistake) against level: 90°.
  const Eigen::Quaterniond rolled(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(tilt_offset_deg(rolled, 0.0, 0.0), 90.0, 1e-9);
  // Upside down (an up sign mistake): 180°.
  const Eigen::Quaterniond flipped(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(tilt_offset_deg(flipped, 0.0, 0.0), 180.0, 1e-6);
  // The vehicle's own pitch of 4° nose up against level mocap: gravity (−sin 4°, 0, cos 4°).
  EXPECT_NEAR(tilt_offset_deg(Eigen::Quaterniond::Identity(), 0.0, 4.0 * kRad), 4.0, 1e-9);
  EXPECT_TRUE(std::isnan(tilt_offset_deg(Eigen::Quaterniond::Identity(), NAN, 0.0)));
}

TEST(AxisFix, ViconZUpRightSetUpAgrees) {
  // Vicon (Z-up): rigid body created level, nose on +x: its axes are the world's.
  const auto fix = find_axis_fix(Eigen::Matrix3d::Identity(),
                                 settings(axis::pos_z, axis::pos_x, axis::pos_x, axis::pos_z),
                                 kLevel, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::agrees);
  EXPECT_TRUE(fix.lines.empty());
  EXPECT_EQ(fix.text,
            "no axis change needed: the settings fit the vehicle at rest (tilt 0.0°, nose "
            "unchecked: the vehicle has no heading of its own)");
}

TEST(AxisFix, ViconWithTheYUpSettingIsNamed) {
  // Issue 48: a Z-up Vicon with `up = "+y"` carried over from OptiTrack. The body is level and
  // nose on +x (identity); the fix is the up line only.
  const auto fix = find_axis_fix(Eigen::Matrix3d::Identity(),
                                 settings(axis::pos_y, axis::pos_x, axis::pos_x, axis::pos_z),
                                 kLevel, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::fix);
  EXPECT_EQ(fix.lines, (std::vector<std::string>{"[mocap] up = \"+z\""}));
  EXPECT_NEAR(fix.tilt_residual_deg, 0.0, 1e-9);
  // Nose on a mocap axis: keeping up = "+y" and taking body_up = "+y" fits this pose as well,
  // but +y is not Vicon's up: named second.
  EXPECT_EQ(fix.alternative_lines, (std::vector<std::string>{"[[vehicle]] body_up = \"+y\""}));
  EXPECT_EQ(fix.text,
            "fix: [mocap] up = \"+z\" (then tilt 0.0°, nose unchecked: the vehicle has no heading "
            "of its own); or, as well at this pose: [[vehicle]] body_up = \"+y\"");
}

TEST(AxisFix, QualisysUpsideDownIsNamed) {
  // QTM (Z-up) with `up = "-z"`: mocap sees the vehicle upside down (180°).
  const auto fix = find_axis_fix(Eigen::Matrix3d::Identity(),
                                 settings(axis::neg_z, axis::pos_x, axis::pos_x, axis::pos_z),
                                 kLevel, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::fix);
  EXPECT_EQ(fix.lines, (std::vector<std::string>{"[mocap] up = \"+z\""}));
  EXPECT_NEAR(fix.tilt_residual_deg, 0.0, 1e-9);
}

TEST(AxisFix, MotiveRightSetUpAndTheBodyUpMistake) {
  // OptiTrack Motive (Y-up): a rigid body created level takes the world's axes, so its up is +y
  // and its nose (placed along +x) is +x.
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  EXPECT_EQ(find_axis_fix(level, settings(axis::pos_y, axis::pos_x, axis::pos_x, axis::pos_y),
                          kLevel, axis::pos_y)
                .kind,
            AxisFixKind::agrees);
  // The same with the default body_up ("+z"): mocap sees it on its side.
  const auto fix = find_axis_fix(
      level, settings(axis::pos_y, axis::pos_x, axis::pos_x, axis::pos_z), kLevel, axis::pos_y);
  EXPECT_EQ(fix.kind, AxisFixKind::fix);
  EXPECT_EQ(fix.lines, (std::vector<std::string>{"[[vehicle]] body_up = \"+y\""}));
  EXPECT_EQ(fix.alternative_lines, (std::vector<std::string>{"[mocap] up = \"+z\""}));
}

TEST(AxisFix, VrpnWithNoCustomaryUpIsDecidedByThePose) {
  // A Z-up VRPN server (no customary up), `up = "+y"` by mistake, the vehicle level but yawed
  // 30° (nose between mocap +x and +y): only `up = "+z"` fits; no body axis can lie along a
  // world axis 30° off every body axis.
  const double c = std::cos(30.0 * kRad);
  const double s = std::sin(30.0 * kRad);
  const Eigen::Matrix3d yawed = columns({c, s, 0}, {-s, c, 0}, kZ);
  const auto fix = find_axis_fix(
      yawed, settings(axis::pos_y, axis::pos_x, axis::pos_x, axis::pos_z), kLevel, std::nullopt);
  EXPECT_EQ(fix.kind, AxisFixKind::fix);
  EXPECT_EQ(fix.lines, (std::vector<std::string>{"[mocap] up = \"+z\""}));
  EXPECT_TRUE(fix.alternative_lines.empty());
  EXPECT_NEAR(fix.tilt_residual_deg, 0.0, 1e-9);
}

TEST(AxisFix, ViconUdpOnASlopeAgreesWithItsResidual) {
  // Vicon Tracker UDP (Z-up): the vehicle stands nose-up 4° on a ramp. Its nose (body x) points
  // (cos 4°, 0, sin 4°), its top (body z) (−sin 4°, 0, cos 4°); the IMU says pitch +4°, and a
  // 1° trim error on top of it leaves a 1° residual.
  const double c = std::cos(4.0 * kRad);
  const double s = std::sin(4.0 * kRad);
  const Eigen::Matrix3d ramp = columns({c, 0, s}, kY, {-s, 0, c});
  const auto fix = find_axis_fix(ramp, settings(axis::pos_z, axis::pos_x, axis::pos_x, axis::pos_z),
                                 VehicleAtRest{0.0, 5.0 * kRad, std::nullopt}, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::agrees);
  EXPECT_NEAR(fix.tilt_residual_deg, 1.0, 1e-9);
}

TEST(AxisFix, NoseNinetyDegreesOffIsNamedWithAHeading) {
  // Vicon (Z-up), the vehicle level with its nose on +x (north, its compass heading 0), but the
  // rigid body was created with its +x out of the vehicle's left side: body x = world +y, body
  // z = world +z, body y = z × x = world −x. The nose is then body −y.
  const Eigen::Matrix3d sideways = columns(kY, -kX, kZ);
  const AxisSettings current = settings(axis::pos_z, axis::pos_x, axis::pos_x, axis::pos_z);
  const auto fix = find_axis_fix(sideways, current, VehicleAtRest{0.0, 0.0, 0.0}, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::fix);
  EXPECT_EQ(fix.lines, (std::vector<std::string>{"[[vehicle]] body_forward = \"-y\""}));
  ASSERT_TRUE(fix.heading_residual_deg);
  EXPECT_NEAR(*fix.heading_residual_deg, 0.0, 1e-9);
  // Turning the arena's north onto the body's +x fits as well, at this pose and at every other
  // one at rest (a turn about the vertical): named second, as the arena's possibility.
  EXPECT_EQ(fix.alternative_lines, (std::vector<std::string>{"[mocap] north = \"+y\""}));
  EXPECT_EQ(fix.text,
            "fix: [[vehicle]] body_forward = \"-y\" (then tilt 0.0°, heading 0.0°); or, if it is "
            "the arena's north that is turned (no pose at rest tells the two apart): [mocap] "
            "north = \"+y\"");
  // Without a heading the mistake is invisible at rest: the settings "agree", nose unchecked.
  const auto blind = find_axis_fix(sideways, current, kLevel, axis::pos_z);
  EXPECT_EQ(blind.kind, AxisFixKind::agrees);
}

TEST(AxisFix, AMirroredFrameIsNamedAsSuch) {
  // A left-handed orientation (a source whose y axis is reflected: determinant −1), the vehicle
  // level with its nose north: every axis choice is left-handed too.
  const Eigen::Matrix3d mirrored = columns(kX, -kY, kZ);
  const auto fix =
      find_axis_fix(mirrored, settings(axis::pos_z, axis::pos_x, axis::pos_x, axis::pos_z),
                    VehicleAtRest{0.0, 0.0, 0.0}, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::mirror);
  EXPECT_TRUE(fix.lines.empty());
  EXPECT_EQ(fix.text,
            "mirrored: only a left-handed axis choice makes mocap agree with the vehicle (tilt "
            "0.0°, heading 0.0°); no up, north, body_forward or body_up setting can fix it: check "
            "the handedness of the mocap system's or its streaming tool's frame");
}

TEST(AxisFix, NothingFitsAVehicleTiltedAgainstItsBody) {
  // The IMU says 45° of roll while the body is level in mocap (another body? not at rest?):
  // no signed-axis choice is within 15° of 45°.
  const auto fix = find_axis_fix(Eigen::Matrix3d::Identity(),
                                 settings(axis::pos_z, axis::pos_x, axis::pos_x, axis::pos_z),
                                 VehicleAtRest{45.0 * kRad, 0.0, std::nullopt}, axis::pos_z);
  EXPECT_EQ(fix.kind, AxisFixKind::no_fit);
  EXPECT_NEAR(fix.tilt_residual_deg, 45.0, 1e-9);
}

}  // namespace
}  // namespace mocaplink::core
