// qtm:// URL options (qtm_options) as check/run/bodies see them through the registry, and the
// `serve --protocol qtm --set` settings (docs/sources.md "qtm://").
#include <gtest/gtest.h>

#include "mocaplink/sources/qtm_options.hpp"
#include "mocaplink/sources/registry.hpp"

namespace mocaplink::sources {
namespace {

namespace wq = wire::qtm;

QtmOptions qtm(const std::string& url) {
  auto parts = config::split_url(url);
  EXPECT_TRUE(parts) << url;
  auto parsed = parse_qtm_options(parts.value());
  EXPECT_TRUE(parsed) << parsed.error();
  return parsed ? parsed.value() : QtmOptions{};
}

std::string error(const std::string& url) {
  return builtin_sources().check(url).error;
}

TEST(QtmOptions, DefaultsAndEveryOption) {
  const QtmOptions plain = qtm("qtm://192.168.1.3");
  EXPECT_EQ(plain.host, "192.168.1.3");
  EXPECT_EQ(plain.port, 22223);
  EXPECT_FALSE(plain.udp_port);
  EXPECT_EQ(plain.component, wq::Component::six_d);
  EXPECT_EQ(plain.newest_minor, 28);
  const QtmOptions full = qtm("qtm://QTM-PC:22300/?udp=0&component=6DEulerRes&version=1.19");
  EXPECT_EQ(full.host, "qtm-pc");
  EXPECT_EQ(full.port, 22300);
  EXPECT_EQ(full.udp_port, 0);
  EXPECT_EQ(full.component, wq::Component::six_d_euler_residual);
  EXPECT_EQ(full.newest_minor, 19);
  EXPECT_EQ(qtm("qtm://h?udp=45000&component=6dres").udp_port, 45000);
  EXPECT_EQ(qtm("qtm://[::1]").host, "::1");
}

TEST(QtmOptions, ErrorsSayWhatIsWrong) {
  EXPECT_EQ(error("qtm://h/x"), "qtm:// takes no path, got \"h/x\"");
  EXPECT_EQ(error("qtm://h?udp=80"), "udp must be 0 (any free port) or 1023 to 65535, got \"80\"");
  EXPECT_NE(error("qtm://h?udp=70000").find("udp must be"), std::string::npos);
  EXPECT_EQ(error("qtm://h?component=3d"),
            "component must be 6d, 6dres, 6deuler or 6deulerres, got \"3d\"");
  EXPECT_EQ(error("qtm://h?version=1.17"), "version must be 1.18 to 1.28, got \"1.17\"");
  EXPECT_EQ(error("qtm://h?verison=1.19"),
            "unknown option \"verison\" for qtm://; did you mean \"version\"? (options: udp, "
            "component, version)");
  EXPECT_NE(error("qtm://").find("host"), std::string::npos);
  EXPECT_EQ(error("qtm://h"), "");
}

TEST(QtmOptions, EmulatorSettings) {
  const auto defaults = parse_qtm_emulator_settings({});
  ASSERT_TRUE(defaults);
  EXPECT_EQ(defaults.value().session.max_minor, 28);
  EXPECT_EQ(defaults.value().session.components.size(), 4u);
  EXPECT_EQ(defaults.value().max_clients, 10u);
  const auto set = parse_qtm_emulator_settings(
      {{"version", "1.19"}, {"components", "6d,6DRes"}, {"max_clients", "2"}});
  ASSERT_TRUE(set) << set.error();
  EXPECT_EQ(set.value().session.max_minor, 19);
  EXPECT_EQ(set.value().session.components,
            (std::vector<wq::Component>{wq::Component::six_d, wq::Component::six_d_residual}));
  EXPECT_EQ(set.value().max_clients, 2u);
  EXPECT_EQ(parse_qtm_emulator_settings({{"version", "2.0"}}).error(),
            "version must be 1.8 to 1.99 (the newest protocol served), got \"2.0\"");
  EXPECT_NE(parse_qtm_emulator_settings({{"components", "6d,,3d"}}).error().find("components"),
            std::string::npos);
  EXPECT_NE(parse_qtm_emulator_settings({{"max_clients", "0"}}).error().find("max_clients"),
            std::string::npos);
  const auto* descriptor = builtin_sources().find("qtm");
  ASSERT_NE(descriptor, nullptr);
  EXPECT_EQ(descriptor->serve_port, 22223);
  EXPECT_TRUE(descriptor->make_emulator);
  EXPECT_FALSE(descriptor->emulator_sends);
}

}  // namespace
}  // namespace mocaplink::sources
