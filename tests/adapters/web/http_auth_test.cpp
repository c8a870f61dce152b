// Access rules as pure functions (docs/api.md "Authentication").
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

}  // namespace
}  // namespace mocaplink::web
