// Source URLs → Sources (DESIGN.md "Source URLs"). URLs are parsed by config::parse_source_url,
// the one parser the config checker also uses, so `check`, `bodies`, `record`, `serve` and `run`
// accept exactly the same URLs; this is the one place that knows which sources are built in.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "mocaplink/config/source_url.hpp"
#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

/// Builds the Source for `url` without starting it. Every configuration problem — the URL's own
/// (config::parse_source_url), a scheme not built into this binary, a replay file that cannot be
/// opened or is not a recording — is returned as a one-line message, so callers can exit 1
/// before anything runs. A reachable-or-not network source is not probed here (that shows as its
/// connection state). Thread-safe.
[[nodiscard]] std::variant<std::unique_ptr<Source>, std::string> make_source(
    const config::SourceUrl& url);
/// parse_source_url, then make_source.
[[nodiscard]] std::variant<std::unique_ptr<Source>, std::string> make_source(std::string_view url);

/// Schemes this binary can open, e.g. {"sim", "replay", "vicon"}.
[[nodiscard]] std::vector<std::string> available_source_schemes();

}  // namespace mocaplink::sources
