// Sender: decimation to rate_hz independent of the mocap rate, what is sent while tracked / lost,
// heartbeat and origin cadence, sequence numbers, pause, runtime rate changes, signing.
#include "mocaplink/core/sender.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include <gtest/gtest.h>

#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;
using std::chrono::seconds;

BodyEstimate tracked_at(SourceTime t) {
  BodyEstimate e;
  e.capture_time = t;
  e.measurement_time = t;
  e.state = TrackingState::tracking;
  e.last_outcome = SampleOutcome::accepted;
  return e;
}

/// Frame k of a mocap stream at rate_hz, in integer nanoseconds (as a source clock would give).
SourceTime frame_time(std::int64_t k, double rate_hz) {
  return SourceTime{nanoseconds(std::llround(static_cast<double>(k) * 1e9 / rate_hz))};
}

HostTime host(SourceTime t) {
  return HostTime{t.time_since_epoch() + milliseconds(5)};
}

SenderConfig config(MessageSet messages, double rate_hz) {
  SenderConfig c;
  c.system_id = 1;
  c.messages = messages;
  c.rate_hz = rate_hz;
  return c;
}

template <typename M>
std::size_t count(const std::vector<OutgoingMessage>& out) {
  std::size_t n = 0;
  for (const auto& o : out) n += std::holds_alternative<M>(o.message) ? std::size_t{1} : 0;
  return n;
}

std::size_t run_stream(Sender& sender, double mocap_hz, double seconds_of_data,
                       std::vector<OutgoingMessage>& out) {
  const auto frames = static_cast<std::int64_t>(std::llround(mocap_hz * seconds_of_data));
  for (std::int64_t k = 0; k < frames; ++k) {
    const SourceTime t = frame_time(k, mocap_hz);
    SendContext ctx;
    ctx.now = host(t);
    ctx.capture = host(t);
    sender.on_estimate(tracked_at(t), ctx, out);
  }
  return static_cast<std::size_t>(frames);
}

TEST(SenderDecimation, FiftyFromTwoFortyOverTenSeconds) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  run_stream(sender, 240.0, 10.0, out);
  EXPECT_NEAR(static_cast<double>(count<mavlink::Odometry>(out)), 500.0, 1.0);
  // Phase-stable: no two sends closer than one mocap period less than 1/50 s apart would be a
  // burst; every interval is 4 or 5 frames (16.7 or 20.8 ms) around the 20 ms slot.
  for (std::size_t i = 1; i < out.size(); ++i) {
    const auto gap = out[i].time - out[i - 1].time;
    EXPECT_GE(gap, milliseconds(16)) << i;
    EXPECT_LE(gap, milliseconds(21)) << i;
  }
}

TEST(SenderSendRate, TheFirstSnapshotAfterAStartReadsTheActualRate) {
  // 240 Hz frames decimated to 50 Hz for 0.5 s, then one snapshot: ~50 Hz, whoever asks first
  // (issue 29: the dashboard measured it between two of its own requests and read 0).
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  run_stream(sender, 240.0, 0.5, out);
  const SenderSnapshot s = sender.snapshot(out.back().time);
  EXPECT_EQ(s.counters.poses, count<mavlink::Odometry>(out));
  EXPECT_NEAR(s.send_rate_hz, 50.0, 0.5);
  // A due send counts once however many messages it holds (three here, as in classic).
  Sender classic(config({MessageKind::vision_position_estimate, MessageKind::local_position_ned,
                         MessageKind::att_pos_mocap},
                        50.0));
  std::vector<OutgoingMessage> classic_out;
  SendContext ctx;
  for (int k = 0; k <= 25; ++k) {
    ctx.now = HostTime{milliseconds(20 * k)};
    classic.on_estimate(tracked_at(SourceTime{milliseconds(20 * k)}), ctx, classic_out);
  }
  EXPECT_DOUBLE_EQ(classic.snapshot(HostTime{milliseconds(500)}).send_rate_hz, 50.0);
  EXPECT_EQ(classic_out.size(), 3U * 26U);
  // Nothing sent since t = 0.5 s: a second later the rate reads 0.
  EXPECT_EQ(classic.snapshot(HostTime{milliseconds(1'501)}).send_rate_hz, 0.0);
}

TEST(SenderDecimation, ThirtyFromHundred) {
  Sender sender(config({MessageKind::odometry}, 30.0));
  std::vector<OutgoingMessage> out;
  run_stream(sender, 100.0, 10.0, out);
  EXPECT_NEAR(static_cast<double>(count<mavlink::Odometry>(out)), 300.0, 1.0);
}

TEST(SenderDecimation, MocapSlowerThanRateSendsEveryFrame) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  const std::size_t frames = run_stream(sender, 30.0, 10.0, out);
  EXPECT_EQ(count<mavlink::Odometry>(out), frames);
}

TEST(SenderDecimation, GapKeepsThePhaseWithoutBurst) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  SendContext ctx;
  sender.on_estimate(tracked_at(SourceTime{milliseconds(0)}), ctx, out);
  // 1 s without frames, then frames every 5 ms: one send at once, the next on the 20 ms grid.
  for (int ms = 1000; ms <= 1040; ms += 5) {
    sender.on_estimate(tracked_at(SourceTime{milliseconds(ms)}), ctx, out);
  }
  EXPECT_EQ(out.size(), 4U);  // t = 0, 1000, 1020, 1040
}

/// A source as the sender sees it: nominal rate, how its timestamps are rounded, jitter, and
/// which frames it drops. Deterministic (a fixed linear congruential generator).
struct SourceShape {
  const char* name;
  double hz;
  std::int64_t rounding_ns;  ///< timestamps are multiples of this (1 = exact ns)
  std::int64_t jitter_ns;    ///< each timestamp moved by up to ± this
  int drop_per_mille;        ///< frames the source drops
};

/// Capture times of `seconds_of_data` of the source (the frames it did not drop).
std::vector<SourceTime> source_frames(const SourceShape& shape, double seconds_of_data) {
  std::vector<SourceTime> times;
  std::uint64_t state = 12345;
  const auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 33;
  };
  const auto frames = static_cast<std::int64_t>(std::llround(shape.hz * seconds_of_data));
  for (std::int64_t k = 0; k < frames; ++k) {
    std::int64_t ns = std::llround(static_cast<double>(k) * 1e9 / shape.hz);
    if (shape.jitter_ns > 0) {
      ns +=
          static_cast<std::int64_t>(next() % static_cast<std::uint64_t>(2 * shape.jitter_ns + 1)) -
          shape.jitter_ns;
    }
    ns = (ns + shape.rounding_ns / 2) / shape.rounding_ns * shape.rounding_ns;
    const bool dropped = k > 0 && static_cast<int>(next() % 1000) < shape.drop_per_mille;
    if (!dropped) times.push_back(SourceTime{nanoseconds(10'000'000'000 + ns)});
  }
  return times;
}

std::vector<SourceTime> sent_captures(Sender& sender, const std::vector<SourceTime>& frames) {
  std::vector<OutgoingMessage> out;
  std::vector<SourceTime> sent;
  for (const SourceTime t : frames) {
    out.clear();
    SendContext ctx;
    ctx.now = host(t);
    sender.on_estimate(tracked_at(t), ctx, out);
    if (!out.empty()) sent.push_back(t);
  }
  return sent;
}

// Issue 15 "exact rates": min(rate_hz, source rate) within 0.5 % for every kind of source — live
// (µs stamps, jitter), emulated and simulated (exact grids), replayed (µs-rounded text), with and
// without dropped frames.
TEST(SenderDecimation, OutputRateIsTheSmallerOfRateAndSourceRate) {
  const SourceShape shapes[] = {
      {"simulated 240 Hz, exact ns", 240.0, 1, 0, 0},
      {"replayed 240 Hz, µs-rounded", 240.0, 1000, 0, 0},
      {"replayed 240 Hz, µs-rounded, 2 % dropped", 240.0, 1000, 0, 20},
      {"live 240 Hz, ±0.4 ms jitter, µs stamps", 240.0, 1000, 400'000, 0},
      {"live 240 Hz, ±0.4 ms jitter, 2 % dropped", 240.0, 1000, 400'000, 20},
      {"emulated 100 Hz, ms stamps", 100.0, 1'000'000, 0, 0},
      {"live 360 Hz, ±0.3 ms jitter, 2 % dropped", 360.0, 1000, 300'000, 20},
      {"live 50 Hz, ±2 ms jitter", 50.0, 1000, 2'000'000, 0},
  };
  const double rates[] = {500.0, 360.0, 240.0, 239.0, 120.0, 100.0, 60.0, 50.0, 30.0, 1.0};
  const double seconds_of_data = 20.0;
  for (const SourceShape& shape : shapes) {
    const std::vector<SourceTime> frames = source_frames(shape, seconds_of_data);
    const double source_hz = static_cast<double>(frames.size()) / seconds_of_data;
    for (const double rate : rates) {
      Sender sender(config({MessageKind::odometry}, rate));
      const std::vector<SourceTime> sent = sent_captures(sender, frames);
      const double expected = std::min(rate, source_hz) * seconds_of_data;
      EXPECT_NEAR(static_cast<double>(sent.size()), expected, std::max(1.0, 0.005 * expected))
          << shape.name << ", rate_hz " << rate;
    }
  }
}

TEST(SenderDecimation, EqualRatesSendEveryFrameWhateverTheRounding) {
  for (const std::int64_t rounding : {std::int64_t{1}, std::int64_t{1000}, std::int64_t{10'000}}) {
    const SourceShape shape{"240 Hz", 240.0, rounding, 0, 0};
    const std::vector<SourceTime> frames = source_frames(shape, 10.0);
    Sender sender(config({MessageKind::odometry}, 240.0));
    EXPECT_EQ(sent_captures(sender, frames).size(), frames.size()) << rounding << " ns";
  }
}

TEST(SenderDecimation, DroppedFramesDoNotShiftThePhase) {
  const SourceShape shape{"240 Hz µs", 240.0, 1000, 0, 0};
  const std::vector<SourceTime> all = source_frames(shape, 4.0);
  // The same stream with 100 ms of frames missing (and a few single drops) after 1 s.
  std::vector<SourceTime> holed;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const bool in_hole = k >= 240 && k < 264;
    const bool single = k == 400 || k == 401 || k == 555;
    if (!in_hole && !single) holed.push_back(all[k]);
  }
  for (const double rate : {50.0, 30.0, 120.0}) {
    Sender a(config({MessageKind::odometry}, rate));
    Sender b(config({MessageKind::odometry}, rate));
    std::vector<SourceTime> sent_all = sent_captures(a, all);
    const std::vector<SourceTime> sent_holed = sent_captures(b, holed);
    // After the disturbances, both send on exactly the same frames.
    const SourceTime after = all[600];
    std::erase_if(sent_all, [after](SourceTime t) { return t < after; });
    std::vector<SourceTime> tail(sent_holed.end() - static_cast<std::ptrdiff_t>(sent_all.size()),
                                 sent_holed.end());
    EXPECT_EQ(tail, sent_all) << rate;
    Sender c(config({MessageKind::odometry}, rate));
    EXPECT_LE(sent_holed.size(), sent_captures(c, all).size()) << "no burst after the hole";
  }
}

TEST(SenderDecimation, RateChangeTakesEffectOnTheNextFrame) {
  const SourceShape shape{"240 Hz µs", 240.0, 1000, 0, 0};
  const std::vector<SourceTime> frames = source_frames(shape, 3.0);
  Sender sender(config({MessageKind::odometry}, 10.0));
  std::vector<OutgoingMessage> out;
  std::vector<std::size_t> sent_at;  // frame indices that sent
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (k == 240) {
      ASSERT_TRUE(sender.set_rate_hz(240.0));
    }
    if (k == 480) {
      ASSERT_TRUE(sender.set_rate_hz(2.0));
    }
    out.clear();
    SendContext ctx;
    sender.on_estimate(tracked_at(frames[k]), ctx, out);
    if (!out.empty()) sent_at.push_back(k);
  }
  const auto sends_in = [&sent_at](std::size_t from, std::size_t to) {
    return std::count_if(sent_at.begin(), sent_at.end(),
                         [&](std::size_t k) { return k >= from && k < to; });
  };
  EXPECT_EQ(sends_in(0, 240), 10);     // 10 Hz for 1 s
  EXPECT_EQ(sends_in(240, 480), 240);  // 240 Hz from frame 240 on, that frame included
  // 2 Hz from frame 480: the first send half a second after the last 240 Hz one, then 2 Hz.
  EXPECT_EQ(sends_in(480, 720), 2);
  EXPECT_EQ(sent_at[sent_at.size() - 2], 479U + 120U);
}

TEST(SenderDecimation, RuntimeRateChange) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  EXPECT_FALSE(sender.set_rate_hz(0.0));
  EXPECT_FALSE(sender.set_rate_hz(501.0));
  EXPECT_FALSE(sender.set_rate_hz(std::nan("")));
  EXPECT_TRUE(sender.set_rate_hz(10.0));
  run_stream(sender, 200.0, 5.0, out);
  EXPECT_NEAR(static_cast<double>(out.size()), 50.0, 1.0);
  EXPECT_EQ(sender.snapshot(HostTime{}).rate_hz, 10.0);
}

TEST(SenderContent, VisionOnlyWhileTrackedGpsWithFixZeroWhenLost) {
  const auto origin = LocalGeodeticFrame::make({47.0, 8.0, 400.0});
  ASSERT_TRUE(origin);
  Sender px4(config({MessageKind::odometry}, 50.0));
  Sender gps(config({MessageKind::gps_input}, 50.0));
  std::vector<OutgoingMessage> out_px4;
  std::vector<OutgoingMessage> out_gps;
  SendContext ctx;
  ctx.origin = &*origin;
  auto e = tracked_at(SourceTime{seconds(1)});
  e.state = TrackingState::lost;
  e.last_outcome = SampleOutcome::untracked;
  px4.on_estimate(e, ctx, out_px4);
  gps.on_estimate(e, ctx, out_gps);
  EXPECT_TRUE(out_px4.empty());
  ASSERT_EQ(out_gps.size(), 1U);
  EXPECT_EQ(std::get<mavlink::GpsInput>(out_gps[0].message).fix_type, 0);
  EXPECT_EQ(px4.snapshot(HostTime{}).counters.due_without_pose, 1U);

  // Tracking but occluded in this frame (prediction only): still no vision message.
  e.capture_time += seconds(1);
  e.state = TrackingState::tracking;
  e.last_outcome = SampleOutcome::untracked;
  px4.on_estimate(e, ctx, out_px4);
  EXPECT_TRUE(out_px4.empty());

  // Unseen bodies produce nothing at all.
  BodyEstimate unseen;
  unseen.capture_time = SourceTime{seconds(3)};
  gps.on_estimate(unseen, ctx, out_gps);
  EXPECT_EQ(out_gps.size(), 1U);
}

TEST(SenderContent, ImplausibleStateIsNeverSent) {
  const auto origin = LocalGeodeticFrame::make({47.0, 8.0, 400.0});
  ASSERT_TRUE(origin);
  Sender sender(config({MessageKind::odometry, MessageKind::hil_gps}, 50.0));
  std::vector<OutgoingMessage> out;
  SendContext ctx;
  ctx.origin = &*origin;
  auto e = tracked_at(SourceTime{seconds(1)});
  e.p_ned_m.x() = std::numeric_limits<double>::quiet_NaN();
  sender.on_estimate(e, ctx, out);
  e = tracked_at(SourceTime{seconds(2)});
  e.p_ned_m.y() = 2e6;  // 2000 km
  sender.on_estimate(e, ctx, out);
  e = tracked_at(SourceTime{seconds(3)});
  e.pose_covariance(0, 0) = std::numeric_limits<double>::infinity();
  sender.on_estimate(e, ctx, out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(sender.snapshot(HostTime{}).counters.implausible, 3U);
}

// Every one of the 85 values the sender checks, each made NaN, +inf and -inf in turn, is refused;
// the largest finite doubles in the covariances and the rates are sent (nothing is "infinite"
// because it is big).
TEST(SenderContent, EachNonFiniteValueIsImplausibleAndNoFiniteOne) {
  Sender sender(config({MessageKind::odometry}, 100.0));
  std::vector<OutgoingMessage> out;
  const SendContext ctx;
  std::int64_t ms = 0;
  std::size_t expected_implausible = 0;
  const auto send = [&](const auto& set) {
    auto e = tracked_at(SourceTime{milliseconds(ms += 10)});
    set(e);
    out.clear();
    sender.on_estimate(e, ctx, out);
    return out.size();
  };
  const auto each_value = [](BodyEstimate& e, auto f) {
    for (int i = 0; i < 3; ++i) f(e.p_ned_m[i]);
    for (int i = 0; i < 3; ++i) f(e.v_ned_mps[i]);
    for (int i = 0; i < 4; ++i) f(e.q_ned_frd.coeffs()[i]);
    for (int i = 0; i < 3; ++i) f(e.w_frd_radps[i]);
    for (int i = 0; i < 36; ++i) f(e.pose_covariance.data()[i]);
    for (int i = 0; i < 36; ++i) f(e.velocity_covariance.data()[i]);
  };
  BodyEstimate probe;
  std::size_t values = 0;
  each_value(probe, [&](double&) { ++values; });
  ASSERT_EQ(values, 85U);
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < values; ++k) {
    for (const double x : bad) {
      EXPECT_EQ(send([&](BodyEstimate& e) {
                  std::size_t n = 0;
                  each_value(e, [&](double& v) { v = n++ == k ? x : v; });
                }),
                0U)
          << "value " << k << " = " << x;
      ++expected_implausible;
    }
  }
  const double huge = std::numeric_limits<double>::max();
  EXPECT_EQ(send([&](BodyEstimate& e) {
              e.pose_covariance.setConstant(huge);
              e.velocity_covariance.setConstant(-huge);
              e.w_frd_radps.setConstant(huge);
            }),
            1U);
  EXPECT_EQ(sender.snapshot(HostTime{}).counters.implausible, expected_implausible);
}

TEST(SenderContent, ClassicSendsThreeMessagesWithTimes) {
  const auto origin = LocalGeodeticFrame::make({47.0, 8.0, 400.0});
  ASSERT_TRUE(origin);
  Sender sender(config(messages_for(Profile::classic), 10.0));
  std::vector<OutgoingMessage> out;
  SendContext ctx;
  ctx.origin = &*origin;
  ctx.start = HostTime{seconds(100)};
  ctx.capture = HostTime{seconds(102) + milliseconds(345) + nanoseconds(678'900)};
  ctx.now = ctx.capture + milliseconds(3);
  sender.on_estimate(tracked_at(SourceTime{seconds(1)}), ctx, out);
  ASSERT_EQ(out.size(), 3U);
  // Enum order: ATT_POS_MOCAP, HIL_GPS, LOCAL_POSITION_NED.
  EXPECT_EQ(std::get<mavlink::AttPosMocap>(out[0].message).time_usec, 102'345'678U);
  EXPECT_EQ(std::get<mavlink::HilGps>(out[1].message).time_usec, 102'345'678U);
  EXPECT_EQ(std::get<mavlink::LocalPositionNed>(out[2].message).time_boot_ms, 2345U);
}

TEST(SenderClock, HeartbeatAtOneHertz) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  for (int ms = 0; ms < 10'000; ms += 100)
    sender.on_tick(HostTime{milliseconds(ms)}, 0, nullptr, false, out);
  ASSERT_EQ(count<mavlink::Heartbeat>(out), 10U);
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].time, HostTime{seconds(static_cast<int>(i))});
  }
  // Irregular ticks: never two heartbeats less than 1 s apart, never a burst after a stall.
  out.clear();
  Sender s2(config({MessageKind::odometry}, 50.0));
  for (int ms : {0, 300, 900, 1000, 1001, 5000, 5100, 5999, 6000}) {
    s2.on_tick(HostTime{milliseconds(ms)}, 0, nullptr, false, out);
  }
  ASSERT_EQ(out.size(), 4U);  // 0, 1000, 5000, 6000
  EXPECT_EQ(out[2].time, HostTime{milliseconds(5000)});
  EXPECT_EQ(out[3].time, HostTime{milliseconds(6000)});
}

// Issue 50: 1000 vehicles' heartbeats (and origins, TIMESYNC requests) once left in one tick of
// the daemon's 100 ms, holding every pose behind 2000 sends for 10 ms once a second. Each vehicle
// keeps its 1 Hz, the first at once, but the ticks after the first share the load.
TEST(SenderClock, ManyVehiclesHousekeepingSpreadOverTheSecond) {
  constexpr std::size_t kVehicles = 1000;
  const GeodeticPosition origin{47.3977418, 8.5455938, 488.0};
  std::vector<Sender> senders;
  senders.reserve(kVehicles);
  for (std::size_t i = 0; i < kVehicles; ++i) {
    SenderConfig c = config({MessageKind::odometry}, 50.0);
    c.vehicle = i;
    senders.emplace_back(c);
  }
  std::vector<std::vector<HostTime>> beats(kVehicles);
  std::vector<std::size_t> per_tick;
  std::vector<OutgoingMessage> out;
  for (int ms = 0; ms < 10'000; ms += 100) {
    std::size_t frames = 0;
    for (std::size_t i = 0; i < kVehicles; ++i) {
      out.clear();
      senders[i].on_tick(HostTime{milliseconds(ms)}, 0, &origin, true, out);
      frames += out.size();
      for (const auto& m : out) {
        if (std::holds_alternative<mavlink::Heartbeat>(m.message)) beats[i].push_back(m.time);
      }
    }
    per_tick.push_back(frames);
  }
  // The first tick: every vehicle at once (heartbeat, origin, TIMESYNC request).
  EXPECT_EQ(per_tick.front(), 3 * kVehicles);
  // Afterwards about a tenth of them per tick, never much more: 3 frames each, plus every third
  // origin's request.
  for (std::size_t t = 11; t < per_tick.size(); ++t) {
    EXPECT_LE(per_tick[t], 3 * kVehicles / 10 * 13 / 10 + kVehicles / 10) << "tick " << t;
    EXPECT_GE(per_tick[t], 3 * kVehicles / 10 * 7 / 10) << "tick " << t;
  }
  for (std::size_t i = 0; i < kVehicles; ++i) {
    ASSERT_GE(beats[i].size(), 9U) << "vehicle " << i;  // 10 s: the second may come at 2 s
    EXPECT_EQ(beats[i].front(), HostTime{});
    // The second within two periods of the first, then one a second exactly (100 ms ticks).
    EXPECT_GE(beats[i][1] - beats[i][0], seconds(1));
    EXPECT_LE(beats[i][1] - beats[i][0], seconds(2));  // due before 2 s, sent at the tick
    for (std::size_t k = 2; k < beats[i].size(); ++k) {
      EXPECT_EQ(beats[i][k] - beats[i][k - 1], seconds(1)) << "vehicle " << i << " beat " << k;
    }
  }
}

// After a stall of the caller longer than a period: one message at once, the next in the
// vehicle's phase again (not the stall's), at least a period later.
TEST(SenderClock, PhaseKeptAfterAStall) {
  SenderConfig c = config({MessageKind::odometry}, 50.0);
  c.vehicle = 1;  // phase 618 ms
  Sender sender(c);
  std::vector<OutgoingMessage> out;
  for (int ms : {0, 1700, 2700, 6050, 6700, 7100, 7700, 8700}) {
    sender.on_tick(HostTime{milliseconds(ms)}, 0, nullptr, false, out);
  }
  std::vector<HostTime> at;
  for (const auto& m : out) at.push_back(m.time);
  // 0 at once; 1.618 due → sent at 1.7; 2.618 → 2.7; stalled to 6.05: one at once, the next at
  // 7.618 (the first in phase a period on; not 7.05, a period after the stall), sent at 7.7;
  // then 8.618 → 8.7.
  const std::vector<HostTime> expected{HostTime{},
                                       HostTime{milliseconds(1700)},
                                       HostTime{milliseconds(2700)},
                                       HostTime{milliseconds(6050)},
                                       HostTime{milliseconds(7700)},
                                       HostTime{milliseconds(8700)}};
  EXPECT_EQ(at, expected);
}

TEST(SenderClock, OriginEverySecondWithRequestEveryThird) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  const GeodeticPosition origin{47.3977418, 8.5455938, 488.0};
  std::vector<OutgoingMessage> out;
  for (int ms = 0; ms < 3000; ms += 100)
    sender.on_tick(HostTime{milliseconds(ms)}, 0, &origin, false, out);
  EXPECT_EQ(count<mavlink::SetGpsGlobalOrigin>(out), 3U);
  EXPECT_EQ(count<mavlink::CommandLong>(out), 1U);
  const auto& set = std::get<mavlink::SetGpsGlobalOrigin>(out[1].message);
  EXPECT_EQ(set.target_system, 1);
  EXPECT_EQ(set.latitude, 473977418);
  EXPECT_EQ(set.time_usec, 0U);  // host µs at t = 0
}

TEST(SenderClock, TimesyncRequests) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  sender.on_tick(HostTime{seconds(7)}, 0, nullptr, true, out);
  ASSERT_EQ(count<mavlink::Timesync>(out), 1U);
  const auto& ts = std::get<mavlink::Timesync>(out[1].message);
  EXPECT_EQ(ts.tc1, 0);
  EXPECT_EQ(ts.ts1, 7'000'000'000);
  EXPECT_EQ(ts.target_system, 1);
}

TEST(SenderFrames, SequenceIsConsecutiveAndWraps) {
  SenderConfig c = config({MessageKind::odometry}, 50.0);
  c.system_id = 7;
  c.component_id = 197;
  Sender sender(c);
  std::vector<OutgoingMessage> out;
  for (int i = 0; i < 300; ++i) {
    sender.send(build_heartbeat(), HostTime{}, 0, out);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto b = out[i].frame.bytes();
    EXPECT_EQ(b[4], static_cast<std::uint8_t>(i % 256)) << i;
    EXPECT_EQ(b[5], 7);
    EXPECT_EQ(b[6], 197);
  }
  EXPECT_EQ(sender.next_seq(), 300 % 256);
}

TEST(SenderFrames, PauseStopsPosesNotHeartbeats) {
  Sender sender(config({MessageKind::odometry}, 50.0));
  std::vector<OutgoingMessage> out;
  sender.set_paused(true);
  run_stream(sender, 100.0, 1.0, out);
  EXPECT_TRUE(out.empty());
  sender.on_tick(HostTime{}, 0, nullptr, false, out);
  EXPECT_EQ(count<mavlink::Heartbeat>(out), 1U);
  sender.set_paused(false);
  sender.set_messages(MessageSet{MessageKind::vision_position_estimate});
  SendContext ctx;
  sender.on_estimate(tracked_at(SourceTime{seconds(5)}), ctx, out);
  EXPECT_EQ(count<mavlink::VisionPositionEstimate>(out), 1U);
}

TEST(SenderFrames, SignedFramesVerifyWithTheKey) {
  SenderConfig c = config({MessageKind::odometry}, 50.0);
  std::array<std::uint8_t, 32> secret{};
  for (std::size_t i = 0; i < secret.size(); ++i) secret[i] = static_cast<std::uint8_t>(i);
  c.signing_key = secret;
  c.signing_link_id = 4;
  Sender sender(c);
  std::vector<OutgoingMessage> out;
  sender.send(build_heartbeat(), HostTime{}, 1000, out);
  sender.send(build_heartbeat(), HostTime{}, 1000, out);
  ASSERT_EQ(out.size(), 2U);
  const mavlink::SigningKey key(secret);
  for (const auto& o : out) {
    const auto b = o.frame.bytes();
    EXPECT_EQ(b[2] & 1, 1);  // incompat flag: signed
    EXPECT_EQ(o.frame.size(), 12U + 9U + 13U);
    EXPECT_TRUE(key.verify(b));
    EXPECT_EQ(b[12 + 9], 4);  // link id
  }
  // Timestamps strictly increase even with the same "now" (mavlink-wire.md §7.3).
  EXPECT_NE(out[0].frame.bytes()[22], out[1].frame.bytes()[22]);
  EXPECT_TRUE(sender.snapshot(HostTime{}).signing);
}

}  // namespace
}  // namespace mocaplink::core
