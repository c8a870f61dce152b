#include "mocaplink/core/tracker.hpp"

#include <algorithm>
#include <chrono>
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
// ... but 1 m/s^2 for a body back after a gap where it could have got to (not a jump): it came
// back within reset_jump_m (0.5 m) of a prediction made a second or more before, so it cannot
// have been accelerating hard. With the envelope's 10 m/s^2 the noise of the first frames was
// taken for acceleration and the velocity rang for half a second: its error there was 4.3x the
// steady state's, and 3.1x with this (tracker_test "ResumedVelocitySettlesWithoutRinging").
constexpr double kResumedAccelVar = 1.0;

double ms_to_s(double ms) {
  return ms * 1e-3;
}

// A return after a gap may lie this many sigma of the last fused velocity estimate, times the gap,
// beyond reset_jump_m from the prediction (3 sigma: where the body could have got to unseen) ...
constexpr double kReachVelocitySigmas = 3.0;
// ... but never more than this many reset_jump_m in all: after a long outage a body re-defined or
// moved by a metre must still be announced.
constexpr double kReachMaxJumps = 2.0;

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
        std::pair{"gate_sigma", c.gate_sigma}, std::pair{"reset_jump_m", c.reset_jump_m},
        std::pair{"reset_jump_rad", c.reset_jump_rad}}) {
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
    // not a late frame. Nobody said how long the outage was (the Bridge does, through
    // on_clock_restart, before this can happen): take it as just over reset_after_ms.
    on_clock_restart(capture_time,
                     std::chrono::duration_cast<Duration>(
                         std::chrono::duration<double, std::milli>(config_.reset_after_ms)) +
                         Duration{1});
  }
  if (last_input_time_ && capture_time <= *last_input_time_) {
    ++estimate_.counters.invalid_input[static_cast<std::size_t>(InvalidInput::time_not_increasing)];
    estimate_.last_outcome = SampleOutcome::invalid_input;
    return false;
  }
  last_input_time_ = capture_time;
  return true;
}

void Tracker::on_clock_restart(SourceTime first_new_time, Duration gap) {
  if (!last_input_time_) return;
  // Move the old time line so that the last call lies `gap` (at least 1 ns) before the first
  // call on the new clock: every interval the filter keeps stays as it was.
  const Duration offset = first_new_time - std::max(gap, Duration{1}) - *last_input_time_;
  shift_time(offset);
  if (estimate_.state == TrackingState::tracking) estimate_.state = TrackingState::lost;
  jump_count_ = 0;
}

void Tracker::shift_time(Duration offset) {
  *last_input_time_ += offset;
  filter_time_ += offset;
  last_valid_time_ += offset;
  jump_time_ += offset;
  estimate_.capture_time += offset;
  estimate_.measurement_time += offset;
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
    start(capture_time, p_ned_m, q_ned_frd, false, false);
    outcome = SampleOutcome::initialised;
  } else if (to_seconds(capture_time - last_valid_time_) > ms_to_s(config_.reset_after_ms)) {
    outcome = judge_return(capture_time, p_ned_m, q_ned_frd);
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
  // Back from a loss: the filter's gate has widened with the gap (6 sigma of a manoeuvring body:
  // a metre within a second), wider than where the autopilot would take the pose as ordinary;
  // beyond the reach it is a jump even inside the gate.
  if (was_lost && (pos_out || att_out || beyond_reach(capture_time, p_ned_m, q_ned_frd))) {
    return judge_return(capture_time, p_ned_m, q_ned_frd);
  }
  if (!pos_out && !att_out) {
    position_.update(p_ned_m, r_position_m2_);
    attitude_.update(att, r_attitude_rad2_);
    last_valid_time_ = capture_time;
    fused_velocity_sigma_mps_ = std::sqrt(position_.velocity_covariance().diagonal().maxCoeff());
    estimate_.state = TrackingState::tracking;
    estimate_.measurement_time = capture_time;
    ++estimate_.counters.accepted;
    jump_count_ = 0;
    return SampleOutcome::accepted;
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
    // Seen in consecutive frames: the body cannot have got there (it left the gate from one
    // frame to the next and stayed away), so this is a jump whatever its size.
    start(capture_time, p_ned_m, q_ned_frd, true, true);
    return SampleOutcome::reset;
  }
  ++estimate_.counters.rejected_outliers;
  return SampleOutcome::rejected_outlier;
}

bool Tracker::beyond_reach(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                           const Eigen::Quaterniond& q_ned_frd) const {
  // Where the body could have got to: the filter's prediction (the filter is predicted at most
  // to loss_timeout_ms past the last fused sample, or to this sample inside reset_after_ms;
  // beyond, on at its velocity) ...
  const double ahead_s = std::max(0.0, to_seconds(capture_time - filter_time_));
  const Eigen::Vector3d predicted_m = position_.p_m() + ahead_s * position_.v_mps();
  // ... widened by the gap times how uncertain the velocity was, capped (kReachMaxJumps).
  const double gap_s = to_seconds(capture_time - last_valid_time_);
  const double reach_m =
      config_.reset_jump_m + std::min(kReachVelocitySigmas * fused_velocity_sigma_mps_ * gap_s,
                                      (kReachMaxJumps - 1.0) * config_.reset_jump_m);
  const double turn_rad = attitude_.innovation(q_ned_frd.normalized(), r_attitude_rad2_).nu.norm();
  return (p_ned_m - predicted_m).norm() > reach_m || turn_rad > config_.reset_jump_rad;
}

SampleOutcome Tracker::judge_return(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                                    const Eigen::Quaterniond& q_ned_frd) {
  const bool jumped = beyond_reach(capture_time, p_ned_m, q_ned_frd);
  // Either way the filter starts again at the sample with its velocity unknown (the velocity
  // covariance says so); only a jump is announced.
  start(capture_time, p_ned_m, q_ned_frd, false, jumped);
  return jumped ? SampleOutcome::reset : SampleOutcome::resumed;
}

void Tracker::start(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                    const Eigen::Quaterniond& q_ned_frd, bool keep_rates, bool jumped) {
  const Eigen::Vector3d v = keep_rates ? position_.v_mps() : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w = keep_rates ? attitude_.w_frd_radps() : Eigen::Vector3d::Zero();
  // First start: the w >= 0 hemisphere; later resets: the hemisphere of the previous output, so
  // the published attitude never jumps between q and -q.
  const Eigen::Quaterniond q = continuous_with(
      q_ned_frd, initialised_ ? estimate_.q_ned_frd : Eigen::Quaterniond::Identity());
  const bool resumed = initialised_ && !jumped;
  position_.initialise(p_ned_m, v, r_position_m2_, kInitialVelocityVar,
                       resumed ? kResumedAccelVar : kInitialAccelVar);
  attitude_.initialise(q, w, r_attitude_rad2_, kInitialRateVar);
  if (initialised_ && jumped) {
    ++estimate_.reset_counter;  // uint8_t: wraps 255 -> 0 as ODOMETRY.reset_counter expects
    ++estimate_.counters.resets;
  } else if (resumed) {
    ++estimate_.counters.resumed;
  }
  initialised_ = true;
  filter_time_ = capture_time;
  last_valid_time_ = capture_time;
  fused_velocity_sigma_mps_ = std::sqrt(kInitialVelocityVar);
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
