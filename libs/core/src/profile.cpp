#include "mocaplink/core/profile.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>

#include "mocaplink/core/message_table.hpp"
#include "mocaplink/core/vehicle_streams.hpp"
#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::core {
namespace {

/// When a profile sends SET_GPS_GLOBAL_ORIGIN (until confirmed, and only with a configured origin).
enum class OriginRule : std::uint8_t { always, never, with_vision };

struct ProfileDescriptor {
  Profile profile;
  std::string_view name;
  MessageSet messages;  ///< ignored for custom (the configured list)
  OriginRule origin;
};

// The profiles: ONE row each, in enum order (autopilots.md §12).
constexpr std::array kProfiles{
    // §12.1/§12.2: ODOMETRY LOCAL_FRD/BODY_FRD, estimator VISION, for both; vision-only vehicles
    // need the EKF origin set (§3.9).
    ProfileDescriptor{Profile::px4, "px4", {MessageKind::odometry}, OriginRule::always},
    ProfileDescriptor{Profile::ardupilot, "ardupilot", {MessageKind::odometry}, OriginRule::always},
    // §12.3, §12.4: the fake GPS defines the origin (§3.5: the first fix sets it).
    ProfileDescriptor{Profile::px4_gps, "px4-gps", {MessageKind::hil_gps}, OriginRule::never},
    ProfileDescriptor{
        Profile::ardupilot_gps, "ardupilot-gps", {MessageKind::gps_input}, OriginRule::never},
    // §12.5: the original ViconMAVLink set, with its defects fixed.
    ProfileDescriptor{
        Profile::classic,
        "classic",
        {MessageKind::hil_gps, MessageKind::local_position_ned, MessageKind::att_pos_mocap},
        OriginRule::never},
    ProfileDescriptor{Profile::custom, "custom", {}, OriginRule::with_vision},
    // px4 or ardupilot, whichever the vehicle runs: their ODOMETRY is the same frame (§12.2).
    ProfileDescriptor{Profile::automatic, "auto", {MessageKind::odometry}, OriginRule::always},
};

constexpr bool profiles_in_enum_order() {
  for (std::size_t i = 0; i < kProfiles.size(); ++i) {
    if (static_cast<std::size_t>(kProfiles[i].profile) != i) return false;
  }
  return true;
}
static_assert(profiles_in_enum_order(), "kProfiles rows must follow Profile's order");

template <typename Row, std::size_t N>
constexpr std::array<std::string_view, N> names_of(const std::array<Row, N>& rows) {
  std::array<std::string_view, N> names{};
  for (std::size_t i = 0; i < N; ++i) names[i] = rows[i].name;
  return names;
}

constexpr auto kProfileNames = names_of(kProfiles);
constexpr auto kMessageNames = names_of(kMessages);

constexpr auto kAllKinds = [] {
  std::array<MessageKind, kMessageKindCount> kinds{};
  for (std::size_t i = 0; i < kinds.size(); ++i) kinds[i] = kMessages[i].kind;
  return kinds;
}();

const MessageDescriptor* find(MessageKind kind) {
  const auto i = static_cast<std::size_t>(kind);
  return i < kMessages.size() ? &kMessages[i] : nullptr;
}

template <typename Pred>
bool any_member(const MessageSet& set, Pred pred) {
  for (const auto& row : kMessages) {
    if (set.contains(row.kind) && pred(row)) return true;
  }
  return false;
}

}  // namespace

std::string_view to_string(Profile profile) {
  const auto i = static_cast<std::size_t>(profile);
  return i < kProfiles.size() ? kProfiles[i].name : "unknown";
}

std::optional<Profile> parse_profile(std::string_view text) {
  for (const auto& row : kProfiles) {
    if (row.name == text) return row.profile;
  }
  return std::nullopt;
}

std::span<const std::string_view> profile_names() {
  return kProfileNames;
}

std::string_view to_string(MessageKind kind) {
  const auto* row = find(kind);
  return row != nullptr ? row->name : "unknown";
}

std::optional<MessageKind> parse_message_kind(std::string_view text) {
  for (const auto& row : kMessages) {
    if (row.name == text) return row.kind;
  }
  return std::nullopt;
}

std::span<const std::string_view> message_kind_names() {
  return kMessageNames;
}

std::span<const MessageKind> message_kinds() {
  return kAllKinds;
}

bool is_gps(MessageKind kind) {
  const auto* row = find(kind);
  return row != nullptr && row->is_gps;
}

bool needs_origin(MessageKind kind) {
  return is_gps(kind);
}

bool is_vision(MessageKind kind) {
  const auto* row = find(kind);
  return row != nullptr && row->is_vision;
}

MessageSet::MessageSet(std::span<const MessageKind> kinds) {
  for (MessageKind kind : kinds) insert(kind);
}

std::size_t MessageSet::size() const {
  return static_cast<std::size_t>(std::popcount(bits_));
}

bool MessageSet::needs_origin() const {
  return any_member(*this, [](const MessageDescriptor& row) { return row.is_gps; });
}

bool MessageSet::has_vision() const {
  return any_member(*this, [](const MessageDescriptor& row) { return row.is_vision; });
}

std::string to_string(const MessageSet& set) {
  std::string text;
  for (const auto& row : kMessages) {
    if (!set.contains(row.kind)) continue;
    if (!text.empty()) text += ',';
    text += row.name;
  }
  return text;
}

MessageSet messages_for(Profile profile, std::span<const MessageKind> custom) {
  if (profile == Profile::custom) return MessageSet{custom};
  const auto i = static_cast<std::size_t>(profile);
  return i < kProfiles.size() ? kProfiles[i].messages : MessageSet{};
}

bool sends_origin(Profile profile, const MessageSet& messages) {
  const auto i = static_cast<std::size_t>(profile);
  if (i >= kProfiles.size()) return false;
  switch (kProfiles[i].origin) {
    case OriginRule::always:
      return true;
    case OriginRule::never:
      return false;
    case OriginRule::with_vision:
      return messages.has_vision();
  }
  return false;
}

std::size_t max_frame_bytes(MessageKind kind, bool signed_frames) {
  const auto* row = find(kind);
  const std::size_t payload = row != nullptr ? row->max_payload : 0;
  return mavlink::kHeaderSizeV2 + payload + mavlink::kChecksumSize +
         (signed_frames ? mavlink::kSignatureSize : 0);
}

namespace {

/// The heading the agreement check may ask a vehicle of this profile for (vehicle_streams.hpp):
/// ArduPilot's RAW_IMU, PX4's HIGHRES_IMU, either where the profile does not say which autopilot;
/// none for px4-gps (HIL_GPS has no yaw: PX4's is its own, no second heading is asked).
struct HeadingStream {
  std::size_t payload_bytes;
  std::string_view name;
};

HeadingStream heading_stream(Profile profile) {
  switch (profile) {
    case Profile::ardupilot:
    case Profile::ardupilot_gps:
      return {mavlink::RawImu::kMaxLength, mavlink::RawImu::kName};
    case Profile::px4:
      return {mavlink::HighresImu::kMaxLength, mavlink::HighresImu::kName};
    case Profile::px4_gps:
      return {0, ""};
    case Profile::classic:
    case Profile::custom:
    case Profile::automatic:
      break;
  }
  return {std::max(mavlink::RawImu::kMaxLength, mavlink::HighresImu::kMaxLength),
          "RAW_IMU or HIGHRES_IMU"};
}

}  // namespace

double link_bytes_per_second(Profile profile, const MessageSet& messages, double rate_hz,
                             bool signed_frames) {
  const HeadingStream heading = heading_stream(profile);
  double per_send = 0.0;
  for (const auto& row : kMessages) {
    if (messages.contains(row.kind)) {
      per_send += static_cast<double>(max_frame_bytes(row.kind, signed_frames));
    }
  }
  // 1 Hz each: HEARTBEAT, a TIMESYNC request and reply, SET_GPS_GLOBAL_ORIGIN.
  const std::size_t frame = mavlink::kHeaderSizeV2 + mavlink::kChecksumSize +
                            (signed_frames ? mavlink::kSignatureSize : 0);
  const double clock_driven =
      static_cast<double>(frame) * 4.0 +
      static_cast<double>(mavlink::Heartbeat::kMaxLength + 2 * mavlink::Timesync::kMaxLength +
                          mavlink::SetGpsGlobalOrigin::kMaxLength);
  // From the vehicle: ATTITUDE and LOCAL_POSITION_NED at the rate the agreement check asks for
  // (vehicle_streams.hpp). A UART carries each direction on its own wire, but a telemetry radio
  // shares one air channel between both, so the bound counts them (signed like ours).
  // The heading's at kHeadingRateHz (ArduPilot's RAW_IMU, PX4's HIGHRES_IMU, the larger where the
  // profile does not say), asked only of a vehicle whose yaw is mocap's (an upper bound counts
  // it). And the estimator's health the set-up list asks for at 1 Hz (the larger of
  // ArduPilot's and PX4's message).
  const double requested =
      static_cast<double>(2 * frame + mavlink::Attitude::kMaxLength +
                          mavlink::LocalPositionNed::kMaxLength) *
          kStreamRateHz +
      static_cast<double>(heading.payload_bytes == 0 ? 0 : frame + heading.payload_bytes) *
          kHeadingRateHz +
      static_cast<double>(frame + std::max(mavlink::EkfStatusReport::kMaxLength,
                                           mavlink::EstimatorStatus::kMaxLength)) *
          kEstimatorRateHz;
  return per_send * rate_hz + clock_driven + requested;
}

double serial_bytes_per_second(std::uint32_t baud) {
  return static_cast<double>(baud) / 10.0;
}

std::optional<std::string> serial_bandwidth_warning(Profile profile, const MessageSet& messages,
                                                    double rate_hz, bool signed_frames,
                                                    std::uint32_t baud) {
  const double needed = link_bytes_per_second(profile, messages, rate_hz, signed_frames);
  const double available = serial_bytes_per_second(baud);
  if (needed <= available) return std::nullopt;
  // autopilots.md §7: a full ODOMETRY frame is 245 bytes; 57600 baud carries ~23/s.
  const std::string_view heading = heading_stream(profile).name;
  char also[64] = "";
  if (!heading.empty()) {
    std::snprintf(also, sizeof also, ", its %.*s at %g Hz", static_cast<int>(heading.size()),
                  heading.data(), kHeadingRateHz);
  }
  char text[320];
  std::snprintf(text, sizeof text,
                "profile %.*s at %g Hz needs up to %.0f bytes/s (with the vehicle's ATTITUDE "
                "and LOCAL_POSITION_NED at %g Hz%s and its estimator status at 1 Hz) but %u "
                "baud carries %.0f: frames will be dropped; lower rate_hz or raise the baud rate",
                static_cast<int>(to_string(profile).size()), to_string(profile).data(), rate_hz,
                needed, kStreamRateHz, also, baud, available);
  return std::string(text);
}

}  // namespace mocaplink::core
