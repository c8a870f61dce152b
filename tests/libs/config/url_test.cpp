// Source URLs, link URLs and host:port syntax (DESIGN.md "Command line"; docs/config.md).
#include <gtest/gtest.h>

#include "mocaplink/config/link_url.hpp"
#include "mocaplink/config/net_address.hpp"
#include "mocaplink/config/source_url.hpp"

namespace mocaplink::config {
namespace {

TEST(SourceUrl, ViconDefaultsAndOptions) {
  const auto plain = parse_source_url("vicon://192.168.1.3");
  ASSERT_TRUE(plain) << plain.error();
  EXPECT_EQ(plain.value().kind, SourceKind::vicon);
  EXPECT_EQ(plain.value().host, "192.168.1.3");
  EXPECT_EQ(plain.value().port, 801);
  EXPECT_EQ(plain.value().vicon_mode, ViconStreamMode::server_push);
  EXPECT_EQ(plain.value().text, "vicon://192.168.1.3");

  const auto full = parse_source_url("vicon://Vicon-PC.lab:802?mode=prefetch");
  ASSERT_TRUE(full) << full.error();
  EXPECT_EQ(full.value().host, "vicon-pc.lab");
  EXPECT_EQ(full.value().port, 802);
  EXPECT_EQ(full.value().vicon_mode, ViconStreamMode::client_pull_prefetch);
  EXPECT_EQ(parse_source_url("vicon://h?mode=pull").value().vicon_mode,
            ViconStreamMode::client_pull);
  EXPECT_EQ(parse_source_url("vicon://h/?mode=pull").value().vicon_mode,
            ViconStreamMode::client_pull);
  const auto v6 = parse_source_url("vicon://[::1]:9000");
  ASSERT_TRUE(v6) << v6.error();
  EXPECT_EQ(v6.value().host, "::1");
  EXPECT_EQ(v6.value().port, 9000);
  EXPECT_EQ(parse_source_url("vicon://h/x").error(), "vicon:// takes no path, got \"h/x\"");
}

TEST(SourceUrl, EverySchemeWithItsDefaults) {
  const auto udp = parse_source_url("vicon-udp://:51002");
  ASSERT_TRUE(udp) << udp.error();
  EXPECT_EQ(udp.value().host, "");
  EXPECT_EQ(udp.value().port, 51002);
  EXPECT_EQ(parse_source_url("vicon-udp://").value().port, 51001);
  EXPECT_EQ(parse_source_url("vicon-udp://10.0.0.2").value().host, "10.0.0.2");

  const auto natnet = parse_source_url("natnet://10.0.0.5?local=10.0.0.9&multicast=239.1.2.3");
  ASSERT_TRUE(natnet) << natnet.error();
  EXPECT_EQ(natnet.value().host, "10.0.0.5");
  EXPECT_EQ(natnet.value().natnet_local_ip, "10.0.0.9");
  EXPECT_EQ(natnet.value().natnet_multicast, "239.1.2.3");
  EXPECT_EQ(parse_source_url("natnet://m").value().natnet_multicast, "239.255.42.99");

  const auto vrpn = parse_source_url("vrpn://Tracker0@localhost");
  ASSERT_TRUE(vrpn) << vrpn.error();
  EXPECT_EQ(vrpn.value().vrpn_tracker, "Tracker0");
  EXPECT_EQ(vrpn.value().host, "localhost");
  EXPECT_EQ(vrpn.value().port, 3883);
  EXPECT_EQ(parse_source_url("vrpn://h:4000").value().vrpn_tracker, "");

  EXPECT_EQ(parse_source_url("qtm://qtm-pc").value().port, 22223);

  const auto sim = parse_source_url("sim://?bodies=5&rate_hz=100&noise_mm=0");
  ASSERT_TRUE(sim) << sim.error();
  EXPECT_EQ(sim.value().sim.bodies, 5u);
  EXPECT_EQ(sim.value().sim.rate_hz, 100.0);
  EXPECT_EQ(sim.value().sim.noise_mm, 0.0);
  const auto sim_default = parse_source_url("sim://");
  EXPECT_EQ(sim_default.value().sim.bodies, 3u);
  EXPECT_EQ(sim_default.value().sim.rate_hz, 200.0);
  EXPECT_EQ(sim_default.value().sim.noise_mm, 0.3);

  const auto replay = parse_source_url("replay://logs/flight 1.csv?speed=2.5");
  ASSERT_TRUE(replay) << replay.error();
  EXPECT_EQ(replay.value().replay_path, "logs/flight 1.csv");
  EXPECT_EQ(replay.value().replay_speed, 2.5);
  EXPECT_EQ(parse_source_url("replay:///abs/f.csv").value().replay_path, "/abs/f.csv");
}

TEST(SourceUrl, EverySimAndReplayOptionTheSourcesTake) {
  const auto sim = parse_source_url(
      "sim://?bodies=64&rate_hz=2000&noise_mm=1000&noise_deg=90&seed=42&drop=0.5&occlude=1"
      "&occlude_s=60&outliers=1&outlier_m=100&frames=7");
  ASSERT_TRUE(sim) << sim.error();
  const SimOptions& s = sim.value().sim;
  EXPECT_EQ(s.bodies, 64u);
  EXPECT_EQ(s.rate_hz, 2000.0);
  EXPECT_EQ(s.noise_mm, 1000.0);
  EXPECT_EQ(s.noise_deg, 90.0);
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.drop, 0.5);
  EXPECT_EQ(s.occlude, 1.0);
  EXPECT_EQ(s.occlude_s, 60.0);
  EXPECT_EQ(s.outliers, 1.0);
  EXPECT_EQ(s.outlier_m, 100.0);
  EXPECT_EQ(s.frames, 7u);
  const SimOptions defaults = parse_source_url("sim://").value().sim;
  EXPECT_EQ(defaults.noise_deg, 0.05);
  EXPECT_EQ(defaults.seed, 1u);
  EXPECT_EQ(defaults.occlude_s, 0.5);
  EXPECT_EQ(defaults.frames, 0u);

  const auto error = [](const char* url) { return parse_source_url(url).error(); };
  EXPECT_EQ(error("sim://?drop=1"), "drop must be a probability from 0 to below 1, got \"1\"");
  EXPECT_EQ(error("sim://?occlude_s=0"), "occlude_s must be a number above 0 up to 60, got \"0\"");
  EXPECT_EQ(error("sim://?seed=-1"),
            "seed must be an integer from 0 to 9223372036854775807, got \"-1\"");
  EXPECT_EQ(error("sim://?bodies=65"), "bodies must be an integer from 1 to 64, got \"65\"");
  EXPECT_EQ(error("sim://?occlud=0.1"),
            "unknown option \"occlud\" for sim://; did you mean \"occlude\"? (options: bodies, "
            "rate_hz, noise_mm, noise_deg, seed, drop, occlude, occlude_s, outliers, outlier_m, "
            "frames)");

  EXPECT_TRUE(parse_source_url("replay://f.csv?loop=1").value().replay_loop);
  EXPECT_FALSE(parse_source_url("replay://f.csv").value().replay_loop);
  EXPECT_EQ(parse_source_url("replay://f.csv?speed=0").value().replay_speed, 0.0);
  EXPECT_EQ(error("replay://f.csv?loop=yes"), "loop must be 0 or 1, got \"yes\"");
}

TEST(SourceUrl, ErrorsSayWhatIsWrong) {
  const auto error = [](const char* url) { return parse_source_url(url).error(); };
  EXPECT_EQ(error("192.168.1.3"),
            "\"192.168.1.3\" is not a source URL; expected SCHEME://..., where SCHEME is one of "
            "vicon, vicon-udp, natnet, vrpn, qtm, sim, replay");
  EXPECT_EQ(error("optitrack://x"),
            "unknown source scheme \"optitrack\" (one of: vicon, vicon-udp, natnet, vrpn, qtm, "
            "sim, replay)");
  EXPECT_EQ(error("natnt://x"),
            "unknown source scheme \"natnt\"; did you mean \"natnet\"? (one of: vicon, vicon-udp, "
            "natnet, vrpn, qtm, sim, replay)");
  EXPECT_EQ(error("vicon://h?mod=push"),
            "unknown option \"mod\" for vicon://; did you mean \"mode\"? (options: mode)");
  EXPECT_EQ(error("vicon://h?mode=fast"), "mode must be push, prefetch or pull, got \"fast\"");
  EXPECT_EQ(error("vicon://h?mode=push&mode=pull"), "option \"mode\" is given twice");
  EXPECT_EQ(error("vicon://"), "missing host in \"\"");
  EXPECT_EQ(error("vicon://h:0"), "port must be 1..65535, got \"0\"");
  EXPECT_EQ(error("qtm://h?x=1"), "qtm:// takes no options, got \"x\"");
  EXPECT_EQ(error("natnet://h:1510"),
            "natnet:// takes no port (Motive's command port 1510 and data port 1511 are used)");
  EXPECT_EQ(error("natnet://h?multicast=10.0.0.1"),
            "multicast must be an IPv4 multicast group (224.0.0.0 to 239.255.255.255), got "
            "\"10.0.0.1\"");
  EXPECT_EQ(error("sim://host"),
            "sim:// takes no host or path, only options, as in sim://?bodies=3");
  EXPECT_EQ(error("sim://?bodies=0"), "bodies must be an integer from 1 to 64, got \"0\"");
  EXPECT_EQ(error("sim://?rate_hz=0"), "rate_hz must be a number above 0 up to 2000, got \"0\"");
  EXPECT_EQ(error("sim://?noise_mm=nan"), "noise_mm must be a number from 0 to 1000, got \"nan\"");
  EXPECT_EQ(error("replay://"), "replay:// needs a file, as in replay://flight.csv");
  EXPECT_EQ(error("vrpn://@h"), "tracker name before '@' must be 1 to 99 characters");
  EXPECT_EQ(error("sim://?bodies"), "query item \"bodies\" is not KEY=VALUE");
}

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

  const auto serial = parse_link_url("serial:///dev/ttyUSB0?baud=921600");
  ASSERT_TRUE(serial) << serial.error();
  EXPECT_EQ(serial.value().device, "/dev/ttyUSB0");
  EXPECT_EQ(serial.value().baud, 921600u);
  EXPECT_EQ(parse_link_url("serial:///dev/ttyAMA0").value().baud, kDefaultSerialBaud);
}

TEST(LinkUrl, RejectsBadAndSharedDestinations) {
  const auto error = [](const char* url) { return parse_link_url(url).error(); };
  EXPECT_EQ(error("192.168.1.21:14540"),
            "expected udp://HOST:PORT, tcp://HOST:PORT or serial:///dev/DEVICE?baud=N, got "
            "\"192.168.1.21:14540\"");
  EXPECT_EQ(error("upd://h:1"),
            "unknown link scheme \"upd\"; did you mean \"udp\"? (expected udp://HOST:PORT, "
            "tcp://HOST:PORT or serial:///dev/DEVICE?baud=N)");
  EXPECT_EQ(error("udp://h"), "missing port: expected HOST:PORT, got \"h\"");
  EXPECT_EQ(error("udp://h:70000"), "port must be 1..65535, got \"70000\"");
  EXPECT_EQ(error("udp://300.1.1.1:5"), "\"300.1.1.1\" is not a valid IPv4 address");
  EXPECT_EQ(error("udp://::1:5"),
            "IPv6 addresses need brackets, as in \"[::1]:8080\", got \"::1:5\"");
  EXPECT_EQ(error("udp://h:1/x"), "udp:// takes HOST:PORT only, got \"h:1/x\"");
  EXPECT_EQ(error("udp://h:1?ttl=2"), "udp:// takes no options, got \"ttl\"");
  const std::string shared =
      "broadcast and multicast addresses are not allowed: pose messages have no target system, "
      "so every vehicle listening would fuse them; give each vehicle its own unicast address";
  EXPECT_EQ(error("udp://255.255.255.255:14550"), shared);
  EXPECT_EQ(error("udp://239.1.1.1:14550"), shared);
  EXPECT_EQ(error("udp://[ff02::1]:14550"), shared);
  EXPECT_TRUE(parse_link_url("udp://192.168.1.255:14550"));  // may be a unicast host in a /23
  EXPECT_EQ(error("serial://dev/ttyUSB0"),
            "serial device must be an absolute path, as in serial:///dev/ttyUSB0?baud=921600, got "
            "\"dev/ttyUSB0\"");
  EXPECT_EQ(error("serial:///dev/ttyUSB0?baud=1234"),
            "baud must be a standard rate (9600, 19200, 38400, 57600, 115200, 230400, 460800, "
            "500000, 576000, 921600, 1000000, 1152000, 1500000, 2000000, 2500000, 3000000, "
            "3500000, 4000000), got \"1234\"");
  EXPECT_EQ(error("serial:///dev/ttyUSB0?bud=9600"),
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
