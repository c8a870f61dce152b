// Shared by the vicon socket tests: a thread-safe collector of what a Source delivers, waited on
// by condition (never by sleeping), and a deterministic frame generator whose values the tests
// can recompute from the frame number.
#pragma once

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources::test {

/// Upper bound for a wait: only a hang ever reaches it (a failure, not a timing assertion).
inline constexpr auto kWaitCap = std::chrono::seconds(10);

struct Event {
  bool is_frame = false;
  core::MocapFrame frame;
  SourceState state = SourceState::connecting;
  std::string detail;
  std::chrono::steady_clock::time_point at;  ///< when the sink was called
};

class Collector {
 public:
  FrameSink frame_sink() {
    return [this](core::MocapFrame f, core::HostTime) {
      std::lock_guard lock(mutex_);
      events_.push_back(Event{true, std::move(f), {}, {}, std::chrono::steady_clock::now()});
      cv_.notify_all();
    };
  }
  StateSink state_sink() {
    return [this](SourceState s, const std::string& detail) {
      std::lock_guard lock(mutex_);
      events_.push_back(Event{false, {}, s, detail, std::chrono::steady_clock::now()});
      cv_.notify_all();
    };
  }
  /// Waits until `done(events)` holds; false if the cap was reached.
  bool wait(const std::function<bool(const std::vector<Event>&)>& done,
            std::chrono::milliseconds cap = kWaitCap) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, cap, [&] { return done(events_); });
  }
  bool wait_frames(std::size_t n) {
    return wait([n](const std::vector<Event>& e) { return frame_count(e) >= n; });
  }
  std::vector<Event> events() const {
    std::lock_guard lock(mutex_);
    return events_;
  }
  static std::size_t frame_count(const std::vector<Event>& events) {
    std::size_t n = 0;
    for (const auto& e : events) n += e.is_frame ? 1 : 0;
    return n;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<Event> events_;
};

/// The frame the test servers publish for frame number n, shifted by `offset_m` in x (to tell two
/// servers apart). Body1 always tracked, yawing; Body2 occluded when n % 5 == 0; latency 2 ms + n
/// µs.
inline core::MocapFrame test_frame(std::uint64_t n, double offset_m = 0.0) {
  core::MocapFrame f;
  f.frame_number = n;
  f.source_latency = std::chrono::microseconds(2000 + static_cast<std::int64_t>(n % 1000));
  core::BodySample b1;
  b1.name = "Body1";
  b1.tracked = true;
  b1.p_world_m = {offset_m + 0.001 * static_cast<double>(n), -0.5,
                  1.0 + 1e-4 * static_cast<double>(n)};
  const double yaw = 0.01 * static_cast<double>(n);
  b1.q_world_body = Eigen::Quaterniond(std::cos(yaw / 2), 0.1, 0.0, std::sin(yaw / 2)).normalized();
  core::BodySample b2;
  b2.name = "Body2";
  b2.tracked = n % 5 != 0;
  b2.p_world_m = {offset_m - 1.234567, 2.5, 0.75};
  b2.q_world_body = Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0);  // 180° about x: trace < 0 branch
  f.bodies = {b1, b2};
  return f;
}

/// Checks one received frame against test_frame(frame_number, offset_m).
inline void expect_matches(const core::MocapFrame& got, double offset_m = 0.0) {
  const core::MocapFrame want = test_frame(got.frame_number, offset_m);
  ASSERT_EQ(got.bodies.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& g = got.bodies[i];
    const auto& w = want.bodies[i];
    EXPECT_EQ(g.name, w.name);
    EXPECT_EQ(g.tracked, w.tracked) << "frame " << got.frame_number << " body " << w.name;
    if (!w.tracked) continue;
    EXPECT_LT((g.p_world_m - w.p_world_m).norm(), 1e-6) << "frame " << got.frame_number;
    // Same rotation (q and −q are equal rotations).
    EXPECT_NEAR(std::abs(g.q_world_body.dot(w.q_world_body)), 1.0, 1e-9);
  }
  ASSERT_TRUE(got.source_latency.has_value());
  EXPECT_EQ(std::chrono::duration_cast<std::chrono::microseconds>(*got.source_latency),
            std::chrono::duration_cast<std::chrono::microseconds>(*want.source_latency));
}

}  // namespace mocaplink::sources::test
