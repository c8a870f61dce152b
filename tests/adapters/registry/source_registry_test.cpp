// The source registry: every source built in opens from its URL, with the options its own folder
// parses; one clear message per bad URL; a scheme without a registered source is refused with the
// available ones; a source's configuration warnings reach the config checker.
#include "mocaplink/sources/registry.hpp"

#include <gtest/gtest.h>

#include "mocaplink/config/load.hpp"

namespace mocaplink::sources {
namespace {

std::string error_of(std::string_view url) {
  auto made = builtin_sources().open(url);
  if (auto* error = std::get_if<std::string>(&made)) return *error;
  return "(accepted)";
}

bool opens(std::string_view url) {
  return std::holds_alternative<std::unique_ptr<Source>>(builtin_sources().open(url));
}

TEST(SourceRegistry, ListsTheBuiltInSourcesAndWhatCanBeServed) {
  const auto registry = builtin_sources();
  EXPECT_EQ(registry.schemes(), (std::vector<std::string_view>{"natnet", "qtm", "replay", "sim",
                                                               "vicon", "vicon-udp", "vrpn"}));
  EXPECT_EQ(registry.servable(),
            (std::vector<std::string_view>{"natnet", "qtm", "vicon", "vicon-udp", "vrpn"}));
  ASSERT_NE(registry.find("vicon"), nullptr);
  EXPECT_EQ(registry.find("vicon")->serve_port, 801);
  ASSERT_NE(registry.find("natnet"), nullptr);
  EXPECT_EQ(registry.find("natnet")->serve_port, 1510);
  EXPECT_EQ(registry.find("optitrack"), nullptr);
}

TEST(SourceRegistry, OpensSimReplayAndVicon) {
  auto sim = builtin_sources().open("sim://?bodies=2&seed=3");
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(sim)) << std::get<std::string>(sim);
  EXPECT_EQ(std::get<std::unique_ptr<Source>>(sim)->url(), "sim://?bodies=2&seed=3");
  EXPECT_TRUE(opens("sim://"));
  // Every simulator option the README lists, as `run --source` gets it.
  EXPECT_TRUE(
      opens("sim://?bodies=5&rate_hz=100&noise_mm=0.1&noise_deg=0.1&seed=9&drop=0.01&occlude=0.1"
            "&occlude_s=0.2&outliers=0.001&outlier_m=0.3&frames=100"));
  auto vicon = builtin_sources().open("vicon://127.0.0.1:8801?mode=prefetch");
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(vicon))
      << std::get<std::string>(vicon);
  EXPECT_EQ(std::get<std::unique_ptr<Source>>(vicon)->url(),
            "vicon://127.0.0.1:8801?mode=prefetch");
}

TEST(SourceRegistry, OneClearMessagePerBadUrl) {
  EXPECT_EQ(error_of("sim://?bodys=3"),
            "unknown option \"bodys\" for sim://; did you mean \"bodies\"? (options: bodies, "
            "rate_hz, noise_mm, noise_deg, seed, drop, occlude, occlude_s, outliers, outlier_m, "
            "frames, churn_s)");
  EXPECT_NE(error_of("sim://?rate_hz=0").find("rate_hz must be"), std::string::npos);
  EXPECT_NE(error_of("sim://host").find("takes no host"), std::string::npos);
  EXPECT_NE(error_of("replay:///nonexistent.csv").find("cannot open '/nonexistent.csv'"),
            std::string::npos);
  EXPECT_NE(error_of("replay://x.csv?speed=-2").find("speed must be a number from 0 to 1000"),
            std::string::npos);
  EXPECT_NE(error_of("ftp://x").find("unknown source scheme \"ftp\""), std::string::npos);
  // Not built into this binary: refused like any unknown scheme, with what is available.
  EXPECT_EQ(error_of("optitrack://10.0.0.5"),
            "unknown source scheme \"optitrack\" (one of: natnet, qtm, replay, sim, vicon, "
            "vicon-udp, vrpn)");
  // natnet:// options (natnet_options.cpp), one message each.
  EXPECT_TRUE(opens("natnet://10.0.0.5"));
  EXPECT_TRUE(
      opens("natnet://motive.lab:1510?local=10.0.0.2&multicast=239.255.42.99&data_port="
            "1511&transport=unicast"));
  EXPECT_EQ(error_of("natnet://10.0.0.5?multicast=10.0.0.1"),
            "multicast must be an IPv4 multicast group (224.0.0.0 to 239.255.255.255), got "
            "\"10.0.0.1\"");
  EXPECT_EQ(error_of("natnet://10.0.0.5?local=eth0"),
            "local must be the IPv4 address of a local interface, got \"eth0\"");
  EXPECT_EQ(error_of("natnet://10.0.0.5?transport=tcp"),
            "transport must be auto, multicast or unicast, got \"tcp\"");
  EXPECT_NE(error_of("natnet://10.0.0.5?data_port=0").find("data_port must be"), std::string::npos);
  EXPECT_NE(error_of("natnet://10.0.0.5?multicst=239.1.1.1").find("did you mean \"multicast\""),
            std::string::npos);
  EXPECT_NE(error_of("natnet://10.0.0.5/x").find("takes no path"), std::string::npos);
}

TEST(SourceRegistry, CheckAgreesWithOpen) {
  const auto registry = builtin_sources();
  for (const char* url : {"sim://?bodys=3", "optitrack://10.0.0.5", "vicon://h?mode=fast", "x",
                          "vicon://h:0", "replay://?speed=2"}) {
    EXPECT_EQ(registry.check(url).error, error_of(url)) << url;
  }
  EXPECT_EQ(registry.check("vicon://h").error, "");
  EXPECT_EQ(registry.check("replay://not-opened-by-check.csv").error, "");
}

// NatNet reminds a user who kept the Z-up default that Motive streams Y-up.
TEST(SourceRegistry, NatnetWarnsWhenUpIsNotWritten) {
  const auto registry = builtin_sources();
  const auto warned = registry.check("natnet://10.0.0.5", config::SourceContext{false});
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_NE(warned.warnings[0].find("Motive streams Y-up"), std::string::npos);
  EXPECT_TRUE(registry.check("natnet://10.0.0.5", config::SourceContext{true}).warnings.empty());
}

// A source's configuration warnings (the hook the NatNet source uses: Motive streams Y-up) reach
// `check` and `run` through the validator, at the [mocap] source key, only when [mocap] up is not
// written.
TEST(SourceRegistry, ASourcesConfigWarningsReachTheConfigChecker) {
  static constexpr std::array<std::string_view, 0> kNoKeys{};
  SourceDescriptor yup;
  yup.scheme = "yup";
  yup.option_keys = kNoKeys;
  yup.check = [](const config::UrlParts&) { return std::string(); };
  yup.open = [](const config::UrlParts&, std::string) -> OpenResult { return "not openable"; };
  yup.config_warnings = [](const config::UrlParts&, const config::SourceContext& context) {
    return context.up_written ? std::vector<std::string>{}
                              : std::vector<std::string>{"streams Y-up; set [mocap] up"};
  };
  const SourceRegistry registry({yup});
  const std::string vehicle =
      "[[vehicle]]\nname = \"q\"\nbody = \"Q\"\nlink = \"udp://127.0.0.1:14540\"\n"
      "system_id = 1\nprofile = \"px4\"\n";

  const auto warned = config::parse_config("[mocap]\nsource = \"yup://h\"\n" + vehicle, "m.toml",
                                           registry.validator());
  ASSERT_TRUE(warned.ok());
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_EQ(config::to_string(warned.warnings[0]),
            "m.toml:2:10: mocap.source: streams Y-up; set [mocap] up");

  const auto quiet = config::parse_config(
      "[mocap]\nsource = \"yup://h\"\nup = \"+y\"\nnorth = \"+x\"\nbody_up = \"+y\"\n"
      "body_forward = \"+x\"\n" +
          vehicle,
      "m.toml", registry.validator());
  EXPECT_TRUE(quiet.ok());
  EXPECT_TRUE(quiet.warnings.empty());

  const auto refused = config::parse_config("[mocap]\nsource = \"sim://\"\n" + vehicle, "m.toml",
                                            registry.validator());
  ASSERT_EQ(refused.errors.size(), 1u);
  EXPECT_EQ(config::to_string(refused.errors[0]),
            "m.toml:2:10: mocap.source: unknown source scheme \"sim\" (one of: yup)");
  config::CommandLineOverrides o;
  o.source = "192.168.1.3";
  const auto not_url = config::load_config("[mocap]\nsource = \"yup://h\"\n" + vehicle, "m.toml", o,
                                           registry.validator());
  ASSERT_EQ(not_url.errors.size(), 1u);
  EXPECT_EQ(config::to_string(not_url.errors[0]),
            "--source: \"192.168.1.3\" is not a source URL; expected SCHEME://..., where SCHEME is "
            "one of yup");
}

}  // namespace
}  // namespace mocaplink::sources
