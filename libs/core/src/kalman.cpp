#include "mocaplink/core/kalman.hpp"

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

using Matrix63d = Eigen::Matrix<double, 6, 3>;

// Mahalanobis distance sqrt(nu^T S^-1 nu); S is symmetric positive definite (P + R, R > 0).
double mahalanobis(const Eigen::Vector3d& nu, const Eigen::Matrix3d& s) {
  return std::sqrt(nu.dot(s.ldlt().solve(nu)));
}

// Kalman update for H = [I 0] (the measurement is the first three states), Joseph form so that P
// stays symmetric positive semi-definite despite rounding. Returns the state correction.
Vector6d joseph_update(Matrix6d& p, const Innovation& in, double r) {
  const Matrix63d pht = p.leftCols<3>();
  const Matrix63d k = in.s.ldlt().solve(pht.transpose()).transpose();  // P H^T S^-1
  Matrix6d i_kh = Matrix6d::Identity();
  i_kh.leftCols<3>() -= k;
  p = i_kh * p * i_kh.transpose() + r * k * k.transpose();
  p = 0.5 * (p + p.transpose());
  return k * in.nu;
}

Innovation make_innovation(const Matrix6d& p, const Eigen::Vector3d& nu, double r) {
  Innovation in;
  in.nu = nu;
  in.s = p.topLeftCorner<3, 3>() + r * Eigen::Matrix3d::Identity();
  in.mahalanobis = mahalanobis(nu, in.s);
  return in;
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

void PositionFilter::initialise(const Eigen::Vector3d& p_m, const Eigen::Vector3d& v_mps,
                                double p_var_m2, double v_var_m2ps2) {
  x_ << p_m, v_mps;
  p_.setZero();
  p_.topLeftCorner<3, 3>().diagonal().setConstant(p_var_m2);
  p_.bottomRightCorner<3, 3>().diagonal().setConstant(v_var_m2ps2);
}

void PositionFilter::predict(double dt_s, double accel_psd) {
  Matrix6d f = Matrix6d::Identity();
  f.topRightCorner<3, 3>().diagonal().setConstant(dt_s);
  x_.head<3>() += dt_s * x_.tail<3>();
  p_ = f * p_ * f.transpose() + constant_velocity_process_noise(dt_s, accel_psd);
}

Innovation PositionFilter::innovation(const Eigen::Vector3d& z_m, double r_m2) const {
  return make_innovation(p_, z_m - x_.head<3>(), r_m2);
}

void PositionFilter::update(const Innovation& innovation, double r_m2) {
  x_ += joseph_update(p_, innovation, r_m2);
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
  Matrix6d f = Matrix6d::Identity();
  f.topLeftCorner<3, 3>() = step.conjugate().toRotationMatrix();
  f.topRightCorner<3, 3>().diagonal().setConstant(dt_s);
  q_ = (q_ * step).normalized();
  p_ = f * p_ * f.transpose() + constant_velocity_process_noise(dt_s, angular_accel_psd);
}

Innovation AttitudeFilter::innovation(const Eigen::Quaterniond& q_meas, double r_rad2) const {
  // rotation_vector_from_quaternion takes the shorter of +-, so q_meas and -q_meas are the same.
  return make_innovation(p_, rotation_vector_from_quaternion(q_.conjugate() * q_meas), r_rad2);
}

void AttitudeFilter::update(const Innovation& innovation, double r_rad2) {
  const Vector6d dx = joseph_update(p_, innovation, r_rad2);
  // Fold the error into the nominal state; the reset Jacobian (I - [dtheta/2]x) is ~I for the
  // sub-degree corrections seen here and is omitted.
  q_ = (q_ * quaternion_from_rotation_vector(dx.head<3>())).normalized();
  w_ += dx.tail<3>();
}

}  // namespace mocaplink::core
