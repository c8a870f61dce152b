// Splitting of "scheme://body?k=v&k=v" URLs, shared by the link URL parser (libs/config) and every
// source's option parser (adapters/sources/<name>/), plus the option readers they share so that
// every URL reports a bad value in the same words. No percent-decoding: values are taken
// literally. Pure and thread-safe.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

struct UrlParts {
  std::string_view scheme;                                           ///< before "://"
  std::string_view body;                                             ///< between "://" and '?'
  std::vector<std::pair<std::string_view, std::string_view>> query;  ///< in order
};

/// Splits a URL. Fails on a missing "://", on query items without '=', on empty keys and on a key
/// given twice.
[[nodiscard]] ValueOrError<UrlParts> split_url(std::string_view text);

/// "" when every query key is in `allowed_keys`; else the first unknown key, with the closest
/// allowed spelling. `what` names the URL kind in messages ("vicon://").
[[nodiscard]] std::string check_query_keys(const UrlParts& parts,
                                           std::span<const std::string_view> allowed_keys,
                                           std::string_view what);

/// Reads a number option in (low, high] or [low, high]; "" on success, else
/// "KEY must be a number from LOW to HIGH, got \"TEXT\"".
[[nodiscard]] std::string read_number_option(std::string_view key, std::string_view text,
                                             double low, double high, bool low_inclusive,
                                             double& out);

/// Reads a whole number option in [low, high]; "" on success.
[[nodiscard]] std::string read_count_option(std::string_view key, std::string_view text,
                                            std::uint64_t low, std::uint64_t high,
                                            std::uint64_t& out);

/// `text` in double quotes, control characters escaped: how messages quote what the user wrote.
[[nodiscard]] std::string quote(std::string_view text);

/// "; did you mean \"X\"?" for the closest of `candidates`, or "" when none is close.
[[nodiscard]] std::string suggest(std::string_view word,
                                  std::span<const std::string_view> candidates);

/// Shortest decimal that round-trips ("50", "0.3", "1e+20").
[[nodiscard]] std::string format_number(double value);

/// "a, b, c".
[[nodiscard]] std::string join_names(std::span<const std::string_view> names);

}  // namespace mocaplink::config
