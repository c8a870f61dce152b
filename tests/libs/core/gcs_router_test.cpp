// GcsRouter (issue 38): the routes of frames between ground stations and vehicles, as
// mavlink-router decides them, with injected time.
#include "mocaplink/core/gcs_router.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using testing::ElementsAre;
using testing::IsEmpty;

const HostTime t0{std::chrono::seconds(100)};

RouteInfo from(std::uint8_t sysid, std::uint8_t compid) {
  return RouteInfo{sysid, compid};
}
RouteInfo to(std::uint8_t sysid, std::uint8_t compid, std::uint8_t target_system,
             std::uint8_t target_component) {
  return RouteInfo{sysid, compid, true, target_system, target_component};
}

class GcsRouterTest : public testing::Test {
 protected:
  // Endpoint 0 serves vehicles 1 (slot 0) and 2 (slot 1); endpoint 1 serves only vehicle 1.
  GcsRouterTest() {
    router.attach(0, 0, 1);
    router.attach(0, 1, 2);
    router.attach(1, 0, 1);
  }
  std::vector<GcsRouter::Slot> gcs(GcsRouter::Endpoint e, const RouteInfo& f, HostTime t = t0) {
    std::vector<GcsRouter::Slot> out;
    router.from_gcs(e, f, t, out, notes, "udpin://:1455" + std::to_string(e));
    return out;
  }
  std::vector<GcsRouter::Endpoint> vehicle(GcsRouter::Slot s, const RouteInfo& f) {
    std::vector<GcsRouter::Endpoint> out;
    router.from_vehicle(s, f, out);
    return out;
  }
  GcsRouter router;
  std::vector<std::string> notes;
};

TEST_F(GcsRouterTest, BroadcastFromAGroundStationReachesEveryVehicleOfItsEndpoint) {
  EXPECT_THAT(gcs(0, from(255, 190)), ElementsAre(0, 1));      // a HEARTBEAT
  EXPECT_THAT(gcs(0, to(255, 190, 0, 0)), ElementsAre(0, 1));  // target system 0: everyone
  EXPECT_THAT(gcs(1, from(255, 190)), ElementsAre(0));
}

TEST_F(GcsRouterTest, ATargetedFrameReachesOnlyItsVehicle) {
  EXPECT_THAT(gcs(0, to(255, 190, 2, 1)), ElementsAre(1));  // COMMAND_LONG to vehicle 2
  EXPECT_THAT(gcs(0, to(255, 190, 1, 0)), ElementsAre(0));
  // Vehicle 2 is not behind endpoint 1: nowhere, counted.
  EXPECT_THAT(gcs(1, to(255, 190, 2, 1)), IsEmpty());
  EXPECT_EQ(router.counters(1).no_route, 1u);
  EXPECT_EQ(router.counters(0).no_route, 0u);
  EXPECT_EQ(router.counters(0).frames_from_gcs, 2u);
}

TEST_F(GcsRouterTest, VehicleFramesGoWhereTheirTargetWasHeard) {
  // Broadcast (a HEARTBEAT, PARAM_VALUE): every endpoint that serves the vehicle.
  EXPECT_THAT(vehicle(0, from(1, 1)), ElementsAre(0, 1));
  EXPECT_THAT(vehicle(1, from(2, 1)), ElementsAre(0));
  // Targeted before any ground station spoke: nowhere.
  EXPECT_THAT(vehicle(0, to(1, 1, 255, 190)), IsEmpty());
  (void)gcs(1, from(255, 190));
  // The COMMAND_ACK for that ground station's command: only its endpoint.
  EXPECT_THAT(vehicle(0, to(1, 1, 255, 190)), ElementsAre(1));
  EXPECT_THAT(vehicle(0, to(1, 1, 255, 0)), ElementsAre(1));  // any component of 255
  EXPECT_THAT(vehicle(0, to(1, 1, 255, 191)), IsEmpty());     // a component not heard
  // The answers to mocaplink's own requests (the vehicle's sysid, component 197) stay here.
  EXPECT_THAT(vehicle(0, to(1, 1, 1, 197)), IsEmpty());
  EXPECT_EQ(router.counters(1).frames_to_gcs, 3u);
  EXPECT_EQ(router.counters(0).frames_to_gcs, 2u);  // both vehicles' broadcasts
}

TEST_F(GcsRouterTest, PeersComeAndGoWithTheirTraffic) {
  (void)gcs(0, from(255, 190), t0);
  EXPECT_THAT(notes, ElementsAre("ground station 255/190 on udpin://:14550 connected"));
  EXPECT_EQ(router.connected_peers(0), 1u);
  (void)gcs(0, from(255, 190), t0 + std::chrono::seconds(4));
  router.on_tick(t0 + std::chrono::seconds(8), notes, {"udpin://:14550"});
  EXPECT_EQ(notes.size(), 1u);  // heard 4 s ago: still here
  router.on_tick(t0 + std::chrono::seconds(9), notes, {"udpin://:14550"});
  EXPECT_THAT(notes.back(), "ground station 255/190 on udpin://:14550 gone (silent 5 s)");
  EXPECT_EQ(router.connected_peers(0), 0u);
  // Gone from the count, still known for routing (mavlink-router keeps what it learnt).
  EXPECT_THAT(vehicle(0, to(1, 1, 255, 190)), ElementsAre(0));
  (void)gcs(0, from(255, 190), t0 + std::chrono::seconds(20));
  EXPECT_EQ(notes.back(), "ground station 255/190 on udpin://:14550 connected");
}

TEST_F(GcsRouterTest, PeersAreBoundedWhateverIsSent) {
  for (int id = 1; id <= 200; ++id) (void)gcs(0, from(static_cast<std::uint8_t>(id), 1));
  EXPECT_EQ(router.peers(0).size(), GcsRouter::kMaxPeers);
  EXPECT_EQ(router.counters(0).frames_from_gcs, 200u);
}

TEST_F(GcsRouterTest, DetachedVehiclesGetNothing) {
  router.detach(0);
  EXPECT_THAT(gcs(0, from(255, 190)), ElementsAre(1));
  EXPECT_TRUE(router.unused(1));
  EXPECT_FALSE(router.unused(0));
  EXPECT_THAT(vehicle(0, from(1, 1)), IsEmpty());
  EXPECT_THAT(router.slots_of(0), ElementsAre(1));
}

// A ground station's TIMESYNC answer never reaches a vehicle (PX4 would take it for the answer to
// its own request); its requests pass. The payloads as the wire carries them (common.xml: tc1
// int64, ts1 int64, target_system, target_component; MAVLink 2 drops trailing zero bytes).
TEST_F(GcsRouterTest, AGroundStationsTimesyncAnswerReachesNoVehicle) {
  const auto timesync = [](std::vector<std::uint8_t> payload) {
    static std::vector<std::uint8_t> keep;
    keep = std::move(payload);
    mavlink::FrameView f;
    f.sysid = 255;
    f.compid = 190;
    f.msgid = 111;
    f.len = static_cast<std::uint8_t>(keep.size());
    f.payload = keep;
    return route_info(f);
  };
  // A request: tc1 0, ts1 = 0x0102030405060708, no target.
  const RouteInfo request = timesync({0, 0, 0, 0, 0, 0, 0, 0, 8, 7, 6, 5, 4, 3, 2, 1});
  EXPECT_FALSE(request.timesync_answer);
  EXPECT_THAT(gcs(0, request), ElementsAre(0, 1));
  // An answer to vehicle 1's request: tc1 = 256 (one non-zero byte, the second), ts1, target 1/1.
  const RouteInfo answer = timesync({0, 1, 0, 0, 0, 0, 0, 0, 8, 7, 6, 5, 4, 3, 2, 1, 1, 1});
  EXPECT_TRUE(answer.timesync_answer);
  EXPECT_THAT(gcs(0, answer), IsEmpty());
  // An answer whose ts1 and targets are zero: the wire keeps only tc1's bytes up to the last
  // non-zero one.
  EXPECT_THAT(gcs(0, timesync({5})), IsEmpty());
  EXPECT_EQ(router.counters(0).timesync_answers, 2u);
  EXPECT_EQ(router.counters(0).no_route, 0u);
  // Any other message with the same bytes routes as before.
  mavlink::FrameView other;
  other.msgid = 0;
  const std::vector<std::uint8_t> bytes{5};
  other.payload = bytes;
  EXPECT_FALSE(route_info(other).timesync_answer);
}

}  // namespace
}  // namespace mocaplink::core
