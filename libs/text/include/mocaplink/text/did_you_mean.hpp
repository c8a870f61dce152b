// "Did you mean" suggestions for misspelled names (config keys, URL options, API keys): the one
// edit distance and closeness rule every parser uses (STYLE.md "Config as a typed schema").
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mocaplink::text {

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

}  // namespace mocaplink::text
