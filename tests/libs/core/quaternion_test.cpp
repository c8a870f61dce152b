// Quaternion utilities against hand-derived values (docs/frames.md "Quaternions", "Euler angles").
#include "mocaplink/core/quaternion.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const double kC45 = std::sqrt(0.5);  // cos 45 deg = sin 45 deg

TEST(CheckQuaternion, AcceptsUnitAndBothSigns) {
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(1, 0, 0, 0)), QuaternionFault::none);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(-1, 0, 0, 0)), QuaternionFault::none);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5)), QuaternionFault::none);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(-0.0, 0.0, -0.0, 1.0)), QuaternionFault::none);
}

TEST(CheckQuaternion, RejectsNonFinite) {
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(kNaN, 0, 0, 0)), QuaternionFault::non_finite);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(1, 0, kNaN, 0)), QuaternionFault::non_finite);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(1, 0, 0, kInf)), QuaternionFault::non_finite);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(-kInf, 0, 0, 0)), QuaternionFault::non_finite);
}

TEST(CheckQuaternion, RejectsNonUnitBeyondTolerance) {
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(0, 0, 0, 0)), QuaternionFault::non_unit);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(2, 0, 0, 0)), QuaternionFault::non_unit);
  // 1.0009 is inside the 1e-3 tolerance, 1.0011 and 0.9989 are outside.
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(1.0009, 0, 0, 0)), QuaternionFault::none);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(1.0011, 0, 0, 0)), QuaternionFault::non_unit);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(0, 0, 0.9989, 0)), QuaternionFault::non_unit);
  EXPECT_EQ(check_quaternion(Eigen::Quaterniond(1.05, 0, 0, 0), 0.1), QuaternionFault::none);
  EXPECT_EQ(to_string(QuaternionFault::non_unit), "non_unit");
}

TEST(ContinuousWith, FlipsIntoPreviousHemisphere) {
  const Eigen::Quaterniond previous(kC45, 0, 0, kC45);
  const Eigen::Quaterniond flipped =
      continuous_with(Eigen::Quaterniond(-kC45, 0, 0, -kC45), previous);
  EXPECT_DOUBLE_EQ(flipped.w(), kC45);
  EXPECT_DOUBLE_EQ(flipped.z(), kC45);
  const Eigen::Quaterniond kept = continuous_with(Eigen::Quaterniond(kC45, 0, 0, kC45), previous);
  EXPECT_DOUBLE_EQ(kept.w(), kC45);
  // Normalises: (2, 0, 0, 0) -> (1, 0, 0, 0); previous (-1, 0, 0, 0) -> (-1, 0, 0, 0).
  const Eigen::Quaterniond n =
      continuous_with(Eigen::Quaterniond(2, 0, 0, 0), Eigen::Quaterniond(-1, 0, 0, 0));
  EXPECT_DOUBLE_EQ(n.w(), -1.0);
  // Yaw 181.1 deg arriving as (0.01, 0, 0, -1) after 178.9 deg (0.01, 0, 0, 1): becomes
  // (-0.01, 0, 0, 1), next to the previous one.
  const Eigen::Quaterniond through =
      continuous_with(Eigen::Quaterniond(0.01, 0, 0, -1), Eigen::Quaterniond(0.01, 0, 0, 1));
  EXPECT_LT(through.w(), 0.0);
  EXPECT_GT(through.z(), 0.0);
}

TEST(Euler321, Identity) {
  const Euler321 e = euler_321_from_quaternion(Eigen::Quaterniond(1, 0, 0, 0));
  EXPECT_EQ(e.roll_rad, 0.0);
  EXPECT_EQ(e.pitch_rad, 0.0);
  EXPECT_EQ(e.yaw_rad, 0.0);
}

TEST(Euler321, SignedZerosGiveZero) {
  // (1, -0, -0, -0) and (-1, 0, 0, 0) are the identity too.
  for (const auto& q : {Eigen::Quaterniond(1, -0.0, -0.0, -0.0), Eigen::Quaterniond(-1, 0, 0, 0),
                        Eigen::Quaterniond(-1, -0.0, 0.0, -0.0)}) {
    const Euler321 e = euler_321_from_quaternion(q);
    EXPECT_EQ(e.roll_rad, 0.0);
    EXPECT_EQ(e.pitch_rad, 0.0);
    EXPECT_EQ(e.yaw_rad, 0.0);
  }
}

TEST(Euler321, SingleAxes) {
  // Half-angle quaternions written out by hand: (cos a/2, sin a/2 * axis).
  const double c15 = std::cos(kPi / 12);
  const double s15 = std::sin(kPi / 12);
  EXPECT_NEAR(euler_321_from_quaternion({c15, s15, 0, 0}).roll_rad, kPi / 6, 1e-15);
  EXPECT_NEAR(euler_321_from_quaternion({c15, 0, s15, 0}).pitch_rad, kPi / 6, 1e-15);
  EXPECT_NEAR(euler_321_from_quaternion({c15, 0, 0, s15}).yaw_rad, kPi / 6, 1e-15);
  EXPECT_NEAR(euler_321_from_quaternion({kC45, 0, 0, kC45}).yaw_rad, kPi / 2, 1e-15);
  EXPECT_NEAR(euler_321_from_quaternion({kC45, 0, 0, -kC45}).yaw_rad, -kPi / 2, 1e-15);
}

TEST(Euler321, Yaw180BothSignsIsPlusPi) {
  // q = (0, 0, 0, +-1) and with signed zeros: always +pi, never -pi.
  for (const auto& q : {Eigen::Quaterniond(0, 0, 0, 1), Eigen::Quaterniond(0, 0, 0, -1),
                        Eigen::Quaterniond(-0.0, -0.0, -0.0, -1), Eigen::Quaterniond(0, -0.0, 0, 1),
                        Eigen::Quaterniond(-0.0, 0, 0, 1)}) {
    const Euler321 e = euler_321_from_quaternion(q);
    EXPECT_EQ(e.yaw_rad, kPi) << q.coeffs().transpose();
    EXPECT_EQ(e.roll_rad, 0.0);
    EXPECT_EQ(e.pitch_rad, 0.0);
  }
  // Just past 180 from either side: +-(pi - 0.002).
  const double c = std::cos(0.5 * (kPi - 0.002));
  const double s = std::sin(0.5 * (kPi - 0.002));
  EXPECT_NEAR(euler_321_from_quaternion({c, 0, 0, s}).yaw_rad, kPi - 0.002, 1e-12);
  EXPECT_NEAR(euler_321_from_quaternion({c, 0, 0, -s}).yaw_rad, -(kPi - 0.002), 1e-12);
}

TEST(Euler321, YawThenPitchComposedByHand) {
  // q = qz(90) * qy(30) = (c45 c15, -s45 s15, c45 s15, s45 c15) by the Hamilton product.
  const double c15 = std::cos(kPi / 12);
  const double s15 = std::sin(kPi / 12);
  const Eigen::Quaterniond q(kC45 * c15, -kC45 * s15, kC45 * s15, kC45 * c15);
  for (const auto& qq : {q, Eigen::Quaterniond(-q.coeffs())}) {
    const Euler321 e = euler_321_from_quaternion(qq);
    EXPECT_NEAR(e.yaw_rad, kPi / 2, 1e-15);
    EXPECT_NEAR(e.pitch_rad, kPi / 6, 1e-15);
    EXPECT_NEAR(e.roll_rad, 0.0, 1e-15);
  }
}

TEST(Euler321, GimbalLockKeepsTheRotation) {
  // Pitch +90 then roll 0: qy(90) = (c45, 0, s45, 0); with yaw 40 deg in front.
  const double c20 = std::cos(kPi / 9);
  const double s20 = std::sin(kPi / 9);
  // qz(40) * qy(90) = (c20 c45, -s20 s45, c20 s45, s20 c45).
  const Eigen::Quaterniond q(c20 * kC45, -s20 * kC45, c20 * kC45, s20 * kC45);
  const Euler321 e = euler_321_from_quaternion(q);
  EXPECT_NEAR(e.pitch_rad, kPi / 2, 1e-6);
  EXPECT_NEAR(e.roll_rad, 0.0, 1e-12);
  EXPECT_NEAR(e.yaw_rad, 2 * kPi / 9, 1e-9);
}

TEST(Euler321, RoundTripsThroughQuaternionFromEuler) {
  for (double roll : {-3.0, -0.4, 0.0, 1.2, 3.1}) {
    for (double pitch : {-1.5, -0.2, 0.0, 0.7, 1.5}) {
      for (double yaw : {-3.1, -1.0, 0.0, 2.0, kPi}) {
        const Euler321 e = euler_321_from_quaternion(quaternion_from_euler_321({roll, pitch, yaw}));
        EXPECT_NEAR(e.roll_rad, roll, 1e-9);
        EXPECT_NEAR(e.pitch_rad, pitch, 1e-9);
        // Yaw is compared modulo 2 pi: pi may come back as -pi + 4e-16 after rounding.
        EXPECT_NEAR(std::remainder(e.yaw_rad - yaw, 2 * kPi), 0.0, 1e-9);
      }
    }
  }
  // quaternion_from_euler_321 against a hand value: yaw 90 -> (c45, 0, 0, s45).
  const Eigen::Quaterniond q = quaternion_from_euler_321({0, 0, kPi / 2});
  EXPECT_NEAR(q.w(), kC45, 1e-15);
  EXPECT_NEAR(q.z(), kC45, 1e-15);
}

TEST(RotationVector, HandValuesAndShortestSign) {
  const Eigen::Vector3d v = rotation_vector_from_quaternion({kC45, 0, 0, kC45});
  EXPECT_NEAR(v.z(), kPi / 2, 1e-15);
  // -q gives the same (shorter) rotation vector.
  const Eigen::Vector3d vn = rotation_vector_from_quaternion({-kC45, 0, 0, -kC45});
  EXPECT_NEAR(vn.z(), kPi / 2, 1e-15);
  // 270 deg about x is -90 deg about x.
  const double c135 = std::cos(3 * kPi / 4);
  const double s135 = std::sin(3 * kPi / 4);
  EXPECT_NEAR(rotation_vector_from_quaternion({c135, s135, 0, 0}).x(), -kPi / 2, 1e-15);
  EXPECT_EQ(rotation_vector_from_quaternion({1, 0, 0, 0}).norm(), 0.0);
  const Eigen::Quaterniond q = quaternion_from_rotation_vector({0, kPi / 2, 0});
  EXPECT_NEAR(q.w(), kC45, 1e-15);
  EXPECT_NEAR(q.y(), kC45, 1e-15);
  const Eigen::Quaterniond tiny = quaternion_from_rotation_vector({2e-10, 0, 0});
  EXPECT_NEAR(tiny.x(), 1e-10, 1e-22);
}

}  // namespace
}  // namespace mocaplink::core
