#include "mocaplink/wire/qtm_server_session.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "mocaplink/wire/qtm_parameters.hpp"

namespace mocaplink::wire::qtm {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::vector<std::string> words_of(std::string_view text) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < text.size() && out.size() < 64) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    const std::size_t begin = i;
    while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i > begin) out.emplace_back(text.substr(begin, i - begin));
  }
  return out;
}

template <typename T>
bool to_number(std::string_view s, T& out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc{} && end == s.data() + s.size();
}

}  // namespace

std::vector<std::byte> ServerSession::welcome() {
  return encode_text(PacketType::command, kWelcome);
}

std::vector<std::byte> ServerSession::error(const std::string& text) {
  ++errors_sent_;
  return encode_text(PacketType::error, text);
}

Packets ServerSession::on_client_packet(std::uint32_t type, std::span<const std::byte> payload,
                                        const std::vector<std::string>& names,
                                        const ServedFrame* latest) {
  if (type != static_cast<std::uint32_t>(PacketType::command)) return {error("Parse Error")};
  const std::vector<std::string> words = words_of(text_of(payload));
  if (words.empty()) return {error("Parse Error")};
  const std::string command = lower(words[0]);
  const auto reply = [](const std::string& text) {
    return Packets{encode_text(PacketType::command, text)};
  };
  if (command == "version") {
    if (words.size() == 1) return reply("Version is 1." + std::to_string(minor_));
    const std::string& v = words[1];
    int minor = 0;
    if (words.size() == 2 && v.starts_with("1.") &&
        to_number(std::string_view(v).substr(2), minor) && minor >= 1 &&
        minor <= settings_.max_minor) {
      minor_ = minor;
      return reply("Version set to 1." + std::to_string(minor));
    }
    return reply("Version NOT supported");
  }
  if (command == "qtmversion") return reply("QTM Version is 0.0 (build 0)");
  if (command == "byteorder") return reply("Byte order is little endian");
  if (command == "getstate") return {encode_event(static_cast<std::uint8_t>(Event::connected))};
  if (command == "getparameters") {
    ParametersRequest sections;
    for (std::size_t i = 1; i < words.size(); ++i) {
      const std::string w = lower(words[i]);
      sections.general = sections.general || w == "all" || w == "general";
      sections.six_d = sections.six_d || w == "all" || w == "6d";
    }
    if (!sections.general && !sections.six_d) return reply("Parameters not available");
    const std::string xml = encode_parameters(names, minor_, sections, settings_.frequency_hz);
    return {encode_text(PacketType::xml, xml)};
  }
  if (command == "streamframes" || command == "getcurrentframe") {
    if (minor_ < 8) return {error("mocaplink's emulator serves data from protocol 1.8 on")};
    if (command == "streamframes") return stream_frames(words, latest);
    std::string problem;
    const auto components = components_of(std::span(words).subspan(1), problem);
    if (!components) return {error(problem)};
    if (latest == nullptr) return {encode_packet(PacketType::no_more_data, {})};
    return {encode(*latest, *components)};
  }
  return {error("Parse Error")};
}

std::optional<std::vector<Component>> ServerSession::components_of(
    std::span<const std::string> words, std::string& problem) const {
  std::vector<Component> out;
  for (const auto& w : words) {
    if (lower(w) == "all") return settings_.components;
    const auto c = component_from_string(w);
    if (!c || std::find(settings_.components.begin(), settings_.components.end(), *c) ==
                  settings_.components.end()) {
      problem = "Component " + w + " not available";
      return std::nullopt;
    }
    if (std::find(out.begin(), out.end(), *c) == out.end()) out.push_back(*c);
  }
  if (out.empty()) {
    problem = "No components";
    return std::nullopt;
  }
  return out;
}

Packets ServerSession::stream_frames(const std::vector<std::string>& words,
                                     const ServedFrame* latest) {
  if (words.size() == 2 && lower(words[1]) == "stop") {
    streaming_ = false;
    udp_.reset();
    return {};
  }
  if (words.size() < 3) return {error("Parse Error")};
  const std::string rate = lower(words[1]);
  std::uint64_t divisor = 0;
  std::uint64_t n = 0;
  if (rate == "allframes") {
    divisor = 1;
  } else if (rate.starts_with("frequency:") && to_number(std::string_view(rate).substr(10), n) &&
             n > 0) {
    divisor = std::max<std::uint64_t>(
        1,
        static_cast<std::uint64_t>(std::llround(settings_.frequency_hz / static_cast<double>(n))));
  } else if (rate.starts_with("frequencydivisor:") &&
             to_number(std::string_view(rate).substr(17), n) && n > 0) {
    divisor = n;
  } else {
    return {error("Parse Error")};
  }
  std::size_t next = 2;
  std::optional<UdpTarget> udp;
  if (lower(words[2]).starts_with("udp")) {
    const std::string_view spec = words[2];
    const auto last = spec.rfind(':');
    unsigned port = 0;
    if (last == std::string_view::npos || last < 3 || !to_number(spec.substr(last + 1), port) ||
        port < 1023 || port > 65535) {
      return {error("UDP port must be 1023 to 65535")};
    }
    UdpTarget target;
    target.port = static_cast<std::uint16_t>(port);
    if (last > 3) target.address = std::string(spec.substr(4, last - 4));
    udp = target;
    ++next;
  }
  std::string problem;
  const auto components = components_of(std::span(words).subspan(next), problem);
  if (!components) return {error(problem)};
  streaming_ = true;
  streamed_ = *components;
  divisor_ = divisor;
  counter_ = 0;
  udp_ = udp;
  if (latest == nullptr) return {encode_packet(PacketType::no_more_data, {})};
  return {};
}

std::optional<std::vector<std::byte>> ServerSession::on_new_frame(const ServedFrame& frame) {
  if (!streaming_) return std::nullopt;
  if (counter_++ % divisor_ != 0) return std::nullopt;
  return encode(frame, streamed_);
}

std::vector<std::byte> ServerSession::encode(const ServedFrame& frame,
                                             const std::vector<Component>& components) const {
  DataPacket packet;
  packet.timestamp_us = frame.timestamp_us;
  packet.frame_number = frame.frame_number;
  for (const Component c : components) {
    SixDof six;
    six.type = c;
    six.bodies = frame.bodies;
    packet.six_dof.push_back(std::move(six));
  }
  return encode_data(packet);
}

}  // namespace mocaplink::wire::qtm
