// Station: every figure with injected host time and hand-derived expectations.
#include "mocaplink/core/station.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

// Host clock far from the source clock's epoch, as on a real machine (days of uptime).
constexpr std::int64_t kHostEpochNs = 3 * 24 * 3600 * 1'000'000'000LL;

HostTime host_ms(double ms) {
  return host_time_from_ns(kHostEpochNs + std::llround(ms * 1e6));
}

MocapFrame make_frame(int number, double capture_ms = 0.0) {
  MocapFrame f;
  f.frame_number = static_cast<std::uint64_t>(number);
  f.capture_time = source_time_from_ns(std::llround(capture_ms * 1e6));
  return f;
}

BodySample body(const std::string& name, bool tracked,
                Eigen::Vector3d p = Eigen::Vector3d::Zero()) {
  BodySample b;
  b.name = name;
  b.tracked = tracked;
  b.p_world_m = p;
  return b;
}

TEST(Station, StartsEmptyAndDisconnected) {
  const Station station;
  const auto s = station.snapshot(host_ms(0));
  EXPECT_FALSE(s.connected);
  EXPECT_EQ(s.frames, 0u);
  EXPECT_EQ(s.frame_rate_hz, 0.0);
  EXPECT_FALSE(s.latency_ms);
  EXPECT_FALSE(s.jitter_ms);
  EXPECT_TRUE(s.bodies.empty());
}

TEST(Station, MeasuresTheArrivalRateOverTheLastSecondAndDecaysWhenFramesStop) {
  Station station;
  for (int i = 0; i <= 400; ++i) station.on_frame(make_frame(i + 1, 5.0 * i), host_ms(5.0 * i));
  // At t = 2000 ms the window (1000, 2000] holds frames at 1005..2000 ms: 200 frames over 995 ms
  // → 199 intervals / 0.995 s = 200 Hz.
  EXPECT_NEAR(station.snapshot(host_ms(2000)).frame_rate_hz, 200.0, 1e-9);
  // 500 ms after the last frame: (1500, 2500] holds 1505..2000 ms, 100 frames → 99 / 0.995 s.
  EXPECT_NEAR(station.snapshot(host_ms(2500)).frame_rate_hz, 99.0 / 0.995, 1e-9);
  EXPECT_EQ(station.snapshot(host_ms(3000)).frame_rate_hz, 0.0);  // nothing left in the window
  EXPECT_EQ(station.snapshot(host_ms(3000)).frames, 401u);
  EXPECT_EQ(station.snapshot(host_ms(3000)).dropped, 0u);
}

TEST(Station, RateOfTheFirstFramesUsesTheTimeSinceTheFirst) {
  Station station;
  station.on_frame(make_frame(1), host_ms(0));
  EXPECT_EQ(station.snapshot(host_ms(0)).frame_rate_hz, 0.0);  // one frame: no interval yet
  station.on_frame(make_frame(2), host_ms(10));
  EXPECT_NEAR(station.snapshot(host_ms(10)).frame_rate_hz, 100.0, 1e-9);
}

TEST(Station, CountsDropsFromGapsInFrameNumbers) {
  Station station;
  for (int n : {1, 2, 5, 6, 10}) station.on_frame(make_frame(n), host_ms(0));
  const auto s = station.snapshot(host_ms(0));
  EXPECT_EQ(s.dropped, 2u + 3u);  // 3,4 and 7,8,9
  EXPECT_EQ(s.frames, 5u);
  EXPECT_EQ(s.last_frame_number, 10u);
}

TEST(Station, CounterRestartsAndDuplicatesAreNotDrops) {
  StationConfig config;
  config.max_gap_frames = 1000;
  Station station(config);
  // 100, 101, restart to 1, 2, duplicate 2, jump by more than max_gap (a new counter), 1003.
  for (int n : {100, 101, 1, 2, 2, 5000, 5002}) station.on_frame(make_frame(n), host_ms(0));
  const auto s = station.snapshot(host_ms(0));
  EXPECT_EQ(s.restarts, 2u);
  EXPECT_EQ(s.duplicates, 1u);
  EXPECT_EQ(s.dropped, 1u);  // only 5001
}

TEST(Station, GapsAreCountedInFrameSteps) {
  // A Vicon UDP stream at half the camera rate: numbers 2 apart, one frame (2 numbers) lost.
  Station station;
  for (int n : {10, 12, 14, 18, 20, 21}) {
    MocapFrame f = make_frame(n);
    f.frame_step = 2;
    station.on_frame(f, host_ms(0));
  }
  const auto s = station.snapshot(host_ms(0));
  EXPECT_EQ(s.dropped, 1u);  // 16; 21 after 20 is a short step, not a drop
  EXPECT_TRUE(s.drops_counted);
}

TEST(Station, FramesNumberedByTheBridgeCountNoDrops) {
  // VRPN: frame numbers are the source adapter's own (frame_step 0), gaps mean nothing.
  Station station;
  for (int n : {1, 5, 9}) {
    MocapFrame f = make_frame(n);
    f.frame_step = 0;
    station.on_frame(f, host_ms(0));
  }
  const auto s = station.snapshot(host_ms(0));
  EXPECT_EQ(s.dropped, 0u);
  EXPECT_EQ(s.restarts, 0u);
  EXPECT_FALSE(s.drops_counted);
  EXPECT_EQ(s.frames, 3u);
}

TEST(Station, FramesMissedWhileDisconnectedAreNotDrops) {
  Station station;
  station.on_frame(make_frame(10), host_ms(0));
  EXPECT_TRUE(station.snapshot(host_ms(0)).connected);
  station.on_connection(false);
  EXPECT_FALSE(station.snapshot(host_ms(0)).connected);
  station.on_connection(true);
  station.on_frame(make_frame(50), host_ms(100));
  station.on_frame(make_frame(52), host_ms(105));
  const auto s = station.snapshot(host_ms(105));
  EXPECT_TRUE(s.connected);
  EXPECT_EQ(s.dropped, 1u);
  EXPECT_EQ(s.restarts, 0u);
}

TEST(Station, LatencyIsTheMeanReportedAndJitterTheSpreadOfArrivalVsCapture) {
  Station station;
  // Captured every 5 ms; arrival offset alternates 0 and 2 ms → population std dev 1 ms.
  for (int i = 0; i < 100; ++i) {
    MocapFrame f = make_frame(i + 1, 5.0 * i);
    f.source_latency = milliseconds(i % 2 == 0 ? 2 : 4);  // mean 3 ms
    station.on_frame(f, host_ms(5.0 * i + (i % 2 == 0 ? 0.0 : 2.0)));
  }
  const auto s = station.snapshot(host_ms(5.0 * 99 + 2.0));
  ASSERT_TRUE(s.latency_ms);
  EXPECT_NEAR(*s.latency_ms, 3.0, 1e-9);
  ASSERT_TRUE(s.jitter_ms);
  EXPECT_NEAR(*s.jitter_ms, 1.0, 1e-6);
}

TEST(Station, NominalRateComesFromTheSource) {
  Station station;
  MocapFrame f = make_frame(1);
  f.frame_rate_hz = 250.0;
  station.on_frame(f, host_ms(0));
  EXPECT_EQ(station.snapshot(host_ms(0)).nominal_rate_hz, 250.0);
}

TEST(Station, AMirroredBodyIsSaidSoUntilItsNextFrameWithout) {
  Station station;
  MocapFrame f1 = make_frame(1);
  BodySample mirrored = body("A", false);
  mirrored.mirrored = true;
  f1.bodies = {mirrored, body("B", true)};
  station.on_frame(f1, host_ms(0));
  auto s = station.snapshot(host_ms(0));
  EXPECT_TRUE(s.bodies[0].mirrored);
  EXPECT_FALSE(s.bodies[0].tracked);
  EXPECT_FALSE(s.bodies[1].mirrored);
  MocapFrame f2 = make_frame(2);
  f2.bodies = {body("B", true)};  // A absent: untracked, no longer mirrored either
  station.on_frame(f2, host_ms(5));
  EXPECT_FALSE(station.snapshot(host_ms(5)).bodies[0].mirrored);
  MocapFrame f3 = make_frame(3);
  f3.bodies = {body("A", true)};
  station.on_frame(f3, host_ms(10));
  EXPECT_FALSE(station.snapshot(host_ms(10)).bodies[0].mirrored);
}

TEST(Station, KeepsEveryBodyWithItsTrackingStateAndLastTrackedPose) {
  Station station;
  MocapFrame f1 = make_frame(1);
  f1.bodies = {body("A", true, {1, 2, 3}), body("B", true, {4, 5, 6})};
  station.on_frame(f1, host_ms(0));
  MocapFrame f2 = make_frame(2);
  f2.bodies = {body("A", true, {1.5, 2, 3}), body("B", false, {99, 99, 99})};
  station.on_frame(f2, host_ms(5));
  MocapFrame f3 = make_frame(3);
  f3.bodies = {body("C", false), body("A", true, {2, 2, 3})};  // B absent, C new and occluded
  station.on_frame(f3, host_ms(10));

  const auto s = station.snapshot(host_ms(10));
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[0].name, "A");  // order of first appearance
  EXPECT_EQ(s.bodies[1].name, "B");
  EXPECT_EQ(s.bodies[2].name, "C");
  EXPECT_TRUE(s.bodies[0].tracked);
  EXPECT_EQ(s.bodies[0].p_world_m, Eigen::Vector3d(2, 2, 3));
  EXPECT_EQ(s.bodies[0].frames_tracked, 3u);
  EXPECT_EQ(s.bodies[0].last_tracked, host_ms(10));
  EXPECT_FALSE(s.bodies[1].tracked);
  EXPECT_EQ(s.bodies[1].p_world_m, Eigen::Vector3d(4, 5, 6));  // last *tracked* position
  EXPECT_EQ(s.bodies[1].frames_tracked, 1u);
  EXPECT_EQ(s.bodies[1].last_tracked, host_ms(0));
  EXPECT_FALSE(s.bodies[2].tracked);
  EXPECT_FALSE(s.bodies[2].ever_tracked);
  EXPECT_EQ(s.bodies[2].frames_tracked, 0u);
}

TEST(Station, BodyRegistryIsBounded) {
  StationConfig config;
  config.max_bodies = 2;
  Station station(config);
  MocapFrame f = make_frame(1);
  f.bodies = {body("A", true), body("B", true), body("C", true)};
  station.on_frame(f, host_ms(0));
  station.on_frame(f, host_ms(1));
  const auto s = station.snapshot(host_ms(1));
  EXPECT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies_ignored, 2u);
}

TEST(Station, WindowMemoryIsBoundedAndRateStillSane) {
  StationConfig config;
  config.max_window_frames = 10;
  Station station(config);
  for (int i = 0; i < 100; ++i) station.on_frame(make_frame(i + 1), host_ms(i));
  // Only the last 10 arrivals (90..99 ms) are kept: 9 intervals over 9 ms.
  EXPECT_NEAR(station.snapshot(host_ms(99)).frame_rate_hz, 1000.0, 1e-9);
}

TEST(Station, HostTimeGoingBackwardsDoesNotBreakTheFigures) {
  Station station;
  station.on_frame(make_frame(1), host_ms(100));
  station.on_frame(make_frame(2), host_ms(50));
  const auto s = station.snapshot(host_ms(100));
  EXPECT_GE(s.frame_rate_hz, 0.0);
  EXPECT_EQ(s.frames, 2u);
}

}  // namespace
}  // namespace mocaplink::core
