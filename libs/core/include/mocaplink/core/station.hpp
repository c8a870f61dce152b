// The Station: what the bridge sees of its mocap source (the original ViconMAVLink Station window,
// and the figures behind `mocaplink bodies` and the dashboard). Pure: fed frames with the host
// time they arrived, asked for a snapshot at an injected host time.
//
// Figures (all over the last `window`, 1 s by default, unless cumulative):
//   frame_rate_hz  (n − 1) / (now − oldest) for the n frames received in (now − window, now]:
//                  the arrival rate, falling smoothly to 0 within one window when frames stop.
//   latency_ms     mean of the latency the source reports with its frames (Vicon's latency
//                  samples); absent when the source reports none.
//   jitter_ms      standard deviation of (host receive time − source capture time): how unevenly
//                  frames arrive relative to when they were captured; the clocks' offset cancels.
//   frames         cumulative frames received.
//   dropped        cumulative frames missing from gaps in frame numbers (n after m: n − m − 1).
//                  Not counted as drops: a counter that goes back or jumps forward by more than
//                  max_gap_frames (a server restart: counted in restarts), a repeated number
//                  (duplicates), and the frames missed while disconnected (on_connection(false)
//                  resets the continuity; the outage shows as the connection state instead).
//                  A gap is counted in units of the frame's frame_step (a Vicon UDP stream at half
//                  the camera rate numbers its frames 2 apart). Frames numbered by the bridge
//                  (frame_step 0: VRPN) are never counted; drops_counted is then false, and
//                  `dropped`, `restarts` and `duplicates` say nothing.
//   bodies         every body ever seen, in order of first appearance: tracked (in the latest
//                  frame; a body absent from the latest frame is untracked), last tracked pose in
//                  the source world frame, frames_tracked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/ring.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

struct StationConfig {
  Duration window = std::chrono::seconds(1);  ///< averaging window of rate, latency, jitter; > 0
  /// A forward jump in frame numbers larger than this is a counter restart, not drops (10 min at
  /// 200 Hz: longer real gaps would have disconnected the source anyway).
  std::uint64_t max_gap_frames = 120'000;
  /// Bodies beyond this many distinct names are not registered (counted in bodies_ignored), so a
  /// source inventing names cannot grow memory without bound.
  std::size_t max_bodies = 1024;
  /// Frames kept for the window figures; older ones are forgotten even inside the window
  /// (bounds memory at absurd rates; 20 000 covers 10 kHz over 2 s).
  std::size_t max_window_frames = 20'000;
};

/// One body as the Station last saw it.
struct StationBody {
  std::string name;
  bool tracked = false;  ///< tracked in the latest frame
  /// Untracked in the latest frame because its rotation was a reflection (BodySample::mirrored).
  bool mirrored = false;
  bool ever_tracked = false;                            ///< false: the pose below is meaningless
  Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();  ///< last tracked position, source world, m
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();  ///< last tracked attitude
  std::uint64_t frames_tracked = 0;      ///< frames in which it was tracked
  std::optional<HostTime> last_tracked;  ///< host time of the last tracked sample
};

/// Immutable copy of the Station's figures at one host time (see the file comment).
struct StationSnapshot {
  bool connected = false;
  double frame_rate_hz = 0.0;
  std::optional<double> nominal_rate_hz;  ///< the rate the source says it runs at
  std::optional<double> latency_ms;
  std::optional<double> jitter_ms;
  std::uint64_t frames = 0;
  std::uint64_t dropped = 0;
  /// false once a frame came without source frame numbers (frame_step 0): `dropped` is unknown.
  bool drops_counted = true;
  std::uint64_t restarts = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t bodies_ignored = 0;
  std::optional<std::uint64_t> last_frame_number;
  std::optional<HostTime> last_received;  ///< host time of the latest frame
  std::vector<StationBody> bodies;
};

/// Not thread-safe: the owner serialises on_frame / on_connection / snapshot (one mutex, or one
/// thread). Host times passed in should not go backwards; if they do, the window figures treat the
/// frame as the newest anyway (no crash, no negative rate).
class Station {
 public:
  explicit Station(StationConfig config = {});

  /// A frame arrived at `received`. Marks the Station connected.
  void on_frame(const MocapFrame& frame, HostTime received);
  /// The source connected or went away (or finished). Disconnecting resets frame continuity.
  void on_connection(bool connected);
  /// The figures as of `now` (normally the latest host time).
  [[nodiscard]] StationSnapshot snapshot(HostTime now) const;

 private:
  struct Arrival {
    HostTime received;
    Duration receive_minus_capture;
    std::optional<Duration> latency;
  };
  void count_frame_number(std::uint64_t frame_number, std::uint32_t step);
  void update_bodies(const MocapFrame& frame, HostTime received);

  StationConfig config_;
  bool connected_ = false;
  bool continuity_ = false;  // last_frame_number_ is comparable with the next frame's
  StationSnapshot totals_;   // cumulative fields; window fields are computed in snapshot()
  Ring<Arrival> window_;     // grows to the window's frames, then allocates no more
  std::unordered_map<std::string, std::size_t> body_index_;
};

}  // namespace mocaplink::core
