#include "mocaplink/core/kalman.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

using Matrix63d = Eigen::Matrix<double, 6, 3>;

// The innovation nu with covariance S (symmetric positive definite: P + R, R > 0): S^-1 once, in
// closed form (Eigen's fixed-size 3x3 inverse, cofactors over the determinant), for both the gate
// and the gain. An LDLT factorisation per use cost a third of the tracker's time on every frame
// (docs/performance.md "Where the time goes"). The cofactor inverse does not pivot: its relative
// error grows with S's condition number, at most 1 + lambda_max(P) / r here (S = P + r I). With
// the default noises and the longest prediction before a body counts as lost (250 ms) that stays
// below about 1e7, which leaves the inverse some nine significant digits.
Innovation make_innovation(const Eigen::Vector3d& nu, const Eigen::Matrix3d& s) {
  Innovation in;
  in.nu = nu;
  in.s = s;
  in.s_inverse = s.inverse();
  in.mahalanobis = std::sqrt(std::max(0.0, nu.dot(in.s_inverse * nu)));
  return in;
}

// Kalman update for H = [I 0] (the measurement is the first three states), Joseph form so that P
// stays symmetric positive semi-definite despite rounding: P' = G P G^T + r K K^T, G = I - K H.
// H's zeros spelled out: G P = P - K (H P) = P - K P.topRows<3>, and (G P) G^T = G P - (G P H^T)
// K^T, a third of the multiplications of the two 6x6 products. Returns the state correction.
Vector6d joseph_update(Matrix6d& p, const Innovation& in, double r) {
  const Matrix63d k = p.leftCols<3>() * in.s_inverse;  // P H^T S^-1
  const Matrix6d gp = p - k * p.topRows<3>();
  p = gp - gp.leftCols<3>() * k.transpose() + r * k * k.transpose();
  p = (0.5 * (p + p.transpose())).eval();  // eval: p is read transposed while it is written
  return k * in.nu;
}

// P <- F P F^T for one axis of the constant-acceleration model, F = [1 dt dt^2/2; 0 1 dt; 0 0 1]:
// F's zeros and ones spelled out (rows, then columns), a third of the two 3x3 products.
void propagate_constant_acceleration(Eigen::Matrix3d& p, double dt_s) {
  const double half_dt2 = 0.5 * dt_s * dt_s;
  p.row(0) += dt_s * p.row(1) + half_dt2 * p.row(2);  // F P: row 0 first, it reads rows 1 and 2
  p.row(1) += dt_s * p.row(2);
  p.col(0) += dt_s * p.col(1) + half_dt2 * p.col(2);  // (F P) F^T
  p.col(1) += dt_s * p.col(2);
}

}  // namespace

Matrix6d constant_velocity_process_noise(double dt_s, double psd) {
  const double dt2 = dt_s * dt_s;
  const Eigen::Matrix3d i3 = Eigen::Matrix3d::Identity();
  Matrix6d q;
  q.topLeftCorner<3, 3>() = (psd * dt2 * dt_s / 3.0) * i3;
  q.topRightCorner<3, 3>() = (psd * dt2 / 2.0) * i3;
  q.bottomLeftCorner<3, 3>() = (psd * dt2 / 2.0) * i3;
  q.bottomRightCorner<3, 3>() = (psd * dt_s) * i3;
  return q;
}

Eigen::Matrix3d constant_acceleration_process_noise(double dt_s, double psd) {
  const double dt2 = dt_s * dt_s;
  const double dt3 = dt2 * dt_s;
  Eigen::Matrix3d q;
  q << dt3 * dt2 / 20.0, dt2 * dt2 / 8.0, dt3 / 6.0,  //
      dt2 * dt2 / 8.0, dt3 / 3.0, dt2 / 2.0,          //
      dt3 / 6.0, dt2 / 2.0, dt_s;
  return psd * q;
}

void PositionFilter::initialise(const Eigen::Vector3d& p_m, const Eigen::Vector3d& v_mps,
                                double p_var_m2, double v_var_m2ps2, double a_var_m2ps4) {
  for (int i = 0; i < 3; ++i) {
    Axis& axis = axis_[i];
    for (Model& m : axis.model) {
      m.x = {p_m[i], v_mps[i], 0.0};
      m.p = Eigen::Vector3d(p_var_m2, v_var_m2ps2, a_var_m2ps4).asDiagonal();
    }
    axis.mu[0] = axis.mu[1] = 0.5;
  }
}

void PositionFilter::predict(double dt_s) {
  // Markov switching probability over dt for a mean sojourn time tau: 1 - exp(-dt / tau).
  const double sw = -std::expm1(-dt_s / params_.mode_switch_time_s);
  const double pi[2][2] = {{1.0 - sw, sw}, {sw, 1.0 - sw}};  // pi[from][to]
  const double half_dt2 = 0.5 * dt_s * dt_s;
  const Eigen::Matrix3d q_unit = constant_acceleration_process_noise(dt_s, 1.0);
  const double psd[2] = {params_.quiet_jerk_psd, params_.manoeuvre_jerk_psd};
  for (Axis& axis : axis_) {
    // IMM interaction: each model restarts from the mixture of both, weighted by the
    // probability that the system was in model i given that it is now in model j:
    //   x_j = w0 x0 + w1 x1,  P_j = w0 (P0 + d0 d0^T) + w1 (P1 + d1 d1^T),  di = xi - x_j.
    // With w0 + w1 = 1, d0 = w1 (x0 - x1) and d1 = -w0 (x0 - x1), so the spread of the means is
    // w0 w1 D D^T with D = x0 - x1: one outer product per axis instead of two per model.
    const Eigen::Vector3d d = axis.model[0].x - axis.model[1].x;
    const Eigen::Matrix3d spread = d * d.transpose();
    Model mixed[2];
    double c[2];
    for (int j = 0; j < 2; ++j) {
      c[j] = pi[0][j] * axis.mu[0] + pi[1][j] * axis.mu[1];
      const double w0 = pi[0][j] * axis.mu[0] / c[j];
      const double w1 = 1.0 - w0;
      mixed[j].x = w0 * axis.model[0].x + w1 * axis.model[1].x;
      mixed[j].p = w0 * axis.model[0].p + w1 * axis.model[1].p + (w0 * w1) * spread;
    }
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector3d& x = mixed[j].x;
      axis.model[j].x = {x[0] + dt_s * x[1] + half_dt2 * x[2], x[1] + dt_s * x[2], x[2]};  // F x
      propagate_constant_acceleration(mixed[j].p, dt_s);
      axis.model[j].p = mixed[j].p + psd[j] * q_unit;
      axis.mu[j] = c[j];  // predicted model probability
    }
  }
}

Innovation PositionFilter::innovation(const Eigen::Vector3d& z_m, double r_m2) const {
  return make_innovation(z_m - p_m(), position_covariance() + r_m2 * Eigen::Matrix3d::Identity());
}

void PositionFilter::update(const Eigen::Vector3d& z_m, double r_m2) {
  // Floor on a model probability so that a long-unused model can take over within a few frames.
  constexpr double kMinProbability = 1e-4;
  for (int i = 0; i < 3; ++i) {
    Axis& axis = axis_[i];
    double s[2];
    double nu2_over_s[2];
    for (int j = 0; j < 2; ++j) {
      Model& m = axis.model[j];
      s[j] = m.p(0, 0) + r_m2;
      const double nu = z_m[i] - m.x[0];
      const Eigen::Vector3d c = m.p.col(0);  // P h^T, h = [1 0 0]
      const Eigen::Vector3d k = c / s[j];
      m.x += k * nu;
      // Joseph form P' = G P G^T + r k k^T, G = I - k h, multiplied out with h P = c^T and
      // h P h^T + r = s: P' = P - k c^T - c k^T + s k k^T. As the Joseph form it holds for any k
      // (a rounded gain costs only second-order error); each element is computed once for both
      // triangles, so P' is exactly symmetric.
      for (int row = 0; row < 3; ++row) {
        for (int col = row; col < 3; ++col) {
          const double v =
              m.p(row, col) - (k[row] * c[col] + c[row] * k[col]) + s[j] * k[row] * k[col];
          m.p(row, col) = v;
          m.p(col, row) = v;
        }
      }
      nu2_over_s[j] = nu * nu / s[j];
    }
    // Bayes on the model probabilities with the Gaussian likelihoods
    // L_j = exp(-nu_j^2 / (2 s_j)) / sqrt(2 pi s_j), as the ratio L1 / L0 (one exp, no logs). A
    // huge innovation sends the ratio to 0 or infinity (mu0, mu1 > 0 keep mu0 a number unless
    // nu^2 itself overflows, as the logs did), and the clamp below keeps both models alive.
    const double ratio = std::sqrt(s[0] / s[1]) * std::exp(0.5 * (nu2_over_s[0] - nu2_over_s[1]));
    const double mu0 = axis.mu[0] / (axis.mu[0] + axis.mu[1] * ratio);
    axis.mu[0] = std::clamp(mu0, kMinProbability, 1.0 - kMinProbability);
    axis.mu[1] = 1.0 - axis.mu[0];
  }
}

Eigen::Vector3d PositionFilter::combined(int row) const {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    const Axis& a = axis_[i];
    out[i] = a.mu[0] * a.model[0].x[row] + a.mu[1] * a.model[1].x[row];
  }
  return out;
}

Eigen::Matrix3d PositionFilter::combined_cov(int row) const {
  Eigen::Matrix3d out = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const Axis& a = axis_[i];
    const double mean = a.mu[0] * a.model[0].x[row] + a.mu[1] * a.model[1].x[row];
    double var = 0.0;
    for (int j = 0; j < 2; ++j) {
      const double d = a.model[j].x[row] - mean;
      var += a.mu[j] * (a.model[j].p(row, row) + d * d);
    }
    out(i, i) = var;
  }
  return out;
}

Eigen::Vector3d PositionFilter::manoeuvre_probability() const {
  return {axis_[0].mu[1], axis_[1].mu[1], axis_[2].mu[1]};
}

void AttitudeFilter::initialise(const Eigen::Quaterniond& q_ned_frd,
                                const Eigen::Vector3d& w_frd_radps, double att_var_rad2,
                                double rate_var_rad2ps2) {
  q_ = q_ned_frd.normalized();
  w_ = w_frd_radps;
  p_.setZero();
  p_.topLeftCorner<3, 3>().diagonal().setConstant(att_var_rad2);
  p_.bottomRightCorner<3, 3>().diagonal().setConstant(rate_var_rad2ps2);
}

void AttitudeFilter::predict(double dt_s, double angular_accel_psd) {
  const Eigen::Quaterniond step = quaternion_from_rotation_vector(w_ * dt_s);
  // Error dynamics of a right-multiplied error: dtheta' = -[w]x dtheta + dw. Over dt the attitude
  // error is carried into the new body axes by step^-1 (Sola, "Quaternion kinematics for the
  // error-state Kalman filter", 2017, eq. 268); the rate error integrates into it (first order).
  // F = [R dt I; 0 I] with R = step^-1, by blocks of P = [A B; B^T C]:
  //   F P F^T = [R A R^T + dt (R B + B^T R^T) + dt^2 C,  R B + dt C;  (R B + dt C)^T,  C].
  const Eigen::Matrix3d r = step.conjugate().toRotationMatrix();
  q_ = (q_ * step).normalized();
  const Eigen::Matrix3d a = p_.topLeftCorner<3, 3>();
  const Eigen::Matrix3d c = p_.bottomRightCorner<3, 3>();
  const Eigen::Matrix3d rb = r * p_.topRightCorner<3, 3>();
  const Eigen::Matrix3d b_new = rb + dt_s * c;
  p_.topLeftCorner<3, 3>() =
      r * a * r.transpose() + dt_s * (rb + rb.transpose()) + (dt_s * dt_s) * c;
  p_.topRightCorner<3, 3>() = b_new;
  p_.bottomLeftCorner<3, 3>() = b_new.transpose();
  p_ += constant_velocity_process_noise(dt_s, angular_accel_psd);
}

Innovation AttitudeFilter::innovation(const Eigen::Quaterniond& q_meas, double r_rad2) const {
  // rotation_vector_from_quaternion takes the shorter of +-, so q_meas and -q_meas are the same.
  return make_innovation(rotation_vector_from_quaternion(q_.conjugate() * q_meas),
                         p_.topLeftCorner<3, 3>() + r_rad2 * Eigen::Matrix3d::Identity());
}

void AttitudeFilter::update(const Innovation& innovation, double r_rad2) {
  const Vector6d dx = joseph_update(p_, innovation, r_rad2);
  // Fold the error into the nominal state; the reset Jacobian (I - [dtheta/2]x) is ~I for the
  // sub-degree corrections seen here and is omitted.
  q_ = (q_ * quaternion_from_rotation_vector(dx.head<3>())).normalized();
  w_ += dx.tail<3>();
}

}  // namespace mocaplink::core
