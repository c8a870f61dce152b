// Helpers shared by the link tests: frames from /work/shared/mavlink/golden-vectors.json (the
// independent oracle) and a loop runner that waits for a condition instead of sleeping.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include <asio/io_context.hpp>

#include "mocaplink/io/link.hpp"

namespace mocaplink::io::test {

/// golden-vectors.json "heartbeat": HEARTBEAT seq 0, sysid 1, compid 197.
inline const std::vector<std::uint8_t> kHeartbeat = {0xfd, 0x09, 0x00, 0x00, 0x00, 0x01, 0xc5,
                                                     0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                                                     0x12, 0x08, 0x00, 0x04, 0x03, 0x1e, 0xe4};

/// golden-vectors.json "heartbeat_signed" (link 1, timestamp 31557600000000, key_hex below).
inline const std::vector<std::uint8_t> kHeartbeatSigned = {
    0xfd, 0x09, 0x01, 0x00, 0x0f, 0x01, 0xc5, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x12, 0x08, 0x00, 0x04, 0x03, 0x7e, 0xfe, 0x01, 0x00, 0xb8,
    0x89, 0x93, 0xb3, 0x1c, 0xbe, 0x3a, 0x9d, 0x79, 0x2e, 0x48};

/// Link options for tests: retries after retry_min, then doubling to retry_max (no short
/// interval phase), optional verification key.
inline LinkOptions options(std::chrono::milliseconds retry_min = std::chrono::milliseconds(250),
                           std::chrono::milliseconds retry_max = std::chrono::milliseconds(4000),
                           std::optional<mavlink::SigningKey> key = std::nullopt) {
  LinkOptions o;
  o.name = "v";
  o.verify_key = std::move(key);
  o.retry = core::RetryPolicy{retry_min, retry_min, std::chrono::milliseconds(0), retry_max};
  return o;
}

/// Runs `loop` until `done()` holds or `timeout` passes; returns done().
inline bool run_until(asio::io_context& loop, const std::function<bool()>& done,
                      std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    if (loop.stopped()) loop.restart();
    loop.run_for(std::chrono::milliseconds(5));
  }
  return done();
}

}  // namespace mocaplink::io::test
