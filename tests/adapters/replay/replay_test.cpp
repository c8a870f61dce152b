// replay://: pacing (pure, injected), URL options, and the source on real files at speed 0.
#include "mocaplink/sources/replay_source.hpp"

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::sources {
namespace {

using std::chrono::milliseconds;

core::SourceTime at_ms(std::int64_t ms) {
  return core::SourceTime{milliseconds(ms)};
}

TEST(ReplaySchedule, RecordedTimingScaledBySpeed) {
  ReplaySchedule normal(1.0), fast(4.0), instant(0.0);
  // A recording whose clock starts at 1000 ms: the first frame is due at once.
  for (auto [capture, due_ms] : {std::pair{1000, 0}, {1005, 5}, {1020, 20}, {2000, 1000}}) {
    EXPECT_EQ(normal.due(at_ms(capture)), milliseconds(due_ms));
    EXPECT_EQ(fast.due(at_ms(capture)), core::Duration(milliseconds(due_ms)) / 4);
    EXPECT_EQ(instant.due(at_ms(capture)), milliseconds(0));
  }
}

TEST(ReplaySchedule, NeverSchedulesBackwardsAndLoopsContinue) {
  ReplaySchedule schedule(1.0);
  EXPECT_EQ(schedule.due(at_ms(0)), milliseconds(0));
  EXPECT_EQ(schedule.due(at_ms(100)), milliseconds(100));
  EXPECT_EQ(schedule.due(at_ms(50)), milliseconds(100));  // earlier capture: due immediately
  schedule.next_pass();
  EXPECT_EQ(schedule.due(at_ms(0)), milliseconds(100));  // second pass starts where the first ended
  EXPECT_EQ(schedule.due(at_ms(30)), milliseconds(130));
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/replay_test_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

const std::string kRecording =
    "# mocaplink recording 1; source=sim://; rate_hz=100\n"
    "time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz\n"
    "0.000000,7,A,1,1.000000,2.000000,3.000000,1.000000,0.000000,0.000000,0.000000\n"
    "0.000000,7,B,0,,,,,,,\n"
    "0.010000,8,A,1,1.100000,2.000000,3.000000,1.000000,0.000000,0.000000,0.000000\n"
    "0.030000,10,A,1,1.300000,2.000000,3.000000,1.000000,0.000000,0.000000,0.000000\n";

struct Collected {
  std::mutex mutex;
  std::condition_variable cv;
  std::vector<core::MocapFrame> frames;
  std::vector<core::HostTime> received;
  std::vector<std::pair<SourceState, std::string>> states;
  bool ended = false;

  void run(Source& source) {
    source.start(
        [this](core::MocapFrame f, core::HostTime t) {
          const std::lock_guard lock(mutex);
          frames.push_back(std::move(f));
          received.push_back(t);
        },
        [this](SourceState s, const std::string& detail) {
          const std::lock_guard lock(mutex);
          states.emplace_back(s, detail);
          ended = ended || s == SourceState::finished;
          cv.notify_all();
        });
    std::unique_lock lock(mutex);
    cv.wait(lock, [this] { return ended; });
  }
};

std::unique_ptr<ReplaySource> open_ok(const std::string& path, double speed, bool loop = false) {
  auto made = ReplaySource::open(ReplayOptions{path, speed, loop}, "replay://" + path);
  if (auto* error = std::get_if<std::string>(&made)) {
    ADD_FAILURE() << *error;
    return nullptr;
  }
  return std::move(std::get<std::unique_ptr<ReplaySource>>(made));
}

TEST(ReplaySource, DeliversTheRecordedFramesThenFinishes) {
  auto source = open_ok(write_file("ok.csv", kRecording), 0.0);
  ASSERT_TRUE(source);
  Collected got;
  got.run(*source);
  source->stop();
  ASSERT_EQ(got.frames.size(), 3u);
  EXPECT_EQ(got.frames[0].frame_number, 7u);
  EXPECT_EQ(got.frames[0].bodies.size(), 2u);
  EXPECT_FALSE(got.frames[0].bodies[1].tracked);
  EXPECT_EQ(got.frames[1].capture_time, at_ms(10));
  EXPECT_EQ(got.frames[2].frame_number, 10u);  // the gap is preserved
  EXPECT_EQ(got.frames[2].bodies[0].p_world_m, Eigen::Vector3d(1.3, 2.0, 3.0));
  EXPECT_EQ(got.frames[2].frame_rate_hz, 100.0);
  ASSERT_EQ(got.states.size(), 2u);
  EXPECT_EQ(got.states[0].first, SourceState::connected);
  EXPECT_EQ(got.states[1].first, SourceState::finished);
  EXPECT_EQ(source->counters().frames.load(), 3u);
}

TEST(ReplaySource, NeverDeliversAFrameBeforeItsRecordedTime) {
  // 3 frames over 30 ms of recording at speed 0.5: due at 0, 20 and 60 ms after start.
  auto source = open_ok(write_file("timed.csv", kRecording), 0.5);
  ASSERT_TRUE(source);
  const auto before = std::chrono::steady_clock::now().time_since_epoch();
  Collected got;
  got.run(*source);
  ASSERT_EQ(got.received.size(), 3u);
  const core::HostTime start{std::chrono::duration_cast<core::Duration>(before)};
  EXPECT_GE(got.received[1] - start, milliseconds(20));
  EXPECT_GE(got.received[2] - start, milliseconds(60));
}

TEST(ReplaySource, LoopRepeatsTheFile) {
  auto source = open_ok(write_file("loop.csv", kRecording), 0.0, true);
  ASSERT_TRUE(source);
  std::mutex mutex;
  std::condition_variable cv;
  std::vector<std::uint64_t> numbers;
  source->start(
      [&](core::MocapFrame f, core::HostTime) {
        const std::lock_guard lock(mutex);
        numbers.push_back(f.frame_number);
        cv.notify_all();
      },
      nullptr);
  {
    std::unique_lock lock(mutex);
    cv.wait(lock, [&] { return numbers.size() >= 7; });
  }
  source->stop();
  const std::vector<std::uint64_t> first7(numbers.begin(), numbers.begin() + 7);
  EXPECT_EQ(first7, (std::vector<std::uint64_t>{7, 8, 10, 7, 8, 10, 7}));
}

TEST(ReplaySource, MalformedLineMidFileStopsWithFileAndLine) {
  auto source = open_ok(write_file("bad.csv", kRecording + "0.040000,11,A,1,oops,0,0,1,0,0,0\n"
                                                           "0.050000,12,A,0,,,,,,,\n"),
                        0.0);
  ASSERT_TRUE(source);
  Collected got;
  got.run(*source);
  source->stop();
  // Frames 7 and 8; frame 10 was still open (a row of it could follow) when line 7 failed.
  EXPECT_EQ(got.frames.size(), 2u);
  ASSERT_EQ(got.states.back().first, SourceState::finished);
  EXPECT_NE(got.states.back().second.find("bad.csv:7: column x_m: 'oops'"), std::string::npos)
      << got.states.back().second;
  EXPECT_EQ(source->counters().malformed.load(), 1u);
}

TEST(ReplaySource, OpenRejectsMissingAndForeignFiles) {
  const auto error = [](const std::string& path) {
    auto made = ReplaySource::open(ReplayOptions{path, 1.0, false}, "replay://" + path);
    return std::holds_alternative<std::string>(made) ? std::get<std::string>(made) : std::string();
  };
  EXPECT_NE(error("/nonexistent/run.csv").find("cannot open '/nonexistent/run.csv'"),
            std::string::npos);
  EXPECT_NE(error(write_file("foreign.csv", "a,b,c\n1,2,3\n")).find(":1: expected the column line"),
            std::string::npos);
  EXPECT_NE(error(write_file("long.csv", std::string(10000, 'x'))).find(":1: line longer"),
            std::string::npos);
  EXPECT_NE(error(write_file("empty.csv", "")).find("no column line"), std::string::npos);
}

}  // namespace
}  // namespace mocaplink::sources
