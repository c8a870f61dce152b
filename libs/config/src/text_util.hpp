// Small text helpers shared by the config parsers: number formatting, lists of names, and the
// "did you mean" suggestions of mocaplink::text. Internal to libs/config.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mocaplink/text/did_you_mean.hpp"

namespace mocaplink::config::detail {

using text::closest_match;
using text::did_you_mean;

/// "a, b, c".
[[nodiscard]] std::string join(std::span<const std::string_view> words,
                               std::string_view sep = ", ");

/// Shortest decimal that round-trips ("50", "0.3", "1e+20").
[[nodiscard]] std::string format_number(double value);

/// `"text"` with control characters and quotes escaped, cut to 60 characters, for messages.
[[nodiscard]] std::string quoted(std::string_view text);

/// Full-match parses; nullopt unless the whole text is a number of that type.
[[nodiscard]] std::optional<long long> parse_integer(std::string_view text);
[[nodiscard]] std::optional<double> parse_double(std::string_view text);

}  // namespace mocaplink::config::detail
