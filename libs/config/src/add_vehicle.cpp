// add_vehicle and update_vehicle (load.hpp): one [[vehicle]] from typed key/value pairs, or a
// change to a running one, checked against a running Config by the same key handlers and
// cross-checks as a file.
#include <algorithm>
#include <string>

#include "draft.hpp"
#include "mocaplink/config/load.hpp"
#include "text_util.hpp"

namespace mocaplink::config {
namespace {

const char* type_name(const VehicleKey& key) {
  switch (key.value.index()) {
    case 0:
      return "a string";
    case 1:
      return "an integer";
    case 2:
      return "a number";
    case 3:
      return "a boolean";
    default:
      return "a list of strings";
  }
}

/// The value converted to the key's declared type, or std::nullopt when it has another type.
std::optional<detail::Value> typed(const VehicleKey& key, detail::ValueType type,
                                   const detail::Where& where) {
  detail::Value value;
  value.where = where;
  value.key = key.key;
  const auto* integer = std::get_if<std::int64_t>(&key.value);
  switch (type) {
    case detail::ValueType::string:
      if (!std::holds_alternative<std::string>(key.value)) return std::nullopt;
      value.data = std::get<std::string>(key.value);
      return value;
    case detail::ValueType::integer:
      if (integer == nullptr) return std::nullopt;
      value.data = *integer;
      return value;
    case detail::ValueType::number:
      if (integer != nullptr) {
        value.data = static_cast<double>(*integer);
      } else if (const auto* number = std::get_if<double>(&key.value)) {
        value.data = *number;
      } else {
        return std::nullopt;
      }
      return value;
    case detail::ValueType::boolean:
      if (!std::holds_alternative<bool>(key.value)) return std::nullopt;
      value.data = std::get<bool>(key.value);
      return value;
    case detail::ValueType::string_list:
      if (!std::holds_alternative<std::vector<std::string>>(key.value)) return std::nullopt;
      value.data = std::get<std::vector<std::string>>(key.value);
      return value;
  }
  return std::nullopt;
}

/// Reads typed keys into `vehicle` with the [[vehicle]] key handlers: unknown keys, keys given
/// twice and values of the wrong type are reported like a file's.
void read_keys(const std::vector<VehicleKey>& keys, const detail::Where& where,
               detail::VehicleDraft& vehicle, detail::Diagnostics& diagnostics) {
  const auto specs = detail::vehicle_keys();
  std::vector<std::string_view> names;
  for (const auto& s : specs) names.push_back(s.name);
  std::vector<std::string_view> seen;
  for (const VehicleKey& key : keys) {
    const auto spec =
        std::find_if(specs.begin(), specs.end(), [&](const auto& s) { return s.name == key.key; });
    if (spec == specs.end()) {
      diagnostics.error(where, key.key, detail::unknown_key_message(key.key, names));
      continue;
    }
    if (std::find(seen.begin(), seen.end(), spec->name) != seen.end()) {
      diagnostics.error(where, key.key, "given twice");
      continue;
    }
    seen.push_back(spec->name);
    if (auto value = typed(key, spec->type, where)) {
      spec->apply(vehicle, *value, diagnostics);
    } else {
      diagnostics.error(
          where, key.key,
          std::string("expected ") + detail::expected_name(spec->type) + ", got " + type_name(key));
      vehicle.mistyped.push_back(key.key);
    }
  }
}

/// finalize(), keeping only the warnings located at `origin`: the other vehicles' warnings were
/// given when they came.
ConfigResult finish(const detail::ConfigDraft& draft, detail::Diagnostics& diagnostics,
                    std::string_view origin) {
  ConfigResult result;
  result.config = detail::finalize(draft, diagnostics);
  result.errors = std::move(diagnostics.errors);
  for (auto& w : diagnostics.warnings) {
    if (w.file == origin) result.warnings.push_back(std::move(w));
  }
  if (!result.errors.empty()) result.config.reset();
  return result;
}

}  // namespace

ConfigResult add_vehicle(const Config& base, const std::vector<VehicleKey>& keys,
                         std::string_view origin) {
  detail::ConfigDraft draft = detail::draft_from_config(base, "configuration");
  detail::Diagnostics diagnostics;
  const detail::Where where{std::string(origin)};
  detail::VehicleDraft vehicle;
  vehicle.header = where;
  read_keys(keys, where, vehicle, diagnostics);
  draft.vehicles.push_back(std::move(vehicle));
  return finish(draft, diagnostics, origin);
}

ConfigResult update_vehicle(const Config& base, std::string_view name,
                            const std::vector<VehicleKey>& keys, std::string_view origin) {
  // What the change touches is attributed to it, so the warnings a file gives about those keys
  // come back with it: ArduPilot above 50 Hz (rate_hz) and a serial link too slow for the new
  // rate (reported at the link, so a rate change attributes the link too).
  std::vector<std::string> changed;
  for (const VehicleKey& key : keys) changed.push_back(key.key);
  if (std::find(changed.begin(), changed.end(), "rate_hz") != changed.end()) {
    changed.emplace_back("link");
  }
  detail::ConfigDraft draft =
      detail::draft_from_config(base, "configuration", name, origin, changed);
  detail::Diagnostics diagnostics;
  const detail::Where where{std::string(origin)};
  const auto target =
      std::find_if(draft.vehicles.begin(), draft.vehicles.end(),
                   [&](const auto& v) { return v.name.value && *v.name.value == name; });
  if (target == draft.vehicles.end()) {
    diagnostics.error(where, "", "no vehicle named " + detail::quoted(name));
    return finish(draft, diagnostics, origin);
  }
  detail::VehicleDraft changes;
  changes.header = where;
  read_keys(keys, where, changes, diagnostics);
  const auto specs = detail::vehicle_keys();
  for (const VehicleKey& key : keys) {
    const bool known =
        std::any_of(specs.begin(), specs.end(), [&](const auto& s) { return s.name == key.key; });
    if (known && key.key != "rate_hz" && key.key != "messages") {
      diagnostics.error(where, key.key,
                        "cannot change while the vehicle runs (only rate_hz and messages can); "
                        "remove the vehicle and add it again");
    }
  }
  // The live message set: any profile, may be empty; the GPS-type ones need the [origin].
  if (const auto& messages = changes.messages.value; messages && !base.origin) {
    if (core::MessageSet(*messages).needs_origin()) {
      diagnostics.error(where, changes.messages.key, detail::kGpsNeedsOrigin);
    }
  }
  // Over uXRCE-DDS the poses are VehicleOdometry, made from ODOMETRY alone (px4_link.hpp).
  if (const auto& messages = changes.messages.value;
      messages && target->link.value && target->link.value->kind == LinkKind::ros2 &&
      !(core::MessageSet(*messages) == core::MessageSet{} ||
        core::MessageSet(*messages) == core::MessageSet{core::MessageKind::odometry})) {
    diagnostics.error(where, changes.messages.key,
                      "link " + to_string(*target->link.value) +
                          " carries the poses as PX4's VehicleOdometry, made from odometry only: "
                          "messages = [\"odometry\"] (or [] to send none)");
  }
  changes.messages = {};  // not the configured list of a custom profile: the Bridge holds it
  detail::merge(*target, changes);
  return finish(draft, diagnostics, origin);
}

}  // namespace mocaplink::config
