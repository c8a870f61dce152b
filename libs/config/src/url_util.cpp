#include "url_util.hpp"

#include "text_util.hpp"

namespace mocaplink::config::detail {

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
           did_you_mean(key, allowed_keys) + " (options: " + join(allowed_keys) + ")";
  }
  return {};
}

}  // namespace mocaplink::config::detail
