// [ros2]: defaults, every key, and every refusal with its file:line:col (counted by hand from the
// texts below); ROS_DOMAIN_ID as rcl reads it.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mocaplink/config/load.hpp"
#include "test_util.hpp"

namespace mocaplink::config {
namespace {

using testing::ElementsAre;
using testing::IsEmpty;
using testing_util::error_lines;
using testing_util::warning_lines;

ConfigResult parse(const std::string& ros2_table) {
  return parse_config("[mocap]\nsource = \"sim://\"\n" + ros2_table, "r.toml");
}

TEST(Ros2Config, AbsentMeansNoRos2) {
  const auto result = parse("");
  ASSERT_TRUE(result.ok());
  EXPECT_FALSE(result.config->ros2.has_value());
  EXPECT_THAT(warning_lines(result),
              ElementsAre("r.toml:1:1: vehicle: no [[vehicle]] tables: nothing will be sent"));
}

TEST(Ros2Config, AnEmptyTableTakesEveryDefault) {
  const auto result = parse("[ros2]\n");
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  EXPECT_THAT(
      warning_lines(result),
      ElementsAre(
          "r.toml:1:1: vehicle: no [[vehicle]] tables: only the [ros2] topics are published"));
  const Ros2Settings& r = *result.config->ros2;
  EXPECT_FALSE(r.domain_id.has_value());  // ROS_DOMAIN_ID, else 0: the caller's to read
  EXPECT_EQ(r.ns, "mocap");
  EXPECT_EQ(r.frame_id, "world");
  EXPECT_THAT(r.bodies, IsEmpty());  // every body
  EXPECT_TRUE(r.pose);
  EXPECT_TRUE(r.odom);
  EXPECT_TRUE(r.tf);
  EXPECT_EQ(r.axes, core::RosAxes::enu_flu);
  EXPECT_EQ(r.network_interface, "all");
}

TEST(Ros2Config, EveryKeySet) {
  const auto result = parse(R"([ros2]
domain_id = 17
namespace = "/lab/mocap"
frame_id = "map"
bodies = ["Quad1", "Rigid Body 2"]
publish = ["tf", "odom"]
axes = "mocap"
interface = "loopback"
)");
  ASSERT_TRUE(result.ok()) << testing::PrintToString(error_lines(result));
  const Ros2Settings& r = *result.config->ros2;
  EXPECT_EQ(r.domain_id, 17u);
  EXPECT_EQ(r.ns, "lab/mocap");  // the leading '/' dropped: absolute either way
  EXPECT_EQ(r.frame_id, "map");
  EXPECT_THAT(r.bodies, ElementsAre("Quad1", "Rigid Body 2"));
  EXPECT_FALSE(r.pose);
  EXPECT_TRUE(r.odom);
  EXPECT_TRUE(r.tf);
  EXPECT_EQ(r.axes, core::RosAxes::mocap);
  EXPECT_EQ(r.network_interface, "loopback");
  // The body that is not a ROS name is said, with the name it gets.
  EXPECT_THAT(
      warning_lines(result),
      testing::Contains("r.toml:7:10: ros2.bodies: body \"Rigid Body 2\" is published as "
                        "\"Rigid_Body_2\" (ROS names hold only letters, digits and single '_', and "
                        "start with no digit): topics /lab/mocap/Rigid_Body_2/…, tf frame "
                        "\"Rigid_Body_2\""));
}

TEST(Ros2Config, AnInterfaceAddress) {
  const auto result = parse("[ros2]\ninterface = \"192.168.1.10\"\n");
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result.config->ros2->network_interface, "192.168.1.10");
}

TEST(Ros2Config, BadValuesAreErrorsWithTheirPlace) {
  const auto result = parse(R"([ros2]
domain_id = 233
namespace = "lab//mocap"
frame_id = "/world"
publish = ["pose", "pos"]
axes = "enu"
interface = "eth0"
colour = "red"
)");
  EXPECT_THAT(
      error_lines(result),
      ElementsAre(
          "r.toml:4:13: ros2.domain_id: must be an integer from 0 to 232, got 233",
          "r.toml:5:13: ros2.namespace: must be a ROS namespace (tokens of letters, digits and "
          "'_' joined by '/', none starting with a digit), got \"lab//mocap\": it has an empty "
          "token (\"//\" or a '/' at an end)",
          "r.toml:6:12: ros2.frame_id: must be a tf2 frame id such as \"world\" or \"map\", got "
          "\"/world\": it may not start with '/' (tf2 frame ids are relative)",
          "r.toml:7:11: ros2.publish: lists \"pos\"; did you mean \"pose\"? (each of \"pose\", "
          "\"odom\", \"tf\" at most once)",
          "r.toml:8:8: ros2.axes: must be \"enu_flu\" (REP 103: ENU world, FLU body) or \"mocap\" "
          "(the mocap system's own axes), got \"enu\"",
          "r.toml:9:13: ros2.interface: must be \"all\", \"loopback\" or an IPv4 address of this "
          "machine (e.g. \"192.168.1.10\"), got \"eth0\"",
          "r.toml:10:1: ros2.colour: unknown key (allowed here: domain_id, namespace, frame_id, "
          "bodies, publish, axes, interface)"));
}

TEST(Ros2Config, NamesThatBreakRosRules) {
  EXPECT_THAT(
      error_lines(parse("[ros2]\nnamespace = \"2lab\"\n")),
      ElementsAre(testing::HasSubstr("it has a token that starts with a digit (\"2lab\")")));
  EXPECT_THAT(
      error_lines(parse("[ros2]\nnamespace = \"my lab\"\n")),
      ElementsAre(testing::HasSubstr("may hold only letters, digits, '_' and '/', not ' '")));
  EXPECT_THAT(error_lines(parse("[ros2]\nframe_id = \"my__world\"\n")),
              ElementsAre(testing::HasSubstr("it may not hold \"__\"")));
  EXPECT_THAT(error_lines(parse("[ros2]\npublish = []\n")),
              ElementsAre("r.toml:4:11: ros2.publish: is empty: list at least one of \"pose\", "
                          "\"odom\", \"tf\" (or remove [ros2]; an empty list is for a [ros2] "
                          "table only ros2:// links use)"));
  EXPECT_THAT(error_lines(parse("[ros2]\npublish = [\"tf\", \"tf\"]\n")),
              ElementsAre("r.toml:4:11: ros2.publish: \"tf\" is listed twice"));
  // An empty namespace is allowed: topics at the root.
  const auto root = parse("[ros2]\nnamespace = \"\"\n");
  ASSERT_TRUE(root.ok());
  EXPECT_EQ(root.config->ros2->ns, "");
}

TEST(Ros2Config, Px4LinksNeedTheTableAndThePx4Profile) {
  const std::string vehicle =
      "[[vehicle]]\nname = \"q1\"\nbody = \"Quad1\"\nlink = \"ros2://px4_1\"\n"
      "system_id = 2\nprofile = \"auto\"\n";
  // With [ros2] (nothing else published): auto means px4, the only autopilot on that path.
  const auto ok = parse("[ros2]\npublish = []\n" + vehicle);
  ASSERT_TRUE(ok.ok()) << testing::PrintToString(error_lines(ok));
  EXPECT_EQ(ok.config->vehicles.at(0).spec.profile, core::Profile::px4);
  EXPECT_EQ(ok.config->vehicles.at(0).link.ros2_namespace, "px4_1");
  EXPECT_FALSE(ok.config->ros2->pose || ok.config->ros2->odom || ok.config->ros2->tf);
  // Without [ros2]: no domain to join.
  EXPECT_THAT(error_lines(parse(vehicle)),
              ElementsAre(testing::HasSubstr("vehicle[1].link: link ros2://px4_1 is on the ROS 2 "
                                             "graph: add a [ros2] table")));
  // Another profile, a signing key, ground stations: none can go over DDS.
  std::string ardupilot = vehicle;
  ardupilot.replace(ardupilot.find("\"auto\""), 6, "\"ardupilot\"");
  EXPECT_THAT(error_lines(parse("[ros2]\n" + ardupilot)),
              ElementsAre(testing::HasSubstr("profile must be \"px4\" (or \"auto\")")));
  EXPECT_THAT(error_lines(parse("[ros2]\n" + vehicle + "gcs = [\"udp://127.0.0.1:14550\"]\n")),
              ElementsAre(testing::HasSubstr("no ground station's traffic")));
  // Two vehicles on one namespace: PX4 would fuse both.
  std::string second = vehicle;
  second.replace(second.find("q1"), 2, "q2");
  second.replace(second.find("Quad1"), 5, "Quad2");
  second.replace(second.find("system_id = 2"), 13, "system_id = 3");
  EXPECT_THAT(error_lines(parse("[ros2]\n" + vehicle + second)),
              ElementsAre(testing::HasSubstr("each PX4 needs its own namespace")));
}

// The dashboard's message boxes on such a vehicle: only odometry becomes a VehicleOdometry, so
// any other set would stop its poses; an empty one sends none, as on every link.
TEST(Ros2Config, ALiveChangeKeepsOdometryOnly) {
  const auto base = parse(
      "[ros2]\npublish = []\n[[vehicle]]\nname = \"q1\"\nbody = \"Quad1\"\n"
      "link = \"ros2://px4_1\"\nsystem_id = 2\nprofile = \"px4\"\n");
  ASSERT_TRUE(base.ok()) << testing::PrintToString(error_lines(base));
  EXPECT_EQ(base.config->vehicles.at(0).spec.link, core::VehicleLink::px4_dds);
  const auto patch = [&](std::vector<std::string> messages) {
    return update_vehicle(*base.config, "q1", {{"messages", std::move(messages)}},
                          "PATCH /api/vehicles/q1");
  };
  EXPECT_TRUE(patch({"odometry"}).ok());
  EXPECT_TRUE(patch({}).ok());
  EXPECT_THAT(
      error_lines(patch({"vision_position_estimate"})),
      ElementsAre(testing::HasSubstr("made from odometry only: messages = [\"odometry\"]")));
  EXPECT_FALSE(patch({"odometry", "hil_gps"}).ok());
}

TEST(Ros2Config, BodiesThatCannotBePublished) {
  EXPECT_THAT(
      error_lines(parse("[ros2]\nbodies = [\"Quad 1\", \"Quad-1\"]\n")),
      ElementsAre("r.toml:4:10: ros2.bodies: bodies \"Quad 1\" and \"Quad-1\" both become the ROS "
                  "name \"Quad_1\": rename one in the mocap system or leave one out"));
  EXPECT_THAT(error_lines(parse("[ros2]\nbodies = [\"Quad1\", \"Quad1\"]\n")),
              ElementsAre("r.toml:4:10: ros2.bodies: body \"Quad1\" is listed twice"));
  EXPECT_THAT(error_lines(parse("[ros2]\nbodies = [\"***\"]\n")),
              ElementsAre("r.toml:4:10: ros2.bodies: body \"***\" has no letter or digit to make "
                          "a ROS name of: it cannot be published (rename it in the mocap system)"));
  const std::string long_name(245, 'a');  // "/mocap/" + 245 + "/pose" = 257 > 247
  EXPECT_THAT(error_lines(parse("[ros2]\nbodies = [\"" + long_name + "\"]\n")),
              ElementsAre(testing::HasSubstr("of 257 characters; ROS allows 247")));
}

TEST(Ros2Config, AHighDomainIsAWarning) {
  const auto result = parse("[ros2]\ndomain_id = 150\n");
  ASSERT_TRUE(result.ok());
  EXPECT_THAT(warning_lines(result),
              testing::Contains(testing::StartsWith(
                  "r.toml:4:13: ros2.domain_id: domain 150 is above 101: on Linux its ports")));
}

TEST(Ros2Config, KeptWhenTheDashboardAddsAVehicle) {
  const auto base = parse("[ros2]\ndomain_id = 3\nbodies = [\"Body1\"]\n");
  ASSERT_TRUE(base.ok());
  CommandLineOverrides o;
  o.vehicles.push_back("q:body=Body2,link=udp://127.0.0.1:14550,system_id=1,profile=px4");
  const auto changed = apply_overrides(*base.config, o, "base");
  ASSERT_TRUE(changed.ok()) << testing::PrintToString(error_lines(changed));
  ASSERT_TRUE(changed.config->ros2.has_value());
  EXPECT_EQ(changed.config->ros2->domain_id, 3u);
  EXPECT_THAT(changed.config->ros2->bodies, ElementsAre("Body1"));
}

TEST(Ros2DomainId, AsRclReadsIt) {
  EXPECT_EQ(parse_ros_domain_id("").value(), 0u);
  EXPECT_EQ(parse_ros_domain_id("42").value(), 42u);
  EXPECT_EQ(parse_ros_domain_id("0x10").value(), 16u);  // strtoul base 0
  EXPECT_EQ(parse_ros_domain_id("010").value(), 8u);
  EXPECT_EQ(parse_ros_domain_id("232").value(), 232u);
  for (const char* bad : {"233", "-1", " 1", "1 ", "abc", "+3", "99999999999999999999"}) {
    const auto parsed = parse_ros_domain_id(bad);
    ASSERT_FALSE(parsed.ok()) << bad;
    EXPECT_THAT(parsed.error(), testing::StartsWith("ROS_DOMAIN_ID must be a whole number from 0 "
                                                    "to 232, got \""));
  }
}

}  // namespace
}  // namespace mocaplink::config
