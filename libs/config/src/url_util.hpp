// Splitting of "scheme://rest?k=v&k=v" URLs shared by the link and source URL parsers.
// Internal to libs/config. No percent-decoding: values are taken literally.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config::detail {

struct UrlParts {
  std::string_view scheme;                                           ///< before "://"
  std::string_view body;                                             ///< between "://" and '?'
  std::vector<std::pair<std::string_view, std::string_view>> query;  ///< in order
};

/// Splits a URL. Fails on a missing "://", on query items without '=', on empty keys and on a key
/// given twice. `allowed_keys` are the only query keys accepted; an unknown key's error suggests
/// the closest. `what` names the URL kind in messages ("vicon://").
[[nodiscard]] ValueOrError<UrlParts> split_url(std::string_view text);
[[nodiscard]] std::string check_query_keys(const UrlParts& parts,
                                           std::span<const std::string_view> allowed_keys,
                                           std::string_view what);

}  // namespace mocaplink::config::detail
