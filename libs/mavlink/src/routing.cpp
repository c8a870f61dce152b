// Target fields of addressed MAVLink messages (routing.hpp).
#include "mocaplink/mavlink/routing.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace mocaplink::mavlink {
namespace {

constexpr std::uint8_t kNoField =
    0xFF;  // no payload offset reaches 255 (payloads are <= 255 bytes)
constexpr bool kBase = false;
constexpr bool kExtension = true;

/// Where one message keeps its target fields: payload byte offsets in wire order (base fields
/// sorted by element size, extensions after, in XML order; mavlink-wire.md §3). Both fields are
/// uint8_t; where a message has both, they are on the same side of <extensions>.
struct TargetOffsets {
  std::uint32_t msgid;
  std::uint8_t system;     ///< offset of target_system
  std::uint8_t component;  ///< offset of target_component, kNoField if the message has none
  bool extension;          ///< the target fields are extension fields: absent from MAVLink 1
};

// Every message with a target_system field in common.xml (with standard.xml and minimal.xml) and
// ardupilotmega.xml, sorted by id. Facts from the MAVLink XML definitions as listed (field offsets,
// extension flags) by npm mavlink-mappings 1.0.21-20250824-1, the tables of node-mavlink 2.3.0
// pinned in package-lock.json; the eight also in libs/mavlink/definitions/messages.json agree.
// tests/conformance/mavlink/node_mavlink_routing.cjs checks every row against node-mavlink.
constexpr auto kTargets = std::to_array<TargetOffsets>({
    {4, 12, 13, kBase},          // PING
    {5, 0, kNoField, kBase},     // CHANGE_OPERATOR_CONTROL
    {11, 4, kNoField, kBase},    // SET_MODE
    {20, 2, 3, kBase},           // PARAM_REQUEST_READ
    {21, 0, 1, kBase},           // PARAM_REQUEST_LIST
    {23, 4, 5, kBase},           // PARAM_SET
    {37, 4, 5, kBase},           // MISSION_REQUEST_PARTIAL_LIST
    {38, 4, 5, kBase},           // MISSION_WRITE_PARTIAL_LIST
    {39, 32, 33, kBase},         // MISSION_ITEM
    {40, 2, 3, kBase},           // MISSION_REQUEST
    {41, 2, 3, kBase},           // MISSION_SET_CURRENT
    {43, 0, 1, kBase},           // MISSION_REQUEST_LIST
    {44, 2, 3, kBase},           // MISSION_COUNT
    {45, 0, 1, kBase},           // MISSION_CLEAR_ALL
    {47, 0, 1, kBase},           // MISSION_ACK
    {48, 12, kNoField, kBase},   // SET_GPS_GLOBAL_ORIGIN
    {50, 18, 19, kBase},         // PARAM_MAP_RC
    {51, 2, 3, kBase},           // MISSION_REQUEST_INT
    {54, 24, 25, kBase},         // SAFETY_SET_ALLOWED_AREA
    {66, 2, 3, kBase},           // REQUEST_DATA_STREAM
    {70, 16, 17, kBase},         // RC_CHANNELS_OVERRIDE
    {73, 32, 33, kBase},         // MISSION_ITEM_INT
    {75, 30, 31, kBase},         // COMMAND_INT
    {76, 30, 31, kBase},         // COMMAND_LONG
    {77, 8, 9, kExtension},      // COMMAND_ACK
    {82, 36, 37, kBase},         // SET_ATTITUDE_TARGET
    {84, 50, 51, kBase},         // SET_POSITION_TARGET_LOCAL_NED
    {86, 50, 51, kBase},         // SET_POSITION_TARGET_GLOBAL_INT
    {110, 1, 2, kBase},          // FILE_TRANSFER_PROTOCOL
    {111, 16, 17, kExtension},   // TIMESYNC
    {117, 4, 5, kBase},          // LOG_REQUEST_LIST
    {119, 10, 11, kBase},        // LOG_REQUEST_DATA
    {121, 0, 1, kBase},          // LOG_ERASE
    {122, 0, 1, kBase},          // LOG_REQUEST_END
    {123, 0, 1, kBase},          // GPS_INJECT_DATA
    {126, 79, 80, kExtension},   // SERIAL_CONTROL
    {139, 41, 42, kBase},        // SET_ACTUATOR_CONTROL_TARGET
    {151, 6, 7, kBase},          // SET_MAG_OFFSETS (ardupilotmega)
    {154, 6, 7, kBase},          // DIGICAM_CONFIGURE (ardupilotmega)
    {155, 4, 5, kBase},          // DIGICAM_CONTROL (ardupilotmega)
    {156, 0, 1, kBase},          // MOUNT_CONFIGURE (ardupilotmega)
    {157, 12, 13, kBase},        // MOUNT_CONTROL (ardupilotmega)
    {158, 12, 13, kBase},        // MOUNT_STATUS (ardupilotmega)
    {160, 8, 9, kBase},          // FENCE_POINT (ardupilotmega)
    {161, 0, 1, kBase},          // FENCE_FETCH_POINT (ardupilotmega)
    {175, 14, 15, kBase},        // RALLY_POINT (ardupilotmega)
    {176, 0, 1, kBase},          // RALLY_FETCH_POINT (ardupilotmega)
    {179, 26, kNoField, kBase},  // CAMERA_STATUS (ardupilotmega)
    {180, 42, kNoField, kBase},  // CAMERA_FEEDBACK (ardupilotmega)
    {183, 0, 1, kBase},          // AUTOPILOT_VERSION_REQUEST (ardupilotmega)
    {184, 4, 5, kBase},          // REMOTE_LOG_DATA_BLOCK (ardupilotmega)
    {185, 4, 5, kBase},          // REMOTE_LOG_BLOCK_STATUS (ardupilotmega)
    {186, 0, 1, kBase},          // LED_CONTROL (ardupilotmega)
    {200, 40, 41, kBase},        // GIMBAL_REPORT (ardupilotmega)
    {201, 12, 13, kBase},        // GIMBAL_CONTROL (ardupilotmega)
    {214, 6, 7, kBase},          // GIMBAL_TORQUE_CMD_REPORT (ardupilotmega)
    {216, 0, 1, kBase},          // GOPRO_GET_REQUEST (ardupilotmega)
    {218, 0, 1, kBase},          // GOPRO_SET_REQUEST (ardupilotmega)
    {243, 52, kNoField, kBase},  // SET_HOME_POSITION
    {248, 3, 4, kBase},          // V2_EXTENSION
    {256, 8, 9, kBase},          // SETUP_SIGNING
    {258, 0, 1, kBase},          // PLAY_TUNE
    {266, 2, 3, kBase},          // LOGGING_DATA
    {267, 2, 3, kBase},          // LOGGING_DATA_ACKED
    {268, 2, 3, kBase},          // LOGGING_ACK
    {282, 32, 33, kBase},        // GIMBAL_MANAGER_SET_ATTITUDE
    {284, 30, 31, kBase},        // GIMBAL_DEVICE_SET_ATTITUDE
    {285, 38, 39, kBase},        // GIMBAL_DEVICE_ATTITUDE_STATUS
    {286, 50, 51, kBase},        // AUTOPILOT_STATE_FOR_GIMBAL_DEVICE
    {287, 20, 21, kBase},        // GIMBAL_MANAGER_SET_PITCHYAW
    {288, 20, 21, kBase},        // GIMBAL_MANAGER_SET_MANUAL_CONTROL
    {320, 2, 3, kBase},          // PARAM_EXT_REQUEST_READ
    {321, 0, 1, kBase},          // PARAM_EXT_REQUEST_LIST
    {323, 0, 1, kBase},          // PARAM_EXT_SET
    {385, 2, 3, kBase},          // TUNNEL
    {386, 4, 5, kBase},          // CAN_FRAME
    {387, 4, 5, kBase},          // CANFD_FRAME
    {388, 32, 33, kBase},        // CAN_FILTER_MODIFY
    {400, 4, 5, kBase},          // PLAY_TUNE_V2
    {401, 4, 5, kBase},          // SUPPORTED_TUNES
    {11000, 4, 5, kBase},        // DEVICE_OP_READ (ardupilotmega)
    {11002, 4, 5, kBase},        // DEVICE_OP_WRITE (ardupilotmega)
    {11004, 8, 9, kBase},        // SECURE_COMMAND (ardupilotmega)
    {11033, 16, 17, kBase},      // OSD_PARAM_CONFIG (ardupilotmega)
    {11035, 4, 5, kBase},        // OSD_PARAM_SHOW_CONFIG (ardupilotmega)
    {12900, 0, 1, kBase},        // OPEN_DRONE_ID_BASIC_ID
    {12901, 30, 31, kBase},      // OPEN_DRONE_ID_LOCATION
    {12902, 4, 5, kBase},        // OPEN_DRONE_ID_AUTHENTICATION
    {12903, 0, 1, kBase},        // OPEN_DRONE_ID_SELF_ID
    {12904, 28, 29, kBase},      // OPEN_DRONE_ID_SYSTEM
    {12905, 0, 1, kBase},        // OPEN_DRONE_ID_OPERATOR_ID
    {12915, 0, 1, kBase},        // OPEN_DRONE_ID_MESSAGE_PACK
    {12919, 16, 17, kBase},      // OPEN_DRONE_ID_SYSTEM_UPDATE
});

static_assert(std::ranges::is_sorted(kTargets, {}, &TargetOffsets::msgid));
static_assert(std::ranges::adjacent_find(kTargets, {}, &TargetOffsets::msgid) == kTargets.end());

/// Byte `offset` of a payload whose missing tail reads as zeros (MAVLink 2 truncation).
std::uint8_t byte_at(std::span<const std::uint8_t> payload, std::size_t offset) noexcept {
  return offset < payload.size() ? payload[offset] : std::uint8_t{0};
}

}  // namespace

std::optional<Target> message_target(std::uint32_t msgid, std::span<const std::uint8_t> payload,
                                     std::uint8_t version) noexcept {
  const auto entry = std::ranges::lower_bound(kTargets, msgid, {}, &TargetOffsets::msgid);
  if (entry == kTargets.end() || entry->msgid != msgid) return std::nullopt;
  if (entry->extension && version == 1) return std::nullopt;
  Target target{.system = byte_at(payload, entry->system)};
  if (entry->component != kNoField) target.component = byte_at(payload, entry->component);
  return target;
}

std::optional<Target> message_target(const FrameView& frame) noexcept {
  return message_target(frame.msgid, frame.payload, frame.version);
}

}  // namespace mocaplink::mavlink
