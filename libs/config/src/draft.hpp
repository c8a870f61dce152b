// The intermediate, partially valid form of a configuration: what the TOML reader, the
// command-line overrides and a base Config all produce, before the cross-field checks of
// finalize(). Every field remembers where it came from so that later errors can point at it.
// Internal to libs/config.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mocaplink/config/config.hpp"
#include "mocaplink/config/config_error.hpp"
#include "mocaplink/config/load.hpp"

namespace mocaplink::config::detail {

/// A place in a file (line/column 1-based) or a command-line option (line 0).
struct Where {
  std::string file;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

/// "FILE:LINE:COL" or "FILE" (for "first defined at ..." in messages).
[[nodiscard]] std::string describe(const Where& where);

/// Collects every error and warning; nothing stops at the first problem.
struct Diagnostics {
  std::vector<ConfigError> errors;
  std::vector<ConfigError> warnings;
  void error(const Where& where, std::string key, std::string message);
  void warning(const Where& where, std::string key, std::string message);
};

/// One key's value: `value` is set when the key was given *and* valid; `present` when given at
/// all (an invalid value has already been reported, so finalize() must not call it missing).
template <typename T>
struct Field {
  std::optional<T> value;
  bool present = false;
  Where where;
  std::string key;  ///< as displayed: "vehicle[2].rate_hz", or "rate_hz" for --vehicle
};

/// The value types a key can declare. `number` accepts TOML integers and floats.
enum class ValueType { string, integer, number, boolean, string_list };

/// A key's raw value, already of its declared type (the TOML reader and the command-line reader
/// both check the type before a key handler sees it).
struct Value {
  std::variant<std::string, std::int64_t, double, bool, std::vector<std::string>> data;
  Where where;
  std::string key;
  [[nodiscard]] const std::string& text() const { return std::get<std::string>(data); }
  [[nodiscard]] std::int64_t integer() const { return std::get<std::int64_t>(data); }
  [[nodiscard]] double number() const { return std::get<double>(data); }
  [[nodiscard]] bool boolean() const { return std::get<bool>(data); }
  [[nodiscard]] const std::vector<std::string>& list() const {
    return std::get<std::vector<std::string>>(data);
  }
};

struct VehicleDraft {
  Where header;        ///< the [[vehicle]] header, or the --vehicle option
  std::string prefix;  ///< "vehicle[2]." in files, "" on the command line
  Field<std::string> name;
  Field<std::string> body;
  Field<LinkUrl> link;
  Field<std::vector<LinkUrl>> gcs;
  Field<std::uint8_t> system_id;
  Field<std::uint8_t> component_id;
  Field<core::Profile> profile;
  Field<std::vector<core::MessageKind>> messages;
  Field<double> rate_hz;
  Field<std::optional<std::array<std::uint8_t, 32>>> signing_key;
  Field<core::SignedAxis> body_forward;
  Field<core::SignedAxis> body_up;
  Field<bool> enabled;
  std::vector<std::string> mistyped;  ///< keys given with a wrong type (reported, not "missing")
};

struct ConfigDraft {
  Where document;  ///< FILE:1:1, where keys of absent tables are reported missing
  std::optional<Where> mocap_header;
  /// Judges [mocap] source / --source when given (the caller's source registry); empty: the
  /// SCHEME://… shape only.
  SourceValidator validate_source;
  Field<SourceUrl> source;
  Field<core::SignedAxis> up;
  Field<core::North> north;
  Field<core::SignedAxis> body_forward;
  Field<core::SignedAxis> body_up;
  std::optional<Where> origin_header;
  Field<double> latitude_deg;
  Field<double> longitude_deg;
  Field<double> altitude_m;
  std::vector<VehicleDraft> vehicles;
  core::TrackerConfig tracking;  ///< the core's defaults, overridden key by key
  /// Where each [tracking] key was set: {bare name, place, displayed key}.
  struct TrackingSite {
    std::string name;
    Where where;
    std::string key;
  };
  std::vector<TrackingSite> tracking_sites;
  Field<HostPort> listen;
  Field<std::string> token;
  Field<std::vector<HostPort>> allowed_hosts;
  Field<std::uint32_t> max_connections_per_client;
  std::optional<Where> ros2_header;
  Field<std::uint32_t> ros2_domain_id;
  Field<std::string> ros2_namespace;
  Field<std::string> ros2_frame_id;
  Field<std::vector<std::string>> ros2_bodies;
  Field<std::array<bool, 3>> ros2_publish;  ///< pose, odom, tf
  Field<core::RosAxes> ros2_axes;
  Field<std::string> ros2_interface;
  /// A draft made from a Config carries its checked [ros2] whole (draft_from_config).
  std::optional<Ros2Settings> ros2_checked;
  std::vector<std::string> mistyped;  ///< keys given with a wrong type (reported, not "missing")
};

/// "a string", "an integer", "a number", "true or false", "an array of strings" (keys.cpp).
[[nodiscard]] const char* expected_name(ValueType type);

/// A key of a table: its name, declared type, and what to do with a value of that type.
template <typename Target>
struct KeySpec {
  std::string_view name;
  ValueType type;
  void (*apply)(Target& target, const Value& value, Diagnostics& diagnostics);
};

/// The schema (keys.cpp). Tables of the file: [mocap], [origin], [[vehicle]], [tracking], [http],
/// [ros2].
[[nodiscard]] std::span<const KeySpec<ConfigDraft>> mocap_keys();
[[nodiscard]] std::span<const KeySpec<ConfigDraft>> origin_keys();
[[nodiscard]] std::span<const KeySpec<ConfigDraft>> tracking_keys();
[[nodiscard]] std::span<const KeySpec<ConfigDraft>> http_keys();
[[nodiscard]] std::span<const KeySpec<ConfigDraft>> ros2_keys();
[[nodiscard]] std::span<const KeySpec<VehicleDraft>> vehicle_keys();

/// "unknown key" with a suggestion from `here`, or the table the key belongs to, or the list of
/// allowed keys (keys.cpp).
[[nodiscard]] std::string unknown_key_message(std::string_view key,
                                              std::span<const std::string_view> here);

/// Reads TOML text into a draft (toml_reader.cpp). False after a TOML syntax error (reported;
/// the draft is then empty).
[[nodiscard]] bool read_toml(std::string_view text, std::string_view filename, ConfigDraft& draft,
                             Diagnostics& diagnostics);

/// Replaces the fields of `target` that `source` gives (overrides.cpp): how `--vehicle NAME:...`
/// and update_vehicle change an existing vehicle.
void merge(VehicleDraft& target, const VehicleDraft& source);

/// The error for GPS-type messages without an [origin] (finalize.cpp, add_vehicle.cpp).
inline constexpr const char* kGpsNeedsOrigin =
    "GPS-type messages (HIL_GPS, GPS_INPUT) need the [origin] table (latitude_deg, longitude_deg, "
    "altitude_m)";

/// One [http] allowed_hosts entry ("NAME", "NAME:PORT", "[V6]:PORT"), appended to the draft's list
/// (--http-allow-host; keys.cpp).
void add_allowed_host(ConfigDraft& draft, const Value& value, Diagnostics& diagnostics);

/// Applies command-line overrides to a draft (overrides.cpp).
void apply_command_line(const CommandLineOverrides& overrides, ConfigDraft& draft,
                        Diagnostics& diagnostics);

/// A draft holding exactly `config`, every field attributed to `origin` (load.cpp) — except the
/// `changed` keys of the vehicle named `vehicle` (when given), which are attributed to
/// `vehicle_origin` under their bare names, as if written there: a change to a running vehicle
/// then gets the warnings a file gives about what it changed, and no others again.
[[nodiscard]] ConfigDraft draft_from_config(const Config& config, std::string_view origin,
                                            std::string_view vehicle = {},
                                            std::string_view vehicle_origin = {},
                                            std::span<const std::string> changed = {});

/// Required keys, defaults and cross-field rules; the Config when no error was found
/// (finalize.cpp).
[[nodiscard]] std::optional<Config> finalize(const ConfigDraft& draft, Diagnostics& diagnostics);

}  // namespace mocaplink::config::detail
