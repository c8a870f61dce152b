// Entry points: TOML text (+ command-line overrides) → validated Config, every problem at once.
// Pure: the caller reads the file and passes its text and display name. Every function here is
// reentrant and thread-safe (no shared state); none throws for bad input.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mocaplink/config/config.hpp"
#include "mocaplink/config/config_error.hpp"

namespace mocaplink::config {

/// The outcome of building a Config. `config` is set exactly when `errors` is empty. Errors are
/// sorted by file position (file errors first, then command-line errors in option order).
/// Warnings never prevent a Config (e.g. two vehicles sharing one link).
struct [[nodiscard]] ConfigResult {
  std::optional<Config> config;
  std::vector<ConfigError> errors;
  std::vector<ConfigError> warnings;
  [[nodiscard]] bool ok() const { return config.has_value(); }
};

/// The raw command-line options of `mocaplink run` that change a configuration.
struct CommandLineOverrides {
  std::optional<std::string> source;  ///< --source URL: replaces [mocap] source
  std::optional<std::string> http;    ///< --http ADDR: replaces [http] listen
  /// --http-allow-host NAME, each added to [http] allowed_hosts ("NAME" or "NAME:PORT").
  std::vector<std::string> http_allow_hosts;
  /// --vehicle SPEC, in command-line order: "NAME:key=value,key=value,...". Keys are those of
  /// [[vehicle]] except name; `messages` joins its entries with '+' ("odometry+hil_gps"); values
  /// cannot contain ','. An existing NAME has the given keys replaced; a new NAME is added and
  /// needs every required key.
  std::vector<std::string> vehicles;
};

/// Parses and validates a TOML configuration. `filename` is only used in error locations.
/// Never throws for bad input; the TOML parser stops at the first syntax error, so a file with a
/// syntax error reports that one error. [mocap] source is judged by `validate_source` (the
/// commands pass their source registry's; empty: only the SCHEME://… shape is checked).
ConfigResult parse_config(std::string_view toml_text, std::string_view filename,
                          const SourceValidator& validate_source = {});

/// parse_config, then the command-line overrides, then validation of the combination: a file
/// without [mocap] source is fine when `overrides.source` is set. Errors from options name the
/// option ("--vehicle 2: rate_hz: ...").
ConfigResult load_config(std::string_view toml_text, std::string_view filename,
                         const CommandLineOverrides& overrides,
                         const SourceValidator& validate_source = {});

/// Applies command-line overrides to an existing valid Config (e.g. demo_config() when no file is
/// given). Cross-checks that involve base vehicles name them as coming from `base_name`.
ConfigResult apply_overrides(const Config& base, const CommandLineOverrides& overrides,
                             std::string_view base_name = "built-in demo",
                             const SourceValidator& validate_source = {});

/// One key of a [[vehicle]] table as a typed value, the way a JSON object gives it (the dashboard's
/// POST /api/vehicles). An integer is accepted where a number is expected.
struct VehicleKey {
  using Value = std::variant<std::string, std::int64_t, double, bool, std::vector<std::string>>;
  std::string key;
  Value value;
};

/// Adds one vehicle to a valid Config, with exactly the checks a [[vehicle]] table gets: keys and
/// their values, required keys, defaults from [mocap], the origin the profile needs, a name not in
/// use and a system id not in use on the same link. On success the new Config's last vehicle is
/// the added one; warnings about it (a shared link) come with it. Errors and warnings are located
/// at `origin` (line 0) and their key is the bare [[vehicle]] key ("system_id"), or "" when the
/// problem is not one key.
ConfigResult add_vehicle(const Config& base, const std::vector<VehicleKey>& keys,
                         std::string_view origin);

/// Changes the running vehicle `name` (the dashboard's PATCH /api/vehicles/NAME), with the checks
/// and warnings a file gets for the same keys (e.g. ArduPilot above 50 Hz). Only the keys a running
/// vehicle can change are allowed: `rate_hz` (replaced in the returned Config) and `messages`,
/// which here is the live set of pose messages, for any profile and possibly empty: checked like
/// the [[vehicle]] key (spelling, duplicates) and for the [origin] GPS-type messages need, but
/// held by the Bridge like a pause, not written into the Config (whose `messages` stays the
/// configured list of a custom profile). Errors and warnings are located as for add_vehicle.
ConfigResult update_vehicle(const Config& base, std::string_view name,
                            const std::vector<VehicleKey>& keys, std::string_view origin);

}  // namespace mocaplink::config
