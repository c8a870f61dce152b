// VehicleClockMonitor and the TIMESYNC answers it decides (issue 45), against a scripted PX4: its
// Timesync filter as PX4 v1.14 runs it (src/lib/timesync/Timesync.{hpp,cpp}: offset sample
// ((ts1 + now)/2 − tc1), samples with a round trip ≥ 10 ms ignored, gains scheduled from 0.05 to
// 0.003 over the first 500 samples, then converged; once converged, a sample over 100 ms from the
// estimate is not used, and more than 5 in a row reset the filter; sync_stamp is time_usec +
// offset once converged, the arrival time before), requests at 10 Hz stamped on its own clock, and
// a clock that is either a crystal's or a simulator's lockstep clock whose rate follows the load.
#include "mocaplink/core/vehicle_clock.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/core/vehicle_state.hpp"

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// ---- The scripted PX4 ----------------------------------------------------------------------

/// PX4's Timesync filter, from the behaviour its source documents (header comment).
class Px4Timesync {
 public:
  void update(std::int64_t now_us, std::int64_t remote_ns, std::int64_t originate_ns) {
    if (remote_ns <= 0) return;
    const std::int64_t offset_us = (originate_ns / 1000 + now_us - (remote_ns / 1000) * 2) / 2;
    const std::int64_t rtt_us = now_us - originate_ns / 1000;
    const double deviation = std::abs(offset_ - static_cast<double>(offset_us));
    if (rtt_us >= 10'000) return;
    if (converged() && deviation > 100'000.0) {
      if (++high_deviation_ > 5) reset();
      return;
    }
    double alpha = 0.003;
    double beta = 0.003;
    if (!converged()) {
      const double progress = static_cast<double>(sequence_) / 500.0;
      const double p = 1.0 - std::exp(0.5 * (1.0 - 1.0 / (1.0 - progress)));
      alpha = p * 0.003 + (1.0 - p) * 0.05;
      beta = p * 0.003 + (1.0 - p) * 0.05;
    }
    const double previous = offset_;
    if (sequence_ == 0) {
      offset_ = static_cast<double>(offset_us);
    } else {
      offset_ = alpha * static_cast<double>(offset_us) + (1.0 - alpha) * (offset_ + skew_);
      skew_ = beta * (offset_ - previous) + (1.0 - beta) * skew_;
    }
    ++sequence_;
    high_deviation_ = 0;
  }
  [[nodiscard]] bool converged() const { return sequence_ >= 500; }
  /// Where PX4 places a sample sent with `time_usec` that arrived at `arrival_us` (its clock).
  [[nodiscard]] std::int64_t sync_stamp(std::int64_t time_usec, std::int64_t arrival_us) const {
    return converged() ? time_usec + static_cast<std::int64_t>(offset_) : arrival_us;
  }
  [[nodiscard]] std::uint32_t resets() const { return resets_; }

 private:
  void reset() {
    sequence_ = 0;
    offset_ = 0;
    skew_ = 0;
    high_deviation_ = 0;
    ++resets_;
  }
  std::uint32_t sequence_ = 0;
  double offset_ = 0;
  double skew_ = 0;
  std::uint32_t high_deviation_ = 0;
  std::uint32_t resets_ = 0;
};

/// A vehicle clock as a function of host time: its rate against the host's, piecewise constant.
class ScriptedClock {
 public:
  /// `rate_at(k)` is the rate in the k-th `segment` of host time.
  ScriptedClock(Duration segment, std::function<double(std::int64_t)> rate_at)
      : segment_ns_(segment.count()), rate_at_(std::move(rate_at)) {}
  /// Vehicle ns at host ns (from 0 at host 0, plus 3 s of boot).
  std::int64_t at(std::int64_t host_ns) {
    while (done_until_ns_ + segment_ns_ <= host_ns) {
      done_vehicle_ns_ += rate_at_(segment_) * static_cast<double>(segment_ns_);
      done_until_ns_ += segment_ns_;
      ++segment_;
    }
    const double v =
        done_vehicle_ns_ + rate_at_(segment_) * static_cast<double>(host_ns - done_until_ns_);
    return 3'000'000'000 + static_cast<std::int64_t>(v);
  }

 private:
  std::int64_t segment_ns_;
  std::function<double(std::int64_t)> rate_at_;
  std::int64_t segment_ = 0;
  std::int64_t done_until_ns_ = 0;
  double done_vehicle_ns_ = 0;
};

/// PX4 SITL's lockstep clock on a loaded machine: 0.4–3 % slow, the rate changing every 10 s.
double lockstep_rate(std::int64_t segment) {
  static constexpr double kRates[] = {0.992, 0.975, 0.996, 0.985, 0.970, 0.990, 0.980, 0.994};
  return kRates[segment % 8];
}

/// Deterministic one-way delays of 0.3–2.3 ms, a few of 15 ms (a busy link).
std::int64_t delay_ns(std::uint32_t& state) {
  state = state * 1664525U + 1013904223U;
  const std::uint32_t r = state >> 8;
  if (r % 50 == 0) return 15'000'000;
  return 300'000 + static_cast<std::int64_t>(r % 2'000'000);
}

struct FlightFigures {
  std::int64_t most_future_us = INT64_MIN;        ///< max over poses of PX4's stamp − its arrival
  std::int64_t most_future_after_us = INT64_MIN;  ///< the same from `judged_after` on
  std::int64_t worst_capture_error_us = 0;  ///< max |PX4's stamp − true capture| while converged
  std::uint64_t converged_poses = 0;
  std::uint64_t poses = 0;
  std::uint32_t resets = 0;
  VehicleSnapshot vehicle;
};

/// `seconds_flown` of a PX4 sending TIMESYNC requests at 10 Hz and receiving 50 Hz poses stamped
/// with their capture time (3 ms before mocaplink sends them), answered by `answer` (mocaplink's
/// VehicleState, or a stand-in that answers every request). Poses from `judged_after` on are also
/// counted apart.
template <class Answer>
FlightFigures fly(ScriptedClock& clock, int seconds_flown, Answer answer,
                  Duration judged_after = Duration::zero()) {
  Px4Timesync px4;
  FlightFigures f;
  std::uint32_t rng = 7;
  const std::int64_t end_ns = std::int64_t{seconds_flown} * 1'000'000'000;
  for (std::int64_t host_ns = 0; host_ns < end_ns; host_ns += 10'000'000) {  // 100 Hz steps
    if (host_ns % 100'000'000 == 0) {
      // A request: PX4 stamps it, it reaches mocaplink, the answer goes back.
      const std::int64_t ts1 = clock.at(host_ns);
      const std::int64_t reached = host_ns + delay_ns(rng);
      if (const std::optional<std::int64_t> tc1 = answer(ts1, HostTime{Duration{reached}})) {
        const std::int64_t back = reached + delay_ns(rng);
        px4.update(clock.at(back) / 1000, *tc1, ts1);
      }
    }
    if (host_ns % 20'000'000 == 0 && host_ns >= 3'000'000) {
      const std::int64_t capture_ns = host_ns - 3'000'000;
      const std::int64_t arrival_us = clock.at(host_ns + delay_ns(rng)) / 1000;
      const std::int64_t stamp_us = px4.sync_stamp(capture_ns / 1000, arrival_us);
      ++f.poses;
      f.most_future_us = std::max(f.most_future_us, stamp_us - arrival_us);
      if (Duration{host_ns} >= judged_after) {
        f.most_future_after_us = std::max(f.most_future_after_us, stamp_us - arrival_us);
      }
      if (px4.converged()) {
        ++f.converged_poses;
        f.worst_capture_error_us =
            std::max(f.worst_capture_error_us, std::abs(stamp_us - clock.at(capture_ns) / 1000));
      }
    }
  }
  f.resets = px4.resets();
  return f;
}

mavlink::Timesync request(std::int64_t ts1) {
  mavlink::Timesync t;
  t.tc1 = 0;
  t.ts1 = ts1;
  return t;
}

mavlink::Heartbeat heartbeat(std::uint8_t autopilot) {
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = autopilot;
  return hb;
}

/// mocaplink's answers: a VehicleState for vehicle 1 that has heard `autopilot`'s heartbeat.
struct Mocaplink {
  explicit Mocaplink(std::uint8_t autopilot) : state(VehicleStateConfig{}) {
    state.on_message(ReceivedMessage{1, 1, heartbeat(autopilot)}, HostTime{}, nullptr);
  }
  std::optional<std::int64_t> operator()(std::int64_t ts1, HostTime arrival) {
    const VehicleReaction r =
        state.on_message(ReceivedMessage{1, 1, request(ts1)}, arrival, nullptr);
    if (!r.timesync_reply) return std::nullopt;
    return r.timesync_reply->tc1;
  }
  VehicleState state;
};

// ---- The tests -------------------------------------------------------------------------------

// The failure of the issue, in the scripted PX4: a bridge that answers every request with its
// host clock, against a lockstep clock, has PX4 place poses tens of ms in its future once the
// filter has converged. (The test the guard must pass below is only worth something if this one
// shows the scenario is hard enough.)
TEST(Px4Timesync, AnsweringALockstepClockPutsPosesInPx4sFuture) {
  ScriptedClock clock(seconds(10), lockstep_rate);
  const FlightFigures f = fly(clock, 600, [](std::int64_t, HostTime arrival) {
    return std::optional<std::int64_t>(arrival.time_since_epoch().count());
  });
  EXPECT_GT(f.converged_poses, 0U);
  EXPECT_GT(f.most_future_us, 20'000) << "the scripted PX4 never saw a pose in its future";
}

// The SITL case: the lockstep clock is judged unsteady in the first 20 s, PX4 is never
// answered enough to converge, and every pose is placed at its arrival for ten minutes.
TEST(Px4Timesync, ALockstepClockIsNeverAnsweredToConvergence) {
  ScriptedClock clock(seconds(10), lockstep_rate);
  Mocaplink mocaplink(kMavAutopilotPx4);
  const FlightFigures f = fly(clock, 600, std::ref(mocaplink));
  const VehicleSnapshot s = mocaplink.state.snapshot();
  EXPECT_EQ(s.clock.verdict, VehicleClockVerdict::unsteady);
  ASSERT_TRUE(s.clock.rate_ppm);
  EXPECT_LT(*s.clock.rate_ppm, -2000.0);
  EXPECT_FALSE(s.capture_stamps);
  EXPECT_EQ(f.converged_poses, 0U);
  EXPECT_LE(f.most_future_us, 0);
  EXPECT_EQ(s.counters.timesync_resets, kTimesyncResetReplies);
  EXPECT_GT(s.counters.timesync_withheld, 5000U);
  EXPECT_LT(s.counters.timesync_requests, 500U);
  EXPECT_NE(vehicle_clock_text(s.clock, s.heartbeat->autopilot).find("no longer answered"),
            std::string::npos)
      << vehicle_clock_text(s.clock, s.heartbeat->autopilot);
}

// A flight controller's crystal (+40 ppm, constant): steady, answered throughout, PX4 converges
// and places every pose within 1.5 ms of its capture, never after its arrival.
TEST(Px4Timesync, ACrystalClockIsAnsweredAndPosesKeepTheirCaptureTime) {
  ScriptedClock clock(seconds(10), [](std::int64_t) { return 1.0 + 40e-6; });
  Mocaplink mocaplink(kMavAutopilotPx4);
  const FlightFigures f = fly(clock, 600, std::ref(mocaplink));
  const VehicleSnapshot s = mocaplink.state.snapshot();
  EXPECT_EQ(s.clock.verdict, VehicleClockVerdict::steady);
  ASSERT_TRUE(s.clock.rate_ppm);
  EXPECT_NEAR(*s.clock.rate_ppm, 40.0, 10.0);
  EXPECT_TRUE(s.capture_stamps);
  EXPECT_EQ(s.counters.timesync_withheld, 0U);
  EXPECT_EQ(s.counters.timesync_resets, 0U);
  EXPECT_GT(f.converged_poses, f.poses * 8 / 10);  // converged after ~50 s of 600
  EXPECT_LE(f.worst_capture_error_us, 1500);
  EXPECT_LE(f.most_future_us, 0);
}

// A clock that was steady long enough for PX4 to converge, then turns into a lockstep clock: the
// verdict changes within a window or two, the reset answers make the scripted PX4 drop its
// filter, and from then on no pose is placed after its arrival.
TEST(Px4Timesync, AClockThatTurnsUnsteadyResetsAConvergedPx4) {
  ScriptedClock clock(seconds(10), [](std::int64_t k) { return k < 12 ? 1.0 : lockstep_rate(k); });
  Mocaplink mocaplink(kMavAutopilotPx4);
  const FlightFigures f = fly(clock, 400, std::ref(mocaplink), seconds(135));
  const VehicleSnapshot s = mocaplink.state.snapshot();
  EXPECT_EQ(s.clock.verdict, VehicleClockVerdict::unsteady);
  EXPECT_GE(f.resets, 1U);
  EXPECT_GT(f.converged_poses, 0U);  // it had converged before the change
  EXPECT_LE(f.most_future_after_us, 0);
}

// ArduPilot takes no pose time from TIMESYNC: it is answered whatever its clock does.
TEST(Px4Timesync, ArduPilotIsAlwaysAnswered) {
  ScriptedClock clock(seconds(10), lockstep_rate);
  Mocaplink mocaplink(kMavAutopilotArdupilot);
  (void)fly(clock, 120, std::ref(mocaplink));
  const VehicleSnapshot s = mocaplink.state.snapshot();
  EXPECT_EQ(s.clock.verdict, VehicleClockVerdict::unsteady);
  EXPECT_EQ(s.counters.timesync_withheld, 0U);
  EXPECT_EQ(s.counters.timesync_resets, 0U);
  EXPECT_EQ(s.counters.timesync_requests, 1200U);
  EXPECT_NE(vehicle_clock_text(s.clock, s.heartbeat->autopilot).find("nothing changes"),
            std::string::npos);
}

TEST(VehicleClockMonitor, VerdictAfterFourWindowsRateAndResidual) {
  VehicleClockMonitor c;
  // 200 ppm fast, requests every 100 ms, 1 ms one-way delay: steady at the fourth window.
  std::optional<std::int64_t> judged_at_ms;
  for (std::int64_t ms = 0; ms <= 30'000; ms += 100) {
    const std::int64_t ts1 =
        5'000'000'000 + static_cast<std::int64_t>(static_cast<double>(ms) * 1e6 * 1.0002);
    if (c.on_request(ts1, HostTime{milliseconds(ms + 1)}) && !judged_at_ms) judged_at_ms = ms;
  }
  ASSERT_TRUE(judged_at_ms);
  EXPECT_EQ(*judged_at_ms, 20'000);
  EXPECT_EQ(c.verdict(), VehicleClockVerdict::steady);
  ASSERT_TRUE(c.figures().rate_ppm);
  EXPECT_NEAR(*c.figures().rate_ppm, 200.0, 1.0);
  EXPECT_LT(*c.figures().residual_ms, 0.01);
  EXPECT_EQ(c.figures().windows, 6U);
  EXPECT_EQ(c.figures().requests, 301U);
}

// A crystal 80 ppm fast on a host whose CLOCK_MONOTONIC NTP slews by the kernel's 500 ppm: steady.
// 1.5 % slow (SITL's lockstep clock on an idle machine): unsteady, however straight its line.
TEST(VehicleClockMonitor, SlewedHostIsSteadyASimulatorsRateIsNot) {
  for (const double rate : {1.0 + 580e-6, 1.0 - 580e-6, 0.985}) {
    VehicleClockMonitor c;
    for (std::int64_t ms = 0; ms <= 30'000; ms += 100) {
      const auto ts1 = static_cast<std::int64_t>(static_cast<double>(ms) * 1e6 * rate);
      c.on_request(ts1, HostTime{milliseconds(ms + 1)});
    }
    EXPECT_EQ(c.verdict(),
              rate > 0.99 ? VehicleClockVerdict::steady : VehicleClockVerdict::unsteady)
        << rate;
  }
}

TEST(VehicleClockMonitor, MinimumOfEachWindowIgnoresDelays) {
  VehicleClockMonitor c;
  std::uint32_t rng = 3;
  for (std::int64_t ms = 0; ms <= 60'000; ms += 100) {
    // Delays of 0.3–2.3 ms and a few of 15 ms: the minima stay on the line.
    const std::int64_t arrival_ns = ms * 1'000'000 + delay_ns(rng);
    c.on_request(ms * 1'000'000, HostTime{Duration{arrival_ns}});
  }
  EXPECT_EQ(c.verdict(), VehicleClockVerdict::steady);
  EXPECT_NEAR(*c.figures().rate_ppm, 0.0, 20.0);
  EXPECT_LT(*c.figures().residual_ms, 0.5);
}

TEST(VehicleClockMonitor, AStallIsUnsteadyAndStaysSoUntilARestart) {
  VehicleClockMonitor c;
  std::int64_t vehicle_ns = 0;
  for (std::int64_t ms = 0; ms <= 40'000; ms += 100) {
    vehicle_ns += ms == 25'000 ? 0 : 100'000'000;  // the clock stood still for 100 ms once
    c.on_request(vehicle_ns, HostTime{milliseconds(ms)});
  }
  EXPECT_EQ(c.verdict(), VehicleClockVerdict::unsteady);
  // Steady again afterwards: still unsteady (a simulator's clock).
  for (std::int64_t ms = 40'100; ms <= 120'000; ms += 100) {
    vehicle_ns += 100'000'000;
    c.on_request(vehicle_ns, HostTime{milliseconds(ms)});
  }
  EXPECT_EQ(c.verdict(), VehicleClockVerdict::unsteady);
  // A reboot: ts1 starts again from 0 and the measurement with it.
  EXPECT_TRUE(c.on_request(1'000'000, HostTime{milliseconds(120'100)}));
  EXPECT_EQ(c.verdict(), VehicleClockVerdict::measuring);
  EXPECT_EQ(c.figures().restarts, 1U);
  EXPECT_EQ(c.figures().requests, 1U);
  EXPECT_EQ(vehicle_clock_text(c.figures(), kMavAutopilotPx4),
            "clock measured afresh: the vehicle restarted");
}

TEST(VehicleClockMonitor, ReorderedRequestIsNoRestart) {
  VehicleClockMonitor c;
  c.on_request(10'000'000'000, HostTime{seconds(1)});
  c.on_request(9'900'000'000, HostTime{seconds(1) + milliseconds(1)});
  EXPECT_EQ(c.figures().restarts, 0U);
  EXPECT_EQ(c.figures().requests, 2U);
}

// While measuring, a PX4 gets at most kTimesyncMeasuringAnswers answers: it cannot converge on a
// clock not yet judged, however fast it asks.
TEST(VehicleClockMonitor, MeasuringAnswersAreCapped) {
  VehicleState v(VehicleStateConfig{});
  std::uint64_t answered = 0;
  for (std::int64_t k = 0; k < 1000; ++k) {  // 100 Hz for 10 s: still measuring
    const auto r = v.on_message(ReceivedMessage{1, 1, request(1'000'000'000 + k * 10'000'000)},
                                HostTime{milliseconds(10 * k)}, nullptr);
    if (r.timesync_reply) ++answered;
  }
  EXPECT_EQ(v.clock().verdict(), VehicleClockVerdict::measuring);
  EXPECT_EQ(vehicle_clock_text(v.clock().figures(), kMavAutopilotPx4),
            "clock being measured: a verdict after 20 s of its TIMESYNC requests");
  EXPECT_EQ(answered, kTimesyncMeasuringAnswers);
  EXPECT_EQ(v.snapshot().counters.timesync_withheld, 1000 - kTimesyncMeasuringAnswers);
  // Somebody else's request (a ground station's) is answered as before, and measures nothing.
  EXPECT_TRUE(v.on_message(ReceivedMessage{255, 190, request(5)}, HostTime{seconds(11)}, nullptr)
                  .timesync_reply);
  EXPECT_EQ(v.clock().figures().requests, 1000U);
}

}  // namespace
}  // namespace mocaplink::core
