#include "mocaplink/config/link_url.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <string>

#include "mocaplink/config/url.hpp"
#include "mocaplink/core/ros.hpp"
#include "text_util.hpp"

namespace mocaplink::config {
namespace {

constexpr std::array<std::string_view, 6> kSchemes = {"udp",   "udpin",  "tcp",
                                                      "tcpin", "serial", "ros2"};
// Serial devices are named the platform's way: a COM port on Windows, a device path on Linux.
#ifdef _WIN32
constexpr std::string_view kForms =
    "udp://HOST:PORT[?bind=ADDR:PORT], udpin://ADDR:PORT, tcp://HOST:PORT, tcpin://ADDR:PORT "
    "serial://COMn?baud=N or ros2://[NAMESPACE]";
constexpr std::string_view kSerialRule = "serial device must be a COM port name, as in ";
constexpr std::string_view kSerialExample = "serial://COM3?baud=921600";
#else
constexpr std::string_view kForms =
    "udp://HOST:PORT[?bind=ADDR:PORT], udpin://ADDR:PORT, tcp://HOST:PORT, tcpin://ADDR:PORT "
    "serial:///dev/DEVICE?baud=N or ros2://[NAMESPACE]";
constexpr std::string_view kSerialRule = "serial device must be an absolute path, as in ";
constexpr std::string_view kSerialExample = "serial:///dev/ttyUSB0?baud=921600";
#endif

// The rates Linux termios can set without termios2 (B9600 ... B4000000): the io adapter maps
// these to Bxxx constants, so any other number could not be honoured.
constexpr std::array<std::uint32_t, 18> kBaudRates = {
    9600,   19200,   38400,   57600,   115200,  230400,  460800,  500000,  576000,
    921600, 1000000, 1152000, 1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

using Result = ValueOrError<LinkUrl>;

bool is_broadcast_or_multicast(const std::string& host) {
  // IPv6 multicast is ff00::/8.
  if (host.find(':') != std::string::npos) return host.rfind("ff", 0) == 0;
  if (!is_ipv4_literal(host)) return false;
  if (host == "255.255.255.255") return true;
  const auto first_octet = detail::parse_integer(host.substr(0, host.find('.'))).value_or(0);
  return first_octet >= 224 && first_octet <= 239;
}

constexpr std::string_view kSharedAddress =
    "broadcast and multicast addresses are not allowed: pose messages have no target system, so "
    "every vehicle listening would fuse them; give each vehicle its own unicast address";

/// "14540": a port without the colon that says the address was left out.
bool is_port_alone(std::string_view text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// A local address to bind: an IP literal of this machine, or empty for every interface. A name
/// is refused rather than resolved (libs/ do no I/O, and a name may stand for several addresses).
std::string check_local_address(const HostPort& address, std::string_view what) {
  const auto& host = address.host;
  if (host.empty() || is_ipv4_literal(host) || host.find(':') != std::string::npos) return "";
  return std::string(what) + " must be an IP address of this machine, or left out for every " +
         "interface (as in :" + std::to_string(address.port) + "), got " + detail::quoted(host);
}

/// udp://HOST:PORT[?bind=ADDR:PORT] and tcp://HOST:PORT: the vehicle's address.
/// udpin://ADDR:PORT and tcpin://ADDR:PORT: the local address to listen on (:PORT: all).
Result parse_network(LinkKind kind, const UrlParts& parts) {
  const std::string scheme = std::string(to_string(kind)) + "://";
  constexpr std::array<std::string_view, 1> kUdpKeys = {"bind"};
  const auto keys = kind == LinkKind::udp ? std::span<const std::string_view>(kUdpKeys)
                                          : std::span<const std::string_view>();
  if (auto error = check_query_keys(parts, keys, scheme); !error.empty()) {
    return Result::failure(error);
  }
  const bool listening = kind == LinkKind::udpin || kind == LinkKind::tcpin;
  if (parts.body.find('/') != std::string_view::npos) {
    return Result::failure(
        scheme +
        (listening ? " takes ADDR:PORT or :PORT only, got " : " takes HOST:PORT only, got ") +
        detail::quoted(parts.body));
  }
  HostPortRules rules;
  rules.host_optional = listening;
  if (listening && is_port_alone(parts.body)) {
    return Result::failure(scheme + " listens on ADDR:PORT or :PORT, got " +
                           detail::quoted(parts.body) +
                           " (a port alone is written :" + std::string(parts.body) + ")");
  }
  auto address = parse_host_port(parts.body, rules);
  if (!address) {
    return Result::failure(listening ? scheme +
                                           " listens on ADDR:PORT (ADDR may be left out "
                                           "for every interface): " +
                                           address.error()
                                     : address.error());
  }
  if (is_broadcast_or_multicast(address.value().host)) {
    return Result::failure(std::string(kSharedAddress));
  }
  if (listening) {
    if (auto error = check_local_address(address.value(), scheme + " ADDR"); !error.empty()) {
      return Result::failure(error);
    }
  }
  LinkUrl link;
  link.kind = kind;
  link.address = std::move(address).value();
  for (const auto& [key, value] : parts.query) {  // only "bind", for udp
    HostPortRules bind_rules;
    bind_rules.host_optional = true;
    if (is_port_alone(value)) {
      return Result::failure(
          "bind must be ADDR:PORT or :PORT, the local address to send from, got " +
          detail::quoted(value) + " (a port alone is written :" + std::string(value) + ")");
    }
    auto bind = parse_host_port(value, bind_rules);
    if (!bind) {
      return Result::failure(
          "bind must be ADDR:PORT, the local address to send from (ADDR may "
          "be left out for every interface, as in bind=:14540): " +
          bind.error());
    }
    if (is_broadcast_or_multicast(bind.value().host)) {
      return Result::failure(std::string(kSharedAddress));
    }
    if (auto error = check_local_address(bind.value(), "bind's ADDR"); !error.empty()) {
      return Result::failure(error);
    }
    link.bind = std::move(bind).value();
  }
  return link;
}

#ifdef _WIN32
/// COM1 … COM999, any case (Windows's own rule for the names a program may open as \\.\COMn).
bool is_com_port(std::string_view device) {
  if (device.size() < 4 || device.size() > 6) return false;
  const auto upper = [](char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; };
  if (upper(device[0]) != 'C' || upper(device[1]) != 'O' || upper(device[2]) != 'M') return false;
  const auto digits = device.substr(3);
  return digits.front() != '0' &&
         std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}
#endif

bool is_device_name(std::string_view device) {
#ifdef _WIN32
  return is_com_port(device);
#else
  return device.size() >= 2 && device.front() == '/' && device.back() != '/';
#endif
}

Result parse_serial(const UrlParts& parts) {
  constexpr std::array<std::string_view, 1> kKeys = {"baud"};
  if (auto error = check_query_keys(parts, kKeys, "serial://"); !error.empty()) {
    return Result::failure(error);
  }
  const auto device = parts.body;
  if (!is_device_name(device)) {
    return Result::failure(std::string(kSerialRule) + std::string(kSerialExample) + ", got " +
                           detail::quoted(device));
  }
  if (std::any_of(device.begin(), device.end(),
                  [](char c) { return static_cast<unsigned char>(c) <= 0x20; })) {
    return Result::failure("serial device path contains a space or control character");
  }
  LinkUrl link;
  link.kind = LinkKind::serial;
  link.device = std::string(device);
  link.baud = kDefaultSerialBaud;
  for (const auto& [key, value] : parts.query) {
    const auto baud = detail::parse_integer(value);
    const bool standard =
        baud && std::find(kBaudRates.begin(), kBaudRates.end(), *baud) != kBaudRates.end();
    if (!standard) {
      return Result::failure(
          "baud must be a standard rate (9600, 19200, 38400, 57600, 115200, "
          "230400, 460800, 500000, 576000, 921600, 1000000, 1152000, 1500000, "
          "2000000, 2500000, 3000000, 3500000, 4000000), got " +
          detail::quoted(value));
    }
    link.baud = static_cast<std::uint32_t>(*baud);
  }
  return link;
}

/// ros2://[NAMESPACE]: PX4's uXRCE-DDS namespace (its `-n`), ROS name segments separated by '/'.
Result parse_ros2(const UrlParts& parts) {
  if (auto error = check_query_keys(parts, {}, "ros2://"); !error.empty()) {
    return Result::failure(error);
  }
  // The namespace of ROS names (core::ros_namespace_problem, as for [ros2] namespace), without
  // the slashes at either end.
  std::string_view ns = parts.body;
  while (!ns.empty() && ns.front() == '/') ns.remove_prefix(1);
  while (!ns.empty() && ns.back() == '/') ns.remove_suffix(1);
  if (auto problem = core::ros_namespace_problem(ns)) {
    return Result::failure(
        "ros2:// takes PX4's namespace: letters, digits and '_' in segments separated by '/', "
        "none starting with a digit (as in ros2://px4_1, or ros2:// for none), got " +
        detail::quoted(parts.body) + ": it " + *problem);
  }
  LinkUrl link;
  link.kind = LinkKind::ros2;
  link.ros2_namespace = std::string(ns);
  return link;
}

}  // namespace

const char* to_string(LinkKind kind) {
  return kSchemes.at(static_cast<std::size_t>(kind)).data();
}

ValueOrError<LinkUrl> parse_link_url(std::string_view text) {
  auto parts = split_url(text);
  if (!parts) {
    if (text.find("://") == std::string_view::npos) {
      return Result::failure("expected " + std::string(kForms) + ", got " + detail::quoted(text));
    }
    return Result::failure(parts.error());
  }
  const auto& p = parts.value();
  if (p.scheme == "udp") return parse_network(LinkKind::udp, p);
  if (p.scheme == "udpin") return parse_network(LinkKind::udpin, p);
  if (p.scheme == "tcp") return parse_network(LinkKind::tcp, p);
  if (p.scheme == "tcpin") return parse_network(LinkKind::tcpin, p);
  if (p.scheme == "serial") return parse_serial(p);
  if (p.scheme == "ros2") return parse_ros2(p);
  return Result::failure("unknown link scheme " + detail::quoted(p.scheme) +
                         detail::did_you_mean(p.scheme, kSchemes) + " (expected " +
                         std::string(kForms) + ")");
}

std::string to_string(const LinkUrl& link) {
  if (link.kind == LinkKind::ros2) return "ros2://" + link.ros2_namespace;
  if (link.kind == LinkKind::serial) {
    return "serial://" + link.device + "?baud=" + std::to_string(link.baud);
  }
  std::string out = std::string(to_string(link.kind)) + "://" + to_string(link.address);
  if (link.bind) out += "?bind=" + to_string(*link.bind);
  return out;
}

bool listens(const LinkUrl& link) {
  return link.kind == LinkKind::udpin || link.kind == LinkKind::tcpin;
}

std::optional<HostPort> local_address(const LinkUrl& link) {
  if (listens(link)) return link.address;
  if (link.kind == LinkKind::udp && link.bind) return link.bind;
  return std::nullopt;
}

bool same_local_port(const LinkUrl& a, const LinkUrl& b) {
  const auto la = local_address(a);
  const auto lb = local_address(b);
  if (!la || !lb || la->port != lb->port) return false;
  if ((a.kind == LinkKind::tcpin) != (b.kind == LinkKind::tcpin)) return false;  // UDP vs TCP
  const auto any = [](const std::string& host) {
    return host.empty() || host == "0.0.0.0" || host == "::";
  };
  return la->host == lb->host || any(la->host) || any(lb->host);
}

}  // namespace mocaplink::config
