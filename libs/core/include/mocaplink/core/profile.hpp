// Message profiles and message kinds: which MAVLink messages a vehicle's Sender emits (DESIGN.md
// "Message profiles", protocols/autopilots.md §12; every field is described in docs/messages.md).
//
// This header holds the light, value-level view (names, sets, rules) that the config, the web API
// and the apps use. The facts about each message kind — config name, MAVLink id and name, frame
// size, GPS / vision role and builder — live in ONE table, kMessages in message_table.hpp; the
// profiles live in ONE table in profile.cpp (kProfiles):
//
//   profile        pose / GPS messages                          SET_GPS_GLOBAL_ORIGIN
//   px4            ODOMETRY                                     until confirmed (origin set)
//   ardupilot      ODOMETRY                                     until confirmed (origin set)
//   px4-gps        HIL_GPS                                      no (the fake GPS is the origin)
//   ardupilot-gps  GPS_INPUT                                    no (the first fix sets it, §3.5)
//   classic        HIL_GPS, LOCAL_POSITION_NED, ATT_POS_MOCAP   no (as the original tool)
//   custom         the configured list                          if it holds a vision message
//   auto           ODOMETRY (as px4 and ardupilot: the same      until confirmed (origin set)
//                  frame suits both); the set-up rules follow the vehicle's autopilot, from its
//                  HEARTBEAT (vehicle_setup.hpp)
// Every profile also sends HEARTBEAT at 1 Hz and answers TIMESYNC requests (§12 "Common").
//
// These are the only Profile / MessageKind types: the config parses straight into them and the
// web API spells them with to_string. Thread-safety: plain values and pure functions.
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
enum class Profile : std::uint8_t {
  px4,
  ardupilot,
  px4_gps,
  ardupilot_gps,
  classic,
  custom,
  automatic,  ///< "auto": px4 or ardupilot, whichever the vehicle's heartbeat says it runs
};

/// "px4", "ardupilot", "px4-gps", "ardupilot-gps", "classic", "custom", "auto".
[[nodiscard]] std::string_view to_string(Profile profile);
/// Exactly the spellings of to_string; nullopt for anything else (the config reports errors).
[[nodiscard]] std::optional<Profile> parse_profile(std::string_view text);
/// Every profile's spelling, in the order above (for "did you mean" and the API's lists).
[[nodiscard]] std::span<const std::string_view> profile_names();

/// A pose or fake-GPS message a Sender can emit at rate_hz (HEARTBEAT, TIMESYNC and
/// SET_GPS_GLOBAL_ORIGIN are not in this list: they are driven by the clock and the vehicle).
/// Each enumerator has exactly one row in kMessages (message_table.hpp), in this order; a
/// static_assert there checks the order.
enum class MessageKind : std::uint8_t {
  odometry,                  ///< ODOMETRY (331)
  vision_position_estimate,  ///< VISION_POSITION_ESTIMATE (102)
  vision_speed_estimate,     ///< VISION_SPEED_ESTIMATE (103)
  att_pos_mocap,             ///< ATT_POS_MOCAP (138)
  hil_gps,                   ///< HIL_GPS (113)
  gps_input,                 ///< GPS_INPUT (232)
  local_position_ned,        ///< LOCAL_POSITION_NED (32)
};

/// "odometry", "vision_position_estimate", ... (the config spelling).
[[nodiscard]] std::string_view to_string(MessageKind kind);
/// Exactly the spellings of to_string; nullopt otherwise.
[[nodiscard]] std::optional<MessageKind> parse_message_kind(std::string_view text);
/// Every message kind's spelling, in enum order (for "did you mean" and the API's lists).
[[nodiscard]] std::span<const std::string_view> message_kind_names();
/// Every message kind, in enum order.
[[nodiscard]] std::span<const MessageKind> message_kinds();

/// True for HIL_GPS and GPS_INPUT: fake-GPS messages, which keep being sent while the body is lost
/// (fix_type 0) so that the autopilot sees the fix drop instead of a silent GPS.
[[nodiscard]] bool is_gps(MessageKind kind);
/// True for the messages that carry a geodetic position and therefore need an origin (the GPS
/// messages).
[[nodiscard]] bool needs_origin(MessageKind kind);
/// True for a vision message fused as external navigation (ODOMETRY, VISION_POSITION_ESTIMATE,
/// VISION_SPEED_ESTIMATE, ATT_POS_MOCAP).
[[nodiscard]] bool is_vision(MessageKind kind);

/// A set of MessageKinds, sent in the enum's order (ODOMETRY first) whenever a send is due.
class MessageSet {
 public:
  constexpr MessageSet() = default;
  constexpr MessageSet(std::initializer_list<MessageKind> kinds) {
    for (MessageKind kind : kinds) insert(kind);
  }
  explicit MessageSet(std::span<const MessageKind> kinds);

  [[nodiscard]] constexpr bool contains(MessageKind kind) const { return (bits_ & bit(kind)) != 0; }
  constexpr void insert(MessageKind kind) { bits_ |= bit(kind); }
  constexpr void erase(MessageKind kind) { bits_ &= ~bit(kind); }
  [[nodiscard]] bool empty() const { return bits_ == 0; }
  [[nodiscard]] std::size_t size() const;
  /// True if any member needs a geodetic origin (HIL_GPS, GPS_INPUT).
  [[nodiscard]] bool needs_origin() const;
  /// True if any member is a vision message (is_vision).
  [[nodiscard]] bool has_vision() const;
  friend bool operator==(const MessageSet&, const MessageSet&) = default;

  /// Largest number of message kinds a set can hold (checked against kMessages).
  static constexpr std::size_t kCapacity = 32;

 private:
  static constexpr std::uint32_t bit(MessageKind kind) {
    return std::uint32_t{1} << static_cast<unsigned>(kind);
  }
  std::uint32_t bits_ = 0;
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

/// Largest MAVLink 2 frame of a message kind on the wire: header 10 + its full payload + CRC 2
/// (+ the 13-byte signature when `signed_frames`).
[[nodiscard]] std::size_t max_frame_bytes(MessageKind kind, bool signed_frames = false);

/// Upper bound of the bytes per second a vehicle puts on its link: every message of `messages`
/// at `rate_hz`, plus HEARTBEAT, a TIMESYNC request and reply and SET_GPS_GLOBAL_ORIGIN at 1 Hz
/// each, plus the ATTITUDE and LOCAL_POSITION_NED the agreement check asks the vehicle for at
/// kStreamRateHz (vehicle_streams.hpp; the other direction, which a telemetry radio shares) and
/// the compass heading it may ask for at that rate too (RAW_IMU of ArduPilot profiles, HIGHRES_IMU
/// of px4, the larger where `profile` does not say; none for px4-gps), every frame at its full
/// MAVLink 2 size (and signature). Compared with a serial link's baud / 10 (serial_link_warning).
[[nodiscard]] double link_bytes_per_second(Profile profile, const MessageSet& messages,
                                           double rate_hz, bool signed_frames);

/// Bytes per second a serial link carries at `baud` (8N1: 10 bits a byte).
[[nodiscard]] double serial_bytes_per_second(std::uint32_t baud);

/// The one warning for a vehicle whose messages need more than its serial link carries: "profile
/// P at R Hz needs up to N bytes/s (with the vehicle's ATTITUDE and LOCAL_POSITION_NED at 5 Hz)
/// but B baud carries M: frames will be dropped; lower rate_hz or raise the baud rate"; nullopt
/// when the link keeps up. The config (`check`) and the daemon print it with the vehicle's name in
/// front.
[[nodiscard]] std::optional<std::string> serial_bandwidth_warning(Profile profile,
                                                                  const MessageSet& messages,
                                                                  double rate_hz,
                                                                  bool signed_frames,
                                                                  std::uint32_t baud);

}  // namespace mocaplink::core
