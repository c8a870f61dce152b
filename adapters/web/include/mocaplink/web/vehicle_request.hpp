// Request bodies of the vehicle endpoints (docs/api.md) → changes for the backend.
//
// This layer checks only what belongs to the API itself: JSON syntax, that the body is an object,
// which keys each endpoint takes (with "did you mean"), that `paused` is true or false, and that
// every other value is a JSON type a [[vehicle]] key can have. The keys then go on as the typed
// keys of a [[vehicle]] table (config::VehicleKey), and the backend checks their values, ranges
// and spellings with the configuration's own rules (config::add_vehicle / update_vehicle), so a
// file, the command line and the dashboard accept the same vehicles and refuse with the same
// messages. A request is valid as a whole or refused with one problem (nothing is half applied).
// Pure functions of their input; never throw.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mocaplink/config/config_error.hpp"
#include "mocaplink/config/load.hpp"

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

/// POST /api/vehicles: a new vehicle, with the keys of a [[vehicle]] table.
struct AddVehicle {
  std::string name{};  ///< the "name" key when it is a string (Location)
  /// Every [[vehicle]] key given, plus the API's defaults for the two keys a file must give
  /// (system_id 1, profile "px4") when absent.
  std::vector<config::VehicleKey> keys{};
  bool paused = false;  ///< start paused
};
struct RemoveVehicle {
  std::string name{};
};
/// PATCH /api/vehicles/NAME: only the keys present change.
struct UpdateVehicle {
  std::string name{};                      ///< from the URL
  std::vector<config::VehicleKey> keys{};  ///< rate_hz and/or messages (config::update_vehicle)
  std::optional<bool> paused{};
};
/// POST /api/vehicles/NAME/setup: write the fixes of the named parameters of its set-up list, or
/// reboot the vehicle (one of the two per request).
struct SetupVehicle {
  std::string name{};                ///< from the URL
  std::vector<std::string> apply{};  ///< parameter names as the list shows them
  bool reboot = false;
};
/// One change the dashboard asks the daemon to make.
using VehicleChange = std::variant<AddVehicle, RemoveVehicle, UpdateVehicle, SetupVehicle>;

/// Parses a POST body (JSON text of any length; the server caps it at 64 KiB).
ApiResult<AddVehicle> parse_vehicle_spec(std::string_view json_text);
/// Parses a POST /api/vehicles/NAME/setup body: {"apply": ["PARAM", ...]} (1 to 32 names of at
/// most 16 characters: A-Z, 0-9, _) or {"reboot": true}.
ApiResult<SetupVehicle> parse_vehicle_setup(std::string_view json_text, std::string name);
/// Parses a PATCH body for the vehicle `name` (taken from the URL). An empty object is refused:
/// a PATCH must change something.
ApiResult<UpdateVehicle> parse_vehicle_patch(std::string_view json_text, std::string name);

/// The answer to a change the configuration refused (config::add_vehicle / update_vehicle): 422,
/// "key: message", and the key as the field (the API's keys are the [[vehicle]] keys).
[[nodiscard]] ApiError refusal(const config::ConfigError& error);

}  // namespace mocaplink::web
