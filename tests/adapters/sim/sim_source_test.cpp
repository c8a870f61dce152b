// SimSource: delivers SimWorld's frames with gaps where frames drop, then finishes.
#include "mocaplink/sources/sim_source.hpp"

#include <condition_variable>
#include <mutex>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::sources {
namespace {

TEST(SimSource, DeliversTheWorldsFramesAndFinishes) {
  SimOptions c;
  c.rate_hz = 1000.0;  // 60 frames in ~60 ms
  c.frames = 60;
  c.drop = 0.2;
  SimSource source(c, "sim://?rate_hz=1000&frames=60&drop=0.2");
  std::mutex mutex;
  std::condition_variable done_cv;
  bool done = false;
  std::vector<core::MocapFrame> frames;
  std::vector<SourceState> states;
  source.start(
      [&](core::MocapFrame frame, core::HostTime) {
        const std::lock_guard lock(mutex);
        frames.push_back(std::move(frame));
      },
      [&](SourceState state, const std::string&) {
        const std::lock_guard lock(mutex);
        states.push_back(state);
        if (state == SourceState::finished) done = true;
        done_cv.notify_all();
      });
  {
    std::unique_lock lock(mutex);
    done_cv.wait(lock, [&] { return done; });  // readiness by event, no sleeps
  }
  source.stop();
  ASSERT_EQ(states, (std::vector<SourceState>{SourceState::connected, SourceState::finished}));
  std::vector<std::uint64_t> expected;
  for (std::uint64_t n = 1; n <= 60; ++n) {
    if (!source.world().dropped(n)) expected.push_back(n);
  }
  ASSERT_LT(expected.size(), 60u);  // some frames dropped at 20 %
  ASSERT_EQ(frames.size(), expected.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(frames[k].frame_number, expected[k]);
    EXPECT_EQ(frames[k].bodies[0].p_world_m, source.world().frame(expected[k]).bodies[0].p_world_m);
  }
  EXPECT_EQ(source.counters().frames.load(), expected.size());
}

TEST(SimSource, StopInterruptsTheWaitForTheNextFrameAndIsIdempotent) {
  // Frame 1 comes at once, frame 2 only 1000 s later: stop() returning at all (within ctest's
  // timeout) shows that it wakes the source's wait instead of sleeping until the next frame.
  SimOptions c;
  c.rate_hz = 0.001;
  c.frames = 0;  // endless
  SimSource source(c, "sim://?rate_hz=0.001");
  std::mutex mutex;
  std::condition_variable first_cv;
  std::size_t frames = 0;
  std::vector<SourceState> states;
  source.start(
      [&](core::MocapFrame, core::HostTime) {
        const std::lock_guard lock(mutex);
        ++frames;
        first_cv.notify_all();
      },
      [&](SourceState state, const std::string&) {
        const std::lock_guard lock(mutex);
        states.push_back(state);
      });
  {
    std::unique_lock lock(mutex);
    first_cv.wait(lock, [&] { return frames == 1; });  // the source is now waiting for frame 2
  }
  source.stop();
  source.stop();  // a second stop is harmless and returns at once too
  const std::lock_guard lock(mutex);
  EXPECT_EQ(frames, 1U);
  // Stopped, not finished: no `finished` state for a source that was told to stop.
  EXPECT_EQ(states, (std::vector<SourceState>{SourceState::connected}));
  EXPECT_EQ(source.counters().frames.load(), 1U);
}

}  // namespace
}  // namespace mocaplink::sources
