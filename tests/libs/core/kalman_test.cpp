// Kalman filters against hand-computed predictions and updates (docs/frames.md "Tracking").
#include "mocaplink/core/kalman.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

TEST(ProcessNoise, MatchesTheContinuousWhiteAccelerationIntegral) {
  // q [dt^3/3, dt^2/2; dt^2/2, dt] with q = 2, dt = 0.1.
  const Matrix6d q = constant_velocity_process_noise(0.1, 2.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(q(i, i), 2.0 * 0.001 / 3.0, 1e-15);
    EXPECT_NEAR(q(i, i + 3), 0.01, 1e-15);
    EXPECT_NEAR(q(i + 3, i), 0.01, 1e-15);
    EXPECT_NEAR(q(i + 3, i + 3), 0.2, 1e-15);
  }
  EXPECT_EQ(q(0, 1), 0.0);
  EXPECT_EQ(q(0, 4), 0.0);
  EXPECT_EQ(constant_velocity_process_noise(0.0, 5.0).norm(), 0.0);
  // Two half steps compose into one full step: F(dt/2) Q(dt/2) F(dt/2)^T + Q(dt/2) = Q(dt).
  Matrix6d f = Matrix6d::Identity();
  f.topRightCorner<3, 3>().diagonal().setConstant(0.05);
  const Matrix6d half = constant_velocity_process_noise(0.05, 2.0);
  EXPECT_NEAR((f * half * f.transpose() + half - q).norm(), 0.0, 1e-15);
}

TEST(ProcessNoise, ConstantAccelerationByHand) {
  // q [dt^5/20 dt^4/8 dt^3/6; dt^4/8 dt^3/3 dt^2/2; dt^3/6 dt^2/2 dt] with q = 2, dt = 0.1.
  const Eigen::Matrix3d q = constant_acceleration_process_noise(0.1, 2.0);
  Eigen::Matrix3d want;
  want << 1e-6, 2.5e-5, 2.0 / 6000.0, 2.5e-5, 2.0 / 3000.0, 0.01, 2.0 / 6000.0, 0.01, 0.2;
  EXPECT_NEAR((q - want).norm(), 0.0, 1e-15);
  // Two half steps compose into one full step.
  Eigen::Matrix3d f;
  f << 1, 0.05, 0.00125, 0, 1, 0.05, 0, 0, 1;
  const Eigen::Matrix3d half = constant_acceleration_process_noise(0.05, 2.0);
  EXPECT_NEAR((f * half * f.transpose() + half - q).norm(), 0.0, 1e-15);
}

// With both models equal the IMM is exactly one constant-acceleration Kalman filter, which can be
// followed by hand.
PositionFilter single_model(double psd) {
  return PositionFilter(PositionFilterParams{psd, psd, 1.0});
}

TEST(PositionFilter, PredictByHand) {
  PositionFilter f = single_model(0.0);
  f.initialise({1, 2, 3}, {1, 0, -1}, 1.0, 4.0, 2.0);
  f.predict(0.5);
  EXPECT_EQ(f.p_m(), Eigen::Vector3d(1.5, 2, 2.5));
  EXPECT_EQ(f.v_mps(), Eigen::Vector3d(1, 0, -1));
  EXPECT_EQ(f.a_mps2(), Eigen::Vector3d::Zero());
  // P = F diag(1, 4, 2) F^T, F = [1 .5 .125; 0 1 .5; 0 0 1]:
  // pp = 1 + .25 * 4 + .015625 * 2 = 2.03125, vv = 4 + .25 * 2 = 4.5.
  EXPECT_DOUBLE_EQ(f.position_covariance()(0, 0), 2.03125);
  EXPECT_DOUBLE_EQ(f.velocity_covariance()(2, 2), 4.5);
  EXPECT_EQ(f.position_covariance()(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(f.manoeuvre_probability().x(), 0.5);
}

TEST(PositionFilter, UpdateByHand) {
  PositionFilter f = single_model(0.0);
  f.initialise({1, 2, 3}, {1, 0, -1}, 1.0, 4.0, 2.0);
  f.predict(0.5);  // x: p 1.5, v 1, a 0; Ppp 2.03125, Ppv 2.125, Ppa 0.25
  const Innovation in = f.innovation({4.5, 2, 2.5}, 1.0);
  EXPECT_DOUBLE_EQ(in.nu.x(), 3.0);
  EXPECT_DOUBLE_EQ(in.s(0, 0), 3.03125);
  EXPECT_NEAR(in.mahalanobis, 3.0 / std::sqrt(3.03125), 1e-15);
  f.update({4.5, 2, 2.5}, 1.0);
  // K = [2.03125, 2.125, 0.25] / 3.03125.
  EXPECT_NEAR(f.p_m().x(), 1.5 + 3.0 * 2.03125 / 3.03125, 1e-14);
  EXPECT_NEAR(f.v_mps().x(), 1.0 + 3.0 * 2.125 / 3.03125, 1e-14);
  EXPECT_NEAR(f.a_mps2().x(), 3.0 * 0.25 / 3.03125, 1e-14);
  // Ppp+ = Ppp - Ppp^2 / S = Ppp r / S.
  EXPECT_NEAR(f.position_covariance()(0, 0), 2.03125 / 3.03125, 1e-14);
  // Measured on its prediction: y unchanged.
  EXPECT_NEAR(f.p_m().y(), 2.0, 1e-15);
  // Equal models: equal likelihoods, probabilities stay 1/2.
  EXPECT_NEAR(f.manoeuvre_probability().x(), 0.5, 1e-15);
}

TEST(PositionFilter, NoVelocityLagUnderConstantAcceleration) {
  // A constant-velocity filter would lag by k1/k2 * a; the constant-acceleration models do not.
  PositionFilter f;
  f.initialise({0, 0, 0}, {0, 0, 0}, 1e-6, 4.0, 100.0);
  const Eigen::Vector3d a(2.0, -1.0, 0.5);
  for (int k = 1; k <= 300; ++k) {
    const double t = 0.01 * k;
    f.predict(0.01);
    f.update(0.5 * a * t * t, 2.5e-7);
  }
  EXPECT_NEAR((f.v_mps() - a * 3.0).norm(), 0.0, 1e-3);
  EXPECT_NEAR((f.a_mps2() - a).norm(), 0.0, 0.05);
  const Eigen::Matrix3d pc = f.position_covariance();
  EXPECT_GT(pc(0, 0), 0.0);
  EXPECT_LT(pc(0, 0), 2.5e-7);
}

TEST(PositionFilter, SwitchesToTheManoeuvreModelWhenTheBodyAccelerates) {
  PositionFilter f;  // defaults: quiet 0.1, manoeuvre 300 m^2/s^5
  f.initialise({0, 0, 0}, {0, 0, 0}, 2.5e-7, 1.0, 1.0);
  for (int k = 1; k <= 200; ++k) {
    f.predict(0.01);
    f.update({0, 0, 0}, 2.5e-7);
  }
  EXPECT_LT(f.manoeuvre_probability().maxCoeff(), 0.05);
  // Sudden 5 m/s^2 along x from t = 0.
  double max_p = 0.0;
  for (int k = 1; k <= 10; ++k) {
    const double t = 0.01 * k;
    f.predict(0.01);
    f.update({2.5 * t * t, 0, 0}, 2.5e-7);
    max_p = std::max(max_p, f.manoeuvre_probability().x());
  }
  EXPECT_GT(max_p, 0.5);
  EXPECT_LT(f.manoeuvre_probability().y(), 0.05);
}

TEST(PositionFilter, HugeInnovationDoesNotBreakTheProbabilities) {
  PositionFilter f;
  f.initialise({0, 0, 0}, {0, 0, 0}, 2.5e-7, 1.0, 1.0);
  f.predict(0.01);
  f.update({1000, 0, 0}, 2.5e-7);  // likelihoods underflow in linear space
  EXPECT_TRUE(f.manoeuvre_probability().allFinite());
  EXPECT_TRUE(f.p_m().allFinite());
  EXPECT_GT(f.manoeuvre_probability().x(), 0.5);
}

TEST(AttitudeFilter, PredictIntegratesTheBodyRate) {
  AttitudeFilter f;
  f.initialise(Eigen::Quaterniond::Identity(), {0, 0, 1}, 0.01, 0.01);
  f.predict(0.5, 0.0);
  // 0.5 rad about z: (cos 0.25, 0, 0, sin 0.25).
  EXPECT_NEAR(f.q_ned_frd().w(), std::cos(0.25), 1e-15);
  EXPECT_NEAR(f.q_ned_frd().z(), std::sin(0.25), 1e-15);
  // Rate 0.5 rad/s about body x after yawing 90 deg: body axes, so q = qz(90) * qx(0.5 * dt).
  AttitudeFilter g;
  const double a = std::sqrt(0.5);
  g.initialise({a, 0, 0, a}, {0.5, 0, 0}, 0.01, 0.01);
  g.predict(1.0, 0.0);
  const Eigen::Quaterniond want =
      Eigen::Quaterniond(a, 0, 0, a) * Eigen::Quaterniond(std::cos(0.25), std::sin(0.25), 0, 0);
  EXPECT_NEAR(std::abs(g.q_ned_frd().dot(want)), 1.0, 1e-15);
}

TEST(AttitudeFilter, UpdateByHandAndSignOfMeasurement) {
  AttitudeFilter f;
  f.initialise(Eigen::Quaterniond::Identity(), {0, 0, 0}, 2.0, 0.0);
  // Measurement 0.3 rad about x, given as -q: the innovation is +0.3 about x either way.
  const Eigen::Quaterniond m(std::cos(0.15), std::sin(0.15), 0, 0);
  const Innovation in = f.innovation(Eigen::Quaterniond(-m.coeffs()), 1.0);
  EXPECT_NEAR(in.nu.x(), 0.3, 1e-15);
  EXPECT_NEAR(in.mahalanobis, 0.3 / std::sqrt(3.0), 1e-15);
  f.update(in, 1.0);
  // K = 2/3: the estimate moves 0.2 rad about x; attitude variance 2 - 4/3.
  EXPECT_NEAR(f.q_ned_frd().w(), std::cos(0.1), 1e-15);
  EXPECT_NEAR(f.q_ned_frd().x(), std::sin(0.1), 1e-15);
  EXPECT_NEAR(f.covariance()(0, 0), 2.0 / 3.0, 1e-15);
}

TEST(AttitudeFilter, ConvergesToAConstantRateThroughYaw180) {
  AttitudeFilter f;
  f.initialise(Eigen::Quaterniond::Identity(), {0, 0, 0}, 1e-4, 10.0);
  const double rate = 2.0;  // rad/s about body z, passes 180 deg at t = 1.57 s
  Eigen::Quaterniond previous = f.q_ned_frd();
  for (int k = 1; k <= 300; ++k) {
    const double t = 0.01 * k;
    f.predict(0.01, 10.0);
    // Measurements in the w >= 0 hemisphere, as a source would canonicalise them: they flip sign
    // at 180 deg, the filter must not.
    Eigen::Quaterniond m(std::cos(rate * t / 2), 0, 0, std::sin(rate * t / 2));
    if (m.w() < 0) m.coeffs() = -m.coeffs();
    f.update(f.innovation(m, 1e-6), 1e-6);
    EXPECT_GT(f.q_ned_frd().dot(previous), 0.99) << t;
    previous = f.q_ned_frd();
  }
  EXPECT_NEAR(f.w_frd_radps().z(), rate, 1e-3);
  EXPECT_NEAR(std::abs(f.q_ned_frd().dot(
                  Eigen::Quaterniond(std::cos(rate * 1.5), 0, 0, std::sin(rate * 1.5)))),
              1.0, 1e-9);
}

}  // namespace
}  // namespace mocaplink::core
