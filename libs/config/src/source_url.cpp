#include "mocaplink/config/source_url.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "mocaplink/config/net_address.hpp"
#include "text_util.hpp"
#include "url_util.hpp"

namespace mocaplink::config {
namespace {

constexpr std::array<std::string_view, 7> kSchemes = {"vicon", "vicon-udp", "natnet", "vrpn",
                                                      "qtm",   "sim",       "replay"};
constexpr std::array<std::string_view, 3> kViconModes = {"push", "prefetch", "pull"};

using Result = ValueOrError<SourceUrl>;

// Port defaults: protocols/vicon-datastream.md (801), vicon-tracker-udp.md (51001),
// vrpn.md (3883), qtm-rt.md (22223, the little-endian protocol port).
constexpr std::uint16_t kViconPort = 801;
constexpr std::uint16_t kViconUdpPort = 51001;
constexpr std::uint16_t kVrpnPort = 3883;
constexpr std::uint16_t kQtmPort = 22223;

std::string scheme_of(SourceKind kind) {
  return std::string(to_string(kind)) + "://";
}

/// Reads a number option in (low, high] or [low, high]; "" on success.
std::string read_number(std::string_view key, std::string_view text, double low, double high,
                        bool low_inclusive, double& out) {
  const auto value = detail::parse_double(text);
  const bool ok = value && std::isfinite(*value) &&
                  (low_inclusive ? *value >= low : *value > low) && *value <= high;
  if (!ok) {
    return std::string(key) + " must be a number " + (low_inclusive ? "from " : "above ") +
           detail::format_number(low) + (low_inclusive ? " to " : " up to ") +
           detail::format_number(high) + ", got " + detail::quoted(text);
  }
  out = *value;
  return {};
}

/// Reads a whole number in [low, high]; "" on success.
std::string read_count(std::string_view key, std::string_view text, std::uint64_t low,
                       std::uint64_t high, std::uint64_t& out) {
  const auto value = detail::parse_integer(text);
  if (!value || *value < 0 || static_cast<std::uint64_t>(*value) < low ||
      static_cast<std::uint64_t>(*value) > high) {
    return std::string(key) + " must be an integer from " + std::to_string(low) + " to " +
           std::to_string(high) + ", got " + detail::quoted(text);
  }
  out = static_cast<std::uint64_t>(*value);
  return {};
}

/// One sim:// option (the key is known: check_query_keys ran first).
std::string read_sim_option(std::string_view key, std::string_view value, SimOptions& sim) {
  struct Number {
    std::string_view key;
    double SimOptions::*field;
    double low;
    double high;
    bool low_inclusive;
  };
  static constexpr std::array<Number, 7> kNumbers{{
      {"rate_hz", &SimOptions::rate_hz, 0.0, 2000.0, false},
      {"noise_mm", &SimOptions::noise_mm, 0.0, 1000.0, true},
      {"noise_deg", &SimOptions::noise_deg, 0.0, 90.0, true},
      {"occlude", &SimOptions::occlude, 0.0, 1.0, true},
      {"occlude_s", &SimOptions::occlude_s, 0.0, 60.0, false},
      {"outliers", &SimOptions::outliers, 0.0, 1.0, true},
      {"outlier_m", &SimOptions::outlier_m, 0.0, 100.0, false},
  }};
  for (const Number& n : kNumbers) {
    if (key == n.key) return read_number(key, value, n.low, n.high, n.low_inclusive, sim.*n.field);
  }
  std::uint64_t count = 0;
  std::string error;
  if (key == "drop") {
    // A probability below 1: at 1 no frame would ever arrive.
    const auto p = detail::parse_double(value);
    if (!p || !(*p >= 0.0 && *p < 1.0)) {
      return "drop must be a probability from 0 to below 1, got " + detail::quoted(value);
    }
    sim.drop = *p;
  } else if (key == "bodies") {
    error = read_count(key, value, 1, 64, count);
    if (error.empty()) sim.bodies = static_cast<std::uint32_t>(count);
  } else if (key == "seed") {
    error = read_count(key, value, 0, std::numeric_limits<std::int64_t>::max(), sim.seed);
  } else if (key == "frames") {
    error = read_count(key, value, 0, std::numeric_limits<std::int64_t>::max(), sim.frames);
  }
  return error;
}

std::string parse_server(SourceUrl& url, std::string_view body, std::uint16_t default_port,
                         bool port_allowed) {
  if (body.ends_with('/')) body.remove_suffix(1);  // vicon://host/ as a browser would write it
  if (body.find('/') != std::string_view::npos) {
    return scheme_of(url.kind) + " takes no path, got " + detail::quoted(body);
  }
  auto address =
      parse_host_port(body, HostPortRules{.port_optional = true, .default_port = default_port});
  if (!address) return address.error();
  if (!port_allowed && address.value().port != default_port) {
    return scheme_of(url.kind) +
           " takes no port (Motive's command port 1510 and data port 1511 "
           "are used)";
  }
  url.host = address.value().host;
  url.port = address.value().port;
  return {};
}

std::string parse_options(SourceUrl& url, const detail::UrlParts& parts) {
  for (const auto& [key, value] : parts.query) {
    std::string error;
    if (key == "mode") {
      bool found = false;
      for (std::size_t i = 0; i < kViconModes.size(); ++i) {
        if (value == kViconModes[i]) {
          url.vicon_mode = static_cast<ViconStreamMode>(i);
          found = true;
        }
      }
      if (!found) error = "mode must be push, prefetch or pull, got " + detail::quoted(value);
    } else if (key == "local" || key == "multicast") {
      const bool ok = is_ipv4_literal(value);
      const bool multicast_ok =
          ok && detail::parse_integer(value.substr(0, value.find('.'))).value_or(0) >= 224 &&
          detail::parse_integer(value.substr(0, value.find('.'))).value_or(0) <= 239;
      if (key == "local") {
        if (!ok)
          error = "local must be an IPv4 address of this machine, got " + detail::quoted(value);
        url.natnet_local_ip = std::string(value);
      } else {
        if (!multicast_ok) {
          error = "multicast must be an IPv4 multicast group (224.0.0.0 to 239.255.255.255), got " +
                  detail::quoted(value);
        }
        url.natnet_multicast = std::string(value);
      }
    } else if (url.kind == SourceKind::sim) {
      error = read_sim_option(key, value, url.sim);
    } else if (key == "speed") {
      error = read_number(key, value, 0.0, 1000.0, true, url.replay_speed);
    } else if (key == "loop") {
      if (value != "0" && value != "1") {
        error = "loop must be 0 or 1, got " + detail::quoted(value);
      }
      url.replay_loop = value == "1";
    }
    if (!error.empty()) return error;
  }
  return {};
}

std::string parse_body(SourceUrl& url, const detail::UrlParts& parts) {
  const std::string_view body = parts.body;
  switch (url.kind) {
    case SourceKind::vicon:
      return parse_server(url, body, kViconPort, true);
    case SourceKind::qtm:
      return parse_server(url, body, kQtmPort, true);
    case SourceKind::natnet:
      return parse_server(url, body, 0, false);
    case SourceKind::vrpn: {
      const auto at = body.find('@');
      if (at != std::string_view::npos) {
        url.vrpn_tracker = std::string(body.substr(0, at));
        // VRPN sender names are at most 99 bytes plus NUL (protocols/vrpn.md §1).
        if (url.vrpn_tracker.empty() || url.vrpn_tracker.size() > 99) {
          return "tracker name before '@' must be 1 to 99 characters";
        }
      }
      return parse_server(url, at == std::string_view::npos ? body : body.substr(at + 1), kVrpnPort,
                          true);
    }
    case SourceKind::vicon_udp: {
      if (body.find('/') != std::string_view::npos) {
        return "vicon-udp:// takes [BIND_ADDRESS][:PORT] only, got " + detail::quoted(body);
      }
      auto address = parse_host_port(
          body, HostPortRules{
                    .host_optional = true, .port_optional = true, .default_port = kViconUdpPort});
      if (!address) return address.error();
      url.host = address.value().host;
      url.port = address.value().port;
      return {};
    }
    case SourceKind::sim:
      if (!body.empty() && body != "/")
        return "sim:// takes no host or path, only options, as in sim://?bodies=3";
      return {};
    case SourceKind::replay:
      if (body.empty()) return "replay:// needs a file, as in replay://flight.csv";
      url.replay_path = std::string(body);
      return {};
  }
  return {};
}

std::span<const std::string_view> allowed_options(SourceKind kind) {
  static constexpr std::array<std::string_view, 1> kVicon = {"mode"};
  static constexpr std::array<std::string_view, 2> kNatnet = {"local", "multicast"};
  static constexpr std::array<std::string_view, 11> kSim = {
      "bodies",  "rate_hz",   "noise_mm", "noise_deg", "seed",  "drop",
      "occlude", "occlude_s", "outliers", "outlier_m", "frames"};
  static constexpr std::array<std::string_view, 2> kReplay = {"speed", "loop"};
  switch (kind) {
    case SourceKind::vicon:
      return kVicon;
    case SourceKind::natnet:
      return kNatnet;
    case SourceKind::sim:
      return kSim;
    case SourceKind::replay:
      return kReplay;
    default:
      return {};
  }
}

}  // namespace

const char* to_string(SourceKind kind) {
  return kSchemes.at(static_cast<std::size_t>(kind)).data();
}

const char* to_string(ViconStreamMode mode) {
  return kViconModes.at(static_cast<std::size_t>(mode)).data();
}

ValueOrError<SourceUrl> parse_source_url(std::string_view text) {
  auto parts = detail::split_url(text);
  if (!parts) {
    if (text.find("://") == std::string_view::npos) {
      return Result::failure(
          detail::quoted(text) +
          " is not a source URL; expected SCHEME://..., where SCHEME is one of " +
          detail::join(kSchemes));
    }
    return Result::failure(parts.error());
  }
  const auto& p = parts.value();
  SourceUrl url;
  url.text = std::string(text);
  bool known = false;
  for (std::size_t i = 0; i < kSchemes.size(); ++i) {
    if (p.scheme == kSchemes[i]) {
      url.kind = static_cast<SourceKind>(i);
      known = true;
    }
  }
  if (!known) {
    return Result::failure("unknown source scheme " + detail::quoted(p.scheme) +
                           detail::did_you_mean(p.scheme, kSchemes) +
                           " (one of: " + detail::join(kSchemes) + ")");
  }
  if (auto error = detail::check_query_keys(p, allowed_options(url.kind), scheme_of(url.kind));
      !error.empty()) {
    return Result::failure(error);
  }
  if (auto error = parse_body(url, p); !error.empty()) return Result::failure(error);
  if (auto error = parse_options(url, p); !error.empty()) return Result::failure(error);
  return url;
}

}  // namespace mocaplink::config
