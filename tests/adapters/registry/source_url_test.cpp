// Each built-in source's URL options, parsed in its own folder (vicon_options, sim_options,
// replay_options) and reached through the registry (DESIGN.md "Source URLs"; docs/sources.md).
#include <gtest/gtest.h>

#include "mocaplink/sources/registry.hpp"
#include "mocaplink/sources/replay_options.hpp"
#include "mocaplink/sources/sim_options.hpp"
#include "mocaplink/sources/vicon_options.hpp"
#include "url_test_support.hpp"

namespace mocaplink::sources {
namespace {

using test::parse;

ViconOptions vicon(const std::string& url) {
  auto parsed = parse(&parse_vicon_options, url);
  EXPECT_TRUE(parsed) << parsed.error();
  return parsed ? parsed.value() : ViconOptions{};
}

SimOptions sim(const std::string& url) {
  auto parsed = parse(&parse_sim_options, url);
  EXPECT_TRUE(parsed) << parsed.error();
  return parsed ? parsed.value() : SimOptions{};
}

ReplayOptions replay(const std::string& url) {
  auto parsed = parse(&parse_replay_options, url);
  EXPECT_TRUE(parsed) << parsed.error();
  return parsed ? parsed.value() : ReplayOptions{};
}

using test::check_error;

TEST(SourceUrl, ViconDefaultsAndOptions) {
  using wire::vicon::StreamMode;
  const ViconOptions plain = vicon("vicon://192.168.1.3");
  EXPECT_EQ(plain.host, "192.168.1.3");
  EXPECT_EQ(plain.port, 801);
  EXPECT_EQ(plain.mode, StreamMode::server_push);

  const ViconOptions full = vicon("vicon://Vicon-PC.lab:802?mode=prefetch");
  EXPECT_EQ(full.host, "vicon-pc.lab");
  EXPECT_EQ(full.port, 802);
  EXPECT_EQ(full.mode, StreamMode::client_prefetch);
  EXPECT_EQ(vicon("vicon://h?mode=pull").mode, StreamMode::client_pull);
  EXPECT_EQ(vicon("vicon://h/?mode=pull").mode, StreamMode::client_pull);
  const ViconOptions v6 = vicon("vicon://[::1]:9000");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 9000);
  EXPECT_EQ(check_error("vicon://h/x"), "vicon:// takes no path, got \"h/x\"");
}

TEST(SourceUrl, SimAndReplayDefaults) {
  const SimOptions s = sim("sim://?bodies=5&rate_hz=100&noise_mm=0");
  EXPECT_EQ(s.bodies, 5u);
  EXPECT_EQ(s.rate_hz, 100.0);
  EXPECT_EQ(s.noise_mm, 0.0);
  const SimOptions d = sim("sim://");
  EXPECT_EQ(d.bodies, 3u);
  EXPECT_EQ(d.rate_hz, 200.0);
  EXPECT_EQ(d.noise_mm, 0.3);

  const ReplayOptions r = replay("replay://logs/flight 1.csv?speed=2.5");
  EXPECT_EQ(r.path, "logs/flight 1.csv");
  EXPECT_EQ(r.speed, 2.5);
  EXPECT_EQ(replay("replay:///abs/f.csv").path, "/abs/f.csv");
}

TEST(SourceUrl, EverySimAndReplayOptionTheSourcesTake) {
  const SimOptions s =
      sim("sim://?bodies=64&rate_hz=2000&noise_mm=1000&noise_deg=90&seed=42&drop=0.5&occlude=1"
          "&occlude_s=60&outliers=1&outlier_m=100&frames=7");
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
  const SimOptions defaults = sim("sim://");
  EXPECT_EQ(defaults.noise_deg, 0.05);
  EXPECT_EQ(defaults.seed, 1u);
  EXPECT_EQ(defaults.occlude_s, 0.5);
  EXPECT_EQ(defaults.frames, 0u);

  EXPECT_EQ(check_error("sim://?drop=1"),
            "drop must be a probability from 0 to below 1, got \"1\"");
  EXPECT_EQ(check_error("sim://?occlude_s=0"),
            "occlude_s must be a number above 0 up to 60, got \"0\"");
  EXPECT_EQ(check_error("sim://?seed=-1"),
            "seed must be an integer from 0 to 9223372036854775807, got \"-1\"");
  EXPECT_EQ(check_error("sim://?bodies=65"), "bodies must be an integer from 1 to 64, got \"65\"");
  EXPECT_EQ(check_error("sim://?occlud=0.1"),
            "unknown option \"occlud\" for sim://; did you mean \"occlude\"? (options: bodies, "
            "rate_hz, noise_mm, noise_deg, seed, drop, occlude, occlude_s, outliers, outlier_m, "
            "frames, churn_s)");

  EXPECT_TRUE(replay("replay://f.csv?loop=1").loop);
  EXPECT_FALSE(replay("replay://f.csv").loop);
  EXPECT_EQ(replay("replay://f.csv?speed=0").speed, 0.0);
  EXPECT_EQ(check_error("replay://f.csv?loop=yes"), "loop must be 0 or 1, got \"yes\"");
}

TEST(SourceUrl, ErrorsSayWhatIsWrong) {
  EXPECT_EQ(check_error("192.168.1.3"),
            "\"192.168.1.3\" is not a source URL; expected SCHEME://..., where SCHEME is one of "
            "natnet, qtm, replay, sim, vicon, vicon-udp, vrpn");
  EXPECT_EQ(check_error("optitrack://x"),
            "unknown source scheme \"optitrack\" (one of: natnet, qtm, replay, sim, vicon, "
            "vicon-udp, vrpn)");
  EXPECT_EQ(check_error("vicn://x"),
            "unknown source scheme \"vicn\"; did you mean \"vicon\"? (one of: natnet, qtm, "
            "replay, sim, vicon, vicon-udp, vrpn)");
  EXPECT_EQ(check_error("vicon://h?mod=push"),
            "unknown option \"mod\" for vicon://; did you mean \"mode\"? (options: mode)");
  EXPECT_EQ(check_error("vicon://h?mode=fast"),
            "mode must be push, prefetch or pull, got \"fast\"");
  EXPECT_EQ(check_error("vicon://h?mode=push&mode=pull"), "option \"mode\" is given twice");
  EXPECT_EQ(check_error("vicon://"), "missing host in \"\"");
  EXPECT_EQ(check_error("vicon://h:0"), "port must be 1..65535, got \"0\"");
  EXPECT_EQ(check_error("sim://host"),
            "sim:// takes no host or path, only options, as in sim://?bodies=3");
  EXPECT_EQ(check_error("sim://?bodies=0"), "bodies must be an integer from 1 to 64, got \"0\"");
  EXPECT_EQ(check_error("sim://?rate_hz=0"),
            "rate_hz must be a number above 0 up to 2000, got \"0\"");
  EXPECT_EQ(check_error("sim://?noise_mm=nan"),
            "noise_mm must be a number from 0 to 1000, got \"nan\"");
  EXPECT_EQ(check_error("replay://"), "replay:// needs a file, as in replay://flight.csv");
  EXPECT_EQ(check_error("sim://?bodies"), "query item \"bodies\" is not KEY=VALUE");
}

}  // namespace
}  // namespace mocaplink::sources
