#include "mocaplink/config/url.hpp"

#include <cmath>

#include "text_util.hpp"

namespace mocaplink::config {

using detail::quoted;

ValueOrError<UrlParts> split_url(std::string_view text) {
  using Result = ValueOrError<UrlParts>;
  const auto sep = text.find("://");
  if (sep == std::string_view::npos || sep == 0) return Result::failure("missing SCHEME://");
  UrlParts parts;
  parts.scheme = text.substr(0, sep);
  const auto rest = text.substr(sep + 3);
  const auto question = rest.find('?');
  parts.body = rest.substr(0, question);
  if (question == std::string_view::npos) return parts;
  std::string_view query = rest.substr(question + 1);
  while (!query.empty()) {
    const auto amp = query.find('&');
    const auto item = query.substr(0, amp);
    const auto eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0) {
      return Result::failure("query item " + quoted(item) + " is not KEY=VALUE");
    }
    const auto key = item.substr(0, eq);
    for (const auto& [seen, value] : parts.query) {
      if (seen == key) return Result::failure("option " + quoted(key) + " is given twice");
    }
    parts.query.emplace_back(key, item.substr(eq + 1));
    if (amp == std::string_view::npos) break;
    query = query.substr(amp + 1);
  }
  return parts;
}

std::string check_query_keys(const UrlParts& parts, std::span<const std::string_view> allowed_keys,
                             std::string_view what) {
  for (const auto& [key, value] : parts.query) {
    bool known = false;
    for (const auto allowed : allowed_keys) known = known || key == allowed;
    if (known) continue;
    if (allowed_keys.empty()) return std::string(what) + " takes no options, got " + quoted(key);
    return "unknown option " + quoted(key) + " for " + std::string(what) +
           detail::did_you_mean(key, allowed_keys) + " (options: " + detail::join(allowed_keys) +
           ")";
  }
  return {};
}

std::string read_number_option(std::string_view key, std::string_view text, double low, double high,
                               bool low_inclusive, double& out) {
  const auto value = detail::parse_double(text);
  const bool ok = value && std::isfinite(*value) &&
                  (low_inclusive ? *value >= low : *value > low) && *value <= high;
  if (!ok) {
    return std::string(key) + " must be a number " + (low_inclusive ? "from " : "above ") +
           detail::format_number(low) + (low_inclusive ? " to " : " up to ") +
           detail::format_number(high) + ", got " + quoted(text);
  }
  out = *value;
  return {};
}

std::string read_count_option(std::string_view key, std::string_view text, std::uint64_t low,
                              std::uint64_t high, std::uint64_t& out) {
  const auto value = detail::parse_integer(text);
  if (!value || *value < 0 || static_cast<std::uint64_t>(*value) < low ||
      static_cast<std::uint64_t>(*value) > high) {
    return std::string(key) + " must be an integer from " + std::to_string(low) + " to " +
           std::to_string(high) + ", got " + quoted(text);
  }
  out = static_cast<std::uint64_t>(*value);
  return {};
}

std::string quote(std::string_view text) {
  return quoted(text);
}

std::string suggest(std::string_view word, std::span<const std::string_view> candidates) {
  return detail::did_you_mean(word, candidates);
}

std::string format_number(double value) {
  return detail::format_number(value);
}

std::string join_names(std::span<const std::string_view> names) {
  return detail::join(names);
}

}  // namespace mocaplink::config
