// Source URL shape, link URLs and host:port syntax (DESIGN.md "Command line"; docs/config.md).
#include <gtest/gtest.h>

#include "mocaplink/config/link_url.hpp"
#include "mocaplink/config/net_address.hpp"
#include "mocaplink/config/source_url.hpp"
#include "serial_device.hpp"

namespace mocaplink::config {
namespace {

TEST(SourceUrl, KeepsTheTextAndScheme) {
  // Options are judged by each source's folder (tests/adapters/registry); config keeps the URL.
  const auto url = parse_source_url("vicon://192.168.1.3?mode=push");
  ASSERT_TRUE(url) << url.error();
  EXPECT_EQ(url.value().text, "vicon://192.168.1.3?mode=push");
  EXPECT_EQ(url.value().scheme, "vicon");
  EXPECT_EQ(parse_source_url("natnet://10.0.0.5").value().scheme, "natnet");
  EXPECT_EQ(parse_source_url("192.168.1.3").error(),
            "\"192.168.1.3\" is not a source URL; expected SCHEME://...");
  EXPECT_EQ(parse_source_url("sim://?bodies").error(), "query item \"bodies\" is not KEY=VALUE");
}

using testing_support::kLinkForms;
using testing_support::kSerialUrlPrefix;

TEST(LinkUrl, ParsesTheThreeKinds) {
  const auto udp = parse_link_url("udp://192.168.1.21:14540");
  ASSERT_TRUE(udp) << udp.error();
  EXPECT_EQ(udp.value().kind, LinkKind::udp);
  EXPECT_EQ(udp.value().address, (HostPort{"192.168.1.21", 14540}));
  EXPECT_EQ(to_string(udp.value()), "udp://192.168.1.21:14540");

  const auto tcp = parse_link_url("tcp://[::1]:5760");
  ASSERT_TRUE(tcp) << tcp.error();
  EXPECT_EQ(tcp.value().address.host, "::1");
  EXPECT_EQ(to_string(tcp.value()), "tcp://[::1]:5760");

#ifdef _WIN32
  const auto serial = parse_link_url("serial://COM3?baud=921600");
  ASSERT_TRUE(serial) << serial.error();
  EXPECT_EQ(serial.value().device, "COM3");
  EXPECT_EQ(serial.value().baud, 921600u);
  EXPECT_EQ(to_string(serial.value()), "serial://COM3?baud=921600");
  EXPECT_EQ(parse_link_url("serial://com12").value().baud, kDefaultSerialBaud);
  EXPECT_TRUE(parse_link_url("serial://COM256"));
#else
  const auto serial = parse_link_url("serial:///dev/ttyUSB0?baud=921600");
  ASSERT_TRUE(serial) << serial.error();
  EXPECT_EQ(serial.value().device, "/dev/ttyUSB0");
  EXPECT_EQ(serial.value().baud, 921600u);
  EXPECT_EQ(parse_link_url("serial:///dev/ttyAMA0").value().baud, kDefaultSerialBaud);
#endif
}

TEST(LinkUrl, ParsesTheEndpointForms) {
  // udp with a fixed local address: the vehicle's address stays `address`, bind is the local one.
  const auto bound = parse_link_url("udp://192.168.1.21:14540?bind=:14540");
  ASSERT_TRUE(bound) << bound.error();
  EXPECT_EQ(bound.value().kind, LinkKind::udp);
  EXPECT_EQ(bound.value().address, (HostPort{"192.168.1.21", 14540}));
  EXPECT_EQ(bound.value().bind, (HostPort{"", 14540}));
  EXPECT_EQ(to_string(bound.value()), "udp://192.168.1.21:14540?bind=:14540");
  EXPECT_FALSE(listens(bound.value()));
  EXPECT_EQ(local_address(bound.value()), (HostPort{"", 14540}));
  const auto bound_v6 = parse_link_url("udp://[fd00::5]:14540?bind=[fd00::1]:14541");
  ASSERT_TRUE(bound_v6) << bound_v6.error();
  EXPECT_EQ(to_string(bound_v6.value()), "udp://[fd00::5]:14540?bind=[fd00::1]:14541");
  EXPECT_EQ(parse_link_url("udp://h:14540").value().bind, std::nullopt);
  EXPECT_EQ(local_address(parse_link_url("udp://h:14540").value()), std::nullopt);

  // Listening forms: the address is local, and may be left out.
  const auto udpin = parse_link_url("udpin://127.0.0.1:14540");
  ASSERT_TRUE(udpin) << udpin.error();
  EXPECT_EQ(udpin.value().kind, LinkKind::udpin);
  EXPECT_EQ(udpin.value().address, (HostPort{"127.0.0.1", 14540}));
  EXPECT_TRUE(listens(udpin.value()));
  EXPECT_EQ(to_string(udpin.value()), "udpin://127.0.0.1:14540");
  const auto any = parse_link_url("udpin://:14550");
  ASSERT_TRUE(any) << any.error();
  EXPECT_EQ(any.value().address, (HostPort{"", 14550}));
  EXPECT_EQ(to_string(any.value()), "udpin://:14550");
  const auto tcpin = parse_link_url("tcpin://0.0.0.0:5770");
  ASSERT_TRUE(tcpin) << tcpin.error();
  EXPECT_EQ(tcpin.value().kind, LinkKind::tcpin);
  EXPECT_EQ(to_string(tcpin.value()), "tcpin://0.0.0.0:5770");
  EXPECT_EQ(to_string(parse_link_url("tcpin://[::]:5770").value()), "tcpin://[::]:5770");
}

TEST(LinkUrl, RejectsBadEndpointForms) {
  const auto error = [](const char* url) { return parse_link_url(url).error(); };
  EXPECT_EQ(error("udpin://vehicle.lab:14540"),
            "udpin:// ADDR must be an IP address of this machine, or left out for every "
            "interface (as in :14540), got \"vehicle.lab\"");
  EXPECT_EQ(error("udp://h:1?bind=localhost:2"),
            "bind's ADDR must be an IP address of this machine, or left out for every interface "
            "(as in :2), got \"localhost\"");
  EXPECT_EQ(error("udp://h:1?bind=:0"),
            "bind must be ADDR:PORT, the local address to send from (ADDR may be left out for "
            "every interface, as in bind=:14540): port must be 1..65535, got \"0\"");
  EXPECT_EQ(error("udp://h:1?bind=14540"),
            "bind must be ADDR:PORT or :PORT, the local address to send from, got \"14540\" (a "
            "port alone is written :14540)");
  EXPECT_EQ(error("udpin://14540"),
            "udpin:// listens on ADDR:PORT or :PORT, got \"14540\" (a port alone is written "
            ":14540)");
  EXPECT_EQ(error("udpin://h:"),
            "udpin:// listens on ADDR:PORT (ADDR may be left out for every interface): " +
                parse_host_port("h:", HostPortRules{}).error());
  EXPECT_EQ(error("tcpin://:1/x"), "tcpin:// takes ADDR:PORT or :PORT only, got \":1/x\"");
  EXPECT_EQ(error("tcpin://:5770?bind=:1"), "tcpin:// takes no options, got \"bind\"");
  EXPECT_EQ(error("tcp://h:5760?bind=:1"), "tcp:// takes no options, got \"bind\"");
  EXPECT_EQ(error("udpin://239.1.1.1:14550"),
            "broadcast and multicast addresses are not allowed: pose messages have no target "
            "system, so every vehicle listening would fuse them; give each vehicle its own "
            "unicast address");
  EXPECT_EQ(error("tcpn://:1"),
            "unknown link scheme \"tcpn\"; did you mean \"tcp\"? (expected " + kLinkForms + ")");
}

TEST(LinkUrl, Ros2NamespacesOfPx4) {
  // PX4's uxrce_dds_client -n NAMESPACE (SITL instance N > 0: px4_N), or none.
  const auto none = parse_link_url("ros2://");
  ASSERT_TRUE(none) << none.error();
  EXPECT_EQ(none.value().kind, LinkKind::ros2);
  EXPECT_EQ(none.value().ros2_namespace, "");
  EXPECT_EQ(to_string(none.value()), "ros2://");
  const auto sitl = parse_link_url("ros2://px4_1");
  ASSERT_TRUE(sitl) << sitl.error();
  EXPECT_EQ(sitl.value().ros2_namespace, "px4_1");
  EXPECT_EQ(to_string(parse_link_url("ros2:///lab/uav_2/").value()), "ros2://lab/uav_2");
  EXPECT_FALSE(listens(sitl.value()));
  EXPECT_EQ(local_address(sitl.value()), std::nullopt);
  for (const char* bad : {"ros2://1uav", "ros2://uav-1", "ros2://a//b", "ros2://px4_1?x=1"}) {
    EXPECT_FALSE(parse_link_url(bad)) << bad;
  }
  EXPECT_NE(parse_link_url("ros2://uav-1").error().find("ros2:// takes PX4's namespace"),
            std::string::npos);
}

TEST(LinkUrl, LocalPortsThatCannotBeSharedInOneProcess) {
  const auto link = [](const char* url) { return parse_link_url(url).value(); };
  // The same UDP port on overlapping addresses: the second socket could not bind it.
  EXPECT_TRUE(same_local_port(link("udpin://:14540"), link("udpin://127.0.0.1:14540")));
  EXPECT_TRUE(same_local_port(link("udpin://:14540"), link("udp://10.0.0.2:14540?bind=:14540")));
  EXPECT_TRUE(same_local_port(link("udpin://0.0.0.0:9"), link("udpin://10.0.0.1:9")));
  // Different addresses, ports or protocols can.
  EXPECT_FALSE(same_local_port(link("udpin://127.0.0.1:9"), link("udpin://10.0.0.1:9")));
  EXPECT_FALSE(same_local_port(link("udpin://:14540"), link("udpin://:14541")));
  EXPECT_FALSE(same_local_port(link("udpin://:5760"), link("tcpin://:5760")));
  // Ephemeral ports never clash.
  EXPECT_FALSE(same_local_port(link("udp://10.0.0.2:14540"), link("udp://10.0.0.2:14540")));
  EXPECT_FALSE(same_local_port(link("tcp://10.0.0.2:5760"), link("tcpin://:5760")));
}

#ifdef _WIN32
TEST(LinkUrl, SerialDevicesAreComPortsOnWindows) {
  for (const char* device : {"/dev/ttyUSB0", "COM", "COM0", "COM1000", "COMx", "LPT1", "COM3 "}) {
    EXPECT_EQ(parse_link_url(std::string("serial://") + device).error(),
              std::string("serial device must be a COM port name, as in "
                          "serial://COM3?baud=921600, got \"") +
                  device + "\"")
        << device;
  }
}
#endif

TEST(LinkUrl, RejectsBadAndSharedDestinations) {
  const auto error = [](const char* url) { return parse_link_url(url).error(); };
  EXPECT_EQ(error("192.168.1.21:14540"), "expected " + kLinkForms + ", got \"192.168.1.21:14540\"");
  EXPECT_EQ(error("upd://h:1"),
            "unknown link scheme \"upd\"; did you mean \"udp\"? (expected " + kLinkForms + ")");
  EXPECT_EQ(error("udp://h"), "missing port: expected HOST:PORT, got \"h\"");
  EXPECT_EQ(error("udp://h:70000"), "port must be 1..65535, got \"70000\"");
  EXPECT_EQ(error("udp://300.1.1.1:5"), "\"300.1.1.1\" is not a valid IPv4 address");
  EXPECT_EQ(error("udp://::1:5"),
            "IPv6 addresses need brackets, as in \"[::1]:8080\", got \"::1:5\"");
  EXPECT_EQ(error("udp://h:1/x"), "udp:// takes HOST:PORT only, got \"h:1/x\"");
  EXPECT_EQ(error("udp://h:1?ttl=2"), "unknown option \"ttl\" for udp:// (options: bind)");
  const std::string shared =
      "broadcast and multicast addresses are not allowed: pose messages have no target system, "
      "so every vehicle listening would fuse them; give each vehicle its own unicast address";
  EXPECT_EQ(error("udp://255.255.255.255:14550"), shared);
  EXPECT_EQ(error("udp://239.1.1.1:14550"), shared);
  EXPECT_EQ(error("udp://[ff02::1]:14550"), shared);
  EXPECT_TRUE(parse_link_url("udp://192.168.1.255:14550"));  // may be a unicast host in a /23
#ifndef _WIN32
  EXPECT_EQ(error("serial://dev/ttyUSB0"),
            "serial device must be an absolute path, as in serial:///dev/ttyUSB0?baud=921600, got "
            "\"dev/ttyUSB0\"");
#endif
  EXPECT_EQ(error((kSerialUrlPrefix + "?baud=1234").c_str()),
            "baud must be a standard rate (9600, 19200, 38400, 57600, 115200, 230400, 460800, "
            "500000, 576000, 921600, 1000000, 1152000, 1500000, 2000000, 2500000, 3000000, "
            "3500000, 4000000), got \"1234\"");
  EXPECT_EQ(error((kSerialUrlPrefix + "?bud=9600").c_str()),
            "unknown option \"bud\" for serial://; did you mean \"baud\"? (options: baud)");
}

TEST(HostPort, LoopbackAndSyntax) {
  EXPECT_TRUE(is_loopback("127.0.0.1"));
  EXPECT_TRUE(is_loopback("127.8.9.10"));
  EXPECT_TRUE(is_loopback("localhost"));
  EXPECT_TRUE(is_loopback("::1"));
  EXPECT_FALSE(is_loopback("0.0.0.0"));
  EXPECT_FALSE(is_loopback("127.example.com"));
  EXPECT_FALSE(is_loopback("192.168.1.2"));
  EXPECT_EQ(parse_host_port("h:0", HostPortRules{}).error(), "port must be 1..65535, got \"0\"");
  EXPECT_EQ(parse_host_port("h:0", HostPortRules{.port_zero_ok = true}).value().port, 0);
  EXPECT_EQ(parse_host_port("a b:1", HostPortRules{}).error(),
            "\"a b\" is not a valid host name or address");
  EXPECT_EQ(parse_host_port("-bad-:1", HostPortRules{}).error(),
            "\"-bad-\" is not a valid host name or address");
  EXPECT_EQ(parse_host_port("[10.0.0.1]:1", HostPortRules{}).error(),
            "brackets are only for IPv6 addresses, got \"[10.0.0.1]:1\"");
  EXPECT_EQ(to_string(HostPort{"fe80::1", 80}), "[fe80::1]:80");
}

}  // namespace
}  // namespace mocaplink::config
