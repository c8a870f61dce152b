// Helpers shared by the source-URL tests: parse a URL with a source's own option parser, and what
// the registry's check says of a URL.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "mocaplink/config/url.hpp"
#include "mocaplink/sources/registry.hpp"

namespace mocaplink::sources::test {

/// Splits `url` (which must split) and hands it to `parse`; the URL text outlives the parts.
template <typename Options>
config::ValueOrError<Options> parse(config::ValueOrError<Options> (*parse)(const config::UrlParts&),
                                    const std::string& url) {
  auto parts = config::split_url(url);
  EXPECT_TRUE(parts) << url;
  return parse(parts.value());
}

/// The options `parse` makes of `url`, which must be accepted (defaults otherwise, after a
/// failure is recorded).
template <typename Options>
Options parsed(config::ValueOrError<Options> (*parse_options)(const config::UrlParts&),
               const std::string& url) {
  auto out = parse(parse_options, url);
  EXPECT_TRUE(out) << out.error();
  return out ? out.value() : Options{};
}

/// The registry's error for `url` ("" when accepted).
inline std::string check_error(const char* url) {
  return builtin_sources().check(url).error;
}

}  // namespace mocaplink::sources::test
