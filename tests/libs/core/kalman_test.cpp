// Kalman filters against hand-computed predictions and updates (docs/frames.md "Tracking").
#include "mocaplink/core/kalman.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

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

// The IMM of one axis as the textbook writes it (Bar-Shalom, Li & Kirubarajan 11.6.6): whole
// matrices, the mixed covariance from each model's own spread, the Joseph form as
// (I - K H) P (I - K H)^T + K R K^T, the model likelihoods as Gaussian log-densities. The filter
// computes the same quantities rearranged for speed; this holds it to the plain form.
struct TextbookImmAxis {
  using Matrix3 = Eigen::Matrix3d;
  using Vector3 = Eigen::Vector3d;
  Vector3 x[2];
  Matrix3 p[2];
  double mu[2] = {0.5, 0.5};
  double psd[2] = {0, 0};
  double tau = 0;

  void predict(double dt) {
    const double sw = 1.0 - std::exp(-dt / tau);
    const double pi[2][2] = {{1.0 - sw, sw}, {sw, 1.0 - sw}};
    Matrix3 f;
    f << 1, dt, dt * dt / 2, 0, 1, dt, 0, 0, 1;
    Matrix3 q;  // white jerk integrated over dt
    q << std::pow(dt, 5) / 20, std::pow(dt, 4) / 8, std::pow(dt, 3) / 6,  //
        std::pow(dt, 4) / 8, std::pow(dt, 3) / 3, dt * dt / 2,            //
        std::pow(dt, 3) / 6, dt * dt / 2, dt;
    Vector3 x0[2];
    Matrix3 p0[2];
    double c[2];
    for (int j = 0; j < 2; ++j) {
      c[j] = pi[0][j] * mu[0] + pi[1][j] * mu[1];
      x0[j].setZero();
      for (int i = 0; i < 2; ++i) x0[j] += pi[i][j] * mu[i] / c[j] * x[i];
      p0[j].setZero();
      for (int i = 0; i < 2; ++i) {
        const Vector3 d = x[i] - x0[j];
        p0[j] += pi[i][j] * mu[i] / c[j] * (p[i] + d * d.transpose());
      }
    }
    for (int j = 0; j < 2; ++j) {
      x[j] = f * x0[j];
      p[j] = f * p0[j] * f.transpose() + psd[j] * q;
      mu[j] = c[j];
    }
  }

  void update(double z, double r) {
    const Eigen::RowVector3d h(1, 0, 0);
    double log_likelihood[2];
    for (int j = 0; j < 2; ++j) {
      const double s = (h * p[j] * h.transpose())(0, 0) + r;
      const double nu = z - (h * x[j])(0, 0);
      const Vector3 k = p[j] * h.transpose() / s;
      const Matrix3 g = Matrix3::Identity() - k * h;
      x[j] += k * nu;
      p[j] = g * p[j] * g.transpose() + k * r * k.transpose();
      log_likelihood[j] = -0.5 * (nu * nu / s + std::log(2 * std::numbers::pi * s));
    }
    // In logs, scaled by the larger: an outlier underflows both densities in linear space.
    const double top = std::max(log_likelihood[0], log_likelihood[1]);
    const double w0 = mu[0] * std::exp(log_likelihood[0] - top);
    const double w1 = mu[1] * std::exp(log_likelihood[1] - top);
    mu[0] = std::clamp(w0 / (w0 + w1), 1e-4, 1.0 - 1e-4);
    mu[1] = 1.0 - mu[0];
  }

  [[nodiscard]] double mean(int row) const { return mu[0] * x[0][row] + mu[1] * x[1][row]; }
  [[nodiscard]] double variance(int row) const {
    double v = 0;
    for (int j = 0; j < 2; ++j) v += mu[j] * (p[j](row, row) + std::pow(x[j][row] - mean(row), 2));
    return v;
  }
};

TEST(PositionFilter, IsTheTextbookImmStepByStep) {
  // Many short runs (a long one would compare rounding amplified through the model switches, which
  // differs between x86-64 and an FMA target), each from its own start, with random steps and
  // measurements from sub-millimetre noise to 5 cm jumps, so that the models part, the
  // probabilities move both ways and the mixing sees every spread.
  const PositionFilterParams params{0.1, 300.0, 2.0};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> step_s(1.0 / 400, 1.0 / 50);
  const double scales[] = {1e-4, 1e-3, 1e-2, 5e-2};
  // Bounds about 20 times the largest difference seen on x86-64 and arm64 (FMA): the covariance
  // updates cancel (the position measurement nearly fixes the velocity), so rounding differs in
  // the 7th digit of a variance, far below any algebra mistake.
  const auto near = [](double got, double want, double bound) {
    return std::abs(got - want) <= bound * std::max(1.0, std::abs(want));
  };
  const auto near_relative = [](double got, double want, double bound) {
    return std::abs(got - want) <= bound * std::abs(want);
  };
  double lowest_mu = 1.0;
  double highest_mu = 0.0;
  for (int run = 0; run < 200; ++run) {
    const Eigen::Vector3d p0(unit(rng), unit(rng), unit(rng));
    const Eigen::Vector3d v0(unit(rng), unit(rng), unit(rng));
    const double r = std::pow(10.0, -7.0 + 3.0 * (unit(rng) + 1.0) / 2.0);  // 1e-7 .. 1e-4 m^2
    PositionFilter f(params);
    f.initialise(p0, v0, r, 4.0, 100.0);
    TextbookImmAxis book[3];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 2; ++j) {
        book[i].x[j] = {p0[i], v0[i], 0.0};
        book[i].p[j] = Eigen::Vector3d(r, 4.0, 100.0).asDiagonal();
      }
      book[i].psd[0] = params.quiet_jerk_psd;
      book[i].psd[1] = params.manoeuvre_jerk_psd;
      book[i].tau = params.mode_switch_time_s;
    }
    Eigen::Vector3d truth = p0;
    for (int step = 0; step < 30; ++step) {
      const double dt = step_s(rng);
      truth += v0 * dt;
      const double scale = scales[std::uniform_int_distribution<int>(0, 3)(rng)];
      const Eigen::Vector3d z = truth + scale * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      f.predict(dt);
      f.update(z, r);
      for (int i = 0; i < 3; ++i) {
        book[i].predict(dt);
        book[i].update(z[i], r);
        SCOPED_TRACE("run " + std::to_string(run) + " step " + std::to_string(step) + " axis " +
                     std::to_string(i));
        EXPECT_PRED3(near, f.p_m()[i], book[i].mean(0), 1e-8);
        EXPECT_PRED3(near, f.v_mps()[i], book[i].mean(1), 1e-6);
        EXPECT_PRED3(near, f.a_mps2()[i], book[i].mean(2), 2e-5);
        EXPECT_PRED3(near_relative, f.position_covariance()(i, i), book[i].variance(0), 2e-7);
        EXPECT_PRED3(near_relative, f.velocity_covariance()(i, i), book[i].variance(1), 1e-5);
        EXPECT_PRED3(near, f.manoeuvre_probability()[i], book[i].mu[1], 4e-6);
        lowest_mu = std::min(lowest_mu, book[i].mu[1]);
        highest_mu = std::max(highest_mu, book[i].mu[1]);
      }
      if (HasFailure()) return;  // one step's differences, not thousands of lines
    }
  }
  // Both models took over somewhere, so the mixing and the likelihoods were exercised.
  EXPECT_LT(lowest_mu, 0.01);
  EXPECT_GT(highest_mu, 0.99);
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
