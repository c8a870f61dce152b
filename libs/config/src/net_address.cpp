#include "mocaplink/config/net_address.hpp"

#include <algorithm>
#include <string>

#include "mocaplink/text/hex.hpp"
#include "text_util.hpp"

namespace mocaplink::config {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_alnum(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

bool is_ipv6_literal(std::string_view host) {
  // Syntax check only: hex groups, ':' separators, at most one "::", an optional dotted IPv4 tail.
  if (host.size() < 2 || host.size() > 45) return false;
  if (!std::all_of(host.begin(), host.end(),
                   [](char c) { return text::is_hex_digit(c) || c == ':' || c == '.'; })) {
    return false;
  }
  const auto first = host.find("::");
  return first == std::string_view::npos || host.find("::", first + 1) == std::string_view::npos;
}

bool is_dns_name(std::string_view host) {
  // RFC 1123 host names (letters, digits, '-'), plus '_' which some lab networks use.
  if (host.empty() || host.size() > 253) return false;
  std::size_t start = 0;
  while (start <= host.size()) {
    const auto dot = host.find('.', start);
    const auto label = host.substr(start, dot == std::string_view::npos ? dot : dot - start);
    if (label.empty() || label.size() > 63 || label.front() == '-' || label.back() == '-') {
      return false;
    }
    if (!std::all_of(label.begin(), label.end(),
                     [](char c) { return is_alnum(c) || c == '-' || c == '_'; })) {
      return false;
    }
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return true;
}

ValueOrError<std::uint16_t> parse_port(std::string_view text, bool zero_ok) {
  const auto value = detail::parse_integer(text);
  const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), is_digit);
  const long long low = zero_ok ? 0 : 1;
  if (!digits || !value || *value < low || *value > 65535) {
    return ValueOrError<std::uint16_t>::failure("port must be " + std::to_string(low) +
                                                "..65535, got " + detail::quoted(text));
  }
  return static_cast<std::uint16_t>(*value);
}

}  // namespace

bool is_ipv4_literal(std::string_view host) {
  int octets = 0;
  std::size_t start = 0;
  while (true) {
    const auto dot = host.find('.', start);
    const auto part = host.substr(start, dot == std::string_view::npos ? dot : dot - start);
    if (part.empty() || part.size() > 3 || !std::all_of(part.begin(), part.end(), is_digit)) {
      return false;
    }
    if (detail::parse_integer(part).value_or(256) > 255) return false;
    ++octets;
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return octets == 4;
}

ValueOrError<std::string> parse_host(std::string_view text) {
  if (text.empty()) return ValueOrError<std::string>::failure("missing host");
  if (text.find(':') != std::string_view::npos) {
    if (is_ipv6_literal(text)) return std::string(text);
    return ValueOrError<std::string>::failure(detail::quoted(text) +
                                              " is not a valid IPv6 address");
  }
  const bool numeric =
      std::all_of(text.begin(), text.end(), [](char c) { return is_digit(c) || c == '.'; });
  if (numeric) {
    if (is_ipv4_literal(text)) return std::string(text);
    return ValueOrError<std::string>::failure(detail::quoted(text) +
                                              " is not a valid IPv4 address");
  }
  if (!is_dns_name(text)) {
    return ValueOrError<std::string>::failure(detail::quoted(text) +
                                              " is not a valid host name or address");
  }
  std::string host(text);
  std::transform(host.begin(), host.end(), host.begin(), [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  });
  return host;
}

ValueOrError<HostPort> parse_host_port(std::string_view text, HostPortRules rules) {
  using Result = ValueOrError<HostPort>;
  std::string_view host_text;
  std::string_view port_text;
  bool has_port = false;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string_view::npos) return Result::failure("missing ']' after IPv6 address");
    host_text = text.substr(1, close - 1);
    const auto rest = text.substr(close + 1);
    if (!rest.empty()) {
      if (rest.front() != ':') {
        return Result::failure("expected ':PORT' after ']', got " + detail::quoted(rest));
      }
      port_text = rest.substr(1);
      has_port = true;
    }
    if (host_text.find(':') == std::string_view::npos) {
      return Result::failure("brackets are only for IPv6 addresses, got " + detail::quoted(text));
    }
  } else {
    const auto colon = text.rfind(':');
    if (colon != std::string_view::npos && text.find(':') != colon) {
      return Result::failure("IPv6 addresses need brackets, as in \"[::1]:8080\", got " +
                             detail::quoted(text));
    }
    host_text = text.substr(0, colon);
    if (colon != std::string_view::npos) {
      port_text = text.substr(colon + 1);
      has_port = true;
    }
  }
  HostPort out;
  if (host_text.empty()) {
    if (!rules.host_optional) return Result::failure("missing host in " + detail::quoted(text));
  } else {
    auto host = parse_host(host_text);
    if (!host) return Result::failure(host.error());
    out.host = std::move(host).value();
  }
  if (!has_port) {
    if (!rules.port_optional) {
      return Result::failure("missing port: expected HOST:PORT, got " + detail::quoted(text));
    }
    out.port = rules.default_port;
    return out;
  }
  auto port = parse_port(port_text, rules.port_zero_ok);
  if (!port) return Result::failure(port.error());
  out.port = port.value();
  return out;
}

std::string to_string(const HostPort& address) {
  const bool v6 = address.host.find(':') != std::string::npos;
  return (v6 ? "[" + address.host + "]" : address.host) + ":" + std::to_string(address.port);
}

bool is_loopback(std::string_view host) {
  if (host == "localhost" || host == "::1") return true;
  return is_ipv4_literal(host) && host.substr(0, 4) == "127.";
}

}  // namespace mocaplink::config
