// Fuzz target for the Host header of dashboard requests (adapters/web http_auth): every request
// is judged by host_allowed before anything else, and a refused one is answered with
// host_refusal's text as JSON. Properties beyond "no crash, no sanitizer report", each checked by
// a rule written here independently of the parser:
// - a Host allowed with no allowed_hosts is a loopback name (localhost, [::1], or a dotted quad
//   127.a.b.c of decimal octets), any case, alone or with the listening
//   port exactly (a leading zero in a later octet is harmless: the first is 127 whatever the
//   base); with ["lab-pc", "tunnel:9000"] also "lab-pc" (alone or with that port) and
//   "tunnel:9000";
// - the refusal text is printable ASCII, bounded, and serialises as JSON.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "mocaplink/web/http_auth.hpp"

namespace {

constexpr std::uint16_t kPort = 8080;

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

bool is_loopback_quad(std::string_view host) {
  int octets = 0;
  std::size_t i = 0;
  while (true) {
    const std::size_t start = i;
    while (i < host.size() && host[i] >= '0' && host[i] <= '9') ++i;
    const std::size_t digits = i - start;
    if (digits == 0 || digits > 3) return false;
    const int value = std::stoi(std::string(host.substr(start, digits)));
    if (value > 255 || (octets == 0 && value != 127)) return false;
    ++octets;
    if (i == host.size()) return octets == 4;
    if (host[i] != '.' || octets == 4) return false;
    ++i;
  }
}

/// The host part when `text` is HOST or HOST:PORT with exactly `port`; "" otherwise.
std::string without_port(const std::string& text, std::uint16_t port) {
  const std::string suffix = ":" + std::to_string(port);
  if (text.size() > suffix.size() &&
      text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0) {
    return text.substr(0, text.size() - suffix.size());
  }
  return text;
}

bool loopback_name(const std::string& host) {
  return host == "localhost" || host == "[::1]" || is_loopback_quad(host);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using mocaplink::web::host_allowed;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string host = lower(text);

  if (host_allowed(text, kPort, {}) && !loopback_name(without_port(host, kPort))) std::abort();

  const std::vector<mocaplink::config::HostPort> allowed = {{"lab-pc", 0}, {"tunnel", 9000}};
  if (host_allowed(text, kPort, allowed)) {
    const std::string name = without_port(host, kPort);
    if (!loopback_name(name) && name != "lab-pc" && host != "tunnel:9000") std::abort();
  }

  const std::string refusal = mocaplink::web::host_refusal(text);
  if (refusal.size() > 600) std::abort();
  for (const char c : refusal) {
    if (c < 0x20 || c > 0x7e) std::abort();
  }
  (void)nlohmann::json{{"error", refusal}}.dump();  // throws (and fails) on invalid UTF-8
  return 0;
}
