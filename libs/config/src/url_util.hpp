// The URL splitter (mocaplink/config/url.hpp) under the names the config parsers use internally.
#pragma once

#include "mocaplink/config/url.hpp"

namespace mocaplink::config::detail {

using config::check_query_keys;
using config::split_url;
using config::UrlParts;

}  // namespace mocaplink::config::detail
