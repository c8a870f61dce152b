// Public entry points: parse_config, load_config, apply_overrides.
#include "mocaplink/config/load.hpp"

#include <algorithm>

#include "draft.hpp"

namespace mocaplink::config {
namespace detail {

std::string describe(const Where& where) {
  if (where.line == 0) return where.file;
  return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column);
}

void Diagnostics::error(const Where& where, std::string key, std::string message) {
  errors.push_back(
      ConfigError{where.file, where.line, where.column, std::move(key), std::move(message)});
}

void Diagnostics::warning(const Where& where, std::string key, std::string message) {
  warnings.push_back(
      ConfigError{where.file, where.line, where.column, std::move(key), std::move(message)});
}

namespace {

template <typename T>
Field<T> given(T value, const Where& where, std::string key) {
  Field<T> field;
  field.value = std::move(value);
  field.present = true;
  field.where = where;
  field.key = std::move(key);
  return field;
}

}  // namespace

ConfigDraft draft_from_config(const Config& config, std::string_view origin,
                              std::string_view vehicle, std::string_view vehicle_origin,
                              std::span<const std::string> changed) {
  const Where where{std::string(origin)};
  const Where change{std::string(vehicle_origin)};
  ConfigDraft d;
  d.document = where;
  d.mocap_header = where;
  d.source = given(config.mocap.source, where, "mocap.source");
  d.up = given(config.mocap.up, where, "mocap.up");
  d.north = given(config.mocap.north, where, "mocap.north");
  d.body_forward = given(config.mocap.body_forward, where, "mocap.body_forward");
  d.body_up = given(config.mocap.body_up, where, "mocap.body_up");
  if (config.origin) {
    d.origin_header = where;
    d.latitude_deg = given(config.origin->latitude_deg, where, "origin.latitude_deg");
    d.longitude_deg = given(config.origin->longitude_deg, where, "origin.longitude_deg");
    d.altitude_m = given(config.origin->altitude_m, where, "origin.altitude_m");
  }
  for (std::size_t i = 0; i < config.vehicles.size(); ++i) {
    const core::VehicleSpec& v = config.vehicles[i].spec;
    const bool is_changed = !vehicle.empty() && v.name == vehicle;
    VehicleDraft vd;
    vd.header = where;
    vd.prefix = "vehicle[" + std::to_string(i + 1) + "].";
    // Where a key is attributed: the change for its changed keys (bare name), else the document.
    const auto at = [&](const auto& value, const char* key) {
      if (is_changed && std::find(changed.begin(), changed.end(), key) != changed.end()) {
        return given(value, change, key);
      }
      return given(value, where, vd.prefix + key);
    };
    vd.name = at(v.name, "name");
    vd.body = at(v.body, "body");
    vd.link = at(config.vehicles[i].link, "link");
    if (!config.vehicles[i].gcs.empty()) vd.gcs = at(config.vehicles[i].gcs, "gcs");
    vd.system_id = at(v.system_id, "system_id");
    vd.component_id = at(v.component_id, "component_id");
    vd.profile = at(v.profile, "profile");
    if (v.profile == core::Profile::custom) vd.messages = at(v.messages, "messages");
    vd.rate_hz = at(v.rate_hz, "rate_hz");
    vd.signing_key = at(v.signing_key, "signing_key");
    vd.body_forward = at(v.body_axes.forward(), "body_forward");
    vd.body_up = at(v.body_axes.up(), "body_up");
    vd.enabled = at(v.enabled, "enabled");
    d.vehicles.push_back(std::move(vd));
  }
  d.tracking = config.tracking;
  d.listen = given(config.http.listen, where, "http.listen");
  d.token = given(config.http.token, where, "http.token");
  d.allowed_hosts = given(config.http.allowed_hosts, where, "http.allowed_hosts");
  d.max_connections_per_client =
      given(config.http.max_connections_per_client, where, "http.max_connections_per_client");
  if (config.ros2) {
    d.ros2_header = where;
    d.ros2_checked = config.ros2;
  }
  return d;
}

}  // namespace detail

namespace {

ConfigResult finish(const detail::ConfigDraft& draft, detail::Diagnostics& diagnostics) {
  ConfigResult result;
  auto config = detail::finalize(draft, diagnostics);
  // File positions first in file order; command-line entries (line 0) after, in option order.
  const auto by_position = [](const ConfigError& a, const ConfigError& b) {
    if ((a.line == 0) != (b.line == 0)) return a.line != 0;
    if (a.line == 0) return false;
    if (a.file != b.file) return a.file < b.file;
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  };
  std::stable_sort(diagnostics.errors.begin(), diagnostics.errors.end(), by_position);
  std::stable_sort(diagnostics.warnings.begin(), diagnostics.warnings.end(), by_position);
  result.errors = std::move(diagnostics.errors);
  result.warnings = std::move(diagnostics.warnings);
  if (result.errors.empty()) result.config = std::move(config);
  return result;
}

}  // namespace

ConfigResult parse_config(std::string_view toml_text, std::string_view filename,
                          const SourceValidator& validate_source) {
  return load_config(toml_text, filename, CommandLineOverrides{}, validate_source);
}

ConfigResult load_config(std::string_view toml_text, std::string_view filename,
                         const CommandLineOverrides& overrides,
                         const SourceValidator& validate_source) {
  detail::ConfigDraft draft;
  draft.validate_source = validate_source;
  detail::Diagnostics diagnostics;
  if (!detail::read_toml(toml_text, filename, draft, diagnostics)) {
    // Nothing after a syntax error is known; more messages would only mislead.
    ConfigResult result;
    result.errors = std::move(diagnostics.errors);
    return result;
  }
  detail::apply_command_line(overrides, draft, diagnostics);
  return finish(draft, diagnostics);
}

ConfigResult apply_overrides(const Config& base, const CommandLineOverrides& overrides,
                             std::string_view base_name, const SourceValidator& validate_source) {
  detail::ConfigDraft draft = detail::draft_from_config(base, base_name);
  draft.validate_source = validate_source;
  detail::Diagnostics diagnostics;
  detail::apply_command_line(overrides, draft, diagnostics);
  return finish(draft, diagnostics);
}

}  // namespace mocaplink::config
