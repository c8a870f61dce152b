#include "mocaplink/core/profile.hpp"

#include <array>
#include <utility>

namespace mocaplink::core {
namespace {

constexpr std::array<std::pair<Profile, std::string_view>, 6> kProfileNames{{
    {Profile::px4, "px4"},
    {Profile::ardupilot, "ardupilot"},
    {Profile::px4_gps, "px4-gps"},
    {Profile::ardupilot_gps, "ardupilot-gps"},
    {Profile::classic, "classic"},
    {Profile::custom, "custom"},
}};

constexpr std::array<std::pair<MessageKind, std::string_view>, kMessageKindCount> kKindNames{{
    {MessageKind::odometry, "odometry"},
    {MessageKind::vision_position_estimate, "vision_position_estimate"},
    {MessageKind::vision_speed_estimate, "vision_speed_estimate"},
    {MessageKind::att_pos_mocap, "att_pos_mocap"},
    {MessageKind::hil_gps, "hil_gps"},
    {MessageKind::gps_input, "gps_input"},
    {MessageKind::local_position_ned, "local_position_ned"},
}};

}  // namespace

std::string_view to_string(Profile profile) {
  for (const auto& [value, name] : kProfileNames) {
    if (value == profile) return name;
  }
  return "unknown";
}

std::optional<Profile> parse_profile(std::string_view text) {
  for (const auto& [value, name] : kProfileNames) {
    if (name == text) return value;
  }
  return std::nullopt;
}

std::string_view to_string(MessageKind kind) {
  for (const auto& [value, name] : kKindNames) {
    if (value == kind) return name;
  }
  return "unknown";
}

std::optional<MessageKind> parse_message_kind(std::string_view text) {
  for (const auto& [value, name] : kKindNames) {
    if (name == text) return value;
  }
  return std::nullopt;
}

bool is_gps(MessageKind kind) {
  return kind == MessageKind::hil_gps || kind == MessageKind::gps_input;
}

bool needs_origin(MessageKind kind) {
  return is_gps(kind);
}

MessageSet::MessageSet(std::initializer_list<MessageKind> kinds) {
  for (MessageKind kind : kinds) insert(kind);
}

MessageSet::MessageSet(std::span<const MessageKind> kinds) {
  for (MessageKind kind : kinds) insert(kind);
}

std::size_t MessageSet::size() const {
  std::size_t n = 0;
  for (const auto& entry : kKindNames) n += contains(entry.first) ? std::size_t{1} : 0;
  return n;
}

bool MessageSet::needs_origin() const {
  return contains(MessageKind::hil_gps) || contains(MessageKind::gps_input);
}

bool MessageSet::has_vision() const {
  return contains(MessageKind::odometry) || contains(MessageKind::vision_position_estimate) ||
         contains(MessageKind::vision_speed_estimate) || contains(MessageKind::att_pos_mocap);
}

std::string to_string(const MessageSet& set) {
  std::string text;
  for (const auto& [kind, name] : kKindNames) {
    if (!set.contains(kind)) continue;
    if (!text.empty()) text += ',';
    text += name;
  }
  return text;
}

MessageSet messages_for(Profile profile, std::span<const MessageKind> custom) {
  switch (profile) {
    case Profile::px4:
    case Profile::ardupilot:
      // autopilots.md §12.1/§12.2: ODOMETRY LOCAL_FRD/BODY_FRD, estimator VISION, for both.
      return MessageSet{MessageKind::odometry};
    case Profile::px4_gps:
      return MessageSet{MessageKind::hil_gps};  // §12.3
    case Profile::ardupilot_gps:
      return MessageSet{MessageKind::gps_input};  // §12.4
    case Profile::classic:
      // §12.5: the original ViconMAVLink set, with its defects fixed.
      return MessageSet{MessageKind::hil_gps, MessageKind::local_position_ned,
                        MessageKind::att_pos_mocap};
    case Profile::custom:
      return MessageSet{custom};
  }
  return {};
}

bool sends_origin(Profile profile, const MessageSet& messages) {
  switch (profile) {
    case Profile::px4:
    case Profile::ardupilot:
      return true;  // §3.9, §12.1, §12.2: vision-only vehicles need the EKF origin set
    case Profile::px4_gps:
    case Profile::ardupilot_gps:
    case Profile::classic:
      return false;  // the fake GPS defines the origin (§3.5: first fix sets it)
    case Profile::custom:
      return messages.has_vision();
  }
  return false;
}

}  // namespace mocaplink::core
