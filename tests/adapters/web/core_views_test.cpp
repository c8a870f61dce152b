// core snapshots → dashboard views: a real core::Station fed two frames.
#include <gtest/gtest.h>

#include "mocaplink/web/core_views.hpp"

namespace mocaplink::web {
namespace {

using namespace std::chrono_literals;

TEST(CoreViews, StationFiguresAndBodiesCarryOver) {
  core::Station station;
  core::MocapFrame frame;
  frame.frame_number = 10;
  frame.bodies = {core::BodySample{"Quad1", true, Eigen::Vector3d(1.0, -2.0, 0.5),
                                   Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5)},
                  core::BodySample{"Wand", false, {}, {}}};
  station.on_frame(frame, core::host_time_from_ns(0));
  frame.frame_number = 12;  // one dropped
  frame.capture_time += 10ms;
  frame.bodies[0].tracked = false;
  station.on_frame(frame, core::host_time_from_ns(10'000'000));
  const core::StationSnapshot snapshot = station.snapshot(core::host_time_from_ns(10'000'000));

  core::BodyEstimate estimate;
  estimate.state = core::TrackingState::tracking;
  estimate.counters.rejected_outliers = 4;
  estimate.counters.invalid_input[0] = 2;
  estimate.counters.resets = 1;
  const StationView view = make_station_view(
      "sim://", snapshot, [&](std::string_view name) -> const core::BodyEstimate* {
        return name == "Quad1" ? &estimate : nullptr;
      });

  EXPECT_EQ(view.source, "sim://");
  EXPECT_TRUE(view.connected);
  EXPECT_EQ(view.frames, 2U);
  EXPECT_EQ(view.dropped, 1U);
  ASSERT_EQ(view.bodies.size(), 2U);
  const BodyView& quad = view.bodies[0];
  EXPECT_EQ(quad.name, "Quad1");
  EXPECT_FALSE(quad.tracked);                            // not in the latest frame...
  EXPECT_EQ(quad.state, core::TrackingState::tracking);  // ...but the Tracker has not lost it
  ASSERT_TRUE(quad.p_m.has_value());
  EXPECT_EQ(*quad.p_m, (std::array<double, 3>{1.0, -2.0, 0.5}));
  ASSERT_TRUE(quad.q_wxyz.has_value());
  EXPECT_EQ(*quad.q_wxyz, (std::array<double, 4>{0.5, 0.5, -0.5, 0.5}));
  EXPECT_EQ(quad.frames_tracked, 1U);
  EXPECT_EQ(quad.rejected, 6U);  // 4 outliers + 2 invalid
  EXPECT_EQ(quad.resets, 1U);
  const BodyView& wand = view.bodies[1];
  EXPECT_EQ(wand.state, core::TrackingState::unseen);  // no Tracker, never tracked
  EXPECT_FALSE(wand.p_m.has_value());
  EXPECT_FALSE(wand.q_wxyz.has_value());
}

TEST(CoreViews, AMirroredBodyIsShownAsSuch) {
  core::StationBody body;
  body.name = "B";
  EXPECT_FALSE(make_body_view(body, nullptr).mirrored);
  body.mirrored = true;
  EXPECT_TRUE(make_body_view(body, nullptr).mirrored);
}

TEST(CoreViews, WithoutATrackerAOnceTrackedBodyIsLost) {
  core::StationBody body;
  body.name = "B";
  body.ever_tracked = true;
  EXPECT_EQ(make_body_view(body, nullptr).state, core::TrackingState::lost);
  body.tracked = true;
  EXPECT_EQ(make_body_view(body, nullptr).state, core::TrackingState::tracking);
}

}  // namespace
}  // namespace mocaplink::web
