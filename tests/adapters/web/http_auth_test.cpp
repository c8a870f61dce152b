// Access rules as pure functions (docs/api.md "Authentication").
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/web/http_auth.hpp"

namespace mocaplink::web {
namespace {

TEST(HttpAuth, LoopbackHosts) {
  for (const char* host : {"127.0.0.1", "127.255.3.4", "localhost", "LocalHost", "::1", "[::1]"}) {
    EXPECT_TRUE(is_loopback_host(host)) << host;
  }
  for (const char* host :
       {"", "0.0.0.0", "::", "192.168.1.3", "128.0.0.1", "127.0.0", "127.0.0.1.5", "127.0.0.256",
        "1270.0.0.1", "127.0.0.1 ", "localhost.evil.com", "::2", "example.org"}) {
    EXPECT_FALSE(is_loopback_host(host)) << host;
  }
}

TEST(HttpAuth, BearerTokenMustMatchExactly) {
  EXPECT_TRUE(bearer_token_matches("Bearer abc123", "abc123"));
  EXPECT_TRUE(bearer_token_matches("bearer abc123", "abc123"));
  EXPECT_FALSE(bearer_token_matches("Bearer abc12", "abc123"));
  EXPECT_FALSE(bearer_token_matches("Bearer abc1234", "abc123"));
  EXPECT_FALSE(bearer_token_matches("Bearer abc123 ", "abc123"));
  EXPECT_FALSE(bearer_token_matches("Bearer ABC123", "abc123"));
  EXPECT_FALSE(bearer_token_matches("Basic abc123", "abc123"));
  EXPECT_FALSE(bearer_token_matches("abc123", "abc123"));
  EXPECT_FALSE(bearer_token_matches("", "abc123"));
  EXPECT_FALSE(bearer_token_matches("Bearer ", ""));  // an empty token never matches
}

TEST(HttpAuth, OriginMustBeTheServerItself) {
  EXPECT_TRUE(origin_allowed("", "127.0.0.1:8080"));  // not a browser
  EXPECT_TRUE(origin_allowed("http://127.0.0.1:8080", "127.0.0.1:8080"));
  EXPECT_TRUE(origin_allowed("https://Lab-PC:8080", "lab-pc:8080"));
  EXPECT_FALSE(origin_allowed("http://127.0.0.1:8081", "127.0.0.1:8080"));
  EXPECT_FALSE(origin_allowed("http://evil.example", "127.0.0.1:8080"));
  EXPECT_FALSE(origin_allowed("null", "127.0.0.1:8080"));
  EXPECT_FALSE(origin_allowed("http://127.0.0.1:8080", ""));
}

TEST(HttpAuth, HostMustNameThisServer) {
  const std::vector<config::HostPort> none;
  for (const char* host : {"127.0.0.1", "127.0.0.1:8080", "127.9.8.7:8080", "localhost",
                           "localhost:8080", "LOCALHOST:8080", "[::1]", "[::1]:8080"}) {
    EXPECT_TRUE(host_allowed(host, 8080, none)) << host;
  }
  for (const char* host : {"",
                           "evil.example",
                           "evil.example:8080",
                           "127.0.0.1:8081",
                           "localhost:80",
                           "[::1]:1",
                           "::1",
                           "[::1",
                           "127.0.0.1:",
                           "127.0.0.1:0",
                           "127.0.0.1:65536",
                           "127.0.0.1:+80",
                           "127.0.0.1 ",
                           " 127.0.0.1",
                           "127.0.0.1\t",
                           "local host",
                           "localhost.",
                           "localhost..",
                           "localhost.evil.example",
                           "127.0.0.1.nip.io",
                           "0x7f.0.0.1",
                           "127.1",
                           "2130706433",
                           "0177.0.0.1:8080",
                           "[127.0.0.1]",
                           "user@127.0.0.1",
                           "127.0.0.1/",
                           "127.0.0.1:8080:8080",
                           "[::ffff:127.0.0.1]",
                           "0.0.0.0:8080",
                           "[::]:8080",
                           "lab-pc:8080"}) {
    EXPECT_FALSE(host_allowed(host, 8080, none)) << host;
  }
}

TEST(HttpAuth, AllowedHostsAddNamesWithTheirPorts) {
  const std::vector<config::HostPort> allowed = {
      {"lab-pc", 0}, {"10.0.0.5", 0}, {"tunnel", 9000}, {"fe80::1", 0}};
  for (const char* host : {"lab-pc", "lab-pc:8080", "LAB-PC:8080", "10.0.0.5:8080", "tunnel:9000",
                           "[fe80::1]:8080", "localhost:8080"}) {
    EXPECT_TRUE(host_allowed(host, 8080, allowed)) << host;
  }
  for (const char* host : {"lab-pc:9000", "tunnel", "tunnel:8080", "lab-pc.evil.example",
                           "x.lab-pc", "10.0.0.6:8080", "[fe80::2]", "fe80::1"}) {
    EXPECT_FALSE(host_allowed(host, 8080, allowed)) << host;
  }
}

TEST(HttpAuth, TheHostRefusalNamesTheHostSafely) {
  const std::string plain = host_refusal("evil.example:8080");
  EXPECT_NE(plain.find("Host \"evil.example:8080\""), std::string::npos) << plain;
  EXPECT_NE(plain.find("[http] allowed_hosts"), std::string::npos) << plain;
  EXPECT_NE(plain.find("--http-allow-host"), std::string::npos) << plain;
  const std::string odd = host_refusal(std::string_view("a\x01\xff\nb", 5));
  EXPECT_NE(odd.find("Host \"a???b\""), std::string::npos) << odd;
  const std::string huge = host_refusal(std::string(1000, 'x'));
  EXPECT_NE(huge.find(std::string(100, 'x') + "...\""), std::string::npos);
  EXPECT_EQ(huge.find(std::string(101, 'x')), std::string::npos);
  EXPECT_NE(host_refusal(std::nullopt).find("exactly one Host header"), std::string::npos);
}

}  // namespace
}  // namespace mocaplink::web
