// make_source: every source built in opens from its URL, with the options the one URL parser
// (config::parse_source_url) accepts; one clear message per bad URL.
#include "mocaplink/sources/source_factory.hpp"

#include <gtest/gtest.h>

namespace mocaplink::sources {
namespace {

std::string error_of(std::string_view url) {
  auto made = make_source(url);
  if (auto* error = std::get_if<std::string>(&made)) return *error;
  return "(accepted)";
}

TEST(MakeSource, BuildsSimAndReplay) {
  auto sim = make_source("sim://?bodies=2&seed=3");
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(sim)) << std::get<std::string>(sim);
  EXPECT_EQ(std::get<std::unique_ptr<Source>>(sim)->url(), "sim://?bodies=2&seed=3");
  EXPECT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(make_source("sim://")));
  // Every simulator option the README lists, as `run --source` gets it.
  EXPECT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(make_source(
      "sim://?bodies=5&rate_hz=100&noise_mm=0.1&noise_deg=0.1&seed=9&drop=0.01&occlude=0.1"
      "&occlude_s=0.2&outliers=0.001&outlier_m=0.3&frames=100")));
  auto vicon = make_source("vicon://127.0.0.1:8801?mode=prefetch");
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(vicon))
      << std::get<std::string>(vicon);
  EXPECT_EQ(std::get<std::unique_ptr<Source>>(vicon)->url(),
            "vicon://127.0.0.1:8801?mode=prefetch");
}

TEST(MakeSource, OneClearMessagePerBadUrl) {
  EXPECT_EQ(error_of("sim://?bodys=3"),
            "unknown option \"bodys\" for sim://; did you mean \"bodies\"? (options: bodies, "
            "rate_hz, noise_mm, noise_deg, seed, drop, occlude, occlude_s, outliers, outlier_m, "
            "frames)");
  EXPECT_NE(error_of("sim://?rate_hz=0").find("rate_hz must be"), std::string::npos);
  EXPECT_NE(error_of("sim://host").find("takes no host"), std::string::npos);
  EXPECT_NE(error_of("replay:///nonexistent.csv").find("cannot open '/nonexistent.csv'"),
            std::string::npos);
  EXPECT_NE(error_of("replay://x.csv?speed=-2").find("speed must be a number from 0 to 1000"),
            std::string::npos);
  EXPECT_NE(error_of("ftp://x").find("unknown source scheme \"ftp\""), std::string::npos);
  // In DESIGN.md but not built into this binary: said so, with what is available.
  EXPECT_EQ(error_of("natnet://10.0.0.5"),
            "natnet://: this mocaplink was built without that source (available: sim, replay, "
            "vicon)");
}

}  // namespace
}  // namespace mocaplink::sources
