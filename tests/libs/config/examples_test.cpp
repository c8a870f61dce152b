// The example configurations committed under docs/examples/ parse to what their comments say.
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mocaplink/config/load.hpp"

namespace mocaplink::config {
namespace {

std::string read_example(const std::string& name) {
  std::ifstream in(std::string(MOCAPLINK_EXAMPLES_DIR) + "/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::ostringstream text;
  text << in.rdbuf();
#ifdef _WIN32
  // The examples name Linux serial devices; Windows takes COM ports (link_url.cpp).
  std::string windows = text.str();
  for (std::size_t at; (at = windows.find("serial:///dev/ttyUSB0")) != std::string::npos;) {
    windows.replace(at, 21, "serial://COM3");
  }
  return windows;
#else
  return text.str();
#endif
}

TEST(Examples, LabWithThreeVehicles) {
  const auto result = parse_config(read_example("lab.toml"), "lab.toml");
  ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : to_string(result.errors[0]));
  EXPECT_THAT(result.warnings, testing::IsEmpty());
  const Config& c = *result.config;
  EXPECT_EQ(c.mocap.source.scheme, "vicon");
  EXPECT_EQ(c.mocap.source.text, "vicon://192.168.1.3?mode=push");
  ASSERT_TRUE(c.origin.has_value());
  ASSERT_EQ(c.vehicles.size(), 3u);
  EXPECT_EQ(c.vehicles[0].spec.profile, core::Profile::px4);
  EXPECT_EQ(c.vehicles[1].spec.profile, core::Profile::ardupilot);
  EXPECT_EQ(c.vehicles[1].link.kind, LinkKind::serial);
  EXPECT_TRUE(c.vehicles[1].spec.signing_key.has_value());
  EXPECT_EQ(c.vehicles[2].spec.profile, core::Profile::ardupilot_gps);
  EXPECT_EQ(c.vehicles[2].spec.rate_hz, 10.0);
  EXPECT_FALSE(is_loopback(c.http.listen.host));
  EXPECT_FALSE(c.http.token.empty());
}

TEST(Examples, SinglePx4Quad) {
  const auto result = parse_config(read_example("px4-quad.toml"), "px4-quad.toml");
  ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : to_string(result.errors[0]));
  EXPECT_THAT(result.warnings, testing::IsEmpty());
  const Config& c = *result.config;
  EXPECT_EQ(c.mocap.source.scheme, "vicon");
  EXPECT_EQ(c.mocap.up, core::axis::pos_z);
  ASSERT_EQ(c.vehicles.size(), 1u);
  EXPECT_EQ(c.vehicles[0].spec.profile,
            core::Profile::automatic);  // PX4 or ArduPilot, as the vehicle says
  EXPECT_EQ(c.vehicles[0].spec.body_axes.up(), core::axis::pos_z);
  EXPECT_EQ(c.vehicles[0].spec.rate_hz, 50.0);
}

}  // namespace
}  // namespace mocaplink::config
