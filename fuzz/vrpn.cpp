// Fuzz target for the VRPN client parsers (libs/wire vrpn_*). The input is a byte stream as a VRPN
// server would send it over TCP: a 24-byte cookie, then messages cut with the framing of vrpn.md
// §3 (24-byte header, payload padded to 8), applied to a connection's id tables and the frame
// assembler, with a drain after every message and an idle check every 16.
#include <cstddef>
#include <cstdint>
#include <span>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vrpn_client.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace vr = mocaplink::wire::vrpn;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto bytes = mocaplink::wire::as_bytes(data, size);
  if (bytes.size() < vr::kCookieBytes) return 0;
  (void)vr::parse_cookie(bytes.first(vr::kCookieBytes));
  bytes = bytes.subspan(vr::kCookieBytes);
  vr::ClientTables tables;
  vr::AssemblerConfig config;
  config.frozen_after = std::chrono::milliseconds(3);
  config.max_bodies = 16;
  vr::FrameAssembler assembler(config);
  std::int64_t now_ms = 0;
  while (bytes.size() >= vr::kHeaderBytes) {
    auto header = vr::parse_header(bytes.first(vr::kHeaderBytes));
    if (!header) return 0;
    const std::size_t whole = vr::kHeaderBytes + header.value().padded_payload_bytes();
    if (bytes.size() < whole) return 0;
    const auto payload = bytes.subspan(vr::kHeaderBytes, header.value().payload_bytes());
    bytes = bytes.subspan(whole);
    auto out = tables.apply(header.value(), payload);
    if (!out) {
      assembler.reset();  // a connection drops on a malformed message
      tables = vr::ClientTables();
      continue;
    }
    const auto now = mocaplink::core::host_time_from_ns(++now_ms * 1'000'000);
    if (out.value().report) (void)assembler.on_report(*out.value().report, now);
    (void)assembler.on_drained();
    if (now_ms % 16 == 0) (void)assembler.on_idle(now + std::chrono::seconds(1));
  }
  (void)assembler.flush();
  return 0;
}
