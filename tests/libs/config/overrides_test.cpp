// Command-line overrides (--source, --http, --vehicle) and the no-argument demo configuration.
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

TEST(DemoConfig, MatchesTheDesign) {
  const Config c = demo_config();
  EXPECT_EQ(c.mocap.source.scheme, "sim");
  EXPECT_EQ(c.mocap.source.text, "sim://");
  EXPECT_EQ(c.mocap.up, core::axis::pos_z);
  ASSERT_EQ(c.vehicles.size(), 1u);
  const Vehicle& v = c.vehicles[0];
  EXPECT_EQ(v.spec.name, "demo");
  EXPECT_EQ(v.spec.body, "Body1");
  EXPECT_EQ(to_string(v.link), "udp://127.0.0.1:14550");
  EXPECT_EQ(v.spec.profile, core::Profile::px4);
  EXPECT_EQ(v.spec.system_id, 1);
  EXPECT_EQ(v.spec.component_id, 197);
  EXPECT_EQ(v.spec.rate_hz, 50.0);
  EXPECT_TRUE(v.spec.enabled);
  EXPECT_EQ(to_string(c.http.listen), "127.0.0.1:8080");
  ASSERT_TRUE(c.origin.has_value());
  EXPECT_EQ(c.origin->latitude_deg, 40.1156786);
  EXPECT_EQ(c.origin->longitude_deg, -88.2243507);
  EXPECT_EQ(c.origin->altitude_m, 222.196);
}

TEST(DemoConfig, SurvivesAnEmptyOverride) {
  const auto result = apply_overrides(demo_config(), CommandLineOverrides{});
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_EQ(result.config->vehicles.size(), 1u);
  EXPECT_THAT(result.warnings, testing::IsEmpty());
}

TEST(Overrides, DesignExampleAddsAVehicle) {
  CommandLineOverrides o;
  o.vehicles = {"quad1:body=Quad1,link=udp://127.0.0.1:14540,profile=px4,system_id=1,rate_hz=50"};
  const auto result = apply_overrides(demo_config(), o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  ASSERT_EQ(result.config->vehicles.size(), 2u);
  const Vehicle& v = result.config->vehicles[1];
  EXPECT_EQ(v.spec.name, "quad1");
  EXPECT_EQ(v.spec.body, "Quad1");
  EXPECT_EQ(v.link.kind, LinkKind::udp);
  EXPECT_EQ(v.link.address, (HostPort{"127.0.0.1", 14540}));
  EXPECT_EQ(v.spec.profile, core::Profile::px4);
  EXPECT_EQ(v.spec.system_id, 1);
  EXPECT_EQ(v.spec.rate_hz, 50.0);
  EXPECT_EQ(v.spec.component_id, 197);
}

TEST(Overrides, EndpointFormsFromTheCommandLine) {
  // A query's '=' stays in the link's value: only the first '=' of an item splits key and value.
  CommandLineOverrides o;
  o.vehicles = {
      "a:body=A,link=udp://192.168.1.30:14540?bind=:14540,system_id=1,profile=px4,"
      "gcs=udpin://:14550+tcpin://:5771",
      "b:body=B,link=udpin://127.0.0.1:14541,system_id=2,profile=px4",
      "c:body=C,link=tcpin://:5770,system_id=3,profile=auto"};
  const auto result = apply_overrides(demo_config(), o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  ASSERT_EQ(result.config->vehicles.size(), 4u);
  EXPECT_EQ(to_string(result.config->vehicles[1].link), "udp://192.168.1.30:14540?bind=:14540");
  ASSERT_EQ(result.config->vehicles[1].gcs.size(), 2u);
  EXPECT_EQ(to_string(result.config->vehicles[1].gcs[1]), "tcpin://:5771");
  EXPECT_EQ(to_string(result.config->vehicles[2].link), "udpin://127.0.0.1:14541");
  EXPECT_EQ(to_string(result.config->vehicles[3].link), "tcpin://:5770");
}

TEST(Overrides, EveryKeyFromTheCommandLine) {
  CommandLineOverrides o;
  o.vehicles = {"x:body=Body 2,link=" + testing_support::kSerialUrlPrefix +
                "?baud=115200,system_id=+7,"
                "component_id=191,profile=custom,messages=odometry+hil_gps,rate_hz=12.5,"
                "signing_key=" +
                std::string(64, 'A') + ",body_forward=-y,body_up=+z,enabled=false"};
  const auto result = apply_overrides(demo_config(), o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  const Vehicle& v = result.config->vehicles.at(1);
  EXPECT_EQ(v.spec.body, "Body 2");
  EXPECT_EQ(v.link.device, testing_support::kSerialDevice);
  EXPECT_EQ(v.link.baud, 115200u);
  EXPECT_EQ(v.spec.system_id, 7);
  EXPECT_EQ(v.spec.component_id, 191);
  EXPECT_EQ(v.spec.profile, core::Profile::custom);
  EXPECT_THAT(v.spec.messages,
              testing::ElementsAre(core::MessageKind::odometry, core::MessageKind::hil_gps));
  EXPECT_EQ(v.spec.rate_hz, 12.5);
  ASSERT_TRUE(v.spec.signing_key.has_value());
  EXPECT_EQ((*v.spec.signing_key)[0], 0xAA);
  EXPECT_EQ(v.spec.body_axes.forward(), core::axis::neg_y);
  EXPECT_FALSE(v.spec.enabled);
}

TEST(Overrides, ExistingNameOverridesOnlyTheGivenKeys) {
  const std::string file = R"([mocap]
source = "vicon://192.168.1.3"
[[vehicle]]
name = "quad1"
body = "Quad1"
link = "udp://192.168.1.21:14540"
system_id = 1
profile = "px4"
rate_hz = 50
)";
  CommandLineOverrides o;
  o.vehicles = {"quad1:rate_hz=30,profile=ardupilot"};
  o.source = "sim://?bodies=2";
  o.http = "127.0.0.1:0";
  const auto result = load_config(file, "lab.toml", o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  const Config& c = *result.config;
  EXPECT_EQ(c.mocap.source.scheme, "sim");
  EXPECT_EQ(c.mocap.source.text, "sim://?bodies=2");
  EXPECT_EQ(c.http.listen.port, 0);
  ASSERT_EQ(c.vehicles.size(), 1u);
  EXPECT_EQ(c.vehicles[0].spec.rate_hz, 30.0);
  EXPECT_EQ(c.vehicles[0].spec.profile, core::Profile::ardupilot);
  EXPECT_EQ(c.vehicles[0].spec.body, "Quad1");  // kept from the file
  EXPECT_EQ(c.vehicles[0].spec.system_id, 1);
}

TEST(Overrides, SourceOnTheCommandLineCompletesAFileWithoutOne) {
  const std::string file =
      "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\n"
      "link = \"udp://127.0.0.1:14540\"\nsystem_id = 1\nprofile = \"px4\"\n";
  EXPECT_EQ(error_lines(parse_config(file, "f.toml")),
            (std::vector<std::string>{"f.toml:1:1: mocap.source: missing required key"}));
  CommandLineOverrides o;
  o.source = "vicon://10.0.0.4";
  const auto result = load_config(file, "f.toml", o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_EQ(result.config->mocap.source.text, "vicon://10.0.0.4");
}

TEST(Overrides, ErrorsNameTheOption) {
  CommandLineOverrides o;
  o.source = "vicon:/192.168.1.3";
  o.http = "0.0.0.0:8080";
  o.vehicles = {
      "quad1:body=Quad1,link=udp://127.0.0.1:14540,profile=px4,system_id=1",  // fine
      "quad2:body=Quad2,link=udp://127.0.0.1:14541,profile=px4,system_id=two,rate=5",
      "quad3",
      "quad4:body=Q4,profile=px4,system_id=4,speed",
      "quad 5:body=Q5",
      "quad6:name=x,enabled=yes,rate_hz=1e9,messages=odometry",
      "quad7:body=Q7,link=udp://127.0.0.1:14540,profile=px4,system_id=1,body=Q8",
  };
  const auto result = apply_overrides(demo_config(), o);
  EXPECT_EQ(
      error_lines(result),
      (std::vector<std::string>{
          "--source: \"vicon:/192.168.1.3\" is not a source URL; expected SCHEME://...",
          "--vehicle 2: system_id: expected an integer, got \"two\"",
          "--vehicle 2: rate: unknown key; did you mean \"rate_hz\"?",
          "--vehicle 3: expected NAME:key=value,key=value,... as in "
          "'quad1:body=Quad1,link=udp://127.0.0.1:14540,profile=px4,system_id=1', got \"quad3\"",
          "--vehicle 4: expected key=value, got \"speed\"",
          "--vehicle 5: name: must be 1 to 64 letters, digits, '_', '-' or '.', got \"quad 5\"",
          "--vehicle 6: name: the name goes before the ':', as in quad1:body=Quad1",
          "--vehicle 6: enabled: expected true or false, got \"yes\"",
          "--vehicle 6: rate_hz: must be above 0 and at most 500, got 1e+09",
          "--vehicle 7: body: given twice",
          // Cross-checks after merging, in vehicle order.
          "--vehicle 4: link: missing required key",
          "--vehicle 6: body: missing required key",
          "--vehicle 6: link: missing required key",
          "--vehicle 6: system_id: missing required key",
          "--vehicle 6: profile: missing required key",
          "--vehicle 7: system_id: system_id 1 is already used on udp://127.0.0.1:14540 by "
          "vehicle \"quad1\" (--vehicle 1)",
          "--http: 0.0.0.0:8080 is reachable from the network, so [http] token is required (16 "
          "or more characters); every mutating request must carry it",
      }));
}

TEST(Overrides, AllowHostAddsToTheFilesList) {
  const std::string file = R"([mocap]
source = "sim://"
[http]
allowed_hosts = ["lab-pc"]
)";
  CommandLineOverrides o;
  o.http_allow_hosts = {"Lab-PC.local", "tunnel:9000"};
  const auto result = load_config(file, "lab.toml", o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_EQ(result.config->http.allowed_hosts,
            (std::vector<HostPort>{{"lab-pc", 0}, {"lab-pc.local", 0}, {"tunnel", 9000}}));

  const auto demo = apply_overrides(demo_config(), o);
  ASSERT_TRUE(demo.ok()) << testing::PrintToString(error_lines(demo));
  EXPECT_EQ(demo.config->http.allowed_hosts,
            (std::vector<HostPort>{{"lab-pc.local", 0}, {"tunnel", 9000}}));

  o.http_allow_hosts = {"lab pc", "tunnel:0"};
  EXPECT_THAT(error_lines(apply_overrides(demo_config(), o)),
              testing::ElementsAre(
                  "--http-allow-host: \"lab pc\" is not a valid host name or address (expected a "
                  "host name or address as the browser's address bar gives it, optionally with "
                  ":PORT, e.g. \"lab-pc\" or \"lab-pc.local:8080\")",
                  "--http-allow-host: port must be 1..65535, got \"0\" (expected a host name or "
                  "address as the browser's address bar gives it, optionally with :PORT, e.g. "
                  "\"lab-pc\" or \"lab-pc.local:8080\")"));
}

TEST(Overrides, ConflictWithAFileVehicleNamesBothPlaces) {
  const std::string file = R"([mocap]
source = "sim://"
[[vehicle]]
name = "a"
body = "Body1"
link = "udp://127.0.0.1:14540"
system_id = 3
profile = "px4"
)";
  CommandLineOverrides o;
  o.vehicles = {"b:body=Body2,link=udp://127.0.0.1:14540,profile=px4,system_id=3"};
  EXPECT_EQ(error_lines(load_config(file, "lab.toml", o)),
            (std::vector<std::string>{
                "--vehicle 1: system_id: system_id 3 is already used on udp://127.0.0.1:14540 by "
                "vehicle \"a\" (lab.toml:7:13)"}));
}

TEST(Overrides, DemoVehicleCanBeRetargeted) {
  CommandLineOverrides o;
  o.vehicles = {"demo:link=udp://10.0.0.9:14540,body=Body2"};
  const auto result = apply_overrides(demo_config(), o);
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  ASSERT_EQ(result.config->vehicles.size(), 1u);
  EXPECT_EQ(result.config->vehicles[0].spec.body, "Body2");
  EXPECT_EQ(to_string(result.config->vehicles[0].link), "udp://10.0.0.9:14540");
}

TEST(Overrides, EmptyMessagesListFromTheCommandLine) {
  CommandLineOverrides o;
  o.vehicles = {"c:body=B,link=udp://127.0.0.1:1,system_id=2,profile=custom,messages="};
  EXPECT_EQ(error_lines(apply_overrides(demo_config(), o)),
            (std::vector<std::string>{
                "--vehicle 1: messages: profile \"custom\" needs at least one message"}));
}

}  // namespace
}  // namespace mocaplink::config
