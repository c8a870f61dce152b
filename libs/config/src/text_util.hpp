// Small text helpers shared by the config parsers: "did you mean" suggestions, number formatting,
// lists of names. Internal to libs/config.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mocaplink::config::detail {

/// Optimal-string-alignment distance (insertions, deletions, substitutions and adjacent
/// transpositions each cost 1), ASCII case-insensitive.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word`, if close enough to be a plausible typo: within 1 edit for
/// words of up to 4 characters, 2 up to 8, 3 beyond; or a prefix of it (or it of the candidate)
/// of at least 3 characters. Ties go to the earlier candidate.
[[nodiscard]] std::optional<std::string_view> closest_match(
    std::string_view word, std::span<const std::string_view> candidates);

/// `; did you mean "x"?` or "" when nothing is close.
[[nodiscard]] std::string did_you_mean(std::string_view word,
                                       std::span<const std::string_view> candidates);

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
