// ConfigDraft → Config: required keys, defaults, and the rules that involve several keys
// (axes at right angles, messages vs profile, origin for GPS messages, unique names, unique
// system ids per link, the dashboard token). Every problem is reported; none stops the others.
#include <algorithm>
#include <string>

#include "draft.hpp"
#include "mocaplink/core/tracker.hpp"
#include "text_util.hpp"

namespace mocaplink::config::detail {
namespace {

constexpr const char* kMissing = "missing required key";

/// The value of a field, or `fallback` when it was not given.
template <typename T>
T value_or(const Field<T>& field, T fallback) {
  return field.value.value_or(std::move(fallback));
}

bool contains(const std::vector<std::string>& keys, std::string_view key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

/// Reports a required field that was not given (given-but-invalid ones are already reported).
/// `name` is the bare key as in `mistyped`, `key` the displayed path.
template <typename T>
bool require(const Field<T>& field, const std::vector<std::string>& mistyped, std::string_view name,
             const Where& where, const std::string& key, Diagnostics& diagnostics) {
  if (field.present) return field.value.has_value();
  if (!contains(mistyped, name)) diagnostics.error(where, key, kMissing);
  return false;
}

/// One axis-valued key as used by a right-angle rule: its effective value and where it was
/// written (or the table it defaults in).
struct AxisUse {
  core::SignedAxis axis = core::axis::pos_x;
  bool written = false;
  bool invalid = false;  ///< written with a bad value: already reported, skip the rule
  Where where;
  std::string key;
  std::string name;
};

template <typename T>
AxisUse axis_use(const Field<T>& field, core::SignedAxis effective, std::string name,
                 const Where& table, const std::string& default_key) {
  return AxisUse{effective,
                 field.present,
                 field.present && !field.value,
                 field.present ? field.where : table,
                 field.present ? field.key : default_key,
                 std::move(name)};
}

/// Checks that two axes are at right angles; the error goes to the one that was written (the
/// second if both were) and names both.
void check_perpendicular(const AxisUse& a, const AxisUse& b, Diagnostics& diagnostics) {
  if (a.invalid || b.invalid || core::are_perpendicular(a.axis, b.axis)) return;
  const AxisUse& blamed = (b.written || !a.written) ? b : a;
  diagnostics.error(blamed.where, blamed.key,
                    b.name + " (" + core::to_string(b.axis) + ") must be at right angles to " +
                        a.name + " (" + core::to_string(a.axis) + ")");
}

MocapSettings finalize_mocap(const ConfigDraft& d, Diagnostics& diagnostics) {
  MocapSettings mocap;
  const Where table = d.mocap_header.value_or(d.document);
  if (require(d.source, d.mistyped, "source", table, "mocap.source", diagnostics))
    mocap.source = *d.source.value;
  mocap.up = value_or(d.up, core::axis::pos_z);
  mocap.north = value_or(d.north, core::North{core::axis::pos_x});
  mocap.body_forward = value_or(d.body_forward, core::axis::pos_x);
  mocap.body_up = value_or(d.body_up, core::axis::pos_z);
  if (const auto* north_axis = std::get_if<core::SignedAxis>(&mocap.north)) {
    check_perpendicular(axis_use(d.up, mocap.up, "up", table, "mocap.up"),
                        axis_use(d.north, *north_axis, "north", table, "mocap.north"), diagnostics);
  }
  check_perpendicular(
      axis_use(d.body_forward, mocap.body_forward, "body_forward", table, "mocap.body_forward"),
      axis_use(d.body_up, mocap.body_up, "body_up", table, "mocap.body_up"), diagnostics);
  if (d.source.value && d.validate_source) {
    // The source's URL was judged when given (keys.cpp); its configuration warnings depend on the
    // rest of [mocap] (e.g. a system that streams Y-up when `up` is not written).
    const std::string key = d.source.key.empty() ? "mocap.source" : d.source.key;
    for (auto& warning :
         d.validate_source(d.source.value->text, SourceContext{d.up.present}).warnings) {
      diagnostics.warning(d.source.where, key, std::move(warning));
    }
  }
  return mocap;
}

std::optional<core::GeodeticPosition> finalize_origin(const ConfigDraft& d,
                                                      Diagnostics& diagnostics) {
  if (!d.origin_header) return std::nullopt;
  const bool lat = require(d.latitude_deg, d.mistyped, "latitude_deg", *d.origin_header,
                           "origin.latitude_deg", diagnostics);
  const bool lon = require(d.longitude_deg, d.mistyped, "longitude_deg", *d.origin_header,
                           "origin.longitude_deg", diagnostics);
  const bool alt = require(d.altitude_m, d.mistyped, "altitude_m", *d.origin_header,
                           "origin.altitude_m", diagnostics);
  if (!lat || !lon || !alt) return std::nullopt;
  return core::GeodeticPosition{*d.latitude_deg.value, *d.longitude_deg.value, *d.altitude_m.value};
}

/// A plain udp:// link (no `bind`) to a PX4 goes deaf after a restart: PX4's UDP link answers
/// only the first address that spoke to it since boot (mavlink_receiver latches its partner), and
/// each process sends from a new ephemeral port. The warning names the form that stays heard.
std::optional<std::string> px4_udp_warning(core::Profile profile, const LinkUrl& link) {
  const bool px4 = profile == core::Profile::px4 || profile == core::Profile::px4_gps ||
                   profile == core::Profile::automatic;
  if (!px4 || link.kind != LinkKind::udp || link.bind) return std::nullopt;
  const std::uint16_t port = link.address.port;
  // On this machine only PX4 SITL can be the vehicle, and it serves known ports (ROMFS
  // init.d-posix/px4-rc.mavlink, instance i): its onboard (API/offboard) link listens on 14580+i
  // and sends to 14540+i from boot — listening there needs no first word at all —, its GCS link
  // listens on 18570+i. Any other loopback port is a listener (QGroundControl's 14550, the demo's).
  const bool loopback = is_loopback(link.address.host);
  const bool sitl_onboard = loopback && port >= 14580 && port <= 14589;
  const bool sitl_gcs = loopback && port >= 18570 && port <= 18579;
  if (loopback && !sitl_onboard && !sitl_gcs) return std::nullopt;
  // Any free local port will do; the vehicle's own number where the vehicle is another machine
  // (mavros's udp://:14540@HOST:14557 convention), another one on this machine, where the
  // vehicle's port is taken.
  const std::uint16_t example_port =
      !is_loopback(link.address.host)
          ? port
          : static_cast<std::uint16_t>(port < 64535 ? port + 1000 : port - 1000);
  std::string advice = sitl_onboard ? "use udpin://127.0.0.1:" + std::to_string(port - 40) +
                                          " (PX4 SITL's onboard link sends there from boot)"
                                    : "send from a fixed local port, as in " + to_string(link) +
                                          "?bind=:" + std::to_string(example_port) +
                                          ", so that every mocaplink process is the same peer";
  return std::string(profile == core::Profile::automatic ? "profile auto may find a PX4, which"
                                                         : "a PX4") +
         " answers only the first address that spoke to its UDP port since it booted, and a "
         "plain udp:// link sends from a new port in every process: after `vehicle setup` or a "
         "restart of `run` the next process would hear nothing until the vehicle reboots; " +
         advice;
}

/// A ros2:// link (docs/ros2.md "PX4 over uXRCE-DDS") reaches a PX4 over DDS: the `px4` profile
/// (auto means it), on the [ros2] table's domain and interface; nothing of MAVLink's own (signing,
/// a ground station's traffic) can go that way. False when the vehicle is refused.
bool check_ros2_link(const VehicleDraft& v, const ConfigDraft& d, Vehicle& vehicle,
                     Diagnostics& diagnostics) {
  bool ok = true;
  const std::string url = to_string(vehicle.link);
  if (!d.ros2_header) {
    diagnostics.error(v.link.where, v.link.key,
                      "link " + url +
                          " is on the ROS 2 graph: add a [ros2] table (its domain_id "
                          "and interface; publish = [] if no body topics are wanted)");
    ok = false;
  }
  core::Profile& profile = vehicle.spec.profile;
  if (profile == core::Profile::automatic) profile = core::Profile::px4;  // only PX4 speaks it
  if (profile != core::Profile::px4) {
    diagnostics.error(v.profile.where, v.profile.key,
                      "link " + url +
                          " feeds PX4's vehicle_visual_odometry: profile must be "
                          "\"px4\" (or \"auto\"), got \"" +
                          std::string(core::to_string(profile)) + "\"");
    ok = false;
  }
  if (vehicle.spec.signing_key) {
    diagnostics.error(v.signing_key.where, v.signing_key.key,
                      "link " + url +
                          " carries no MAVLink, so nothing is signed: remove "
                          "signing_key, or reach the vehicle by a MAVLink link");
    ok = false;
  }
  if (!vehicle.gcs.empty()) {
    diagnostics.error(v.gcs.where, v.gcs.key,
                      "link " + url +
                          " carries no MAVLink, so no ground station's traffic "
                          "can go through it: remove gcs, or reach the vehicle by a MAVLink link");
    ok = false;
  }
  return ok;
}

std::optional<Vehicle> finalize_vehicle(const VehicleDraft& v, const ConfigDraft& d,
                                        const MocapSettings& mocap, bool have_origin,
                                        Diagnostics& diagnostics) {
  const auto key = [&](const char* name) { return v.prefix + name; };
  bool ok = require(v.name, v.mistyped, "name", v.header, key("name"), diagnostics);
  ok = require(v.body, v.mistyped, "body", v.header, key("body"), diagnostics) && ok;
  ok = require(v.link, v.mistyped, "link", v.header, key("link"), diagnostics) && ok;
  ok = require(v.system_id, v.mistyped, "system_id", v.header, key("system_id"), diagnostics) && ok;
  ok = require(v.profile, v.mistyped, "profile", v.header, key("profile"), diagnostics) && ok;
  Vehicle vehicle;
  core::VehicleSpec& out = vehicle.spec;
  out.profile = value_or(v.profile, core::Profile::px4);
  if (v.profile.value) {
    const bool custom = out.profile == core::Profile::custom;
    if (!custom && v.messages.present) {
      diagnostics.error(v.messages.where, v.messages.key,
                        "messages is only allowed with profile = \"custom\"; profile \"" +
                            std::string(core::to_string(out.profile)) + "\" sends a fixed set");
      ok = false;
    } else if (custom && v.messages.present && v.messages.value && v.messages.value->empty()) {
      diagnostics.error(v.messages.where, v.messages.key,
                        "profile \"custom\" needs at least one message");
      ok = false;
    } else if (custom && !v.messages.present && !contains(v.mistyped, "messages")) {
      diagnostics.error(v.profile.where, key("messages"),
                        "profile \"custom\" needs a messages list, e.g. "
                        "messages = [\"odometry\"]");
      ok = false;
    }
  }
  out.messages = value_or(v.messages, std::vector<core::MessageKind>{});
  const bool gps = (v.profile.value && core::messages_for(out.profile).needs_origin()) ||
                   core::MessageSet(out.messages).needs_origin();
  if (gps && !have_origin && !d.origin_header) {
    const bool by_profile = out.profile != core::Profile::custom;
    const auto& where = by_profile ? v.profile.where : v.messages.where;
    diagnostics.error(where, by_profile ? v.profile.key : v.messages.key, kGpsNeedsOrigin);
    ok = false;
  }
  const core::SignedAxis body_forward = value_or(v.body_forward, mocap.body_forward);
  const core::SignedAxis body_up = value_or(v.body_up, mocap.body_up);
  if (v.body_forward.present || v.body_up.present) {
    check_perpendicular(
        axis_use(v.body_forward, body_forward, "body_forward", v.header, key("body_forward")),
        axis_use(v.body_up, body_up, "body_up", v.header, key("body_up")), diagnostics);
  }
  if (!ok) return std::nullopt;
  // A parallel pair was reported just above (or for [mocap]); the config is refused then anyway.
  if (const auto axes = core::BodyAxisMapping::make(body_forward, body_up)) out.body_axes = *axes;
  out.name = *v.name.value;
  out.body = *v.body.value;
  vehicle.link = *v.link.value;
  out.link =
      vehicle.link.kind == LinkKind::ros2 ? core::VehicleLink::px4_dds : core::VehicleLink::mavlink;
  vehicle.gcs = value_or(v.gcs, std::vector<LinkUrl>{});
  out.system_id = *v.system_id.value;
  // Keys not given keep the core's defaults (component 197, the vision component of
  // protocols/autopilots.md §9; 50 Hz).
  const core::VehicleSpec defaults;
  out.component_id = value_or(v.component_id, defaults.component_id);
  out.rate_hz = value_or(v.rate_hz, defaults.rate_hz);
  out.signing_key = value_or(v.signing_key, std::optional<std::array<std::uint8_t, 32>>{});
  out.enabled = value_or(v.enabled, true);
  if (out.system_id == 255) {
    diagnostics.warning(v.system_id.where, v.system_id.key,
                        "255 is the usual ground-station system id; a vehicle using it can mask "
                        "the GCS (protocols/autopilots.md §11.13)");
  }
  if (out.profile == core::Profile::ardupilot && out.rate_hz > 50.0) {
    diagnostics.warning(v.rate_hz.where, v.rate_hz.key,
                        "ArduPilot's external-navigation input is meant for at most 50 Hz");
  }
  if (out.profile == core::Profile::automatic && out.rate_hz > 50.0) {
    diagnostics.warning(v.rate_hz.where, v.rate_hz.key,
                        "profile auto may find ArduPilot, whose external-navigation input is meant "
                        "for at most 50 Hz");
  }
  if (auto warning = px4_udp_warning(out.profile, vehicle.link)) {
    diagnostics.warning(v.link.where, v.link.key, *warning);
  }
  if (vehicle.link.kind == LinkKind::ros2 && !check_ros2_link(v, d, vehicle, diagnostics)) {
    return std::nullopt;
  }
  if (vehicle.link.kind == LinkKind::serial) {
    // The one bandwidth rule (core::serial_bandwidth_warning): `check`, `run` and a dashboard
    // POST all report it from here.
    const auto warning =
        core::serial_bandwidth_warning(out.profile, core::messages_for(out.profile, out.messages),
                                       out.rate_hz, out.signing_key.has_value(), vehicle.link.baud);
    if (warning) diagnostics.warning(v.link.where, v.link.key, *warning);
  }
  return vehicle;
}

/// Ground-station endpoints (issue 38): one URL on several vehicles is one shared endpoint; but
/// an endpoint may not be a vehicle's link, nor own a local port another endpoint or link owns.
void cross_check_gcs(const ConfigDraft& d, Diagnostics& diagnostics) {
  for (std::size_t i = 0; i < d.vehicles.size(); ++i) {
    const auto& v = d.vehicles[i];
    if (!v.gcs.value) continue;
    for (const LinkUrl& endpoint : *v.gcs.value) {
      const std::string name = to_string(endpoint);
      std::string clash;
      for (std::size_t j = 0; j < d.vehicles.size() && clash.empty(); ++j) {
        const auto& other = d.vehicles[j];
        const std::string other_name = quoted(other.name.value.value_or("?"));
        if (other.link.value &&
            (*other.link.value == endpoint || same_local_port(*other.link.value, endpoint))) {
          clash = "is vehicle " + other_name + "'s link " + to_string(*other.link.value) + " (" +
                  describe(other.link.where) + ") or needs its local port";
        }
        if (j >= i || !other.gcs.value) continue;
        for (const LinkUrl& earlier : *other.gcs.value) {
          if (earlier != endpoint && same_local_port(earlier, endpoint)) {
            clash = "needs the local port of vehicle " + other_name + "'s ground-station " +
                    "endpoint " + to_string(earlier) + " (" + describe(other.gcs.where) +
                    "); the same URL would share it";
          }
        }
      }
      if (!clash.empty()) {
        diagnostics.error(v.gcs.where, v.gcs.key, "ground-station endpoint " + name + " " + clash);
      }
    }
  }
}

/// Unique names; unique system ids per link; a warning for links shared between vehicles.
void cross_check_vehicles(const ConfigDraft& d, Diagnostics& diagnostics) {
  for (std::size_t i = 0; i < d.vehicles.size(); ++i) {
    const auto& v = d.vehicles[i];
    for (std::size_t j = 0; j < i; ++j) {
      const auto& first = d.vehicles[j];
      if (v.name.value && first.name.value && *v.name.value == *first.name.value) {
        diagnostics.error(v.name.where, v.name.key,
                          "duplicate vehicle name " + quoted(*v.name.value) +
                              " (first defined at " + describe(first.name.where) + ")");
        break;
      }
    }
    if (!v.link.value) continue;
    bool shared_warned = false;
    for (std::size_t j = 0; j < i; ++j) {
      const auto& first = d.vehicles[j];
      if (!first.link.value) continue;
      const std::string first_name = first.name.value.value_or("?");
      if (same_local_port(*first.link.value, *v.link.value)) {
        // Each vehicle opens its own socket: the second could not bind the port the first owns.
        diagnostics.error(v.link.where, v.link.key,
                          "link " + to_string(*v.link.value) + " needs the local port " +
                              std::to_string(local_address(*v.link.value)->port) +
                              " that vehicle " + quoted(first_name) + "'s link " +
                              to_string(*first.link.value) + " already owns (" +
                              describe(first.link.where) + "); give each vehicle its own port");
        break;
      }
      if (*first.link.value != *v.link.value) continue;
      if (v.link.value->kind == LinkKind::ros2) {
        // One topic, two writers: PX4 would fuse both vehicles' poses.
        diagnostics.error(v.link.where, v.link.key,
                          "link " + to_string(*v.link.value) + " is vehicle " + quoted(first_name) +
                              "'s (" + describe(first.link.where) +
                              "): each PX4 needs its own namespace (uxrce_dds_client -n)");
        break;
      }
      if (v.system_id.value && first.system_id.value &&
          *v.system_id.value == *first.system_id.value) {
        diagnostics.error(v.system_id.where, v.system_id.key,
                          "system_id " + std::to_string(*v.system_id.value) +
                              " is already used on " + to_string(*v.link.value) + " by vehicle " +
                              quoted(first_name) + " (" + describe(first.system_id.where) + ")");
      } else if (!shared_warned) {
        diagnostics.warning(v.link.where, v.link.key,
                            "link " + to_string(*v.link.value) + " is shared with vehicle " +
                                quoted(first_name) + " (" + describe(first.link.where) +
                                "): pose messages have no target system, so every vehicle on it "
                                "fuses every pose unless a router filters by system id");
        shared_warned = true;
      }
    }
  }
}

/// The tracker's own rules across [tracking] keys (e.g. reset_after_ms ≥ loss_timeout_ms), with
/// the tracker's defaults for the keys not set, so that `check` rejects what `run` would.
void check_tracking(const ConfigDraft& d, Diagnostics& diagnostics) {
  if (d.tracking_sites.empty()) return;
  const core::TrackerConfig& merged = d.tracking;  // the defaults with the keys set
  const auto problem = core::validate(merged);
  if (!problem) return;
  const auto& sites = d.tracking_sites;
  auto site = std::find_if(sites.begin(), sites.end(),
                           [&](const auto& s) { return s.name == problem->field; });
  if (site == sites.end()) site = sites.begin();  // the rule involves a default value
  std::string message = problem->message;
  if (problem->field == "reset_after_ms") {
    message += " (loss_timeout_ms is " + format_number(merged.loss_timeout_ms) +
               ", reset_after_ms is " + format_number(merged.reset_after_ms) +
               "; keys not set take the tracker's defaults)";
  }
  diagnostics.error(site->where, "tracking." + problem->field, message);
}

HttpSettings finalize_http(const ConfigDraft& d, Diagnostics& diagnostics) {
  HttpSettings http;
  if (d.listen.value) http.listen = *d.listen.value;
  if (d.token.value) http.token = *d.token.value;
  if (d.allowed_hosts.value) http.allowed_hosts = *d.allowed_hosts.value;
  if (d.max_connections_per_client.value) {
    http.max_connections_per_client = *d.max_connections_per_client.value;
  }
  if (d.listen.value && !is_loopback(http.listen.host) && http.token.empty() &&
      (!d.token.present || d.token.value)) {
    diagnostics.error(d.listen.where, d.listen.key,
                      to_string(http.listen) +
                          " is reachable from the network, so [http] token is required (16 or "
                          "more characters); every mutating request must carry it");
  }
  return http;
}

std::optional<Ros2Settings> finalize_ros2(const ConfigDraft& d, Diagnostics& diagnostics) {
  if (!d.ros2_header) return std::nullopt;
  if (d.ros2_checked) return d.ros2_checked;
  Ros2Settings ros2;
  if (d.ros2_domain_id.value) {
    ros2.domain_id = *d.ros2_domain_id.value;
    if (*ros2.domain_id > kMaxAdvisedRosDomainId) {
      diagnostics.warning(d.ros2_domain_id.where, d.ros2_domain_id.key,
                          "domain " + std::to_string(*ros2.domain_id) +
                              " is above 101: on Linux its ports may fall in the ephemeral range "
                              "and clash with other programs' sockets (ROS docs \"About Domain "
                              "ID\")");
    }
  }
  if (d.ros2_namespace.value) ros2.ns = *d.ros2_namespace.value;
  if (d.ros2_frame_id.value) ros2.frame_id = *d.ros2_frame_id.value;
  if (d.ros2_axes.value) ros2.axes = *d.ros2_axes.value;
  if (d.ros2_interface.value) ros2.network_interface = *d.ros2_interface.value;
  if (d.ros2_publish.value) {
    ros2.pose = (*d.ros2_publish.value)[0];
    ros2.odom = (*d.ros2_publish.value)[1];
    ros2.tf = (*d.ros2_publish.value)[2];
    const bool px4_links = std::any_of(d.vehicles.begin(), d.vehicles.end(), [](const auto& v) {
      return v.link.value && v.link.value->kind == LinkKind::ros2;
    });
    if (!ros2.pose && !ros2.odom && !ros2.tf && !px4_links) {
      diagnostics.error(d.ros2_publish.where, d.ros2_publish.key,
                        "is empty: list at least one of \"pose\", \"odom\", \"tf\" (or remove "
                        "[ros2]; an empty list is for a [ros2] table only ros2:// links use)");
    }
  }
  if (d.ros2_bodies.value) {
    ros2.bodies = *d.ros2_bodies.value;
    const Field<std::vector<std::string>>& f = d.ros2_bodies;
    std::vector<std::pair<std::string, std::string>> tokens;  // token, body
    for (const std::string& body : ros2.bodies) {
      const std::string token = core::ros_name_token(body);
      if (token.empty()) {
        diagnostics.error(f.where, f.key,
                          "body " + quoted(body) +
                              " has no letter or digit to make a ROS name of: it cannot be "
                              "published (rename it in the mocap system)");
        continue;
      }
      const auto same = std::find_if(tokens.begin(), tokens.end(),
                                     [&](const auto& t) { return t.first == token; });
      if (same != tokens.end()) {
        diagnostics.error(f.where, f.key,
                          same->second == body
                              ? "body " + quoted(body) + " is listed twice"
                              : "bodies " + quoted(same->second) + " and " + quoted(body) +
                                    " both become the ROS name " + quoted(token) +
                                    ": rename one in the mocap system or leave one out");
        continue;
      }
      tokens.emplace_back(token, body);
      const std::string topic = core::ros_body_topic(ros2.ns, token, "pose");
      if (topic.size() > core::kMaxRosTopicLength) {
        diagnostics.error(f.where, f.key,
                          "body " + quoted(body) + " makes the topic " + quoted(topic) + " of " +
                              std::to_string(topic.size()) + " characters; ROS allows " +
                              std::to_string(core::kMaxRosTopicLength));
      } else if (token != body) {
        diagnostics.warning(f.where, f.key,
                            "body " + quoted(body) + " is published as " + quoted(token) +
                                " (ROS names hold only letters, digits and single '_', and "
                                "start with no digit): topics " +
                                core::ros_body_topic(ros2.ns, token, "…") + ", tf frame " +
                                quoted(token));
      }
    }
  }
  return ros2;
}

}  // namespace

std::optional<Config> finalize(const ConfigDraft& d, Diagnostics& diagnostics) {
  Config config;
  config.mocap = finalize_mocap(d, diagnostics);
  config.origin = finalize_origin(d, diagnostics);
  for (const auto& vehicle : d.vehicles) {
    if (auto v =
            finalize_vehicle(vehicle, d, config.mocap, config.origin.has_value(), diagnostics)) {
      config.vehicles.push_back(std::move(*v));
    }
  }
  cross_check_vehicles(d, diagnostics);
  cross_check_gcs(d, diagnostics);
  config.tracking = d.tracking;
  check_tracking(d, diagnostics);
  config.http = finalize_http(d, diagnostics);
  config.ros2 = finalize_ros2(d, diagnostics);
  if (d.vehicles.empty()) {
    diagnostics.warning(d.document, "vehicle",
                        config.ros2 ? "no [[vehicle]] tables: only the [ros2] topics are published"
                                    : "no [[vehicle]] tables: nothing will be sent");
  }
  if (!diagnostics.errors.empty()) return std::nullopt;
  return config;
}

}  // namespace mocaplink::config::detail
