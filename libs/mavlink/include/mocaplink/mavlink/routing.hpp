// MAVLink routing facts: where a message is addressed, read from its payload as on the wire.
//
//   std::optional<Target> t = message_target(frame);              // a FrameView from the parser
//   std::optional<Target> t = message_target(msgid, payload, 2);  // raw id and payload bytes
//
// A message is addressed when its definition has a `target_system` field (the rule of the MAVLink
// routing guide, en/guide/routing.md, and of mavlink-router and the C library's message entries);
// every other message is for everyone (broadcast). Known: every message of common.xml (with
// standard.xml and minimal.xml) and of ardupilotmega.xml that has `target_system`, 93 messages,
// including those whose target fields are extensions (COMMAND_ACK, TIMESYNC, SERIAL_CONTROL).
// Other dialects' messages (development, storm32, ASLUAV, cubepilot, ...) and unknown ids read as
// not addressed. Deciding where to forward (which endpoint has seen which system) is the caller's.
// Thread-safety: pure functions over an immutable table.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::mavlink {

/// The target of an addressed message: its `target_system` and `target_component` fields.
struct Target {
  std::uint8_t system = 0;     ///< target_system; 0 = every system (broadcast)
  std::uint8_t component = 0;  ///< target_component; 0 = every component of `system`, also
                               ///< when the message has no target_component field (SET_MODE, ...)
  friend bool operator==(const Target&, const Target&) = default;
};

/// The target of message `msgid` whose payload on the wire is `payload`, from a MAVLink `version`
/// 1 or 2 frame; nullopt if the message has no `target_system` field (or an unknown id).
/// A byte past the end of `payload` reads as 0: MAVLink 2 truncates trailing zero bytes, so a
/// COMMAND_LONG to 0/0 with confirmation 0 arrives without its target bytes. MAVLink 1 frames carry
/// no extension fields: a message whose target fields are extensions (COMMAND_ACK 77, TIMESYNC 111,
/// SERIAL_CONTROL 126) has no target there (nullopt), as in the MAVLink 1 definition. Bytes past
/// the fields (a newer definition's extensions) are ignored. Any `payload` and `msgid` are safe; a
/// `version` other than 1 is read as 2.
[[nodiscard]] std::optional<Target> message_target(std::uint32_t msgid,
                                                   std::span<const std::uint8_t> payload,
                                                   std::uint8_t version) noexcept;

/// The target of the message in `frame` (its msgid, payload and version); see above. Works for
/// frames of unknown message id too (frame.info == nullptr): the table is wider than messages.hpp.
[[nodiscard]] std::optional<Target> message_target(const FrameView& frame) noexcept;

}  // namespace mocaplink::mavlink
