// Command-line overrides (--source, --http, --vehicle NAME:key=value,...) applied to a draft.
// The same key handlers as the TOML reader parse the values, so a key means the same thing in both
// places; only the text → typed value step differs (TOML has types, the command line has text).
#include <algorithm>
#include <string>

#include "draft.hpp"
#include "text_util.hpp"

namespace mocaplink::config::detail {
namespace {

template <typename Target>
const KeySpec<Target>& find_spec(std::span<const KeySpec<Target>> specs, std::string_view name) {
  const auto found =
      std::find_if(specs.begin(), specs.end(), [&](const auto& s) { return s.name == name; });
  return *found;  // callers name keys that exist in keys.cpp
}

/// Turns option text into a value of the declared type; std::nullopt after reporting an error.
std::optional<Value> text_to_value(std::string_view text, ValueType type, Where where,
                                   std::string key, Diagnostics& diagnostics) {
  Value value;
  value.where = std::move(where);
  value.key = std::move(key);
  switch (type) {
    case ValueType::string:
      value.data = std::string(text);
      return value;
    case ValueType::integer:
      if (const auto i = parse_integer(text)) {
        value.data = static_cast<std::int64_t>(*i);
        return value;
      }
      diagnostics.error(value.where, value.key, "expected an integer, got " + quoted(text));
      return std::nullopt;
    case ValueType::number:
      if (const auto n = parse_double(text)) {
        value.data = *n;
        return value;
      }
      diagnostics.error(value.where, value.key, "expected a number, got " + quoted(text));
      return std::nullopt;
    case ValueType::boolean:
      if (text == "true" || text == "false") {
        value.data = text == "true";
        return value;
      }
      diagnostics.error(value.where, value.key, "expected true or false, got " + quoted(text));
      return std::nullopt;
    case ValueType::string_list: {
      // messages=odometry+hil_gps ('+' because ',' separates keys).
      std::vector<std::string> items;
      std::size_t start = 0;
      while (start < text.size()) {
        const auto plus = text.find('+', start);
        items.emplace_back(
            text.substr(start, plus == std::string_view::npos ? plus : plus - start));
        if (plus == std::string_view::npos) break;
        start = plus + 1;
      }
      value.data = std::move(items);
      return value;
    }
  }
  return std::nullopt;
}

template <typename Field>
void overwrite(Field& target, const Field& source) {
  if (source.present) target = source;
}

}  // namespace

void merge(VehicleDraft& target, const VehicleDraft& source) {
  overwrite(target.body, source.body);
  overwrite(target.link, source.link);
  overwrite(target.gcs, source.gcs);
  overwrite(target.system_id, source.system_id);
  overwrite(target.component_id, source.component_id);
  overwrite(target.profile, source.profile);
  overwrite(target.messages, source.messages);
  overwrite(target.rate_hz, source.rate_hz);
  overwrite(target.signing_key, source.signing_key);
  overwrite(target.body_forward, source.body_forward);
  overwrite(target.body_up, source.body_up);
  overwrite(target.enabled, source.enabled);
  target.mistyped.insert(target.mistyped.end(), source.mistyped.begin(), source.mistyped.end());
}

namespace {

/// Parses one --vehicle SPEC into a draft holding only the keys it gives.
std::optional<VehicleDraft> parse_vehicle_spec(std::string_view spec, const Where& where,
                                               Diagnostics& diagnostics) {
  const auto colon = spec.find(':');
  if (colon == std::string_view::npos) {
    diagnostics.error(where, "",
                      "expected NAME:key=value,key=value,... as in "
                      "'quad1:body=Quad1,link=udp://127.0.0.1:14540,profile=px4,system_id=1', "
                      "got " +
                          quoted(spec));
    return std::nullopt;
  }
  VehicleDraft draft;
  draft.header = where;
  const auto specs = vehicle_keys();
  std::vector<std::string_view> names;
  for (const auto& s : specs) {
    if (s.name != "name") names.push_back(s.name);
  }
  if (auto value =
          text_to_value(spec.substr(0, colon), ValueType::string, where, "name", diagnostics)) {
    find_spec(specs, "name").apply(draft, *value, diagnostics);
  }
  std::string_view rest = spec.substr(colon + 1);
  std::vector<std::string_view> seen;
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    const auto item = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    const auto eq = item.find('=');
    if (eq == std::string_view::npos) {
      diagnostics.error(where, "", "expected key=value, got " + quoted(item));
      continue;
    }
    const auto key = item.substr(0, eq);
    const std::string key_text(key);
    if (key == "name") {
      diagnostics.error(where, key_text, "the name goes before the ':', as in quad1:body=Quad1");
      continue;
    }
    const auto found =
        std::find_if(specs.begin(), specs.end(), [&](const auto& s) { return s.name == key; });
    if (found == specs.end()) {
      diagnostics.error(where, key_text, unknown_key_message(key, names));
      continue;
    }
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
      diagnostics.error(where, key_text, "given twice");
      continue;
    }
    seen.push_back(key);
    if (auto value =
            text_to_value(item.substr(eq + 1), found->type, where, key_text, diagnostics)) {
      found->apply(draft, *value, diagnostics);
    } else {
      draft.mistyped.push_back(key_text);
    }
  }
  return draft;
}

}  // namespace

void apply_command_line(const CommandLineOverrides& overrides, ConfigDraft& draft,
                        Diagnostics& diagnostics) {
  if (overrides.source) {
    Value value{*overrides.source, Where{"--source"}, ""};
    find_spec(mocap_keys(), "source").apply(draft, value, diagnostics);
  }
  if (overrides.http) {
    Value value{*overrides.http, Where{"--http"}, ""};
    find_spec(http_keys(), "listen").apply(draft, value, diagnostics);
  }
  for (const std::string& host : overrides.http_allow_hosts) {
    add_allowed_host(draft, Value{host, Where{"--http-allow-host"}, ""}, diagnostics);
  }
  const std::vector<std::string>& vehicles = overrides.vehicles;
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const Where where{"--vehicle " + std::to_string(i + 1)};
    auto spec = parse_vehicle_spec(vehicles[i], where, diagnostics);
    if (!spec) continue;
    if (!spec->name.value) {
      // A bad name was reported; keep the other keys' errors but do not guess a target.
      continue;
    }
    const auto existing = std::find_if(
        draft.vehicles.begin(), draft.vehicles.end(),
        [&](const auto& v) { return v.name.value && *v.name.value == *spec->name.value; });
    if (existing != draft.vehicles.end()) {
      merge(*existing, *spec);
    } else {
      draft.vehicles.push_back(std::move(*spec));
    }
  }
}

}  // namespace mocaplink::config::detail
