// One frame of motion-capture data as every Source hands it to the Station.
//
// Positions are metres and quaternions rotate body vectors into the mocap world frame *as the
// source reports it* (before the axis mapping to NED, which the core applies per configuration).
// This is exactly what a recording row holds (DESIGN.md "Recording format").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// One rigid body (subject, asset) in one frame.
struct BodySample {
  std::string name;      ///< rigid-body name as the mocap system spells it
  bool tracked = false;  ///< false: occluded / untracked; pose fields are then meaningless
  Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();  ///< position in the source world frame, m
  /// Rotation body → source world frame, Hamilton. Eigen stores x,y,z,w internally but constructs
  /// and prints w first: Quaterniond(w, x, y, z).
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();
  /// Untracked because the source's rotation was a reflection (a left-handed matrix, det −1):
  /// a mirrored frame, which no axis setting can fix (Vicon DataStream and QTM send matrices).
  bool mirrored = false;
};

/// A whole frame. `frame_number` is the source's own counter (gaps = dropped frames, see
/// frame_step).
struct MocapFrame {
  std::uint64_t frame_number = 0;
  /// How much frame_number grows from one frame to the next when none is lost (1 for most
  /// sources; a Vicon UDP stream slower than the cameras skips numbers). 0: the numbers are the
  /// bridge's own, given on arrival (VRPN has none), so gaps say nothing about lost frames.
  std::uint32_t frame_step = 1;
  SourceTime capture_time{};               ///< capture time on the source's clock
  std::optional<double> frame_rate_hz;     ///< the source's nominal rate, when it says
  std::optional<Duration> source_latency;  ///< latency the source reports for this frame
  std::vector<BodySample> bodies;
};

}  // namespace mocaplink::core
