#include "mocaplink/web/vehicle_request.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <set>

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
      for (std::string_view candidate : known) message += " " + std::string(candidate);
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

bool has_control_characters(std::string_view s) {
  return std::any_of(s.begin(), s.end(),
                     [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

ApiResult<std::string> get_string(const json& object, const std::string& key,
                                  std::size_t max_length) {
  const json& value = object.at(key);
  if (!value.is_string()) return invalid(key, "must be a string");
  std::string s = value.get<std::string>();
  if (s.size() > max_length) {
    return invalid(key, "must be at most " + std::to_string(max_length) + " bytes");
  }
  if (has_control_characters(s)) return invalid(key, "must not contain control characters");
  return s;
}

ApiResult<double> get_rate(const json& object) {
  const json& value = object.at("rate_hz");
  if (!value.is_number()) return invalid("rate_hz", "must be a number");
  const double rate = value.get<double>();
  if (!std::isfinite(rate) || rate <= 0.0 || rate > core::kMaxSenderRateHz) {
    return invalid("rate_hz",
                   "must be > 0 and <= " + core::max_rate_text() + ", got " + value.dump());
  }
  return rate;
}

ApiResult<std::vector<std::string>> get_messages(const json& object) {
  const json& value = object.at("messages");
  if (!value.is_array()) return invalid("messages", "must be an array of message names");
  std::vector<std::string> messages;
  std::set<std::string> seen;
  for (const json& item : value) {
    const auto& names = message_names();
    if (!item.is_string() ||
        std::find(names.begin(), names.end(), item.get<std::string>()) == names.end()) {
      return invalid("messages", "unknown message " + item.dump() + "; expected " + join(names));
    }
    if (!seen.insert(item.get<std::string>()).second) {
      return invalid("messages", "duplicate message " + item.dump());
    }
    messages.push_back(item.get<std::string>());
  }
  return messages;
}

ApiResult<bool> get_bool(const json& object, const std::string& key) {
  const json& value = object.at(key);
  if (!value.is_boolean()) return invalid(key, "must be true or false");
  return value.get<bool>();
}

// Reads `key` with `get` into `out` when present; returns the error when it is invalid.
template <typename T, typename Get>
std::optional<ApiError> read_optional(const json& object, const char* key, Get get, T& out) {
  if (!object.contains(key)) return std::nullopt;
  auto value = get(object);
  if (!value.ok()) return value.error();
  out = value.value();
  return std::nullopt;
}

ApiResult<bool> get_paused(const json& object) {
  return get_bool(object, "paused");
}

}  // namespace

const std::vector<std::string>& profile_names() {
  static const std::vector<std::string> names(core::profile_names().begin(),
                                              core::profile_names().end());
  return names;
}

const std::vector<std::string>& message_names() {
  static const std::vector<std::string> names(core::message_kind_names().begin(),
                                              core::message_kind_names().end());
  return names;
}

bool is_valid_vehicle_name(std::string_view name) {
  return core::is_valid_vehicle_name(name);
}

ApiResult<VehicleSpec> parse_vehicle_spec(std::string_view json_text) {
  auto parsed = parse_object(json_text);
  if (!parsed.ok()) return parsed.error();
  const json& object = parsed.value();
  if (auto error = check_keys(object, {"name", "body", "link", "system_id", "profile", "messages",
                                       "rate_hz", "signing_key", "paused"})) {
    return *error;
  }
  for (const char* required : {"name", "body", "link"}) {
    if (!object.contains(required)) return invalid(required, "is required");
  }
  VehicleSpec spec;
  auto name = get_string(object, "name", core::kMaxVehicleNameLength);
  if (!name.ok()) return name.error();
  if (!is_valid_vehicle_name(name.value())) {
    return invalid("name", "must be 1.." + std::to_string(core::kMaxVehicleNameLength) +
                               " characters of A-Z a-z 0-9 _ . -");
  }
  spec.name = name.value();

  auto body = get_string(object, "body", core::kMaxBodyNameLength);
  if (!body.ok()) return body.error();
  if (body.value().empty()) return invalid("body", "must not be empty");
  spec.body = body.value();

  auto link = get_string(object, "link", kMaxLinkLength);
  if (!link.ok()) return link.error();
  const std::string& url = link.value();
  if (url.rfind("udp://", 0) != 0 && url.rfind("tcp://", 0) != 0 &&
      url.rfind("serial://", 0) != 0) {
    return invalid("link", "must be udp://host:port, tcp://host:port or serial:///dev/...");
  }
  spec.link = url;

  if (object.contains("system_id")) {
    const json& value = object.at("system_id");
    if (!value.is_number_integer() || value.get<std::int64_t>() < 1 ||
        value.get<std::int64_t>() > 255) {
      return invalid("system_id", "must be an integer 1..255, got " + value.dump());
    }
    spec.system_id = static_cast<std::uint8_t>(value.get<std::int64_t>());
  }
  if (object.contains("profile")) {
    auto profile = get_string(object, "profile", 32);
    const auto& names = profile_names();
    if (!profile.ok() || std::find(names.begin(), names.end(), profile.value()) == names.end()) {
      return invalid("profile", "must be one of " + join(names));
    }
    spec.profile = profile.value();
  }
  if (auto error = read_optional(object, "messages", get_messages, spec.messages)) return *error;
  if (spec.profile == "custom" && spec.messages.empty()) {
    return invalid("messages", "profile \"custom\" needs at least one message");
  }
  if (spec.profile != "custom" && !spec.messages.empty()) {
    return invalid("messages", "only profile \"custom\" takes a message list");
  }
  if (auto error = read_optional(object, "rate_hz", get_rate, spec.rate_hz)) return *error;
  if (object.contains("signing_key")) {
    auto key = get_string(object, "signing_key", 64);
    if (!key.ok() ||
        !(key.value().empty() || (key.value().size() == 64 && text::is_hex(key.value())))) {
      return invalid("signing_key", "must be \"\" or 64 hex digits");
    }
    spec.signing_key = key.value();
  }
  if (auto error = read_optional(object, "paused", get_paused, spec.paused)) return *error;
  return spec;
}

ApiResult<VehiclePatch> parse_vehicle_patch(std::string_view json_text, std::string name) {
  auto parsed = parse_object(json_text);
  if (!parsed.ok()) return parsed.error();
  const json& object = parsed.value();
  if (auto error = check_keys(object, {"rate_hz", "messages", "paused"})) return *error;
  if (object.empty()) {
    return ApiError{422, "nothing to change: give rate_hz, messages or paused", ""};
  }
  VehiclePatch patch;
  patch.name = std::move(name);
  if (auto error = read_optional(object, "rate_hz", get_rate, patch.rate_hz)) return *error;
  if (auto error = read_optional(object, "messages", get_messages, patch.messages)) return *error;
  if (auto error = read_optional(object, "paused", get_paused, patch.paused)) return *error;
  return patch;
}

}  // namespace mocaplink::web
