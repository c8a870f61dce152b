// The message table: ONE row per output message kind (profile.hpp MessageKind), holding everything
// the rest of the program derives from it — the config / API spelling, the MAVLink id and name,
// the largest frame (bandwidth estimates), the GPS / vision role (when it is sent, whether it needs
// an origin, whether it makes a custom profile send SET_GPS_GLOBAL_ORIGIN) and its builder (what
// the Sender calls). kMessageKindCount, to_string / parse_message_kind, the Sender's dispatch, the
// frame sizes, the dashboard's message list and the dashboard test fake all read this table.
//
// Adding an output message (docs/architecture.md, "Add an output message"): its MAVLink definition
// (libs/mavlink/definitions/messages.json → scripts/gen_mavlink.py), its builder
// (message_builders.hpp/.cpp), an enumerator in MessageKind (profile.hpp) and its row here.
// Thread-safety: constant data and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/message_builders.hpp"
#include "mocaplink/core/profile.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::core {

/// What a builder may use besides the estimate (the Sender fills it on every due send).
struct MessageInputs {
  std::uint64_t time_usec = 0;      ///< host capture time, µs (host_time_usec)
  std::uint32_t time_boot_ms = 0;   ///< ms since the bridge started (wraps at 2^32)
  const GpsContext* gps = nullptr;  ///< non-null with a non-null origin for is_gps kinds
};

/// One output message kind.
struct MessageDescriptor {
  MessageKind kind;
  std::string_view name;          ///< config / API spelling, lower snake case
  std::uint32_t mavlink_id;       ///< MAVLink message id
  std::string_view mavlink_name;  ///< MAVLink XML name ("ODOMETRY")
  std::size_t max_payload;        ///< payload bytes with every extension field
  bool is_gps;                    ///< fake GPS: sent while lost (fix 0), needs an origin
  bool is_vision;                 ///< external-navigation vision message (origin for custom)
  mavlink::Message (*build)(const BodyEstimate& estimate, const MessageInputs& inputs);
};

namespace detail {
/// A row whose MAVLink facts come from the generated message type M.
template <typename M>
constexpr MessageDescriptor message_row(MessageKind kind, std::string_view name, bool gps,
                                        bool vision,
                                        mavlink::Message (*build)(const BodyEstimate&,
                                                                  const MessageInputs&)) {
  return MessageDescriptor{kind, name, M::kId, M::kName, M::kMaxLength, gps, vision, build};
}
}  // namespace detail

// clang-format off
inline constexpr std::array kMessages{
    detail::message_row<mavlink::Odometry>(
        MessageKind::odometry, "odometry", false, true,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_odometry(e, in.time_usec);
        }),
    detail::message_row<mavlink::VisionPositionEstimate>(
        MessageKind::vision_position_estimate, "vision_position_estimate", false, true,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_vision_position_estimate(e, in.time_usec);
        }),
    detail::message_row<mavlink::VisionSpeedEstimate>(
        MessageKind::vision_speed_estimate, "vision_speed_estimate", false, true,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_vision_speed_estimate(e, in.time_usec);
        }),
    detail::message_row<mavlink::AttPosMocap>(
        MessageKind::att_pos_mocap, "att_pos_mocap", false, true,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_att_pos_mocap(e, in.time_usec);
        }),
    detail::message_row<mavlink::HilGps>(
        MessageKind::hil_gps, "hil_gps", true, false,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_hil_gps(e, in.time_usec, *in.gps);
        }),
    detail::message_row<mavlink::GpsInput>(
        MessageKind::gps_input, "gps_input", true, false,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_gps_input(e, in.time_usec, *in.gps);
        }),
    detail::message_row<mavlink::LocalPositionNed>(
        MessageKind::local_position_ned, "local_position_ned", false, false,
        [](const BodyEstimate& e, const MessageInputs& in) -> mavlink::Message {
          return build_local_position_ned(e, in.time_boot_ms);
        }),
};
// clang-format on

/// Number of MessageKinds (the table's size).
inline constexpr std::size_t kMessageKindCount = kMessages.size();

namespace detail {
constexpr bool rows_in_enum_order() {
  for (std::size_t i = 0; i < kMessages.size(); ++i) {
    if (static_cast<std::size_t>(kMessages[i].kind) != i) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::rows_in_enum_order(), "kMessages rows must follow MessageKind's order");
static_assert(kMessageKindCount <= MessageSet::kCapacity, "MessageSet holds at most 32 kinds");

/// The row of `kind`.
[[nodiscard]] constexpr const MessageDescriptor& describe(MessageKind kind) {
  return kMessages[static_cast<std::size_t>(kind)];
}

}  // namespace mocaplink::core
