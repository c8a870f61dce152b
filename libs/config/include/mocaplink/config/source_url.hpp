// The `[mocap] source` value (DESIGN.md "Source URLs"). The configuration keeps it as written,
// with its scheme; what a scheme's options mean is the business of that source's own folder
// (adapters/sources/<name>/), which the caller hands in as a SourceValidator. libs/config never
// knows which sources exist, so `check` and `run`, both validating through the caller's source
// registry, accept exactly the same URLs.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

/// A source URL as written in [mocap] source or --source. Syntax only: SCHEME://… .
struct SourceUrl {
  std::string text;    ///< the URL as written, for display and for opening the source
  std::string scheme;  ///< before "://", e.g. "vicon"
};

/// Checks only the shape SCHEME://[BODY][?KEY=VALUE&…] (what every source URL shares).
[[nodiscard]] ValueOrError<SourceUrl> parse_source_url(std::string_view text);

/// Facts of [mocap] that a source's configuration warnings may depend on.
struct SourceContext {
  bool up_written = false;  ///< [mocap] up was given (otherwise the default +z applies)
};

/// A source validator's verdict on one URL.
struct SourceCheck {
  std::string error;                  ///< "" when the URL is valid
  std::vector<std::string> warnings;  ///< valid but probably not what the user meant
};

/// Validates a source URL: an unknown scheme, a malformed body or a bad option is an error, located
/// at the [mocap] source key (or --source). Supplied by the caller (adapters/sources: the source
/// registry); an empty validator checks the shape only (parse_source_url).
using SourceValidator = std::function<SourceCheck(std::string_view url, const SourceContext&)>;

}  // namespace mocaplink::config
