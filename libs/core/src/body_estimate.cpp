#include "mocaplink/core/body_estimate.hpp"

namespace mocaplink::core {

std::string_view to_string(TrackingState state) {
  switch (state) {
    case TrackingState::unseen:
      return "unseen";
    case TrackingState::tracking:
      return "tracking";
    case TrackingState::lost:
      return "lost";
  }
  return "unknown";
}

std::string_view to_string(SampleOutcome outcome) {
  switch (outcome) {
    case SampleOutcome::accepted:
      return "accepted";
    case SampleOutcome::initialised:
      return "initialised";
    case SampleOutcome::reset:
      return "reset";
    case SampleOutcome::rejected_outlier:
      return "rejected_outlier";
    case SampleOutcome::invalid_input:
      return "invalid_input";
    case SampleOutcome::untracked:
      return "untracked";
    case SampleOutcome::resumed:
      return "resumed";
  }
  return "unknown";
}

std::string_view to_string(InvalidInput reason) {
  switch (reason) {
    case InvalidInput::non_finite_position:
      return "non_finite_position";
    case InvalidInput::non_finite_quaternion:
      return "non_finite_quaternion";
    case InvalidInput::non_unit_quaternion:
      return "non_unit_quaternion";
    case InvalidInput::time_not_increasing:
      return "time_not_increasing";
  }
  return "unknown";
}

bool BodyEstimate::pose_valid() const {
  if (state != TrackingState::tracking) return false;
  switch (last_outcome) {
    case SampleOutcome::accepted:
    case SampleOutcome::initialised:
    case SampleOutcome::reset:
    case SampleOutcome::resumed:
    case SampleOutcome::rejected_outlier:
      return true;
    case SampleOutcome::invalid_input:
    case SampleOutcome::untracked:
      return false;
  }
  return false;
}

Eigen::Vector3d BodyEstimate::v_frd_mps() const {
  return q_ned_frd.toRotationMatrix().transpose() * v_ned_mps;
}

Matrix6d BodyEstimate::velocity_covariance_frd() const {
  const Eigen::Matrix3d r_frd_ned = q_ned_frd.toRotationMatrix().transpose();
  Matrix6d out = velocity_covariance;
  out.topLeftCorner<3, 3>() =
      r_frd_ned * velocity_covariance.topLeftCorner<3, 3>() * r_frd_ned.transpose();
  return out;
}

}  // namespace mocaplink::core
