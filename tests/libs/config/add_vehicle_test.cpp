// add_vehicle / update_vehicle: a vehicle added to or changed in a running configuration (the
// dashboard's POST and PATCH /api/vehicles) gets the checks of a [[vehicle]] table, against the
// vehicles already there.
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mocaplink/config/demo.hpp"
#include "mocaplink/config/load.hpp"
#include "serial_device.hpp"
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
  EXPECT_EQ(result.config->vehicles[0].spec.name, "demo");
  const Vehicle& v = result.config->vehicles[1];
  EXPECT_EQ(v.spec.name, "quad2");
  EXPECT_EQ(v.spec.body, "Quad2");
  EXPECT_EQ(to_string(v.link), "udp://127.0.0.1:14560");
  EXPECT_EQ(v.spec.system_id, 2);
  EXPECT_EQ(v.spec.component_id, 197);  // MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY
  EXPECT_EQ(v.spec.profile, core::Profile::ardupilot);
  EXPECT_EQ(v.spec.rate_hz, 30.0);  // an integer where a number is expected
  EXPECT_EQ(v.spec.body_axes.forward(), core::axis::pos_y);
  EXPECT_TRUE(v.spec.enabled);
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

constexpr std::string_view kPatch = "PATCH /api/vehicles/quad2";

/// The demo plus quad2 (ArduPilot at 30 Hz on its own link).
Config with_quad2() {
  auto added = add_vehicle(demo_config(), quad2(), kOrigin);
  EXPECT_TRUE(added.ok());
  return *added.config;
}

TEST(UpdateVehicle, ChangesTheRateWithTheWarningsAFileGets) {
  const auto result =
      update_vehicle(with_quad2(), "quad2", {{"rate_hz", std::int64_t{60}}}, kPatch);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  ASSERT_EQ(result.config->vehicles.size(), 2U);
  EXPECT_EQ(result.config->vehicles[1].spec.rate_hz, 60.0);
  EXPECT_EQ(result.config->vehicles[0].spec.rate_hz, demo_config().vehicles[0].spec.rate_hz);
  // The same warning a [[vehicle]] table with profile = "ardupilot", rate_hz = 60 gets.
  EXPECT_THAT(warning_lines(result),
              ElementsAre("PATCH /api/vehicles/quad2: rate_hz: ArduPilot's external-navigation "
                          "input is meant for at most 50 Hz"));
  const auto file = parse_config(R"(
[mocap]
source = "sim://"
[[vehicle]]
name = "quad2"
body = "Quad2"
link = "udp://127.0.0.1:14560"
system_id = 2
profile = "ardupilot"
rate_hz = 60
)",
                                 "lab.toml");
  ASSERT_EQ(file.warnings.size(), 1U);
  EXPECT_EQ(file.warnings[0].message, result.warnings[0].message);
  // Within ArduPilot's range: nothing to say.
  EXPECT_TRUE(update_vehicle(with_quad2(), "quad2", {{"rate_hz", 40.0}}, kPatch).warnings.empty());
}

TEST(UpdateVehicle, ARateTooHighForASerialLinkGetsTheFilesBandwidthWarning) {
  // 57600 baud carries 5760 bytes/s; px4's ODOMETRY (full frame up to 245 bytes) at 30 Hz fits,
  // at 100 Hz it does not — the same warning a [[vehicle]] table with that rate gets.
  const auto file = [](const char* rate) {
    return parse_config(std::string(R"(
[mocap]
source = "sim://"
[[vehicle]]
name = "radio"
body = "Body1"
link = ")") + testing_support::kSerialUrlPrefix +
                            R"(?baud=57600"
system_id = 1
profile = "px4"
rate_hz = )" + rate + "\n",
                        "lab.toml");
  };
  const auto slow = file("20");
  ASSERT_TRUE(slow.ok()) << testing::PrintToString(error_lines(slow));
  ASSERT_TRUE(slow.warnings.empty()) << testing::PrintToString(warning_lines(slow));
  const auto fast = file("100");
  ASSERT_EQ(fast.warnings.size(), 1U) << testing::PrintToString(warning_lines(fast));
  const auto patched = update_vehicle(*slow.config, "radio", {{"rate_hz", 100.0}}, kPatch);
  ASSERT_TRUE(patched.ok()) << testing::PrintToString(error_lines(patched));
  ASSERT_EQ(patched.warnings.size(), 1U) << testing::PrintToString(warning_lines(patched));
  EXPECT_EQ(patched.warnings[0].file, kPatch);
  EXPECT_EQ(patched.warnings[0].message, fast.warnings[0].message);
}

TEST(UpdateVehicle, RefusesWhatAFileWouldRefuseWithTheSameMessages) {
  const Config base = with_quad2();
  auto errors = [&](std::vector<VehicleKey> keys) {
    return error_lines(update_vehicle(base, "quad2", keys, kPatch));
  };
  EXPECT_THAT(errors({{"rate_hz", 0.0}}),
              ElementsAre("PATCH /api/vehicles/quad2: rate_hz: must be above 0 and at most 500, "
                          "got 0"));
  EXPECT_THAT(errors({{"rate_hz", 500.5}}), ElementsAre(HasSubstr("got 500.5")));
  EXPECT_THAT(errors({{"rate_hz", std::string("50")}}),
              ElementsAre(HasSubstr("rate_hz: expected a number, got a string")));
  EXPECT_THAT(errors({{"messages", std::vector<std::string>{"odometry", "nope"}}}),
              ElementsAre(HasSubstr("messages: unknown message \"nope\"")));
  EXPECT_THAT(errors({{"messages", std::vector<std::string>{"odometry", "odometry"}}}),
              ElementsAre(HasSubstr("messages: \"odometry\" is listed twice")));
  EXPECT_THAT(errors({{"profile", std::string("px4")}}),
              ElementsAre(HasSubstr("profile: cannot change while the vehicle runs")));
  EXPECT_THAT(errors({{"rate", 10.0}}),
              ElementsAre(HasSubstr("rate: unknown key; did you mean \"rate_hz\"?")));
  EXPECT_THAT(error_lines(update_vehicle(base, "ghost", {{"rate_hz", 10.0}}, kPatch)),
              ElementsAre(HasSubstr("no vehicle named \"ghost\"")));
  // GPS-type messages need the [origin], as for a file.
  Config no_origin = base;
  no_origin.origin.reset();
  no_origin.vehicles.pop_back();  // quad2 is px4-only then
  no_origin = *add_vehicle(no_origin, quad2(), kOrigin).config;
  EXPECT_THAT(
      error_lines(update_vehicle(no_origin, "quad2",
                                 {{"messages", std::vector<std::string>{"hil_gps"}}}, kPatch)),
      ElementsAre(HasSubstr("messages: GPS-type messages (HIL_GPS, GPS_INPUT) need the [origin]")));
}

TEST(UpdateVehicle, MessagesAreTheLiveSetForAnyProfile) {
  const Config base = with_quad2();
  // ardupilot is not custom, and [] is allowed: the Bridge holds the live set, like a pause.
  for (const auto& list : {std::vector<std::string>{}, std::vector<std::string>{"hil_gps"}}) {
    const auto result = update_vehicle(base, "quad2", {{"messages", list}}, kPatch);
    ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
    EXPECT_EQ(result.config->vehicles[1].spec.profile, core::Profile::ardupilot);
    EXPECT_TRUE(result.config->vehicles[1].spec.messages.empty());
  }
}

TEST(UpdateVehicle, LaterChangesAreCheckedAgainstThePatchedState) {
  const auto patched = update_vehicle(with_quad2(), "quad2", {{"rate_hz", 60.0}}, kPatch);
  ASSERT_TRUE(patched.ok());
  // An add keeps the patched rate (the base of every later change is the state now) ...
  auto third = quad2();
  third[0].value = std::string("quad3");
  third[2].value = std::string("udp://127.0.0.1:14570");
  const auto added = add_vehicle(*patched.config, third, kOrigin);
  ASSERT_TRUE(added.ok()) << testing::PrintToString(error_lines(added));
  EXPECT_EQ(added.config->vehicles[1].spec.rate_hz, 60.0);
  EXPECT_TRUE(added.warnings.empty() ||
              added.warnings[0].message.find("quad2") == std::string::npos);
  // ... and an add that clashes with the patched vehicle is refused naming it.
  auto clash = third;
  clash[2].value = std::string("udp://127.0.0.1:14560");
  EXPECT_THAT(error_lines(add_vehicle(*patched.config, clash, kOrigin)),
              ElementsAre(HasSubstr("system_id 2 is already used on udp://127.0.0.1:14560 by "
                                    "vehicle \"quad2\"")));
  // A later PATCH starts from the patched rate.
  const auto again =
      update_vehicle(*patched.config, "quad2", {{"messages", std::vector<std::string>{}}}, kPatch);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again.config->vehicles[1].spec.rate_hz, 60.0);
  EXPECT_TRUE(again.warnings.empty());  // the rate was not given again: no repeated warning
}

}  // namespace
}  // namespace mocaplink::config
