// Message profiles: which MAVLink messages a vehicle's Sender emits (DESIGN.md "Message profiles",
// protocols/autopilots.md §12; every field is described in docs/messages.md).
//
//   profile        pose / GPS messages                          SET_GPS_GLOBAL_ORIGIN
//   px4            ODOMETRY                                     until confirmed (origin set)
//   ardupilot      ODOMETRY                                     until confirmed (origin set)
//   px4-gps        HIL_GPS                                      no (the fake GPS is the origin)
//   ardupilot-gps  GPS_INPUT                                    no (the first fix sets it, §3.5)
//   classic        HIL_GPS, LOCAL_POSITION_NED, ATT_POS_MOCAP   no (as the original tool)
//   custom         the configured list                          if it holds a vision message
// Every profile also sends HEARTBEAT at 1 Hz and answers TIMESYNC requests (§12 "Common").
//
// This is the core's own copy of the profile names: libs/core does not depend on libs/config; the
// app maps config::Profile / config::MessageKind to these one to one (same spellings).
// Thread-safety: plain values and pure functions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mocaplink::core {

/// `profile = "..."` of a vehicle.
enum class Profile : std::uint8_t { px4, ardupilot, px4_gps, ardupilot_gps, classic, custom };

/// "px4", "ardupilot", "px4-gps", "ardupilot-gps", "classic", "custom".
[[nodiscard]] std::string_view to_string(Profile profile);
/// Exactly the spellings of to_string; nullopt for anything else (the config reports errors).
[[nodiscard]] std::optional<Profile> parse_profile(std::string_view text);

/// A pose or fake-GPS message a Sender can emit at rate_hz (HEARTBEAT, TIMESYNC and
/// SET_GPS_GLOBAL_ORIGIN are not in this list: they are driven by the clock and the vehicle).
enum class MessageKind : std::uint8_t {
  odometry,                  ///< ODOMETRY (331)
  vision_position_estimate,  ///< VISION_POSITION_ESTIMATE (102)
  vision_speed_estimate,     ///< VISION_SPEED_ESTIMATE (103)
  att_pos_mocap,             ///< ATT_POS_MOCAP (138)
  hil_gps,                   ///< HIL_GPS (113)
  gps_input,                 ///< GPS_INPUT (232)
  local_position_ned,        ///< LOCAL_POSITION_NED (32)
};
inline constexpr std::size_t kMessageKindCount = 7;

/// "odometry", "vision_position_estimate", ... (the config spelling).
[[nodiscard]] std::string_view to_string(MessageKind kind);
/// Exactly the spellings of to_string; nullopt otherwise.
[[nodiscard]] std::optional<MessageKind> parse_message_kind(std::string_view text);

/// True for HIL_GPS and GPS_INPUT: fake-GPS messages, which keep being sent while the body is lost
/// (fix_type 0) so that the autopilot sees the fix drop instead of a silent GPS.
[[nodiscard]] bool is_gps(MessageKind kind);
/// True for the messages that carry a geodetic position and therefore need an origin.
[[nodiscard]] bool needs_origin(MessageKind kind);

/// A set of MessageKinds, sent in the enum's order (ODOMETRY first) whenever a send is due.
class MessageSet {
 public:
  constexpr MessageSet() = default;
  MessageSet(std::initializer_list<MessageKind> kinds);
  explicit MessageSet(std::span<const MessageKind> kinds);

  [[nodiscard]] bool contains(MessageKind kind) const { return (bits_ & bit(kind)) != 0; }
  void insert(MessageKind kind) { bits_ = static_cast<std::uint8_t>(bits_ | bit(kind)); }
  void erase(MessageKind kind) { bits_ = static_cast<std::uint8_t>(bits_ & ~bit(kind)); }
  [[nodiscard]] bool empty() const { return bits_ == 0; }
  [[nodiscard]] std::size_t size() const;
  /// True if any member needs a geodetic origin (HIL_GPS, GPS_INPUT).
  [[nodiscard]] bool needs_origin() const;
  /// True if any member is a vision message fused as external navigation (ODOMETRY,
  /// VISION_POSITION_ESTIMATE, VISION_SPEED_ESTIMATE, ATT_POS_MOCAP).
  [[nodiscard]] bool has_vision() const;
  friend bool operator==(const MessageSet&, const MessageSet&) = default;

 private:
  static constexpr std::uint8_t bit(MessageKind kind) {
    return static_cast<std::uint8_t>(1U << static_cast<unsigned>(kind));
  }
  std::uint8_t bits_ = 0;
};

/// "odometry,hil_gps": members in enum order, comma-separated; "" when empty.
[[nodiscard]] std::string to_string(const MessageSet& set);

/// The message set of a profile (table above). For Profile::custom, `custom` is the configured
/// list (duplicates collapse); it is ignored for every other profile.
[[nodiscard]] MessageSet messages_for(Profile profile, std::span<const MessageKind> custom = {});

/// Whether the profile sends SET_GPS_GLOBAL_ORIGIN until the vehicle confirms it (table above).
/// For custom: when `messages` holds a vision message. Always false without a configured origin
/// (the Bridge checks that).
[[nodiscard]] bool sends_origin(Profile profile, const MessageSet& messages);

}  // namespace mocaplink::core
