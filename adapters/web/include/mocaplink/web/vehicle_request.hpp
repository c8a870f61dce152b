// Request bodies of the vehicle endpoints (docs/api.md) → validated changes for the backend.
//
// Everything the API itself can check is checked here, before the backend sees anything, and a
// request is either valid as a whole or refused with the first problem found (nothing is half
// applied): JSON syntax, object shape, unknown keys, types, ranges and spellings. The backend
// checks what needs the daemon's state (unique names, link URL details, origin availability) and
// refuses the same way. Pure functions of their input; never throw.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace mocaplink::web {

/// A refused request: HTTP status (4xx), one readable sentence, and the JSON key at fault ("" when
/// the problem is not one field, e.g. malformed JSON or an unknown vehicle in the URL).
struct ApiError {
  int status = 400;
  std::string error{};
  std::string field{};
};

/// A value or the ApiError explaining why there is none.
template <typename T>
class [[nodiscard]] ApiResult {
 public:
  ApiResult(T value) : value_(std::move(value)) {}         // NOLINT(google-explicit-constructor)
  ApiResult(ApiError error) : error_(std::move(error)) {}  // NOLINT(google-explicit-constructor)
  [[nodiscard]] bool ok() const { return value_.has_value(); }
  [[nodiscard]] const T& value() const { return *value_; }  ///< only when ok()
  [[nodiscard]] const ApiError& error() const { return error_; }

 private:
  std::optional<T> value_{};
  ApiError error_;
};

/// The longest link URL the API takes. The rate and name limits are the core's, shared with the
/// configuration file (core::kMaxSenderRateHz, core::kMaxVehicleNameLength,
/// core::kMaxBodyNameLength).
inline constexpr std::size_t kMaxLinkLength = 512;

/// The profiles and pose-message names, in display order: the core's spellings
/// (core::profile_names, core::message_kind_names), as strings.
[[nodiscard]] const std::vector<std::string>& profile_names();
[[nodiscard]] const std::vector<std::string>& message_names();

/// POST /api/vehicles: a new vehicle, with the keys of a [[vehicle]] table.
struct VehicleSpec {
  std::string name{};                   ///< 1..64 of [A-Za-z0-9_.-]
  std::string body{};                   ///< 1..256 bytes, no control characters
  std::string link{};                   ///< udp://, tcp:// or serial:// URL (backend parses it)
  std::uint8_t system_id = 1;           ///< 1..255
  std::string profile = "px4";          ///< one of profile_names()
  std::vector<std::string> messages{};  ///< non-empty iff profile is "custom"; message_names()
  double rate_hz = 50.0;                ///< 0 < rate ≤ 500
  std::string signing_key{};            ///< "" or 64 hex digits
  bool paused = false;                  ///< start paused
};

/// PATCH /api/vehicles/NAME: only the keys present change.
struct VehiclePatch {
  std::string name{};               ///< from the URL
  std::optional<double> rate_hz{};  ///< 0 < rate ≤ 500
  std::optional<std::vector<std::string>>
      messages{};  ///< message_names(), no duplicates, may be []
  std::optional<bool> paused{};
};

struct AddVehicle {
  VehicleSpec spec;
};
struct RemoveVehicle {
  std::string name{};
};
struct UpdateVehicle {
  VehiclePatch patch;
};
/// One change the dashboard asks the daemon to make.
using VehicleChange = std::variant<AddVehicle, RemoveVehicle, UpdateVehicle>;

/// Parses and validates a POST body (JSON text of any length; the server caps it at 64 KiB).
ApiResult<VehicleSpec> parse_vehicle_spec(std::string_view json_text);
/// Parses and validates a PATCH body for the vehicle `name` (taken from the URL). An empty
/// object is refused: a PATCH must change something.
ApiResult<VehiclePatch> parse_vehicle_patch(std::string_view json_text, std::string name);
/// Validates a vehicle name as it appears in a URL or a spec (404 is the caller's business).
[[nodiscard]] bool is_valid_vehicle_name(std::string_view name);

}  // namespace mocaplink::web
