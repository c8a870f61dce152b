// make_source: URL grammar and one clear message per bad URL.
#include "mocaplink/sources/source_factory.hpp"

#include <gtest/gtest.h>

namespace mocaplink::sources {
namespace {

std::string error_of(std::string_view url) {
  auto made = make_source(url);
  if (auto* error = std::get_if<std::string>(&made)) return *error;
  return "(accepted)";
}

TEST(SourceUrl, SplitsSchemeRestAndQuery) {
  auto parsed = parse_source_url("VICON://10.0.0.2:801?mode=pull&&x=");
  ASSERT_TRUE(std::holds_alternative<SourceUrl>(parsed));
  const auto& url = std::get<SourceUrl>(parsed);
  EXPECT_EQ(url.scheme, "vicon");
  EXPECT_EQ(url.rest, "10.0.0.2:801");
  ASSERT_EQ(url.query.size(), 2u);
  EXPECT_EQ(url.query[0], (std::pair<std::string, std::string>{"mode", "pull"}));
  EXPECT_EQ(url.query[1], (std::pair<std::string, std::string>{"x", ""}));

  EXPECT_NE(std::get<std::string>(parse_source_url("sim")).find("not a source URL"),
            std::string::npos);
  EXPECT_NE(std::get<std::string>(parse_source_url("://x")).find("not a source URL"),
            std::string::npos);
  EXPECT_NE(std::get<std::string>(parse_source_url("sim://?bodies")).find("'bodies' is not key="),
            std::string::npos);
}

TEST(MakeSource, BuildsSimAndReplay) {
  auto sim = make_source("sim://?bodies=2&seed=3");
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(sim)) << std::get<std::string>(sim);
  EXPECT_EQ(std::get<std::unique_ptr<Source>>(sim)->url(), "sim://?bodies=2&seed=3");
  EXPECT_TRUE(std::holds_alternative<std::unique_ptr<Source>>(make_source("sim://")));
}

TEST(MakeSource, OneClearMessagePerBadUrl) {
  EXPECT_NE(error_of("sim://?bodys=3").find("unknown key 'bodys'"), std::string::npos);
  EXPECT_NE(error_of("sim://?rate_hz=0").find("rate_hz must be"), std::string::npos);
  EXPECT_NE(error_of("sim://host").find("takes no host"), std::string::npos);
  EXPECT_NE(error_of("replay:///nonexistent.csv").find("cannot open '/nonexistent.csv'"),
            std::string::npos);
  EXPECT_NE(error_of("replay://x.csv?speed=-2").find("speed='-2'"), std::string::npos);
  EXPECT_NE(error_of("ftp://x").find("unknown source scheme 'ftp://'"), std::string::npos);
  EXPECT_NE(error_of("ftp://x").find("available: sim, replay"), std::string::npos);
}

}  // namespace
}  // namespace mocaplink::sources
