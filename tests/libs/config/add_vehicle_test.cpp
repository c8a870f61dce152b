// add_vehicle: a vehicle added to a running configuration (the dashboard's POST /api/vehicles)
// gets the checks of a [[vehicle]] table, against the vehicles already there.
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mocaplink/config/demo.hpp"
#include "mocaplink/config/load.hpp"
#include "test_util.hpp"

namespace mocaplink::config {
namespace {

using testing::ElementsAre;
using testing::HasSubstr;
using testing_util::error_lines;
using testing_util::warning_lines;

constexpr std::string_view kOrigin = "POST /api/vehicles";

std::vector<VehicleKey> quad2() {
  return {{"name", std::string("quad2")},
          {"body", std::string("Quad2")},
          {"link", std::string("udp://127.0.0.1:14560")},
          {"system_id", std::int64_t{2}},
          {"profile", std::string("ardupilot")},
          {"rate_hz", std::int64_t{30}}};
}

TEST(AddVehicle, AppendsAResolvedVehicle) {
  Config base = demo_config();
  base.mocap.body_forward = core::axis::pos_y;  // the [mocap] defaults apply to the new vehicle
  base.mocap.body_up = core::axis::pos_z;
  const auto result = add_vehicle(base, quad2(), kOrigin);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  ASSERT_EQ(result.config->vehicles.size(), 2U);
  EXPECT_EQ(result.config->vehicles[0].name, "demo");
  const Vehicle& v = result.config->vehicles[1];
  EXPECT_EQ(v.name, "quad2");
  EXPECT_EQ(v.body, "Quad2");
  EXPECT_EQ(to_string(v.link), "udp://127.0.0.1:14560");
  EXPECT_EQ(v.system_id, 2);
  EXPECT_EQ(v.component_id, kDefaultComponentId);
  EXPECT_EQ(v.profile, core::Profile::ardupilot);
  EXPECT_EQ(v.rate_hz, 30.0);  // an integer where a number is expected
  EXPECT_EQ(v.body_forward, core::axis::pos_y);
  EXPECT_TRUE(v.enabled);
  EXPECT_TRUE(result.warnings.empty());
}

TEST(AddVehicle, RefusesWhatAFileWouldRefuse) {
  const Config base = demo_config();
  auto errors = [&](std::vector<VehicleKey> keys) {
    return error_lines(add_vehicle(base, keys, kOrigin));
  };
  auto with = [](std::string key, VehicleKey::Value value) {
    auto keys = quad2();
    for (auto& k : keys) {
      if (k.key == key) k.value = value;
    }
    return keys;
  };
  EXPECT_THAT(errors(with("name", std::string("demo"))),
              ElementsAre(HasSubstr("POST /api/vehicles: name: duplicate vehicle name")));
  // Same link and system id as the demo vehicle.
  auto clash = with("link", std::string("udp://127.0.0.1:14550"));
  clash[3].value = std::int64_t{1};
  EXPECT_THAT(errors(clash), ElementsAre(HasSubstr("system_id: system_id 1 is already used on "
                                                   "udp://127.0.0.1:14550 by vehicle \"demo\"")));
  EXPECT_THAT(errors(with("system_id", std::int64_t{0})), ElementsAre(HasSubstr("system_id: ")));
  EXPECT_THAT(errors(with("system_id", std::string("2"))),
              ElementsAre(HasSubstr("system_id: expected an integer, got a string")));
  EXPECT_THAT(errors(with("link", std::string("udp://255.255.255.255:14550"))),
              ElementsAre(HasSubstr("link: ")));
  EXPECT_THAT(errors(with("profile", std::string("px5"))), ElementsAre(HasSubstr("profile: ")));
  EXPECT_THAT(errors(with("rate_hz", 0.0)), ElementsAre(HasSubstr("rate_hz: ")));
  auto unknown = quad2();
  unknown.push_back({"rate", 10.0});
  EXPECT_THAT(errors(unknown),
              ElementsAre(HasSubstr("rate: unknown key; did you mean \"rate_hz\"?")));
  auto twice = quad2();
  twice.push_back({"body", std::string("Other")});
  EXPECT_THAT(errors(twice), ElementsAre(HasSubstr("body: given twice")));
  auto missing = quad2();
  missing.erase(missing.begin() + 1);  // no body
  EXPECT_THAT(errors(missing), ElementsAre(HasSubstr("body")));
}

TEST(AddVehicle, GpsProfilesNeedTheConfiguredOrigin) {
  Config base = demo_config();
  base.origin.reset();
  auto keys = quad2();
  keys[4].value = std::string("ardupilot-gps");
  EXPECT_THAT(error_lines(add_vehicle(base, keys, kOrigin)), ElementsAre(HasSubstr("origin")));
  EXPECT_TRUE(add_vehicle(demo_config(), keys, kOrigin).ok());
}

TEST(AddVehicle, WarnsWhenTheLinkIsShared) {
  auto keys = quad2();
  keys[2].value = std::string("udp://127.0.0.1:14550");
  const auto result = add_vehicle(demo_config(), keys, kOrigin);
  ASSERT_TRUE(result.ok());
  EXPECT_THAT(warning_lines(result), ElementsAre(HasSubstr("is shared with vehicle \"demo\"")));
  // A third vehicle on another link: the second one's warning is not repeated.
  auto third = quad2();
  third[0].value = std::string("quad3");
  third[3].value = std::int64_t{3};
  const auto next = add_vehicle(*result.config, third, kOrigin);
  ASSERT_TRUE(next.ok());
  EXPECT_TRUE(next.warnings.empty()) << testing::PrintToString(warning_lines(next));
}

}  // namespace
}  // namespace mocaplink::config
