#include "mocaplink/config/profile.hpp"

#include <optional>
#include <span>
#include <string>

#include "text_util.hpp"

namespace mocaplink::config {
namespace {

template <typename Enum>
ValueOrError<Enum> parse_name(std::string_view text, const std::optional<Enum>& parsed,
                              std::span<const std::string_view> names, std::string_view what) {
  if (parsed) return *parsed;
  return ValueOrError<Enum>::failure("unknown " + std::string(what) + " " + detail::quoted(text) +
                                     detail::did_you_mean(text, names) +
                                     " (one of: " + detail::join(names) + ")");
}

}  // namespace

ValueOrError<core::Profile> parse_profile(std::string_view text) {
  return parse_name(text, core::parse_profile(text), core::profile_names(), "profile");
}

ValueOrError<core::MessageKind> parse_message_kind(std::string_view text) {
  return parse_name(text, core::parse_message_kind(text), core::message_kind_names(), "message");
}

}  // namespace mocaplink::config
