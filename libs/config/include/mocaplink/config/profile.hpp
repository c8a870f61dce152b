// Parsing `profile = "..."` and `messages = [...]` of a [[vehicle]] straight into the core's
// types (DESIGN.md "Message profiles", protocols/autopilots.md §12). The names, the message table
// and which messages a profile sends belong to the core (mocaplink/core/profile.hpp); this only
// adds the configuration's error messages ("did you mean").
#pragma once

#include <string_view>

#include "mocaplink/config/value_or_error.hpp"
#include "mocaplink/core/profile.hpp"

namespace mocaplink::config {

/// Parses core::to_string's spellings; the error names the closest one ("did you mean").
[[nodiscard]] ValueOrError<core::Profile> parse_profile(std::string_view text);
/// Parses core::to_string's spellings of a message kind; the error names the closest one.
[[nodiscard]] ValueOrError<core::MessageKind> parse_message_kind(std::string_view text);

}  // namespace mocaplink::config
