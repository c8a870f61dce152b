// The per-body Kalman filters the Tracker runs on every mocap frame (docs/frames.md "Tracking").
//
// PositionFilter: constant-velocity model, state [p; v] in NED, driven by continuous white-noise
// acceleration of spectral density q (m^2/s^3), discretised exactly for the step dt (Bar-Shalom,
// "Estimation with Applications to Tracking and Navigation", 6.2.2):
//     F = [I  dt I; 0  I],   Q = q [dt^3/3 I  dt^2/2 I; dt^2/2 I  dt I].
// AttitudeFilter: error-state filter on the nominal attitude q_ned_frd and body rate w_frd, error
// state [dtheta; dw] (rotation error about the FRD body axes, right-multiplied: q_true = q *
// Exp(dtheta)), constant-angular-velocity model with white angular-acceleration noise, discretised
// the same way.
//
// Fixed-size Eigen matrices only: no allocation on the per-frame path. Not thread-safe (one owner).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mocaplink::core {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Discrete process noise of a constant-velocity (or constant-angular-velocity) model over dt >= 0
/// seconds for white acceleration of spectral density psd >= 0 (units^2/s^3); state order
/// [three positions; three velocities].
[[nodiscard]] Matrix6d constant_velocity_process_noise(double dt_s, double psd);

/// A measurement's innovation against the prediction.
struct Innovation {
  Eigen::Vector3d nu = Eigen::Vector3d::Zero();     ///< measurement - prediction (m or rad)
  Eigen::Matrix3d s = Eigen::Matrix3d::Identity();  ///< innovation covariance H P H^T + R
  double mahalanobis = 0.0;                         ///< sqrt(nu^T S^-1 nu), dimensionless
};

/// Constant-velocity position filter (NED, metres).
class PositionFilter {
 public:
  /// Starts at position p (m) and velocity v (m/s) with isotropic variances (m^2, (m/s)^2).
  void initialise(const Eigen::Vector3d& p_m, const Eigen::Vector3d& v_mps, double p_var_m2,
                  double v_var_m2ps2);
  /// Propagates by dt_s >= 0 with acceleration spectral density accel_psd (m^2/s^3).
  void predict(double dt_s, double accel_psd);
  /// Innovation of a position measurement with isotropic noise variance r_m2 > 0.
  [[nodiscard]] Innovation innovation(const Eigen::Vector3d& z_m, double r_m2) const;
  /// Fuses the measurement whose innovation was computed with the same r_m2 (Joseph form).
  void update(const Innovation& innovation, double r_m2);

  [[nodiscard]] Eigen::Vector3d p_m() const { return x_.head<3>(); }
  [[nodiscard]] Eigen::Vector3d v_mps() const { return x_.tail<3>(); }
  /// Covariance of [p; v].
  [[nodiscard]] const Matrix6d& covariance() const { return p_; }

 private:
  Vector6d x_ = Vector6d::Zero();
  Matrix6d p_ = Matrix6d::Identity();
};

/// Error-state attitude and body-rate filter.
class AttitudeFilter {
 public:
  /// Starts at attitude q (normalised here) and body rate w (rad/s) with isotropic variances.
  void initialise(const Eigen::Quaterniond& q_ned_frd, const Eigen::Vector3d& w_frd_radps,
                  double att_var_rad2, double rate_var_rad2ps2);
  /// Propagates by dt_s >= 0: q <- q * Exp(w dt); angular-acceleration spectral density in
  /// rad^2/s^3.
  void predict(double dt_s, double angular_accel_psd);
  /// Innovation of an attitude measurement: nu = Log(q^-1 * q_meas) (shorter of q_meas and
  /// -q_meas, so the sign of the measurement does not matter); noise variance r_rad2 > 0 per axis.
  [[nodiscard]] Innovation innovation(const Eigen::Quaterniond& q_meas, double r_rad2) const;
  /// Fuses the measurement (Joseph form) and folds the error state into the nominal state.
  void update(const Innovation& innovation, double r_rad2);

  /// Unit quaternion, continuous (never jumps to -q between steps).
  [[nodiscard]] const Eigen::Quaterniond& q_ned_frd() const { return q_; }
  [[nodiscard]] const Eigen::Vector3d& w_frd_radps() const { return w_; }
  /// Covariance of [dtheta; dw] (rad^2, (rad/s)^2), FRD body axes.
  [[nodiscard]] const Matrix6d& covariance() const { return p_; }

 private:
  Eigen::Quaterniond q_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_ = Eigen::Vector3d::Zero();
  Matrix6d p_ = Matrix6d::Identity();
};

}  // namespace mocaplink::core
