#include "mocaplink/sources/vicon_url.hpp"

#include <charconv>

namespace mocaplink::sources {

namespace {

std::variant<std::uint16_t, std::string> parse_port(std::string_view text) {
  unsigned value = 0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc{} || ptr != end || value == 0 || value > 65535) {
    return "vicon://: bad port '" + std::string(text) + "' (expected 1..65535)";
  }
  return static_cast<std::uint16_t>(value);
}

}  // namespace

std::variant<ViconUrl, std::string> parse_vicon_url(std::string_view url) {
  constexpr std::string_view scheme = "vicon://";
  if (!url.starts_with(scheme)) return "not a vicon:// URL: '" + std::string(url) + "'";
  std::string_view rest = url.substr(scheme.size());
  std::string_view query;
  if (const auto q = rest.find('?'); q != std::string_view::npos) {
    query = rest.substr(q + 1);
    rest = rest.substr(0, q);
  }
  if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);

  ViconUrl out;
  std::string_view port_text;
  if (rest.starts_with('[')) {  // [IPv6]:port
    const auto close = rest.find(']');
    if (close == std::string_view::npos) return "vicon://: unterminated '[' in host";
    out.host = std::string(rest.substr(1, close - 1));
    const std::string_view after = rest.substr(close + 1);
    if (!after.empty()) {
      if (after.front() != ':') return "vicon://: unexpected text after ']'";
      port_text = after.substr(1);
      if (port_text.empty()) return "vicon://: empty port";
    }
  } else if (const auto colon = rest.rfind(':'); colon != std::string_view::npos) {
    out.host = std::string(rest.substr(0, colon));
    port_text = rest.substr(colon + 1);
    if (port_text.empty()) return "vicon://: empty port";
  } else {
    out.host = std::string(rest);
  }
  if (out.host.empty()) return "vicon://: missing host (vicon://HOST[:801][?mode=push])";
  if (!port_text.empty()) {
    auto port = parse_port(port_text);
    if (const auto* err = std::get_if<std::string>(&port)) return *err;
    out.port = std::get<std::uint16_t>(port);
  }

  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    if (pair.empty()) continue;
    const auto eq = pair.find('=');
    const std::string_view key = pair.substr(0, eq);
    const std::string_view value = eq == std::string_view::npos ? "" : pair.substr(eq + 1);
    if (key != "mode") return "vicon://: unknown key '" + std::string(key) + "' (known: mode)";
    if (value == "push") {
      out.mode = wire::vicon::StreamMode::server_push;
    } else if (value == "prefetch") {
      out.mode = wire::vicon::StreamMode::client_prefetch;
    } else if (value == "pull") {
      out.mode = wire::vicon::StreamMode::client_pull;
    } else {
      return "vicon://: bad mode '" + std::string(value) + "' (expected push, prefetch or pull)";
    }
  }
  return out;
}

}  // namespace mocaplink::sources
