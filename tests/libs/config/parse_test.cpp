// parse_config: good files become the expected typed values; bad files give exactly the expected
// messages at the expected lines and columns (positions counted by hand from the texts below).
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

using testing_util::error_lines;
using testing_util::warning_lines;

constexpr const char* kGoodFile = R"(# every key, most of them away from their defaults
[mocap]
source = "qtm://10.0.0.7:22224"
up = "+y"
north = "angle:-12.5"
body_forward = "+z"
body_up = "+y"

[origin]
latitude_deg = 47.3977419
longitude_deg = 8
altitude_m = 488.0

[[vehicle]]
name = "alpha"
body = "Alpha Body"
link = "tcp://sitl.local:5760"
system_id = 42
component_id = 191
profile = "custom"
messages = ["vision_position_estimate", "vision_speed_estimate", "gps_input"]
rate_hz = 30.5
signing_key = "000102030405060708090a0b0c0d0e0f101112131415161718191A1B1C1D1E1F"
body_forward = "-x"
enabled = false

[[vehicle]]
name = "beta"
body = "Beta"
link = "udp://10.0.0.8:14555"
system_id = 43
profile = "classic"

[tracking]
loss_timeout_ms = 250
reset_after_ms = 1000
position_noise_m = 0.002
attitude_noise_rad = 0.01
accel_noise_mps2 = 20
angular_accel_noise_radps2 = 50.5
gate_sigma = 5
gate_min_m = 0.05
jump_confirm_frames = 3
reset_jump_m = 0.1
reset_jump_rad = 0.2

[http]
listen = "[::1]:0"
token = "0123456789abcdef"
max_connections_per_client = 8
allowed_hosts = ["Lab-PC", "lab-pc.local:9000", "[fe80::1]", "10.0.0.5"]
)";

TEST(ParseConfig, GoodFileGivesTypedValues) {
  const auto result = parse_config(kGoodFile, "good.toml");
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_THAT(warning_lines(result), testing::IsEmpty());
  const Config& c = *result.config;

  // Kept as written: the caller's source validator judges the options (tests/adapters/registry).
  EXPECT_EQ(c.mocap.source.scheme, "qtm");
  EXPECT_EQ(c.mocap.source.text, "qtm://10.0.0.7:22224");
  EXPECT_EQ(c.mocap.up, core::axis::pos_y);
  EXPECT_EQ(c.mocap.north, core::North{core::NorthAngle{-12.5}});
  EXPECT_EQ(c.mocap.body_forward, core::axis::pos_z);
  EXPECT_EQ(c.mocap.body_up, core::axis::pos_y);

  ASSERT_TRUE(c.origin.has_value());
  EXPECT_EQ(c.origin->latitude_deg, 47.3977419);
  EXPECT_EQ(c.origin->longitude_deg, 8.0);  // TOML integer accepted for a number
  EXPECT_EQ(c.origin->altitude_m, 488.0);

  ASSERT_EQ(c.vehicles.size(), 2u);
  const Vehicle& a = c.vehicles[0];
  EXPECT_EQ(a.spec.name, "alpha");
  EXPECT_EQ(a.spec.body, "Alpha Body");
  EXPECT_EQ(a.link.kind, LinkKind::tcp);
  EXPECT_EQ(a.link.address, (HostPort{"sitl.local", 5760}));
  EXPECT_EQ(a.spec.system_id, 42);
  EXPECT_EQ(a.spec.component_id, 191);
  EXPECT_EQ(a.spec.profile, core::Profile::custom);
  EXPECT_THAT(a.spec.messages, testing::ElementsAre(core::MessageKind::vision_position_estimate,
                                                    core::MessageKind::vision_speed_estimate,
                                                    core::MessageKind::gps_input));
  EXPECT_EQ(a.spec.rate_hz, 30.5);
  ASSERT_TRUE(a.spec.signing_key.has_value());
  for (std::size_t i = 0; i < 32; ++i) EXPECT_EQ((*a.spec.signing_key)[i], i) << i;
  EXPECT_EQ(a.spec.body_axes.forward(), core::axis::neg_x);  // the vehicle's own
  EXPECT_EQ(a.spec.body_axes.up(), core::axis::pos_y);       // inherited from [mocap]
  EXPECT_FALSE(a.spec.enabled);

  const Vehicle& b = c.vehicles[1];
  EXPECT_EQ(b.spec.name, "beta");
  EXPECT_EQ(b.spec.profile, core::Profile::classic);
  EXPECT_EQ(b.spec.component_id, 197);  // MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY
  EXPECT_EQ(b.spec.rate_hz, 50.0);
  EXPECT_FALSE(b.spec.signing_key.has_value());
  EXPECT_TRUE(b.spec.messages.empty());
  EXPECT_EQ(b.spec.body_axes.forward(), core::axis::pos_z);
  EXPECT_EQ(b.spec.body_axes.up(), core::axis::pos_y);
  EXPECT_TRUE(b.spec.enabled);

  EXPECT_EQ(c.tracking.loss_timeout_ms, 250.0);
  EXPECT_EQ(c.tracking.reset_after_ms, 1000.0);
  EXPECT_EQ(c.tracking.position_noise_m, 0.002);
  EXPECT_EQ(c.tracking.attitude_noise_rad, 0.01);
  EXPECT_EQ(c.tracking.accel_noise_mps2, 20.0);
  EXPECT_EQ(c.tracking.angular_accel_noise_radps2, 50.5);
  EXPECT_EQ(c.tracking.gate_sigma, 5.0);
  EXPECT_EQ(c.tracking.gate_min_m, 0.05);
  EXPECT_EQ(c.tracking.jump_confirm_frames, 3u);
  EXPECT_EQ(c.tracking.reset_jump_m, 0.1);
  EXPECT_EQ(c.tracking.reset_jump_rad, 0.2);

  EXPECT_EQ(c.http.listen, (HostPort{"::1", 0}));
  EXPECT_EQ(c.http.token, "0123456789abcdef");
  EXPECT_EQ(c.http.max_connections_per_client, 8U);
  EXPECT_EQ(c.http.allowed_hosts,
            (std::vector<HostPort>{
                {"lab-pc", 0}, {"lab-pc.local", 9000}, {"fe80::1", 0}, {"10.0.0.5", 0}}));
}

TEST(ParseConfig, MinimalFileGetsDocumentedDefaults) {
  const auto result = parse_config(R"([mocap]
source = "vicon://192.168.1.3"
[[vehicle]]
name = "quad1"
body = "Quad1"
link = "udp://192.168.1.21:14540"
system_id = 1
profile = "px4"
)",
                                   "min.toml");
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  const Config& c = *result.config;
  EXPECT_EQ(c.mocap.up, core::axis::pos_z);
  EXPECT_EQ(c.mocap.north, core::North{core::axis::pos_x});
  EXPECT_EQ(c.mocap.body_forward, core::axis::pos_x);
  EXPECT_EQ(c.mocap.body_up, core::axis::pos_z);
  EXPECT_FALSE(c.origin.has_value());
  // No [tracking]: every value is the tracker's own default (docs/config.md "[tracking]").
  const core::TrackerConfig defaults;
  EXPECT_EQ(c.tracking.loss_timeout_ms, defaults.loss_timeout_ms);
  EXPECT_EQ(c.tracking.reset_after_ms, defaults.reset_after_ms);
  EXPECT_EQ(c.tracking.position_noise_m, defaults.position_noise_m);
  EXPECT_EQ(c.tracking.attitude_noise_rad, defaults.attitude_noise_rad);
  EXPECT_EQ(c.tracking.accel_noise_mps2, defaults.accel_noise_mps2);
  EXPECT_EQ(c.tracking.angular_accel_noise_radps2, defaults.angular_accel_noise_radps2);
  EXPECT_EQ(c.tracking.gate_sigma, defaults.gate_sigma);
  EXPECT_EQ(c.tracking.gate_min_m, defaults.gate_min_m);
  EXPECT_EQ(c.tracking.jump_confirm_frames, defaults.jump_confirm_frames);
  EXPECT_EQ(c.http.listen, (HostPort{"127.0.0.1", 8080}));
  EXPECT_EQ(c.http.token, "");
  EXPECT_EQ(c.http.max_connections_per_client, 32U);
  EXPECT_TRUE(c.http.allowed_hosts.empty());
  ASSERT_EQ(c.vehicles.size(), 1u);
  EXPECT_EQ(c.vehicles[0].spec.rate_hz, 50.0);
  EXPECT_EQ(c.vehicles[0].spec.component_id, 197);
  EXPECT_TRUE(c.vehicles[0].spec.enabled);
}

TEST(ParseConfig, SameSystemIdOnDifferentLinksIsFine) {
  const auto result = parse_config(R"([mocap]
source = "sim://"
[[vehicle]]
name = "a"
body = "Body1"
link = "udp://127.0.0.1:14540"
system_id = 1
profile = "px4"
[[vehicle]]
name = "b"
body = "Body2"
link = "udp://127.0.0.1:14541"
system_id = 1
profile = "px4"
)",
                                   "t.toml");
  EXPECT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_THAT(warning_lines(result), testing::IsEmpty());
}

struct BadCase {
  const char* name;
  std::string toml;
  std::vector<std::string> errors;
};

// Lines 1-2 of most cases; a vehicle block of lines 3-8 follows where needed.
const std::string kMocap = "[mocap]\nsource = \"sim://\"\n";
const std::string kVehicle =
    "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\nlink = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
    "profile = \"px4\"\n";

std::vector<BadCase> bad_cases() {
  return {
      {"TableTypo",
       kMocap + "[trackng]\ngate_sigma = 3\n",
       {"t.toml:3:2: trackng: unknown key; did you mean \"tracking\"?"}},
      {"KeyInWrongTable",
       kMocap + "rate_hz = 50\n",
       {"t.toml:3:1: mocap.rate_hz: unknown key here; it belongs in [[vehicle]]"}},
      {"TopLevelKey",
       "source = \"sim://\"\n",
       {"t.toml:1:1: source: unknown key here; it belongs in [mocap]",
        "t.toml:1:1: mocap.source: missing required key"}},
      {"UnknownKeyListsAllowed",
       kMocap + "colour = \"red\"\n",
       {"t.toml:3:1: mocap.colour: unknown key (allowed here: source, up, north, body_forward, "
        "body_up)"}},
      {"VehicleKeyTypo",
       kMocap + kVehicle + "rate = 50\n",
       {"t.toml:9:1: vehicle[1].rate: unknown key; did you mean \"rate_hz\"?"}},
      {"VehicleKeyTransposed",
       kMocap + kVehicle + "sytsem_id = 2\n",
       {"t.toml:9:1: vehicle[1].sytsem_id: unknown key; did you mean \"system_id\"?"}},
      {"MissingSource",
       "[mocap]\nup = \"+z\"\n",
       {"t.toml:1:1: mocap.source: missing required key"}},
      {"MissingMocapTable",
       "[http]\nlisten = \"127.0.0.1:9000\"\n",
       {"t.toml:1:1: mocap.source: missing required key"}},
      {"MocapNotATable",
       "mocap = \"vicon://x\"\n",
       {"t.toml:1:1: mocap: expected a table ([mocap]), got a string"}},
      {"VehicleNotAnArray",
       kMocap + "[vehicle]\nname = \"a\"\n",
       {"t.toml:3:2: vehicle: expected an array of tables ([[vehicle]]), got a table"}},
      {"VehicleElementNotATable",
       "vehicle = [1]\n" + kMocap,
       {"t.toml:1:12: vehicle[1]: expected a table, got an integer"}},
      {"SourceNotAString",
       "[mocap]\nsource = 5\n",
       {"t.toml:2:10: mocap.source: expected a string, got an integer"}},
      {"SourceNotAUrl",
       "[mocap]\nsource = \"192.168.1.3\"\n",
       {"t.toml:2:10: mocap.source: \"192.168.1.3\" is not a source URL; expected SCHEME://..."}},
      {"BadAxis",
       kMocap + "up = \"z\"\n",
       {"t.toml:3:6: mocap.up: expected one of +x, -x, +y, -y, +z, -z, got \"z\""}},
      {"NorthAlongUp",
       kMocap + "north = \"-z\"\n",
       {"t.toml:3:9: mocap.north: north (-z) must be at right angles to up (+z)"}},
      {"UpAlongDefaultNorth",
       kMocap + "up = \"+x\"\n",
       {"t.toml:3:6: mocap.up: north (+x) must be at right angles to up (+x)"}},
      {"BodyAxesAlong",
       kMocap + "body_forward = \"+z\"\n",
       {"t.toml:3:16: mocap.body_forward: body_up (+z) must be at right angles to body_forward "
        "(+z)"}},
      {"VehicleBodyAxesAlong",
       kMocap + kVehicle + "body_up = \"-x\"\n",
       {"t.toml:9:11: vehicle[1].body_up: body_up (-x) must be at right angles to body_forward "
        "(+x)"}},
      {"OriginIncomplete",
       kMocap + "[origin]\nlatitude_deg = 40\n",
       {"t.toml:3:1: origin.longitude_deg: missing required key",
        "t.toml:3:1: origin.altitude_m: missing required key"}},
      {"OriginOutOfRange",
       kMocap + "[origin]\nlatitude_deg = 91\nlongitude_deg = -180.5\naltitude_m = 222196\n",
       {"t.toml:4:16: origin.latitude_deg: must be from -90 to 90, got 91",
        "t.toml:5:17: origin.longitude_deg: must be from -180 to 180, got -180.5",
        "t.toml:6:14: origin.altitude_m: must be from -1000 to 10000, got 222196"}},
      {"OriginWrongType",
       kMocap + "[origin]\nlatitude_deg = \"40.1\"\nlongitude_deg = 0\naltitude_m = 0\n",
       {"t.toml:4:16: origin.latitude_deg: expected a number, got a string"}},
      {"VehicleMissingKeys",
       kMocap + "[[vehicle]]\nname = \"q\"\n",
       {"t.toml:3:1: vehicle[1].body: missing required key",
        "t.toml:3:1: vehicle[1].link: missing required key",
        "t.toml:3:1: vehicle[1].system_id: missing required key",
        "t.toml:3:1: vehicle[1].profile: missing required key"}},
      {"SystemIdWrongType",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = \"1\"\n"
                "profile = \"px4\"\n",
       {"t.toml:7:13: vehicle[1].system_id: expected an integer, got a string"}},
      {"SystemIdRange",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 256\n"
                "profile = \"px4\"\n",
       {"t.toml:7:13: vehicle[1].system_id: must be an integer from 1 to 255, got 256"}},
      {"SystemIdFloat",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1.0\n"
                "profile = \"px4\"\n",
       {"t.toml:7:13: vehicle[1].system_id: expected an integer, got a float"}},
      {"ComponentIsAutopilot",
       kMocap + kVehicle + "component_id = 1\n",
       {"t.toml:9:16: vehicle[1].component_id: 1 is the autopilot itself "
        "(MAV_COMP_ID_AUTOPILOT1); use another id, normally 197"}},
      {"ComponentZero",
       kMocap + kVehicle + "component_id = 0\n",
       {"t.toml:9:16: vehicle[1].component_id: must be an integer from 1 to 255, got 0"}},
      {"RateZero",
       kMocap + kVehicle + "rate_hz = 0\n",
       {"t.toml:9:11: vehicle[1].rate_hz: must be above 0 and at most 500, got 0"}},
      {"RateTooHigh",
       kMocap + kVehicle + "rate_hz = 500.5\n",
       {"t.toml:9:11: vehicle[1].rate_hz: must be above 0 and at most 500, got 500.5"}},
      {"RateNaN",
       kMocap + kVehicle + "rate_hz = nan\n",
       {"t.toml:9:11: vehicle[1].rate_hz: must be above 0 and at most 500, got nan"}},
      {"RateString",
       kMocap + kVehicle + "rate_hz = \"50\"\n",
       {"t.toml:9:11: vehicle[1].rate_hz: expected a number, got a string"}},
      {"EnabledNotBool",
       kMocap + kVehicle + "enabled = 1\n",
       {"t.toml:9:11: vehicle[1].enabled: expected true or false, got an integer"}},
      {"BadName",
       kMocap + "[[vehicle]]\nname = \"quad 1\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\nprofile = \"px4\"\n",
       {"t.toml:4:8: vehicle[1].name: must be 1 to 64 letters, digits, '_', '-' or '.', got "
        "\"quad 1\""}},
      {"EmptyBody",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\nprofile = \"px4\"\n",
       {"t.toml:5:8: vehicle[1].body: must be the rigid-body name as the mocap system spells it "
        "(1 to 256 characters, no control characters), got \"\""}},
      {"LinkWithoutPort",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://192.168.1.21\"\nsystem_id = 1\n"
                "profile = \"px4\"\n",
       {"t.toml:6:8: vehicle[1].link: missing port: expected HOST:PORT, got \"192.168.1.21\""}},
      {"ProfileTypo",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"ardupliot\"\n",
       {"t.toml:8:11: vehicle[1].profile: unknown profile \"ardupliot\"; did you mean "
        "\"ardupilot\"? (one of: px4, ardupilot, px4-gps, ardupilot-gps, classic, custom, auto)"}},
      {"MessagesWithoutCustom",
       kMocap + kVehicle + "messages = [\"odometry\"]\n",
       {"t.toml:9:12: vehicle[1].messages: messages is only allowed with profile = \"custom\"; "
        "profile \"px4\" sends a fixed set"}},
      {"CustomWithoutMessages",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"custom\"\n",
       {"t.toml:8:11: vehicle[1].messages: profile \"custom\" needs a messages list, e.g. "
        "messages = [\"odometry\"]"}},
      {"CustomWithEmptyMessages",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"custom\"\nmessages = []\n",
       {"t.toml:9:12: vehicle[1].messages: profile \"custom\" needs at least one message"}},
      {"MessagesBadEntries",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"custom\"\nmessages = [\"odometry\", 3]\n",
       {"t.toml:9:25: vehicle[1].messages[2]: expected a string, got an integer"}},
      {"MessagesTypoAndTwice",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"custom\"\n"
                "messages = [\"odometry\", \"odometry\"]\n"
                "[[vehicle]]\nname = \"r\"\nbody = \"R\"\n"
                "link = \"udp://127.0.0.1:14541\"\nsystem_id = 1\n"
                "profile = \"custom\"\nmessages = [\"hil_gsp\"]\n",
       {"t.toml:9:12: vehicle[1].messages: \"odometry\" is listed twice",
        "t.toml:16:12: vehicle[2].messages: unknown message \"hil_gsp\"; did you mean "
        "\"hil_gps\"? (one of: odometry, vision_position_estimate, vision_speed_estimate, "
        "att_pos_mocap, hil_gps, gps_input, local_position_ned)"}},
      {"GpsProfileNeedsOrigin",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"px4-gps\"\n",
       {"t.toml:8:11: vehicle[1].profile: GPS-type messages (HIL_GPS, GPS_INPUT) need the "
        "[origin] table (latitude_deg, longitude_deg, altitude_m)"}},
      {"GpsMessageNeedsOrigin",
       kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
                "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\n"
                "profile = \"custom\"\nmessages = [\"gps_input\"]\n",
       {"t.toml:9:12: vehicle[1].messages: GPS-type messages (HIL_GPS, GPS_INPUT) need the "
        "[origin] table (latitude_deg, longitude_deg, altitude_m)"}},
      {"SigningKeyShort",
       kMocap + kVehicle + "signing_key = \"abc\"\n",
       {"t.toml:9:15: vehicle[1].signing_key: must be 64 hexadecimal characters (a 32-byte "
        "secret) or \"\" for unsigned, got 3 characters"}},
      {"SigningKeyNotHex",
       kMocap + kVehicle + "signing_key = \"" + std::string(63, '0') + "g\"\n",
       {"t.toml:9:15: vehicle[1].signing_key: must be 64 hexadecimal characters (a 32-byte "
        "secret) or \"\" for unsigned, got 64 characters including non-hex ones"}},
      {"DuplicateName",
       kMocap + kVehicle +
           "[[vehicle]]\nname = \"q\"\nbody = \"Q2\"\n"
           "link = \"udp://127.0.0.1:14541\"\nsystem_id = 2\nprofile = \"px4\"\n",
       {"t.toml:10:8: vehicle[2].name: duplicate vehicle name \"q\" (first defined at "
        "t.toml:4:8)"}},
      {"DuplicateSystemIdOnLink",
       kMocap + kVehicle +
           "[[vehicle]]\nname = \"r\"\nbody = \"R\"\n"
           "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\nprofile = \"ardupilot\"\n",
       {"t.toml:13:13: vehicle[2].system_id: system_id 1 is already used on "
        "udp://127.0.0.1:14540 by vehicle \"q\" (t.toml:7:13)"}},
      {"PublicDashboardNeedsToken",
       kMocap + "[http]\nlisten = \"0.0.0.0:8080\"\n",
       {"t.toml:4:10: http.listen: 0.0.0.0:8080 is reachable from the network, so [http] token "
        "is required (16 or more characters); every mutating request must carry it"}},
      {"ShortToken",
       kMocap + "[http]\ntoken = \"secret\"\n",
       {"t.toml:4:9: http.token: must be empty or at least 16 characters, got 6"}},
      {"ConnectionsPerClientRange",
       kMocap + "[http]\nmax_connections_per_client = 0\n",
       {"t.toml:4:30: http.max_connections_per_client: must be an integer from 1 to 256, got 0"}},
      {"AllowedHostNotAName",
       kMocap + "[http]\nallowed_hosts = [\"lab-pc\", \"http://lab-pc:8080/\"]\n",
       {"t.toml:4:17: http.allowed_hosts: expected a host name, not a URL: write \"lab-pc:8080\" "
        "for \"http://lab-pc:8080/\""}},
      {"AllowedHostWildcard",
       kMocap + "[http]\nallowed_hosts = [\"*.local\"]\n",
       {"t.toml:4:17: http.allowed_hosts: \"*.local\" is not a valid host name or address "
        "(expected a host name or address as the browser's address bar gives it, optionally with "
        ":PORT, e.g. \"lab-pc\" or \"lab-pc.local:8080\")"}},
      {"AllowedHostsNotAList",
       kMocap + "[http]\nallowed_hosts = \"lab-pc\"\n",
       {"t.toml:4:17: http.allowed_hosts: expected an array of strings, got a string"}},
      {"ListenWithoutPort",
       kMocap + "[http]\nlisten = \"localhost\"\n",
       {"t.toml:4:10: http.listen: missing port: expected HOST:PORT, got \"localhost\""}},
      {"TrackingRanges",
       kMocap + "[tracking]\ngate_sigma = 0\njump_confirm_frames = 0\ngate_min_m = -1\n"
                "attitude_noise_rad = 4\n",
       {"t.toml:4:14: tracking.gate_sigma: must be above 0 and at most 100, got 0",
        "t.toml:5:23: tracking.jump_confirm_frames: must be an integer from 1 to 1000, got 0",
        "t.toml:6:14: tracking.gate_min_m: must be from 0 to 100, got -1",
        "t.toml:7:22: tracking.attitude_noise_rad: must be above 0 and at most "
        "3.141592653589793, got 4"}},
      {"TrackingResetBeforeLoss",
       kMocap + "[tracking]\nloss_timeout_ms = 500\nreset_after_ms = 100\n",
       {"t.toml:5:18: tracking.reset_after_ms: must be >= loss_timeout_ms (loss_timeout_ms is 500, "
        "reset_after_ms is 100; keys not set take the tracker's defaults)"}},
      {"TrackingUnknownKey",
       kMocap + "[tracking]\nloss_timeout = 300\n",
       {"t.toml:4:1: tracking.loss_timeout: unknown key; did you mean \"loss_timeout_ms\"?"}},
      {"DateIsNotANumber",
       kMocap + "[origin]\nlatitude_deg = 1979-05-27\nlongitude_deg = 0\n"
                "altitude_m = 0\n",
       {"t.toml:4:16: origin.latitude_deg: expected a number, got a date"}},
  };
}

class BadFile : public testing::TestWithParam<BadCase> {};

TEST_P(BadFile, GivesExactlyTheExpectedErrors) {
  const auto result = parse_config(GetParam().toml, "t.toml");
  EXPECT_FALSE(result.ok());
  EXPECT_FALSE(result.config.has_value());
  EXPECT_EQ(error_lines(result), GetParam().errors);
}

INSTANTIATE_TEST_SUITE_P(Table, BadFile, testing::ValuesIn(bad_cases()),
                         [](const testing::TestParamInfo<BadCase>& param_info) {
                           return std::string(param_info.param.name);
                         });

TEST(ParseConfig, SyntaxErrorIsTheOnlyErrorAndUsesTheParserPosition) {
  const auto result = parse_config("[mocap]\nsource = \"sim://\nup = \"+z\"\n", "s.toml");
  ASSERT_EQ(result.errors.size(), 1u);
  const auto& e = result.errors[0];
  EXPECT_EQ(e.file, "s.toml");
  EXPECT_EQ(e.line, 2u);
  EXPECT_EQ(e.key, "");
  EXPECT_THAT(e.message, testing::StartsWith("TOML syntax error: "));
  EXPECT_THAT(result.warnings, testing::IsEmpty());
}

TEST(ParseConfig, DuplicateKeyIsASyntaxError) {
  const auto result = parse_config("[mocap]\nsource = \"sim://\"\nsource = \"sim://\"\n", "d.toml");
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0].line, 3u);
  EXPECT_THAT(result.errors[0].message, testing::HasSubstr("redefine"));
}

TEST(ParseConfig, ReportsEveryErrorAtOnceInFileOrder) {
  const std::string text = R"([mocap]
source = "vicon://192.168.1.3"
north = "+z"
rate_hz = 50

[[vehicle]]
name = "quad1"
body = "Quad1"
link = "udp://192.168.1.21:14540"
system_id = 0
profile = "px5"
rate = 50

[[vehicle]]
name = "quad1"
body = "Quad2"
link = "udp://192.168.1.22:14540"
system_id = 2
profile = "px4"
messages = ["odometry"]

[http]
listen = "0.0.0.0:8080"
)";
  const auto result = parse_config(text, "lab.toml");
  EXPECT_EQ(
      error_lines(result),
      (std::vector<std::string>{
          "lab.toml:3:9: mocap.north: north (+z) must be at right angles to up (+z)",
          "lab.toml:4:1: mocap.rate_hz: unknown key here; it belongs in [[vehicle]]",
          "lab.toml:10:13: vehicle[1].system_id: must be an integer from 1 to 255, got 0",
          "lab.toml:11:11: vehicle[1].profile: unknown profile \"px5\"; did you mean \"px4\"? (one "
          "of: px4, ardupilot, px4-gps, ardupilot-gps, classic, custom, auto)",
          "lab.toml:12:1: vehicle[1].rate: unknown key; did you mean \"rate_hz\"?",
          "lab.toml:15:8: vehicle[2].name: duplicate vehicle name \"quad1\" (first defined at "
          "lab.toml:7:8)",
          "lab.toml:20:12: vehicle[2].messages: messages is only allowed with profile = "
          "\"custom\"; profile \"px4\" sends a fixed set",
          "lab.toml:23:10: http.listen: 0.0.0.0:8080 is reachable from the network, so [http] "
          "token is required (16 or more characters); every mutating request must carry it",
      }));
}

TEST(ParseConfig, WarningsDoNotFail) {
  const auto result = parse_config(kMocap + kVehicle +
                                       "[[vehicle]]\nname = \"r\"\nbody = \"R\"\n"
                                       "link = \"udp://127.0.0.1:14540\"\nsystem_id = 255\n"
                                       "profile = \"ardupilot\"\nrate_hz = 100\n",
                                   "w.toml");
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_EQ(warning_lines(result),
            (std::vector<std::string>{
                "w.toml:12:8: vehicle[2].link: link udp://127.0.0.1:14540 is shared with vehicle "
                "\"q\" (w.toml:6:8): pose messages have no target system, so every vehicle on it "
                "fuses every pose unless a router filters by system id",
                "w.toml:13:13: vehicle[2].system_id: 255 is the usual ground-station system id; a "
                "vehicle using it can mask the GCS (protocols/autopilots.md §11.13)",
                "w.toml:15:11: vehicle[2].rate_hz: ArduPilot's external-navigation input is meant "
                "for at most 50 Hz",
            }));
}

TEST(ParseConfig, SerialLinkTooSlowForTheProfileIsAWarning) {
  const auto vehicle = [](const char* baud) {
    return kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\nlink = \"" +
           testing_support::kSerialUrlPrefix + "?baud=" + baud +
           "\"\nsystem_id = 1\nprofile = \"px4\"\n";
  };
  const auto slow = parse_config(vehicle("57600"), "s.toml");
  ASSERT_TRUE(slow.ok()) << testing::PrintToString(error_lines(slow));
  // MAVLink 2 frames are 12 bytes + payload (common.xml lengths with extensions): ODOMETRY 233 at
  // 50 Hz = 50 × 245; HEARTBEAT 9, TIMESYNC 18 (request and reply) and SET_GPS_GLOBAL_ORIGIN 21 at
  // 1 Hz = 4 × 12 + 66; from the vehicle, ATTITUDE and LOCAL_POSITION_NED (28 each) at 5 Hz =
  // 5 × (2 × 12 + 56), and ESTIMATOR_STATUS (42) at 1 Hz = 54. 57600 baud at 10 bits a byte
  // carries 5760 bytes/s.
  EXPECT_EQ(warning_lines(slow),
            (std::vector<std::string>{
                "s.toml:6:8: vehicle[1].link: profile px4 at 50 Hz needs up to 12968 bytes/s (with "
                "the vehicle's ATTITUDE and LOCAL_POSITION_NED at 5 Hz, its HIGHRES_IMU at 2 Hz "
                "and its estimator status at 1 Hz) but 57600 baud carries 5760: frames will be "
                "dropped; lower rate_hz or raise the baud rate"}));
  const auto fast = parse_config(vehicle("921600"), "f.toml");
  ASSERT_TRUE(fast.ok());
  EXPECT_THAT(fast.warnings, testing::IsEmpty());
}

TEST(ParseConfig, PlainUdpToAPx4IsAWarningThatNamesTheFormToUse) {
  const auto vehicle = [](const std::string& link, const char* profile) {
    return kMocap + "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\nlink = \"" + link +
           "\"\nsystem_id = 1\nprofile = \"" + profile + "\"\n";
  };
  const std::string deaf =
      "answers only the first address that spoke to its UDP port since it booted, and a plain "
      "udp:// link sends from a new port in every process: after `vehicle setup` or a restart of "
      "`run` the next process would hear nothing until the vehicle reboots; ";
  // PX4 SITL's onboard link: listen where it sends.
  EXPECT_EQ(warning_lines(parse_config(vehicle("udp://127.0.0.1:14580", "px4"), "p.toml")),
            (std::vector<std::string>{"p.toml:6:8: vehicle[1].link: a PX4 " + deaf +
                                      "use udpin://127.0.0.1:14540 (PX4 SITL's onboard link sends "
                                      "there from boot)"}));
  EXPECT_THAT(warning_lines(parse_config(vehicle("udp://127.0.0.1:14583", "px4"), "p.toml")),
              testing::ElementsAre(testing::HasSubstr("use udpin://127.0.0.1:14543 ")));
  // A PX4 on another machine: the same local port number; on this one, another.
  EXPECT_EQ(warning_lines(parse_config(vehicle("udp://192.168.1.30:14540", "auto"), "a.toml")),
            (std::vector<std::string>{
                "a.toml:6:8: vehicle[1].link: profile auto may find a PX4, which " + deaf +
                "send from a fixed local port, as in udp://192.168.1.30:14540?bind=:14540, so "
                "that every mocaplink process is the same peer"}));
  EXPECT_THAT(warning_lines(parse_config(vehicle("udp://127.0.0.1:18570", "px4"), "p.toml")),
              testing::ElementsAre(testing::HasSubstr("as in udp://127.0.0.1:18570?bind=:19570,")));
  // On this machine only PX4 SITL's ports are a PX4's: another loopback port is a listener (the
  // demo's and QGroundControl's 14550, MAVSDK's 14540).
  for (const char* link : {"udp://127.0.0.1:14550", "udp://127.0.0.1:14540"}) {
    EXPECT_THAT(parse_config(vehicle(link, "px4"), "o.toml").warnings, testing::IsEmpty()) << link;
  }
  // The forms that stay heard, and autopilots that answer whoever speaks: no warning.
  for (const char* link : {"udp://192.168.1.30:14540?bind=:14540", "udpin://127.0.0.1:14540",
                           "tcp://127.0.0.1:5760", "tcpin://:5760"}) {
    EXPECT_THAT(parse_config(vehicle(link, "px4"), "o.toml").warnings, testing::IsEmpty()) << link;
  }
  EXPECT_THAT(parse_config(vehicle("udp://127.0.0.1:14550", "ardupilot"), "o.toml").warnings,
              testing::IsEmpty());
}

TEST(ParseConfig, TwoLinksOwningOnePortIsAnError) {
  const auto result = parse_config(kMocap +
                                       "[[vehicle]]\nname = \"a\"\nbody = \"A\"\n"
                                       "link = \"udpin://:14540\"\nsystem_id = 1\n"
                                       "profile = \"px4\"\n"
                                       "[[vehicle]]\nname = \"b\"\nbody = \"B\"\n"
                                       "link = \"udp://10.0.0.9:14540?bind=127.0.0.1:14540\"\n"
                                       "system_id = 2\nprofile = \"px4\"\n",
                                   "two.toml");
  EXPECT_EQ(error_lines(result),
            (std::vector<std::string>{
                "two.toml:12:8: vehicle[2].link: link udp://10.0.0.9:14540?bind=127.0.0.1:14540 "
                "needs the local port 14540 that vehicle \"a\"'s link udpin://:14540 already owns "
                "(two.toml:6:8); give each vehicle its own port"}));
}

TEST(ParseConfig, GroundStationEndpoints) {
  const auto vehicle = [](const char* name, int id, const char* link, const char* gcs) {
    return std::string("[[vehicle]]\nname = \"") + name + "\"\nbody = \"B\"\nlink = \"" + link +
           "\"\nsystem_id = " + std::to_string(id) + "\nprofile = \"ardupilot\"\ngcs = " + gcs +
           "\n";
  };
  // Several per vehicle; one URL on two vehicles is one shared endpoint.
  const auto shared =
      parse_config(kMocap +
                       vehicle("a", 1, (testing_support::kSerialUrlPrefix + "?baud=921600").c_str(),
                               "[\"udpin://:14550\", \"tcpin://127.0.0.1:5770\"]") +
                       vehicle("b", 2, "udp://10.0.0.2:14550", "[\"udpin://0.0.0.0:14550\"]"),
                   "g.toml");
  EXPECT_THAT(error_lines(shared), testing::ElementsAre(testing::HasSubstr(
                                       "vehicle[2].gcs: ground-station endpoint "
                                       "udpin://0.0.0.0:14550 needs the local port of vehicle "
                                       "\"a\"'s ground-station endpoint udpin://:14550")));
  const auto same =
      parse_config(kMocap + vehicle("a", 1, "udp://10.0.0.1:14550", "[\"udpin://:14550\"]") +
                       vehicle("b", 2, "udp://10.0.0.2:14550", "[\"udpin://:14550\"]"),
                   "g.toml");
  ASSERT_TRUE(same.ok()) << testing::PrintToString(error_lines(same));
  ASSERT_EQ(same.config->vehicles[0].gcs.size(), 1u);
  EXPECT_EQ(same.config->vehicles[0].gcs[0], same.config->vehicles[1].gcs[0]);
  EXPECT_EQ(to_string(same.config->vehicles[0].gcs[0]), "udpin://:14550");
  // Errors name the entry (the accepted forms that follow are the platform's).
  EXPECT_EQ(
      error_lines(parse_config(
          kMocap + vehicle("a", 1, "udp://10.0.0.1:14550", "[\"udpin://:14550\", \"udpn://:1\"]"),
          "e.toml")),
      (std::vector<std::string>{
          "e.toml:9:7: vehicle[1].gcs: entry 2 (\"udpn://:1\"): unknown link scheme \"udpn\"; did "
          "you mean \"udp\"? (expected " +
          testing_support::kLinkForms + ")"}));
  EXPECT_THAT(
      error_lines(parse_config(kMocap + vehicle("a", 1, "udp://10.0.0.1:14550",
                                                "[\"udpin://:14550\", \"udpin://:14550\"]"),
                               "e.toml")),
      testing::ElementsAre(testing::HasSubstr("entry 2 (\"udpin://:14550\"): listed twice")));
  // Never a vehicle's link, nor its local port.
  EXPECT_THAT(
      error_lines(parse_config(
          kMocap + vehicle("a", 1, "udpin://:14550", "[\"udpin://127.0.0.1:14550\"]"), "e.toml")),
      testing::ElementsAre(testing::HasSubstr(
          "ground-station endpoint udpin://127.0.0.1:14550 is vehicle \"a\"'s link "
          "udpin://:14550 (e.toml:6:8) or needs its local port")));
  EXPECT_THAT(
      error_lines(parse_config(kMocap + vehicle("a", 1, "udp://10.0.0.1:14550", "[3]"), "e.toml")),
      testing::ElementsAre(
          testing::HasSubstr("vehicle[1].gcs[1]: expected a string, got an integer")));
}

TEST(ParseConfig, NoVehiclesIsAWarning) {
  const auto result = parse_config(kMocap, "n.toml");
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(warning_lines(result),
            (std::vector<std::string>{
                "n.toml:1:1: vehicle: no [[vehicle]] tables: nothing will be sent"}));
}

TEST(ParseConfig, TheSourceValidatorJudgesTheSourceAtItsKey) {
  const SourceValidator validator = [](std::string_view url, const SourceContext& context) {
    SourceCheck check;
    if (url.starts_with("bad://")) check.error = "no such source";
    if (!context.up_written) check.warnings.push_back("up is not written");
    return check;
  };
  const auto bad =
      parse_config("[mocap]\nsource = \"bad://10.0.0.5\"\n" + kVehicle, "m.toml", validator);
  EXPECT_THAT(error_lines(bad), testing::ElementsAre("m.toml:2:10: mocap.source: no such source"));
  const auto warned =
      parse_config("[mocap]\nsource = \"good://10.0.0.5\"\n" + kVehicle, "m.toml", validator);
  ASSERT_TRUE(warned.ok());
  EXPECT_THAT(warning_lines(warned),
              testing::ElementsAre("m.toml:2:10: mocap.source: up is not written"));
  const auto quiet =
      parse_config("[mocap]\nsource = \"good://h\"\nup = \"+z\"\n" + kVehicle, "m.toml", validator);
  EXPECT_THAT(warning_lines(quiet), testing::IsEmpty());
  CommandLineOverrides o;
  o.source = "bad://x";
  EXPECT_THAT(error_lines(apply_overrides(demo_config(), o, "built-in demo", validator)),
              testing::ElementsAre("--source: no such source"));
}

TEST(ParseConfig, NeverEchoesTheSigningKey) {
  const std::string secret = "s3cr3t-s3cr3t-s3cr3t";
  const auto result =
      parse_config(kMocap + kVehicle + "signing_key = \"" + secret + "\"\n", "k.toml");
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_THAT(result.errors[0].message, testing::Not(testing::HasSubstr(secret)));
}

TEST(ConfigError, Formatting) {
  EXPECT_EQ(to_string(ConfigError{"a.toml", 3, 7, "vehicle[1].rate_hz", "bad"}),
            "a.toml:3:7: vehicle[1].rate_hz: bad");
  EXPECT_EQ(to_string(ConfigError{"a.toml", 3, 7, "", "syntax"}), "a.toml:3:7: syntax");
  EXPECT_EQ(to_string(ConfigError{"--vehicle 2", 0, 0, "rate_hz", "bad"}),
            "--vehicle 2: rate_hz: bad");
}

}  // namespace
}  // namespace mocaplink::config
