#include "mocaplink/core/tracker.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::core {
namespace {

// Initial velocity / body-rate uncertainty of a freshly (re)started filter: 2 m/s and 3 rad/s
// standard deviation, enough for a body picked up in flight; a few frames of sub-mm data shrink it.
constexpr double kInitialVelocityVar = 4.0;
constexpr double kInitialRateVar = 9.0;
// Initial acceleration uncertainty: 10 m/s^2 standard deviation (a multirotor's envelope).
constexpr double kInitialAccelVar = 100.0;

double ms_to_s(double ms) {
  return ms * 1e-3;
}

std::optional<TrackerConfigError> positive(const char* field, double value) {
  if (std::isfinite(value) && value > 0.0) return std::nullopt;
  return TrackerConfigError{field, "must be a finite number > 0"};
}

}  // namespace

std::optional<TrackerConfigError> validate(const TrackerConfig& c) {
  for (const auto& [field, value] :
       {std::pair{"loss_timeout_ms", c.loss_timeout_ms},
        std::pair{"reset_after_ms", c.reset_after_ms},
        std::pair{"position_noise_m", c.position_noise_m},
        std::pair{"attitude_noise_rad", c.attitude_noise_rad},
        std::pair{"accel_noise_mps2", c.accel_noise_mps2},
        std::pair{"angular_accel_noise_radps2", c.angular_accel_noise_radps2},
        std::pair{"gate_sigma", c.gate_sigma}}) {
    if (auto e = positive(field, value)) return e;
  }
  if (c.reset_after_ms < c.loss_timeout_ms) {
    return TrackerConfigError{"reset_after_ms", "must be >= loss_timeout_ms"};
  }
  if (!std::isfinite(c.gate_min_m) || c.gate_min_m < 0.0) {
    return TrackerConfigError{"gate_min_m", "must be a finite number >= 0"};
  }
  if (c.jump_confirm_frames < 1) {
    return TrackerConfigError{"jump_confirm_frames", "must be >= 1"};
  }
  return std::nullopt;
}

Tracker::Tracker(const TrackerConfig& config, const AxisMapping& mapping)
    : config_(config), mapping_(mapping) {
  if (const auto e = validate(config)) {
    std::fprintf(stderr, "mocaplink::core::Tracker: invalid TrackerConfig.%s: %s\n",
                 e->field.c_str(), e->message.c_str());
    std::abort();
  }
  // Spectral densities (TrackerConfig docs): sigma^2 / 1 s for jerk, sigma^2 * 1 s for angular
  // acceleration.
  const double manoeuvre_psd = config.accel_noise_mps2 * config.accel_noise_mps2;
  position_ = PositionFilter(
      PositionFilterParams{manoeuvre_psd * kQuietJerkRatio, manoeuvre_psd, kModeSwitchTimeS});
  angular_accel_psd_ = config.angular_accel_noise_radps2 * config.angular_accel_noise_radps2;
  r_position_m2_ = config.position_noise_m * config.position_noise_m;
  r_attitude_rad2_ = config.attitude_noise_rad * config.attitude_noise_rad;
}

SampleOutcome Tracker::on_sample(SourceTime capture_time, const BodySample& sample) {
  if (!sample.tracked) return on_missing(capture_time);
  // The mapping is a rotation: it keeps non-finite components non-finite and the norm of q.
  return on_pose_ned(capture_time, mapping_.position_ned(sample.p_world_m),
                     mapping_.attitude_ned_frd(sample.q_world_body));
}

bool Tracker::accept_time(SourceTime capture_time) {
  if (last_input_time_ &&
      to_seconds(*last_input_time_ - capture_time) > ms_to_s(config_.reset_after_ms)) {
    // Far backwards: the source's clock restarted (mocap server restarted, recording looped),
    // not a late frame. Forget the old time line: lost now, restarted at the next valid sample.
    clock_restarted_ = true;
    if (estimate_.state == TrackingState::tracking) estimate_.state = TrackingState::lost;
    last_valid_time_ = capture_time;
    last_input_time_ = capture_time;
    return true;
  }
  if (last_input_time_ && capture_time <= *last_input_time_) {
    ++estimate_.counters.invalid_input[static_cast<std::size_t>(InvalidInput::time_not_increasing)];
    estimate_.last_outcome = SampleOutcome::invalid_input;
    return false;
  }
  last_input_time_ = capture_time;
  return true;
}

void Tracker::update_liveness(SourceTime capture_time) {
  if (estimate_.state == TrackingState::tracking &&
      to_seconds(capture_time - last_valid_time_) > ms_to_s(config_.loss_timeout_ms)) {
    estimate_.state = TrackingState::lost;
    jump_count_ = 0;
  }
}

void Tracker::predict_to(SourceTime capture_time) {
  const double dt = to_seconds(capture_time - filter_time_);
  if (dt <= 0.0) return;
  position_.predict(dt);
  attitude_.predict(dt, angular_accel_psd_);
  filter_time_ = capture_time;
}

SampleOutcome Tracker::on_missing(SourceTime capture_time) {
  if (!accept_time(capture_time)) return SampleOutcome::invalid_input;
  ++estimate_.counters.untracked;
  update_liveness(capture_time);
  if (estimate_.state == TrackingState::tracking) predict_to(capture_time);
  publish(capture_time, SampleOutcome::untracked);
  return SampleOutcome::untracked;
}

SampleOutcome Tracker::on_pose_ned(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                                   const Eigen::Quaterniond& q_ned_frd) {
  ++estimate_.counters.samples;
  if (!accept_time(capture_time)) return SampleOutcome::invalid_input;

  std::optional<InvalidInput> invalid;
  if (!p_ned_m.allFinite()) {
    invalid = InvalidInput::non_finite_position;
  } else if (const auto fault = check_quaternion(q_ned_frd); fault != QuaternionFault::none) {
    invalid = fault == QuaternionFault::non_finite ? InvalidInput::non_finite_quaternion
                                                   : InvalidInput::non_unit_quaternion;
  }
  if (invalid) {
    // Counted, then handled like a frame without this body.
    ++estimate_.counters.invalid_input[static_cast<std::size_t>(*invalid)];
    update_liveness(capture_time);
    if (estimate_.state == TrackingState::tracking) predict_to(capture_time);
    publish(capture_time, SampleOutcome::invalid_input);
    return SampleOutcome::invalid_input;
  }

  SampleOutcome outcome = SampleOutcome::accepted;
  if (!initialised_) {
    start(capture_time, p_ned_m, q_ned_frd, false);
    outcome = SampleOutcome::initialised;
  } else if (clock_restarted_ ||
             to_seconds(capture_time - last_valid_time_) > ms_to_s(config_.reset_after_ms)) {
    start(capture_time, p_ned_m, q_ned_frd, false);
    outcome = SampleOutcome::reset;
  } else {
    update_liveness(capture_time);
    outcome = fuse(capture_time, p_ned_m, q_ned_frd);
  }
  publish(capture_time, outcome);
  return outcome;
}

SampleOutcome Tracker::fuse(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                            const Eigen::Quaterniond& q_ned_frd) {
  const bool was_lost = estimate_.state == TrackingState::lost;
  predict_to(capture_time);
  const Innovation pos = position_.innovation(p_ned_m, r_position_m2_);
  const Innovation att = attitude_.innovation(q_ned_frd.normalized(), r_attitude_rad2_);
  // Gate with a floor (TrackerConfig::gate_min_m, kAttitudeGateMinRad): reject only what is both
  // improbable and large.
  const bool pos_out = pos.mahalanobis > config_.gate_sigma && pos.nu.norm() > config_.gate_min_m;
  const bool att_out = att.mahalanobis > config_.gate_sigma && att.nu.norm() > kAttitudeGateMinRad;
  if (!pos_out && !att_out) {
    position_.update(p_ned_m, r_position_m2_);
    attitude_.update(att, r_attitude_rad2_);
    last_valid_time_ = capture_time;
    estimate_.state = TrackingState::tracking;
    estimate_.measurement_time = capture_time;
    ++estimate_.counters.accepted;
    jump_count_ = 0;
    return SampleOutcome::accepted;
  }
  if (was_lost) {
    // The body came back far from where it was lost: start again there.
    start(capture_time, p_ned_m, q_ned_frd, false);
    return SampleOutcome::reset;
  }
  return handle_gated(capture_time, p_ned_m, q_ned_frd);
}

SampleOutcome Tracker::handle_gated(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                                    const Eigen::Quaterniond& q_ned_frd) {
  // Consistent with the previous gated sample: where that one would have moved with the filter's
  // velocity, within gate_min_m, and the same attitude within kAttitudeGateMinRad.
  bool consistent = false;
  if (jump_count_ > 0) {
    const double dt = to_seconds(capture_time - jump_time_);
    const Eigen::Vector3d expected = jump_p_ned_m_ + dt * position_.v_mps();
    const double att_jump =
        rotation_vector_from_quaternion(jump_q_ned_frd_.conjugate() * q_ned_frd.normalized())
            .norm();
    consistent =
        (p_ned_m - expected).norm() <= config_.gate_min_m && att_jump <= kAttitudeGateMinRad;
  }
  jump_count_ = consistent ? jump_count_ + 1 : 1;
  jump_p_ned_m_ = p_ned_m;
  jump_q_ned_frd_ = q_ned_frd.normalized();
  jump_time_ = capture_time;
  if (jump_count_ >= config_.jump_confirm_frames) {
    start(capture_time, p_ned_m, q_ned_frd, true);
    return SampleOutcome::reset;
  }
  ++estimate_.counters.rejected_outliers;
  return SampleOutcome::rejected_outlier;
}

void Tracker::start(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                    const Eigen::Quaterniond& q_ned_frd, bool keep_rates) {
  const Eigen::Vector3d v = keep_rates ? position_.v_mps() : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w = keep_rates ? attitude_.w_frd_radps() : Eigen::Vector3d::Zero();
  // First start: the w >= 0 hemisphere; later resets: the hemisphere of the previous output, so
  // the published attitude never jumps between q and -q.
  const Eigen::Quaterniond q = continuous_with(
      q_ned_frd, initialised_ ? estimate_.q_ned_frd : Eigen::Quaterniond::Identity());
  position_.initialise(p_ned_m, v, r_position_m2_, kInitialVelocityVar, kInitialAccelVar);
  attitude_.initialise(q, w, r_attitude_rad2_, kInitialRateVar);
  if (initialised_) {
    ++estimate_.reset_counter;  // uint8_t: wraps 255 -> 0 as ODOMETRY.reset_counter expects
    ++estimate_.counters.resets;
  }
  initialised_ = true;
  clock_restarted_ = false;
  filter_time_ = capture_time;
  last_valid_time_ = capture_time;
  jump_count_ = 0;
  estimate_.state = TrackingState::tracking;
  estimate_.measurement_time = capture_time;
  ++estimate_.counters.accepted;
}

void Tracker::publish(SourceTime capture_time, SampleOutcome outcome) {
  estimate_.capture_time = capture_time;
  estimate_.last_outcome = outcome;
  if (!initialised_) return;
  estimate_.p_ned_m = position_.p_m();
  estimate_.v_ned_mps = position_.v_mps();
  estimate_.q_ned_frd = attitude_.q_ned_frd();
  estimate_.w_frd_radps = attitude_.w_frd_radps();
  estimate_.pose_covariance.setZero();
  estimate_.pose_covariance.topLeftCorner<3, 3>() = position_.position_covariance();
  estimate_.pose_covariance.bottomRightCorner<3, 3>() =
      attitude_.covariance().topLeftCorner<3, 3>();
  estimate_.velocity_covariance.setZero();
  estimate_.velocity_covariance.topLeftCorner<3, 3>() = position_.velocity_covariance();
  estimate_.velocity_covariance.bottomRightCorner<3, 3>() =
      attitude_.covariance().bottomRightCorner<3, 3>();
}

}  // namespace mocaplink::core
