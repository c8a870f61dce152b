// The per-body Kalman filters the Tracker runs on every mocap frame (docs/frames.md "Tracking").
//
// PositionFilter: interacting multiple model (IMM; Blom & Bar-Shalom 1988) of two
// constant-acceleration models per NED axis, state [p v a], driven by white jerk of spectral
// density q (m^2/s^5), discretised exactly for the step dt (Bar-Shalom, Li & Kirubarajan,
// "Estimation with Applications to Tracking and Navigation", 6.2.3):
//     F = [1 dt dt^2/2; 0 1 dt; 0 0 1],
//     Q = q [dt^5/20 dt^4/8 dt^3/6; dt^4/8 dt^3/3 dt^2/2; dt^3/6 dt^2/2 dt].
// A "quiet" model (small q: hover, slow motion, low noise) and a "manoeuvre" model (large q: fast
// changes of acceleration) run side by side; their estimates are mixed by the probability of each
// model given the innovations. Why not one constant-velocity filter: its velocity lags the truth
// by k1/k2 = sqrt(2)/omega_n under acceleration, so a lag below 5 ms needs a bandwidth near the
// Nyquist rate of a 100 Hz mocap system, i.e. no noise reduction at all (docs/performance.md
// "Filter accuracy" has the figures).
// The three axes are independent filters (isotropic measurement noise, no cross-axis dynamics).
//
// AttitudeFilter: error-state filter on the nominal attitude q_ned_frd and body rate w_frd, error
// state [dtheta; dw] (rotation error about the FRD body axes, right-multiplied: q_true = q *
// Exp(dtheta)), constant-angular-velocity model with white angular-acceleration noise of spectral
// density q (rad^2/s^3): F = [I dt I; 0 I], Q = q [dt^3/3 I, dt^2/2 I; dt^2/2 I, dt I].
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

/// Discrete process noise of one axis of a constant-acceleration model over dt >= 0 seconds for
/// white jerk of spectral density psd >= 0 (m^2/s^5); state order [p, v, a].
[[nodiscard]] Eigen::Matrix3d constant_acceleration_process_noise(double dt_s, double psd);

/// A measurement's innovation against the prediction.
struct Innovation {
  Eigen::Vector3d nu = Eigen::Vector3d::Zero();             ///< measurement - prediction (m or rad)
  Eigen::Matrix3d s = Eigen::Matrix3d::Identity();          ///< innovation covariance H P H^T + R
  Eigen::Matrix3d s_inverse = Eigen::Matrix3d::Identity();  ///< S^-1 (the gain uses it)
  double mahalanobis = 0.0;                                 ///< sqrt(nu^T S^-1 nu), dimensionless
};

/// Parameters of the two-model position filter.
struct PositionFilterParams {
  double quiet_jerk_psd = 0.1;      ///< m^2/s^5, > 0
  double manoeuvre_jerk_psd = 300;  ///< m^2/s^5, >= quiet_jerk_psd
  double mode_switch_time_s = 2.0;  ///< mean sojourn time in a model (Markov switching), > 0
};

/// Two-model (IMM) constant-acceleration position filter, NED metres. See the file comment.
class PositionFilter {
 public:
  PositionFilter() = default;
  explicit PositionFilter(const PositionFilterParams& params) : params_(params) {}

  /// Starts both models at position p (m), velocity v (m/s), zero acceleration, with isotropic
  /// variances (m^2, (m/s)^2, (m/s^2)^2); probability of the manoeuvre model 0.5.
  void initialise(const Eigen::Vector3d& p_m, const Eigen::Vector3d& v_mps, double p_var_m2,
                  double v_var_m2ps2, double a_var_m2ps4);
  /// Mixes the models (IMM interaction) and propagates both by dt_s >= 0.
  void predict(double dt_s);
  /// Innovation of a position measurement (isotropic noise variance r_m2 > 0) against the mixed
  /// prediction; S includes the spread between the models. For gating.
  [[nodiscard]] Innovation innovation(const Eigen::Vector3d& z_m, double r_m2) const;
  /// Fuses the measurement into both models and updates the model probabilities.
  void update(const Eigen::Vector3d& z_m, double r_m2);

  [[nodiscard]] Eigen::Vector3d p_m() const { return combined(0); }
  [[nodiscard]] Eigen::Vector3d v_mps() const { return combined(1); }
  [[nodiscard]] Eigen::Vector3d a_mps2() const { return combined(2); }
  /// Diagonal covariance of the combined position / velocity estimate (the axes are independent).
  [[nodiscard]] Eigen::Matrix3d position_covariance() const { return combined_cov(0); }
  [[nodiscard]] Eigen::Matrix3d velocity_covariance() const { return combined_cov(1); }
  /// Probability of the manoeuvre model per axis, [0, 1].
  [[nodiscard]] Eigen::Vector3d manoeuvre_probability() const;

 private:
  struct Model {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();  ///< [p, v, a] of one axis
    Eigen::Matrix3d p = Eigen::Matrix3d::Identity();
  };
  struct Axis {
    Model model[2];             ///< 0 = quiet, 1 = manoeuvre
    double mu[2] = {0.5, 0.5};  ///< model probabilities
  };
  [[nodiscard]] Eigen::Vector3d combined(int row) const;
  [[nodiscard]] Eigen::Matrix3d combined_cov(int row) const;

  PositionFilterParams params_;
  Axis axis_[3];
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
