// Tracker: one per rigid body. Runs the Kalman filters (kalman.hpp) on every mocap frame with dt
// from capture timestamps, gates outliers, tracks TRACKING / LOST and counts resets
// (DESIGN.md "Behaviour under faults"; docs/frames.md "Tracking").
//
// Input: BodySample in the source's world frame (metres, q_world_body), mapped to NED/FRD by the
// AxisMapping given at construction; or a pose already in NED/FRD (on_pose_ned).
// Time: SourceTime capture timestamps only; the Tracker never reads a clock. Each call must carry a
// capture time later than the previous call's, otherwise the input is refused and counted
// (duplicate or out-of-order frame) — except a step back of more than reset_after_ms, which is
// taken as a restart of the source's clock (the Bridge says so earlier, with the outage's length,
// through on_clock_restart): the body turns LOST and the next valid sample is judged as a return
// after a gap.
//
// reset_counter means the pose jumped, nothing else (docs/frames.md "Gaps and jumps"). A return
// after a gap continues the stream when it lies where the body could have got to: within
// reset_jump_m of the filter's prediction (widened by 3 sigma of the last velocity estimate times
// the gap) and within reset_jump_rad of its attitude. Only a return beyond that, or a persisting
// jump seen between consecutive frames (jump_confirm_frames), increments it.
// Not thread-safe: one owner (the Station) calls it; copy estimate() to share.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mocaplink/core/axis_mapping.hpp"
#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/kalman.hpp"
#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// Tracker parameters: the `[tracking]` TOML table uses exactly these names. Defaults suit
/// 100-360 Hz Vicon / OptiTrack with sub-millimetre noise (see docs/performance.md for the tuning).
struct TrackerConfig {
  /// No valid sample for this long (source time) -> state LOST. > 0.
  double loss_timeout_ms = 250.0;
  /// A gap without valid samples longer than this -> the next valid sample re-initialises the
  /// filter there with its velocity unknown; reset_counter++ only if that sample is beyond the
  /// jump thresholds below. >= loss_timeout_ms.
  double reset_after_ms = 1000.0;
  /// Jump thresholds of a return after a gap: a pose farther than this from the prediction (m) or
  /// turned by more than this (rad) is announced as a jump (reset_counter++); nearer, the
  /// autopilot takes it as an ordinary measurement. Defaults from the tightest default innovation
  /// gate of the autopilots (docs/frames.md "Gaps and jumps"): PX4 EKF2_EVP_GATE 5 SD x the
  /// EKF2_EVP_NOISE floor 0.1 m; 3 SD x the EKF2_EVA_NOISE floor 0.1 rad. Lower them with the
  /// floors. > 0.
  double reset_jump_m = 0.5;
  double reset_jump_rad = 0.3;
  /// Standard deviation of mocap position noise per axis, m. > 0.
  double position_noise_m = 0.0005;
  /// Standard deviation of mocap attitude noise per axis, rad. > 0.
  double attitude_noise_rad = 0.003;
  /// How fast the acceleration of a manoeuvring body may change: the position filter's manoeuvre
  /// model has white jerk of spectral density accel_noise_mps2^2 / 1 s (m^2/s^5), i.e. its
  /// acceleration random-walks by accel_noise_mps2 m/s^2 per sqrt(second). The quiet model uses
  /// kQuietJerkRatio of that. Larger = faster response to manoeuvres, more noise. > 0.
  double accel_noise_mps2 = 17.3;
  /// Angular-acceleration process noise of the attitude filter (constant angular velocity model):
  /// white angular acceleration of spectral density angular_accel_noise_radps2^2 * 1 s
  /// (rad^2/s^3): the body rate random-walks by this many rad/s per sqrt(second). > 0.
  double angular_accel_noise_radps2 = 60.0;
  /// Innovation gate in standard deviations (Mahalanobis distance). > 0.
  double gate_sigma = 6.0;
  /// Position innovations up to this size are always accepted, whatever the Mahalanobis distance
  /// (keeps very tight covariances from rejecting real motion). Must be < the outliers to reject
  /// (10 cm). >= 0, m.
  double gate_min_m = 0.02;
  /// A jump (gated-out samples) that persists for this many consecutive mutually consistent
  /// samples is accepted as the new truth: filter reset there, reset_counter++. >= 1.
  std::uint32_t jump_confirm_frames = 5;
};

/// Which parameter is out of range, and why.
struct TrackerConfigError {
  std::string field;  ///< the parameter name, as in [tracking]
  std::string message;
};

/// Range check of every parameter (the ranges documented above); nullopt when valid. The first
/// problem found is returned.
[[nodiscard]] std::optional<TrackerConfigError> validate(const TrackerConfig& config);

/// Jerk spectral density of the quiet model / that of the manoeuvre model (docs/performance.md
/// "Filter accuracy": tuned on the hover, figure-eight and point-to-point scenarios).
inline constexpr double kQuietJerkRatio = 1.0 / 3000.0;
/// Mean time the position filter stays in one model (IMM Markov switching), s.
inline constexpr double kModeSwitchTimeS = 2.0;

/// Attitude innovations up to this many radians are always accepted (the attitude counterpart of
/// gate_min_m; 0.1 rad = 5.7 deg, far above mocap attitude noise, far below a marker swap).
inline constexpr double kAttitudeGateMinRad = 0.1;

class Tracker {
 public:
  /// `config` must satisfy validate() (checked: a programming error aborts).
  explicit Tracker(const TrackerConfig& config = {}, const AxisMapping& mapping = {});

  /// One frame's sample for this body, in the source's world frame. sample.tracked == false is
  /// the same as on_missing(capture_time). sample.name is not looked at.
  SampleOutcome on_sample(SourceTime capture_time, const BodySample& sample);

  /// One frame's pose already in NED / FRD (m; q_ned_frd need not be normalised but must be unit
  /// within kQuaternionUnitTolerance).
  SampleOutcome on_pose_ned(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                            const Eigen::Quaterniond& q_ned_frd);

  /// A frame in which the body is occluded, flagged untracked or absent: predicts to
  /// capture_time and updates the TRACKING/LOST state. Returns untracked (or invalid_input for a
  /// non-increasing time).
  SampleOutcome on_missing(SourceTime capture_time);

  /// The source's clock started again (a server restart, a recording looped): the next call
  /// carries `first_new_time` on the new clock, `gap` (>= 0, host time) after the last call on
  /// the old one. The Tracker moves its time line onto the new clock, turns LOST, and judges the
  /// next valid sample as a return after that gap. Nothing before the first call: no-op.
  void on_clock_restart(SourceTime first_new_time, Duration gap);

  /// The estimate after the latest call (state unseen before the first valid sample).
  [[nodiscard]] const BodyEstimate& estimate() const { return estimate_; }
  [[nodiscard]] const TrackerConfig& config() const { return config_; }
  [[nodiscard]] const AxisMapping& mapping() const { return mapping_; }

 private:
  bool accept_time(SourceTime capture_time);
  void predict_to(SourceTime capture_time);
  void update_liveness(SourceTime capture_time);
  SampleOutcome fuse(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                     const Eigen::Quaterniond& q_ned_frd);
  SampleOutcome handle_gated(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                             const Eigen::Quaterniond& q_ned_frd);
  [[nodiscard]] bool beyond_reach(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                                  const Eigen::Quaterniond& q_ned_frd) const;
  SampleOutcome judge_return(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
                             const Eigen::Quaterniond& q_ned_frd);
  void start(SourceTime capture_time, const Eigen::Vector3d& p_ned_m,
             const Eigen::Quaterniond& q_ned_frd, bool keep_rates, bool jumped);
  void shift_time(Duration offset);
  void publish(SourceTime capture_time, SampleOutcome outcome);

  TrackerConfig config_;
  AxisMapping mapping_;
  double angular_accel_psd_ = 0.0;
  double r_position_m2_ = 0.0;
  double r_attitude_rad2_ = 0.0;

  PositionFilter position_;
  AttitudeFilter attitude_;
  bool initialised_ = false;
  /// 1 sigma of the velocity estimate at the last fused sample, m/s (the largest axis): how fast
  /// the prediction of a body lost from there may be off.
  double fused_velocity_sigma_mps_ = 0.0;
  std::optional<SourceTime> last_input_time_;  ///< last accepted capture time of any call
  SourceTime filter_time_{};                   ///< time the filter state refers to
  SourceTime last_valid_time_{};               ///< last valid (finite, unit) sample

  // Jump confirmation: consecutive gated-out samples consistent with each other.
  std::uint32_t jump_count_ = 0;
  Eigen::Vector3d jump_p_ned_m_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond jump_q_ned_frd_ = Eigen::Quaterniond::Identity();
  SourceTime jump_time_{};

  BodyEstimate estimate_;
};

}  // namespace mocaplink::core
