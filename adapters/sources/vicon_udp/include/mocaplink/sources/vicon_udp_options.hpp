// Where a `vicon-udp://[BIND]:PORT[?rotation=xyz|zyx&from=IP&lost_ms=500&frozen=10&arena_m=1000]`
// source listens and how it reads the stream (DESIGN.md "Source URLs", docs/sources.md
// "vicon-udp://").
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "mocaplink/config/url.hpp"
#include "mocaplink/wire/vicon_udp.hpp"

namespace mocaplink::sources {

struct ViconUdpOptions {
  std::string bind_host = "0.0.0.0";  ///< local address to bind ("" in the URL: every address)
  std::uint16_t port = wire::vicon_udp::kDefaultPort;
  /// Euler convention of RotX/RotY/RotZ (unverified, vicon-tracker-udp.md §3): xyz by default.
  wire::vicon_udp::EulerOrder rotation = wire::vicon_udp::EulerOrder::xyz;
  std::string from;  ///< accept datagrams only from this IP ("" = any sender)
  /// No datagram for this long: one frame with every body untracked, then nothing.
  std::chrono::milliseconds lost{500};
  /// An object whose six values stay bit-identical over more than this many datagrams is
  /// untracked (a Tracker repeating a lost object); 0 = never.
  std::uint32_t frozen = 10;
  double arena_m = 1000.0;  ///< |x|, |y|, |z| above this (m) reject the datagram
};

/// The `vicon-udp://` query keys.
inline constexpr std::array<std::string_view, 5> kViconUdpOptionKeys = {"arena_m", "from", "frozen",
                                                                        "lost_ms", "rotation"};

/// A split `vicon-udp://` URL (query keys already checked) → its options.
[[nodiscard]] config::ValueOrError<ViconUdpOptions> parse_vicon_udp_options(
    const config::UrlParts& url);

}  // namespace mocaplink::sources
