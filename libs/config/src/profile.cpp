#include "mocaplink/config/profile.hpp"

#include <array>
#include <string>

#include "text_util.hpp"

namespace mocaplink::config {
namespace {

// Index order matches the enums.
constexpr std::array<std::string_view, 6> kProfileNames = {"px4",           "ardupilot", "px4-gps",
                                                           "ardupilot-gps", "classic",   "custom"};
constexpr std::array<std::string_view, 7> kMessageNames = {
    "odometry",  "vision_position_estimate", "vision_speed_estimate", "att_pos_mocap", "hil_gps",
    "gps_input", "local_position_ned"};

template <typename Enum, std::size_t N>
ValueOrError<Enum> parse_name(std::string_view text, const std::array<std::string_view, N>& names,
                              std::string_view what) {
  for (std::size_t i = 0; i < N; ++i) {
    if (text == names[i]) return static_cast<Enum>(i);
  }
  return ValueOrError<Enum>::failure("unknown " + std::string(what) + " " + detail::quoted(text) +
                                     detail::did_you_mean(text, names) +
                                     " (one of: " + detail::join(names) + ")");
}

}  // namespace

const char* to_string(Profile profile) {
  return kProfileNames.at(static_cast<std::size_t>(profile)).data();
}

ValueOrError<Profile> parse_profile(std::string_view text) {
  return parse_name<Profile>(text, kProfileNames, "profile");
}

const char* to_string(MessageKind kind) {
  return kMessageNames.at(static_cast<std::size_t>(kind)).data();
}

ValueOrError<MessageKind> parse_message_kind(std::string_view text) {
  return parse_name<MessageKind>(text, kMessageNames, "message");
}

bool needs_origin(Profile profile) {
  return profile == Profile::px4_gps || profile == Profile::ardupilot_gps ||
         profile == Profile::classic;
}

bool needs_origin(MessageKind kind) {
  return kind == MessageKind::hil_gps || kind == MessageKind::gps_input;
}

}  // namespace mocaplink::config
