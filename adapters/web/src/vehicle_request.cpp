#include "mocaplink/web/vehicle_request.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <nlohmann/json.hpp>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/profile.hpp"
#include "mocaplink/text/did_you_mean.hpp"
#include "mocaplink/text/hex.hpp"

namespace mocaplink::web {
namespace {

using nlohmann::json;

ApiError invalid(std::string field, std::string message) {
  return ApiError{422, field + ": " + message, field};
}

std::optional<ApiError> check_keys(const json& object, const std::vector<std::string_view>& known) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string message = "unknown key";
    // The same closeness rule as the config file's keys ("rate" → "rate_hz" by prefix).
    if (const auto best = text::closest_match(key, known)) {
      message += " (did you mean \"" + std::string(*best) + "\"?)";
    } else {
      message += "; expected one of:";
      for (std::string_view candidate : known) {
        message += ' ';
        message += candidate;
      }
    }
    return invalid(key, message);
  }
  return std::nullopt;
}

ApiResult<json> parse_object(std::string_view text) {
  json parsed = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) return ApiError{400, "request body is not valid JSON", ""};
  if (!parsed.is_object()) return ApiError{400, "request body must be a JSON object", ""};
  return parsed;
}

/// A JSON value as the typed value of a [[vehicle]] key; its range and spelling are the
/// configuration's to check. Null, objects and arrays holding anything but strings have no such
/// type.
ApiResult<config::VehicleKey> vehicle_key(const std::string& key, const json& value) {
  config::VehicleKey out{key, std::string()};
  if (value.is_string()) {
    out.value = value.get<std::string>();
  } else if (value.is_boolean()) {
    out.value = value.get<bool>();
  } else if (value.is_number_unsigned() &&
             value.get<std::uint64_t>() >
                 static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    out.value = value.get<double>();  // out of every range anyway
  } else if (value.is_number_integer()) {
    out.value = value.get<std::int64_t>();
  } else if (value.is_number()) {
    out.value = value.get<double>();
  } else if (value.is_array() &&
             std::all_of(value.begin(), value.end(), [](const json& j) { return j.is_string(); })) {
    out.value = value.get<std::vector<std::string>>();
  } else {
    return invalid(key, "expected a string, a number, true or false, or an array of strings, got " +
                            value.dump());
  }
  return out;
}

/// Reads every key of `object` but `paused` into `keys`; the first unusable one is the error.
std::optional<ApiError> read_keys(const json& object, std::vector<config::VehicleKey>& keys) {
  for (const auto& [key, value] : object.items()) {
    if (key == "paused") continue;
    auto typed = vehicle_key(key, value);
    if (!typed.ok()) return typed.error();
    keys.push_back(typed.value());
  }
  return std::nullopt;
}

/// `paused`, when given: the API's own key (not one of a [[vehicle]] table).
std::optional<ApiError> read_paused(const json& object, std::optional<bool>& paused) {
  if (!object.contains("paused")) return std::nullopt;
  if (!object.at("paused").is_boolean()) return invalid("paused", "must be true or false");
  paused = object.at("paused").get<bool>();
  return std::nullopt;
}

}  // namespace

ApiResult<AddVehicle> parse_vehicle_spec(std::string_view json_text) {
  auto parsed = parse_object(json_text);
  if (!parsed.ok()) return parsed.error();
  const json& object = parsed.value();
  if (auto error = check_keys(object, {"name", "body", "link", "system_id", "profile", "messages",
                                       "rate_hz", "signing_key", "paused"})) {
    return *error;
  }
  AddVehicle add;
  std::optional<bool> paused;
  if (auto error = read_paused(object, paused)) return *error;
  add.paused = paused.value_or(false);
  if (auto error = read_keys(object, add.keys)) return *error;
  // docs/api.md: the API's defaults for the two keys a [[vehicle]] table must give.
  if (!object.contains("system_id")) add.keys.push_back({"system_id", std::int64_t{1}});
  if (!object.contains("profile")) add.keys.push_back({"profile", std::string("px4")});
  if (object.contains("name") && object.at("name").is_string()) {
    add.name = object.at("name").get<std::string>();
  }
  return add;
}

ApiResult<UpdateVehicle> parse_vehicle_patch(std::string_view json_text, std::string name) {
  auto parsed = parse_object(json_text);
  if (!parsed.ok()) return parsed.error();
  const json& object = parsed.value();
  if (auto error = check_keys(object, {"rate_hz", "messages", "paused"})) return *error;
  if (object.empty()) {
    return ApiError{422, "nothing to change: give rate_hz, messages or paused", ""};
  }
  UpdateVehicle update;
  update.name = std::move(name);
  if (auto error = read_paused(object, update.paused)) return *error;
  if (auto error = read_keys(object, update.keys)) return *error;
  return update;
}

ApiResult<SetupVehicle> parse_vehicle_setup(std::string_view json_text, std::string name) {
  auto parsed = parse_object(json_text);
  if (!parsed.ok()) return parsed.error();
  const json& object = parsed.value();
  if (auto error = check_keys(object, {"apply", "reboot"})) return *error;
  if (object.size() != 1) {
    return ApiError{422, "give exactly one of apply (parameter names) or reboot (true)", ""};
  }
  SetupVehicle setup;
  setup.name = std::move(name);
  if (object.contains("reboot")) {
    if (!object.at("reboot").is_boolean() || !object.at("reboot").get<bool>()) {
      return invalid("reboot", "must be true");
    }
    setup.reboot = true;
    return setup;
  }
  const json& apply = object.at("apply");
  constexpr std::size_t kMaxNames = 32;  // more than any set-up list holds
  if (!apply.is_array() || apply.empty() || apply.size() > kMaxNames) {
    return invalid("apply", "must be a list of 1 to 32 parameter names");
  }
  for (const json& item : apply) {
    const std::string parameter = item.is_string() ? item.get<std::string>() : std::string();
    const bool spelled = !parameter.empty() && parameter.size() <= 16 &&
                         std::all_of(parameter.begin(), parameter.end(), [](char c) {
                           return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
                         });
    if (!spelled) return invalid("apply", "parameter names are 1 to 16 of A-Z, 0-9 and _");
    setup.apply.push_back(parameter);
  }
  return setup;
}

ApiError refusal(const config::ConfigError& error) {
  return ApiError{422, error.key.empty() ? error.message : error.key + ": " + error.message,
                  error.key};
}

}  // namespace mocaplink::web
