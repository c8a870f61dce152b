// Axis mapping against hand-derived rotations (docs/frames.md "Axis mapping").
#include "mocaplink/core/axis_mapping.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_vec(const Eigen::Vector3d& got, const Eigen::Vector3d& want, double tol = 1e-12) {
  EXPECT_NEAR((got - want).norm(), 0.0, tol)
      << "got " << got.transpose() << " want " << want.transpose();
}

WorldAxisMapping world(std::string_view up, std::string_view north) {
  const auto m = WorldAxisMapping::parse(up, north);
  EXPECT_TRUE(m.has_value()) << (m ? "" : m.error().message);
  return m ? *m : WorldAxisMapping{};
}

TEST(SignedAxis, ParsesExactlySixStrings) {
  EXPECT_EQ(*parse_signed_axis("+x", "up"), (SignedAxis{0, 1}));
  EXPECT_EQ(*parse_signed_axis("-y", "up"), (SignedAxis{1, -1}));
  EXPECT_EQ(*parse_signed_axis("+z", "up"), (SignedAxis{2, 1}));
  for (std::string_view bad : {"", "x", "+X", "z+", "+w", "++x", "+x ", " -z", "-", "1"}) {
    const auto r = parse_signed_axis(bad, "body_up");
    ASSERT_FALSE(r.has_value()) << bad;
    EXPECT_EQ(r.error().field, "body_up");
  }
  EXPECT_EQ(to_string(SignedAxis{1, -1}), "-y");
  EXPECT_EQ(to_string(SignedAxis{2, 1}), "+z");
}

TEST(WorldAxisMapping, ViconZUpXNorth) {
  // N = +x, D = -z, E = D x N = -y: (1, 2, 3) -> (1, -2, -3).
  const auto m = world("+z", "+x");
  expect_vec(m.to_ned({1, 2, 3}), {1, -2, -3});
  // That is a 180 deg rotation about x: q = (0, 1, 0, 0).
  EXPECT_NEAR(std::abs(m.q_ned_world().x()), 1.0, 1e-15);
  EXPECT_NEAR(m.r_ned_world().determinant(), 1.0, 1e-15);
}

TEST(WorldAxisMapping, MotiveYUpXNorth) {
  // N = +x, D = -y, E = D x N = -(y x x) = +z: (1, 2, 3) -> (1, 3, -2).
  expect_vec(world("+y", "+x").to_ned({1, 2, 3}), {1, 3, -2});
  // Motive with north = -z: N = -z, D = -y, E = -y x -z = y x z = +x: (1, 2, 3) -> (-3, 1, -2).
  expect_vec(world("+y", "-z").to_ned({1, 2, 3}), {-3, 1, -2});
}

TEST(WorldAxisMapping, ZDownFrameIsIdentity) {
  // A frame that already is NED: up = -z, north = +x. E = +z x +x = +y.
  const auto m = world("-z", "+x");
  expect_vec(m.to_ned({1, 2, 3}), {1, 2, 3});
  EXPECT_NEAR(std::abs(m.q_ned_world().w()), 1.0, 1e-15);
}

TEST(WorldAxisMapping, AngleNorthRotatesAboutUp) {
  // angle:0 == +x; angle:90 == +y (counter-clockwise seen from above, up = +z).
  expect_vec(world("+z", "angle:0").to_ned({1, 2, 3}), world("+z", "+x").to_ned({1, 2, 3}));
  expect_vec(world("+z", "angle:90").to_ned({1, 2, 3}), world("+z", "+y").to_ned({1, 2, 3}));
  expect_vec(world("+z", "angle:-90").to_ned({1, 2, 3}), world("+z", "-y").to_ned({1, 2, 3}));
  expect_vec(world("+z", "angle:180").to_ned({1, 2, 3}), world("+z", "-x").to_ned({1, 2, 3}));
  expect_vec(world("+z", "angle:450").to_ned({1, 2, 3}), world("+z", "+y").to_ned({1, 2, 3}));
  // angle:90 with up = +z: N = +y, E = -z x +y = +x: (1, 2, 3) -> (2, 1, -3).
  expect_vec(world("+z", "angle:90").to_ned({1, 2, 3}), {2, 1, -3});
  // angle:45: N = (a, a, 0), E = -z x N = (a, -a, 0), a = sqrt(1/2).
  const double a = std::sqrt(0.5);
  expect_vec(world("+z", "angle:45").to_ned({1, 0, 0}), {a, a, 0});
  expect_vec(world("+z", "angle:+45").to_ned({0, 1, 0}), {a, -a, 0});
  expect_vec(world("+z", "angle:37.5").to_ned({1, 0, 0}),
             {std::cos(37.5 * kPi / 180), std::sin(37.5 * kPi / 180), 0});
  // Motive (up = +y): reference +x, rotating about +y: angle:90 -> x rotated to -z.
  expect_vec(world("+y", "angle:90").to_ned({1, 2, 3}), world("+y", "-z").to_ned({1, 2, 3}));
  // up = +x: the reference is +y.
  expect_vec(world("+x", "angle:0").to_ned({1, 2, 3}), world("+x", "+y").to_ned({1, 2, 3}));
  // up = -z (down): rotating about -z is clockwise seen from +z.
  expect_vec(world("-z", "angle:90").to_ned({1, 2, 3}), world("-z", "-y").to_ned({1, 2, 3}));
}

TEST(WorldAxisMapping, RejectsBadCombinations) {
  struct Case {
    std::string_view up, north, field;
  };
  for (const auto& c :
       {Case{"+z", "+z", "north"}, Case{"+z", "-z", "north"}, Case{"-y", "+y", "north"},
        Case{"z", "+x", "up"}, Case{"+z", "x", "north"}, Case{"+z", "angle:", "north"},
        Case{"+z", "angle:abc", "north"}, Case{"+z", "angle:nan", "north"},
        Case{"+z", "angle:inf", "north"}, Case{"+z", "angle:1e999", "north"},
        Case{"+z", "angle:12deg", "north"}, Case{"+z", "Angle:12", "north"}, Case{"", "", "up"}}) {
    const auto r = WorldAxisMapping::parse(c.up, c.north);
    ASSERT_FALSE(r.has_value()) << c.up << " " << c.north;
    EXPECT_EQ(r.error().field, c.field) << c.up << " " << c.north;
    EXPECT_FALSE(r.error().message.empty());
  }
}

TEST(BodyAxisMapping, DefaultViconFluToFrd) {
  const auto b = BodyAxisMapping::parse("+x", "+z");
  ASSERT_TRUE(b.has_value());
  // F = +x, D = -z, R = D x F = -y.
  Eigen::Matrix3d want;
  want << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  EXPECT_NEAR((b->r_body_frd() - want).norm(), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(b->q_body_frd().x()), 1.0, 1e-15);
}

TEST(BodyAxisMapping, NoseOnY) {
  // F = +y, D = -z, R = -z x +y = +x.
  const auto b = BodyAxisMapping::parse("+y", "+z");
  ASSERT_TRUE(b.has_value());
  expect_vec(b->r_body_frd().col(0), {0, 1, 0});
  expect_vec(b->r_body_frd().col(1), {1, 0, 0});
  expect_vec(b->r_body_frd().col(2), {0, 0, -1});
  const auto bad = BodyAxisMapping::parse("+x", "-x");
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().field, "body_up");
  EXPECT_EQ(BodyAxisMapping::parse("x", "+z").error().field, "body_forward");
}

TEST(BodyAxisMapping, KeepsTheAxesItWasMadeFrom) {
  // The config writes a running vehicle's mapping back as its body_forward / body_up keys.
  const auto b = BodyAxisMapping::parse("-y", "+x");
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->forward(), axis::neg_y);
  EXPECT_EQ(b->up(), axis::pos_x);
  // The identity is FRD itself: nose +x, top -z.
  const BodyAxisMapping identity;
  EXPECT_EQ(identity.forward(), axis::pos_x);
  EXPECT_EQ(identity.up(), axis::neg_z);
  EXPECT_NEAR((identity.r_body_frd() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
}

TEST(AxisMapping, LevelViconBodyFacingNorthIsIdentity) {
  const auto m = AxisMapping::parse("+z", "+x");
  ASSERT_TRUE(m.has_value());
  const Eigen::Quaterniond q = m->attitude_ned_frd(Eigen::Quaterniond::Identity());
  EXPECT_NEAR(std::abs(q.w()), 1.0, 1e-15);
}

TEST(AxisMapping, ViconBodyYawedTowardsMocapYFacesWest) {
  // Body rotated +90 deg about mocap z: its nose (+x) points along mocap +y, which is NED west
  // (E = -y), so yaw = -90 deg; its top (+z) still points up: FRD z maps to NED down.
  const auto m = AxisMapping::parse("+z", "+x");
  ASSERT_TRUE(m.has_value());
  const double a = std::sqrt(0.5);
  const Eigen::Quaterniond q = m->attitude_ned_frd(Eigen::Quaterniond(a, 0, 0, a));
  expect_vec(q * Eigen::Vector3d::UnitX(), {0, -1, 0});
  expect_vec(q * Eigen::Vector3d::UnitZ(), {0, 0, 1});
  EXPECT_NEAR(euler_321_from_quaternion(q).yaw_rad, -kPi / 2, 1e-12);
}

TEST(AxisMapping, MotiveBodyPitchedNoseUp) {
  // Motive: y up, north = +x (so E = +z), body axes x forward / y up. Nose up 30 deg turns the
  // nose (+x) towards +y (up): +30 deg about mocap +z, q = (cos 15, 0, 0, sin 15). In NED that is
  // +30 deg about east: pitch +30 deg, roll 0, yaw 0.
  const auto m = AxisMapping::parse("+y", "+x", "+x", "+y");
  ASSERT_TRUE(m.has_value());
  const Eigen::Quaterniond q =
      m->attitude_ned_frd(Eigen::Quaterniond(std::cos(kPi / 12), 0, 0, std::sin(kPi / 12)));
  const Euler321 e = euler_321_from_quaternion(q);
  EXPECT_NEAR(e.pitch_rad, kPi / 6, 1e-12);
  EXPECT_NEAR(e.roll_rad, 0.0, 1e-12);
  EXPECT_NEAR(e.yaw_rad, 0.0, 1e-12);
  // Nose direction in NED: (cos 30, 0, -sin 30) (north and up).
  expect_vec(q * Eigen::Vector3d::UnitX(), {std::cos(kPi / 6), 0, -0.5});
}

TEST(AxisMapping, KeepsTheInputNorm) {
  const auto m = AxisMapping::parse("+z", "angle:20");
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->attitude_ned_frd(Eigen::Quaterniond(2, 0, 0, 0)).norm(), 2.0, 1e-12);
  const auto bad = AxisMapping::parse("+z", "+x", "+y", "-y");
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().field, "body_up");
}

TEST(AxisMapping, DocsFramesWorkedExample) {
  // docs/frames.md "Worked example": Vicon (up +z, north +x, FLU body) reports (1234.5, -678.9,
  // 1500.0) mm and the x-first quaternion (0, 0, sin 15, cos 15): yawed 30 deg from mocap +x
  // towards mocap +y. By hand: N = x, E = -y, D = -z; the nose points 30 deg west of north.
  const auto m = AxisMapping::parse("+z", "+x", "+x", "+z");
  ASSERT_TRUE(m.has_value());
  const double s15 = std::sin(kPi / 12);
  const double c15 = std::cos(kPi / 12);
  const double vicon_xyzw[4] = {0.0, 0.0, s15, c15};
  const Eigen::Quaterniond q_world_body(vicon_xyzw[3], vicon_xyzw[0], vicon_xyzw[1], vicon_xyzw[2]);
  expect_vec(m->position_ned(Eigen::Vector3d(1234.5, -678.9, 1500.0) / 1000.0),
             {1.2345, 0.6789, -1.5}, 1e-15);
  // (0,1,0,0) * (c15,0,0,s15) * (0,1,0,0) = (-c15, 0, 0, s15), the same rotation as
  // (c15, 0, 0, -s15): yaw -30 deg.
  const Eigen::Quaterniond q = m->attitude_ned_frd(q_world_body);
  EXPECT_NEAR(std::abs(q.w()), c15, 1e-15);
  EXPECT_NEAR(q.z() / q.w(), -s15 / c15, 1e-15);
  EXPECT_NEAR(q.x(), 0.0, 1e-15);
  EXPECT_NEAR(q.y(), 0.0, 1e-15);
  const Euler321 e = euler_321_from_quaternion(q);
  EXPECT_NEAR(e.roll_rad, 0.0, 1e-15);
  EXPECT_NEAR(e.pitch_rad, 0.0, 1e-15);
  EXPECT_NEAR(e.yaw_rad, -kPi / 6, 1e-15);
  expect_vec(q * Eigen::Vector3d::UnitX(), {std::sqrt(0.75), -0.5, 0.0}, 1e-15);
}

}  // namespace
}  // namespace mocaplink::core
