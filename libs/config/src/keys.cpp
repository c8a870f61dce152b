// The schema of every table: key names, types, ranges and value parsers. docs/config.md documents
// the same table for users; keep them in step.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "draft.hpp"
#include "mocaplink/core/bridge.hpp"
#include "text_util.hpp"

namespace mocaplink::config::detail {
namespace {

template <typename T>
void assign(Field<T>& field, const Value& value, ValueOrError<T> parsed, Diagnostics& diagnostics) {
  field.present = true;
  field.where = value.where;
  field.key = value.key;
  field.value.reset();
  if (parsed) {
    field.value = std::move(parsed).value();
  } else {
    diagnostics.error(value.where, value.key, parsed.error());
  }
}

/// Inclusive range check on a number; the bounds appear in the message.
ValueOrError<double> number_in(double v, double low, double high, bool low_inclusive = true) {
  const bool ok = std::isfinite(v) && (low_inclusive ? v >= low : v > low) && v <= high;
  if (ok) return v;
  return ValueOrError<double>::failure(std::string("must be ") +
                                       (low_inclusive ? "from " : "above ") + format_number(low) +
                                       (low_inclusive ? " to " : " and at most ") +
                                       format_number(high) + ", got " + format_number(v));
}

ValueOrError<std::uint8_t> byte_in(std::int64_t v, std::int64_t low) {
  if (v >= low && v <= 255) return static_cast<std::uint8_t>(v);
  return ValueOrError<std::uint8_t>::failure("must be an integer from " + std::to_string(low) +
                                             " to 255, got " + std::to_string(v));
}

void note_tracking_site(ConfigDraft& d, const Value& value) {
  const auto dot = value.key.rfind('.');
  d.tracking_sites.push_back(
      {dot == std::string::npos ? value.key : value.key.substr(dot + 1), value.where, value.key});
}

void set_optional(ConfigDraft& d, double& slot, const Value& value, ValueOrError<double> parsed,
                  Diagnostics& diagnostics) {
  note_tracking_site(d, value);
  if (parsed) {
    slot = parsed.value();
  } else {
    diagnostics.error(value.where, value.key, parsed.error());
  }
}

// ---- [mocap] ----

void mocap_source(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  // The shape here; what the scheme and its options mean, the caller's source validator says.
  auto parsed = parse_source_url(v.text());
  if (d.validate_source) {
    if (auto error = d.validate_source(v.text(), SourceContext{}).error; !error.empty()) {
      parsed = ValueOrError<SourceUrl>::failure(std::move(error));
    }
  }
  assign(d.source, v, std::move(parsed), diag);
}
void mocap_up(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.up, v, parse_axis(v.text()), diag);
}
void mocap_north(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.north, v, parse_north(v.text()), diag);
}
void mocap_body_forward(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.body_forward, v, parse_axis(v.text()), diag);
}
void mocap_body_up(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.body_up, v, parse_axis(v.text()), diag);
}

constexpr std::array<KeySpec<ConfigDraft>, 5> kMocapKeys = {{
    {"source", ValueType::string, mocap_source},
    {"up", ValueType::string, mocap_up},
    {"north", ValueType::string, mocap_north},
    {"body_forward", ValueType::string, mocap_body_forward},
    {"body_up", ValueType::string, mocap_body_up},
}};

// ---- [origin] ----

void origin_latitude(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.latitude_deg, v, number_in(v.number(), -90.0, 90.0), diag);
}
void origin_longitude(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.longitude_deg, v, number_in(v.number(), -180.0, 180.0), diag);
}
void origin_altitude(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  // Dead Sea shore to well above any lab; catches feet-for-metres and mm-for-metres slips.
  assign(d.altitude_m, v, number_in(v.number(), -1000.0, 10000.0), diag);
}

constexpr std::array<KeySpec<ConfigDraft>, 3> kOriginKeys = {{
    {"latitude_deg", ValueType::number, origin_latitude},
    {"longitude_deg", ValueType::number, origin_longitude},
    {"altitude_m", ValueType::number, origin_altitude},
}};

// ---- [tracking] (sanity bounds only; the core owns the defaults and the cross-key rules) ----

void tracking_loss(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.loss_timeout_ms, v, number_in(v.number(), 0.0, 60000.0, false), diag);
}
void tracking_reset(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.reset_after_ms, v, number_in(v.number(), 0.0, 600000.0), diag);
}
void tracking_position_noise(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.position_noise_m, v, number_in(v.number(), 0.0, 10.0, false), diag);
}
void tracking_attitude_noise(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.attitude_noise_rad, v,
               number_in(v.number(), 0.0, std::numbers::pi, false), diag);
}
void tracking_accel_noise(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.accel_noise_mps2, v, number_in(v.number(), 0.0, 1000.0, false), diag);
}
void tracking_angular_noise(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.angular_accel_noise_radps2, v,
               number_in(v.number(), 0.0, 10000.0, false), diag);
}
void tracking_gate_sigma(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.gate_sigma, v, number_in(v.number(), 0.0, 100.0, false), diag);
}
void tracking_gate_min(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.gate_min_m, v, number_in(v.number(), 0.0, 100.0), diag);
}
void tracking_jump_m(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.reset_jump_m, v, number_in(v.number(), 0.0, 100.0, false), diag);
}
void tracking_jump_rad(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  set_optional(d, d.tracking.reset_jump_rad, v, number_in(v.number(), 0.0, std::numbers::pi, false),
               diag);
}
void tracking_jump_frames(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  note_tracking_site(d, v);
  if (v.integer() >= 1 && v.integer() <= 1000) {
    d.tracking.jump_confirm_frames = static_cast<std::uint32_t>(v.integer());
  } else {
    diag.error(v.where, v.key,
               "must be an integer from 1 to 1000, got " + std::to_string(v.integer()));
  }
}

constexpr std::array<KeySpec<ConfigDraft>, 11> kTrackingKeys = {{
    {"loss_timeout_ms", ValueType::number, tracking_loss},
    {"reset_after_ms", ValueType::number, tracking_reset},
    {"position_noise_m", ValueType::number, tracking_position_noise},
    {"attitude_noise_rad", ValueType::number, tracking_attitude_noise},
    {"accel_noise_mps2", ValueType::number, tracking_accel_noise},
    {"angular_accel_noise_radps2", ValueType::number, tracking_angular_noise},
    {"gate_sigma", ValueType::number, tracking_gate_sigma},
    {"gate_min_m", ValueType::number, tracking_gate_min},
    {"jump_confirm_frames", ValueType::integer, tracking_jump_frames},
    {"reset_jump_m", ValueType::number, tracking_jump_m},
    {"reset_jump_rad", ValueType::number, tracking_jump_rad},
}};

// ---- [http] ----

void http_listen(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.listen, v, parse_host_port(v.text(), HostPortRules{.port_zero_ok = true}), diag);
}
void http_token(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  // Never echo the token. 16 characters keep a guessing attack over HTTP impractical.
  ValueOrError<std::string> parsed = v.text();
  if (!v.text().empty() && v.text().size() < 16) {
    parsed = ValueOrError<std::string>::failure("must be empty or at least 16 characters, got " +
                                                std::to_string(v.text().size()));
  }
  assign(d.token, v, std::move(parsed), diag);
}

void http_max_connections_per_client(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  // 256: the dashboard serves that many connections at once (web::DashboardServerConfig).
  ValueOrError<std::uint32_t> parsed = ValueOrError<std::uint32_t>::failure(
      "must be an integer from 1 to 256, got " + std::to_string(v.integer()));
  if (v.integer() >= 1 && v.integer() <= 256) parsed = static_cast<std::uint32_t>(v.integer());
  assign(d.max_connections_per_client, v, std::move(parsed), diag);
}

ValueOrError<HostPort> parse_allowed_host(const std::string& text) {
  if (const auto scheme = text.find("://"); scheme != std::string::npos) {
    return ValueOrError<HostPort>::failure(
        "expected a host name, not a URL: write " +
        quoted(std::string_view(text).substr(scheme + 3, text.find('/', scheme + 3) - scheme - 3)) +
        " for " + quoted(text));
  }
  auto parsed = parse_host_port(text, HostPortRules{.port_optional = true});
  if (!parsed) {
    return ValueOrError<HostPort>::failure(
        parsed.error() +
        " (expected a host name or address as the browser's address bar gives "
        "it, optionally with :PORT, e.g. \"lab-pc\" or \"lab-pc.local:8080\")");
  }
  return parsed;
}

void http_allowed_hosts(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  std::vector<HostPort> hosts;
  for (const std::string& entry : v.list()) {
    auto parsed = parse_allowed_host(entry);
    if (!parsed) {
      assign(d.allowed_hosts, v, ValueOrError<std::vector<HostPort>>::failure(parsed.error()),
             diag);
      return;
    }
    hosts.push_back(std::move(parsed).value());
  }
  assign(d.allowed_hosts, v, ValueOrError<std::vector<HostPort>>(std::move(hosts)), diag);
}

constexpr std::array<KeySpec<ConfigDraft>, 4> kHttpKeys = {{
    {"listen", ValueType::string, http_listen},
    {"token", ValueType::string, http_token},
    {"allowed_hosts", ValueType::string_list, http_allowed_hosts},
    {"max_connections_per_client", ValueType::integer, http_max_connections_per_client},
}};

// ---- [[vehicle]] ----

ValueOrError<std::string> parse_name(const std::string& text) {
  if (core::is_valid_vehicle_name(text)) return text;
  return ValueOrError<std::string>::failure(
      "must be 1 to " + std::to_string(core::kMaxVehicleNameLength) +
      " letters, digits, '_', '-' or '.', got " + quoted(text));
}

ValueOrError<std::string> parse_body(const std::string& text) {
  if (core::is_valid_body_name(text)) return text;
  return ValueOrError<std::string>::failure(
      "must be the rigid-body name as the mocap system spells it (1 to " +
      std::to_string(core::kMaxBodyNameLength) + " characters, no control characters), got " +
      quoted(text));
}

ValueOrError<std::vector<core::MessageKind>> parse_messages(const std::vector<std::string>& names) {
  std::vector<core::MessageKind> out;
  for (const auto& name : names) {
    auto kind = parse_message_kind(name);
    if (!kind) return ValueOrError<std::vector<core::MessageKind>>::failure(kind.error());
    if (std::find(out.begin(), out.end(), kind.value()) != out.end()) {
      return ValueOrError<std::vector<core::MessageKind>>::failure(quoted(name) +
                                                                   " is listed twice");
    }
    out.push_back(kind.value());
  }
  return out;
}

using SigningKey = std::optional<std::array<std::uint8_t, 32>>;

ValueOrError<SigningKey> parse_signing_key(const std::string& text) {
  if (text.empty()) return SigningKey{};
  const auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  const bool hex = std::all_of(text.begin(), text.end(), [&](char c) { return nibble(c) >= 0; });
  if (text.size() != 64 || !hex) {
    // The key is a secret: describe it, never print it.
    return ValueOrError<SigningKey>::failure(
        "must be 64 hexadecimal characters (a 32-byte secret) or \"\" for unsigned, got " +
        std::to_string(text.size()) + " characters" + (hex ? "" : " including non-hex ones"));
  }
  std::array<std::uint8_t, 32> key{};
  for (std::size_t i = 0; i < key.size(); ++i) {
    key[i] = static_cast<std::uint8_t>(nibble(text[2 * i]) * 16 + nibble(text[2 * i + 1]));
  }
  return SigningKey{key};
}

void vehicle_name(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.name, v, parse_name(v.text()), diag);
}
void vehicle_body(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.body, v, parse_body(v.text()), diag);
}
void vehicle_link(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.link, v, parse_link_url(v.text()), diag);
}
/// gcs = ["udpin://:14550", ...]: each a link URL (the same forms), none twice.
ValueOrError<std::vector<LinkUrl>> parse_gcs(const std::vector<std::string>& urls) {
  using Result = ValueOrError<std::vector<LinkUrl>>;
  std::vector<LinkUrl> out;
  for (std::size_t i = 0; i < urls.size(); ++i) {
    auto url = parse_link_url(urls[i]);
    const std::string which = "entry " + std::to_string(i + 1) + " (" + quoted(urls[i]) + "): ";
    if (!url) return Result::failure(which + url.error());
    if (std::find(out.begin(), out.end(), url.value()) != out.end()) {
      return Result::failure(which + "listed twice");
    }
    out.push_back(std::move(url).value());
  }
  return out;
}

void vehicle_gcs(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.gcs, v, parse_gcs(v.list()), diag);
}
void vehicle_system_id(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.system_id, v, byte_in(v.integer(), 1), diag);
}
void vehicle_component_id(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  auto parsed = byte_in(v.integer(), 1);
  if (parsed && parsed.value() == 1) {
    parsed = ValueOrError<std::uint8_t>::failure(
        "1 is the autopilot itself (MAV_COMP_ID_AUTOPILOT1); use another id, normally 197");
  }
  assign(d.component_id, v, std::move(parsed), diag);
}
void vehicle_profile(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.profile, v, parse_profile(v.text()), diag);
}
void vehicle_messages(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.messages, v, parse_messages(v.list()), diag);
}
void vehicle_rate(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.rate_hz, v, number_in(v.number(), 0.0, core::kMaxSenderRateHz, false), diag);
}
void vehicle_signing_key(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.signing_key, v, parse_signing_key(v.text()), diag);
}
void vehicle_body_forward(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.body_forward, v, parse_axis(v.text()), diag);
}
void vehicle_body_up(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.body_up, v, parse_axis(v.text()), diag);
}
void vehicle_enabled(VehicleDraft& d, const Value& v, Diagnostics& diag) {
  assign(d.enabled, v, ValueOrError<bool>(v.boolean()), diag);
}

constexpr std::array<KeySpec<VehicleDraft>, 13> kVehicleKeys = {{
    {"name", ValueType::string, vehicle_name},
    {"body", ValueType::string, vehicle_body},
    {"link", ValueType::string, vehicle_link},
    {"gcs", ValueType::string_list, vehicle_gcs},
    {"system_id", ValueType::integer, vehicle_system_id},
    {"component_id", ValueType::integer, vehicle_component_id},
    {"profile", ValueType::string, vehicle_profile},
    {"messages", ValueType::string_list, vehicle_messages},
    {"rate_hz", ValueType::number, vehicle_rate},
    {"signing_key", ValueType::string, vehicle_signing_key},
    {"body_forward", ValueType::string, vehicle_body_forward},
    {"body_up", ValueType::string, vehicle_body_up},
    {"enabled", ValueType::boolean, vehicle_enabled},
}};

template <typename Spec, std::size_t N>
bool has_key(const std::array<Spec, N>& specs, std::string_view key) {
  return std::any_of(specs.begin(), specs.end(), [&](const Spec& s) { return s.name == key; });
}

// ---- [ros2] ----

void ros2_domain_id(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  // 232: the largest domain whose RTPS ports (7400 + 250·d + …) fit in 16 bits; ROS advises at
  // most 101 on Linux (finalize warns).
  ValueOrError<std::uint32_t> parsed = ValueOrError<std::uint32_t>::failure(
      "must be an integer from 0 to " + std::to_string(kMaxRosDomainId) + ", got " +
      std::to_string(v.integer()));
  if (v.integer() >= 0 && v.integer() <= static_cast<std::int64_t>(kMaxRosDomainId)) {
    parsed = static_cast<std::uint32_t>(v.integer());
  }
  assign(d.ros2_domain_id, v, std::move(parsed), diag);
}
void ros2_namespace(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  ValueOrError<std::string> parsed = v.text();
  if (auto problem = core::ros_namespace_problem(v.text())) {
    parsed = ValueOrError<std::string>::failure(
        "must be a ROS namespace (tokens of letters, digits and '_' joined by '/', none starting "
        "with a digit), got " +
        quoted(v.text()) + ": it " + *problem);
  } else if (!v.text().empty() && v.text().front() == '/') {
    parsed = v.text().substr(1);
  }
  assign(d.ros2_namespace, v, std::move(parsed), diag);
}
void ros2_frame_id(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  ValueOrError<std::string> parsed = v.text();
  if (auto problem = core::ros_frame_id_problem(v.text())) {
    parsed = ValueOrError<std::string>::failure(
        "must be a tf2 frame id such as \"world\" or "
        "\"map\", got " +
        quoted(v.text()) + ": it " + *problem);
  }
  assign(d.ros2_frame_id, v, std::move(parsed), diag);
}
void ros2_bodies(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  for (const std::string& body : v.list()) {
    if (auto parsed = parse_body(body); !parsed) {
      assign(d.ros2_bodies, v, ValueOrError<std::vector<std::string>>::failure(parsed.error()),
             diag);
      return;
    }
  }
  assign(d.ros2_bodies, v, ValueOrError<std::vector<std::string>>(v.list()), diag);
}
void ros2_publish(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  constexpr std::array<std::string_view, 3> kTopics = {"pose", "odom", "tf"};
  std::array<bool, 3> chosen{};
  for (const std::string& name : v.list()) {
    const auto it = std::find(kTopics.begin(), kTopics.end(), name);
    if (it == kTopics.end()) {
      assign(d.ros2_publish, v,
             ValueOrError<std::array<bool, 3>>::failure(
                 "lists " + quoted(name) + did_you_mean(name, kTopics) +
                 " (each of \"pose\", \"odom\", \"tf\" at most once)"),
             diag);
      return;
    }
    auto& slot = chosen[static_cast<std::size_t>(it - kTopics.begin())];
    if (slot) {
      assign(d.ros2_publish, v,
             ValueOrError<std::array<bool, 3>>::failure(quoted(name) + " is listed twice"), diag);
      return;
    }
    slot = true;
  }
  // An empty list is for a [ros2] table that only ros2:// links use (finalize_ros2 checks).
  assign(d.ros2_publish, v, ValueOrError<std::array<bool, 3>>(chosen), diag);
}
void ros2_axes(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  ValueOrError<core::RosAxes> parsed = ValueOrError<core::RosAxes>::failure(
      "must be \"enu_flu\" (REP 103: ENU world, FLU body) or \"mocap\" (the mocap system's own "
      "axes), got " +
      quoted(v.text()));
  for (const core::RosAxes axes : {core::RosAxes::enu_flu, core::RosAxes::mocap}) {
    if (v.text() == core::to_string(axes)) parsed = axes;
  }
  assign(d.ros2_axes, v, std::move(parsed), diag);
}
void ros2_interface(ConfigDraft& d, const Value& v, Diagnostics& diag) {
  ValueOrError<std::string> parsed = v.text();
  if (v.text() != "all" && v.text() != "loopback" && !is_ipv4_literal(v.text())) {
    parsed = ValueOrError<std::string>::failure(
        "must be \"all\", \"loopback\" or an IPv4 address of this machine (e.g. "
        "\"192.168.1.10\"), got " +
        quoted(v.text()));
  }
  assign(d.ros2_interface, v, std::move(parsed), diag);
}

constexpr std::array<KeySpec<ConfigDraft>, 7> kRos2Keys = {{
    {"domain_id", ValueType::integer, ros2_domain_id},
    {"namespace", ValueType::string, ros2_namespace},
    {"frame_id", ValueType::string, ros2_frame_id},
    {"bodies", ValueType::string_list, ros2_bodies},
    {"publish", ValueType::string_list, ros2_publish},
    {"axes", ValueType::string, ros2_axes},
    {"interface", ValueType::string, ros2_interface},
}};

}  // namespace

std::span<const KeySpec<ConfigDraft>> mocap_keys() {
  return kMocapKeys;
}
std::span<const KeySpec<ConfigDraft>> origin_keys() {
  return kOriginKeys;
}
std::span<const KeySpec<ConfigDraft>> tracking_keys() {
  return kTrackingKeys;
}
std::span<const KeySpec<ConfigDraft>> http_keys() {
  return kHttpKeys;
}
std::span<const KeySpec<ConfigDraft>> ros2_keys() {
  return kRos2Keys;
}

void add_allowed_host(ConfigDraft& draft, const Value& value, Diagnostics& diagnostics) {
  auto parsed = parse_allowed_host(value.text());
  if (!parsed) {
    diagnostics.error(value.where, value.key, parsed.error());
    return;
  }
  Field<std::vector<HostPort>>& field = draft.allowed_hosts;
  if (!field.present) {  // the file's list, if any, stays attributed to the file
    field.present = true;
    field.where = value.where;
    field.key = value.key;
  }
  if (!field.value) field.value.emplace();
  field.value->push_back(std::move(parsed).value());
}
const char* expected_name(ValueType type) {
  switch (type) {
    case ValueType::string:
      return "a string";
    case ValueType::integer:
      return "an integer";
    case ValueType::number:
      return "a number";
    case ValueType::boolean:
      return "true or false";
    case ValueType::string_list:
      return "an array of strings";
  }
  return "?";
}

std::span<const KeySpec<VehicleDraft>> vehicle_keys() {
  return kVehicleKeys;
}

std::string unknown_key_message(std::string_view key, std::span<const std::string_view> here) {
  if (auto suggestion = did_you_mean(key, here); !suggestion.empty()) {
    return "unknown key" + suggestion;
  }
  struct Home {
    std::string_view table;
    bool found;
  };
  const std::array<Home, 6> homes = {{
      {"[mocap]", has_key(kMocapKeys, key)},
      {"[origin]", has_key(kOriginKeys, key)},
      {"[[vehicle]]", has_key(kVehicleKeys, key)},
      {"[tracking]", has_key(kTrackingKeys, key)},
      {"[http]", has_key(kHttpKeys, key)},
      {"[ros2]", has_key(kRos2Keys, key)},
  }};
  for (const auto& home : homes) {
    if (home.found) return "unknown key here; it belongs in " + std::string(home.table);
  }
  return "unknown key (allowed here: " + join(here) + ")";
}

}  // namespace mocaplink::config::detail
