// Bridge::published_bodies ([ros2], issue 46): which bodies, when, and with which axes.
#include <chrono>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mocaplink/core/bridge.hpp"

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

VehicleSpec quad() {
  VehicleSpec v;
  v.name = "quad";
  v.body = "Quad";
  v.profile = Profile::px4;
  v.system_id = 1;
  v.body_axes = *BodyAxisMapping::parse("+y", "+z");  // this vehicle's own body axes
  return v;
}

/// Frame n at 100 Hz: Quad, Crate and (from frame 50 on) Late; Crate occluded in frames 20..59.
MocapFrame frame_at(std::uint64_t n) {
  MocapFrame f;
  f.frame_number = n;
  f.capture_time = SourceTime{milliseconds(10 * static_cast<std::int64_t>(n))};
  for (const char* name : {"Quad", "Crate", "Late"}) {
    if (std::string(name) == "Late" && n < 50) continue;
    BodySample s;
    s.name = name;
    s.tracked = !(std::string(name) == "Crate" && n >= 20 && n < 60);
    s.p_world_m = {1.0, 2.0, 3.0};
    f.bodies.push_back(s);
  }
  return f;
}

std::vector<std::string> published_after(Bridge& bridge, std::uint64_t n) {
  BridgeOutput out;
  const MocapFrame f = frame_at(n);
  bridge.on_frame(f, HostTime{seconds(100) + milliseconds(10 * static_cast<std::int64_t>(n) + 3)},
                  out);
  std::vector<PublishedBody> bodies;
  bridge.published_bodies(bodies);
  std::vector<std::string> names;
  for (const auto& b : bodies) names.emplace_back(b.name);
  return names;
}

Bridge make(const BridgeConfig& c) {
  auto made = Bridge::make(c, HostTime{seconds(100)});
  return std::get<Bridge>(std::move(made));
}

TEST(BridgePublished, EveryBodyFromItsFirstFrameAndOnlyWhenFresh) {
  BridgeConfig c;
  c.vehicles.push_back(quad());
  c.timesync_requests = false;
  c.published.enabled = true;
  Bridge bridge = make(c);
  using testing::ElementsAre;
  EXPECT_THAT(published_after(bridge, 1), ElementsAre("Quad", "Crate"));
  for (std::uint64_t n = 2; n < 30; ++n) (void)published_after(bridge, n);
  EXPECT_THAT(published_after(bridge, 30), ElementsAre("Quad"));  // Crate occluded: not sent
  for (std::uint64_t n = 31; n < 50; ++n) (void)published_after(bridge, n);
  EXPECT_THAT(published_after(bridge, 50), ElementsAre("Quad", "Late"));
  for (std::uint64_t n = 51; n < 70; ++n) (void)published_after(bridge, n);
  EXPECT_THAT(published_after(bridge, 70), ElementsAre("Quad", "Crate", "Late"));
  // The vehicle's body keeps its vehicle's axes; the others take the published ones.
  std::vector<PublishedBody> bodies;
  bridge.published_bodies(bodies);
  ASSERT_EQ(bodies.size(), 3u);
  EXPECT_EQ(bodies[0].axes->forward(), axis::pos_y);
  EXPECT_EQ(bodies[1].axes->forward(), axis::pos_x);
  // Removing the vehicle leaves its body published.
  ASSERT_TRUE(bridge.remove_vehicle(0));
  EXPECT_THAT(published_after(bridge, 71), ElementsAre("Quad", "Crate", "Late"));
}

TEST(BridgePublished, OnlyTheListedBodies) {
  BridgeConfig c;
  c.vehicles.push_back(quad());
  c.timesync_requests = false;
  c.published.enabled = true;
  c.published.all = false;
  c.published.names = {"Late", "Nowhere"};
  Bridge bridge = make(c);
  EXPECT_THAT(published_after(bridge, 1), testing::IsEmpty());  // Quad is a vehicle's, not listed
  for (std::uint64_t n = 2; n < 60; ++n) (void)published_after(bridge, n);
  EXPECT_THAT(published_after(bridge, 60), testing::ElementsAre("Late"));
}

TEST(BridgePublished, NothingWithoutPublishing) {
  BridgeConfig c;
  c.vehicles.push_back(quad());
  c.timesync_requests = false;
  Bridge bridge = make(c);
  EXPECT_THAT(published_after(bridge, 1), testing::IsEmpty());
}

}  // namespace
}  // namespace mocaplink::core
