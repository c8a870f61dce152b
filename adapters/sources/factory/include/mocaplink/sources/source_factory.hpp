// Source URLs → Sources (DESIGN.md "Source URLs"). The single place that knows every scheme, so
// `bodies`, `record`, `run` and the config checker accept exactly the same URLs.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

/// A URL split as `scheme://rest?key=value&key=value`. No percent-decoding: values are literal.
struct SourceUrl {
  std::string scheme;  ///< lower-cased, e.g. "sim", "vicon"
  std::string rest;    ///< host[:port] or path, between "://" and '?'
  std::vector<std::pair<std::string, std::string>> query;  ///< in order; empty parts skipped
};

/// Splits a URL; errors ("not a source URL ...", "query part 'x' is not key=value") are returned
/// as the string alternative. Pure; thread-safe.
[[nodiscard]] std::variant<SourceUrl, std::string> parse_source_url(std::string_view url);

/// Builds the Source for `url` without starting it. Every configuration problem — unknown
/// scheme, a scheme not built into this binary, unknown query key, out-of-range value, a replay
/// file that cannot be opened or is not a recording — is returned as a one-line message, so
/// callers can exit 1 before anything runs. A reachable-or-not network source is not probed here
/// (that shows as its connection state). Thread-safe.
[[nodiscard]] std::variant<std::unique_ptr<Source>, std::string> make_source(std::string_view url);

/// Schemes this binary can open, e.g. {"sim", "replay", "vicon"}.
[[nodiscard]] std::vector<std::string> available_source_schemes();

}  // namespace mocaplink::sources
