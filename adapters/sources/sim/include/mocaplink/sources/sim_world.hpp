// The simulated mocap system as a pure function of (config, frame number): no clock, no thread,
// no state. SimSource (sim_source.hpp) runs it in real time; `mocaplink serve --from sim` and tests
// call it directly.
//
// World frame: Vicon-like, right-handed, +z up, metres, origin at the middle of the room; the
// bodies sit side by side along x, 2.5 m apart. Body frame: x forward (nose), y left, z up, as a
// Vicon object is usually defined. Quaternions are Hamilton, rotate body vectors into the world
// frame, and are canonicalised to w >= 0.
//
// Trajectories (body index i, 0-based; kind = i % 3, lane = i / 3 makes repeats distinct):
//   kind 0  hover: small oscillation (±5 cm) about a point 1.0 m up, yaw swinging ±0.3 rad
//   kind 1  circle: radius 1 m at 1.2 m height, one turn every 8 + 2·lane s, nose along velocity
//   kind 2  figure-eight (lemniscate of Gerono) 2 m × 1 m at 1.5 m, nose along velocity
// Attitude is that of a multirotor flying the path: thrust axis (body z) along a + g·z, yaw as
// above — so roll and pitch are consistent with the acceleration.
//
// Determinism: each random draw is a hash of (seed, frame or time slot, body, purpose), not a
// stream, so frame n is the same whatever frames were asked for before it, on every platform.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/sources/sim_options.hpp"

namespace mocaplink::sources {

/// Exact state of one simulated body (what a perfect mocap system would report).
struct BodyTruth {
  Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();     ///< position, world frame, m
  Eigen::Vector3d v_world_m_s = Eigen::Vector3d::Zero();   ///< velocity, world frame, m/s
  Eigen::Vector3d a_world_m_s2 = Eigen::Vector3d::Zero();  ///< acceleration, world frame, m/s²
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();  ///< body → world, w >= 0
};

class SimWorld {
 public:
  /// `config` must pass validate_sim_options (programming error otherwise: aborts).
  explicit SimWorld(SimOptions config);

  [[nodiscard]] const SimOptions& config() const { return config_; }
  [[nodiscard]] std::size_t body_count() const { return config_.bodies; }
  /// "Body1" for index 0 (DESIGN.md: simulated bodies are Body1, Body2, ...).
  [[nodiscard]] static std::string body_name(std::size_t index);

  /// Ground truth of body `index` (< body_count()) at `t` seconds after frame 1. Any finite t.
  [[nodiscard]] BodyTruth truth(std::size_t index, double t_s) const;

  /// Capture time of frame `frame_number` (>= 1): (frame_number − 1) / rate_hz after the source
  /// clock's epoch.
  [[nodiscard]] core::SourceTime capture_time(std::uint64_t frame_number) const;
  /// Seconds since frame 1 of frame `frame_number` (>= 1).
  [[nodiscard]] double time_s(std::uint64_t frame_number) const;

  /// Whether frame `frame_number` is dropped (never delivered) under config().drop.
  [[nodiscard]] bool dropped(std::uint64_t frame_number) const;
  /// Whether body `index` is occluded at frame `frame_number` under config().occlude.
  [[nodiscard]] bool occluded(std::size_t index, std::uint64_t frame_number) const;
  /// Whether body `index` is absent from frame `frame_number` under config().churn_s (the last
  /// body, in every odd slot of churn_s seconds).
  [[nodiscard]] bool absent(std::size_t index, std::uint64_t frame_number) const;

  /// The frame as the mocap system reports it: truth + noise, with occluded bodies flagged
  /// untracked and outliers applied; every body is present, in index order. Ignores drops (ask
  /// dropped()). frame_rate_hz is set; source_latency is not (the simulator has none).
  [[nodiscard]] core::MocapFrame frame(std::uint64_t frame_number) const;

 private:
  SimOptions config_;
};

}  // namespace mocaplink::sources
