// Fuzz target for the Vicon Tracker UDP parser and stream (libs/wire vicon_udp*). The input is a
// series of datagrams, each prefixed by its length as a u16 little-endian (as a receiver would get
// them one by one), fed to a Stream; every 8th datagram is followed by a silence.
#include <cstddef>
#include <cstdint>
#include <span>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vicon_udp_stream.hpp"

namespace vu = mocaplink::wire::vicon_udp;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mocaplink::wire::ByteReader r(mocaplink::wire::as_bytes(data, size));
  vu::StreamConfig config;
  config.frozen = 2;
  config.max_abs_mm = 1e7;
  vu::Stream stream(config);
  std::int64_t n = 0;
  while (auto length = r.read<std::uint16_t>()) {
    auto datagram = r.bytes(std::min<std::size_t>(*length, r.remaining()));
    if (!datagram) return 0;
    const auto now = mocaplink::core::host_time_from_ns(++n * 1'000'000);
    (void)vu::parse_datagram(*datagram);
    (void)stream.on_datagram(*datagram, now);
    if (n % 8 == 0) (void)stream.on_silence(now);
  }
  return 0;
}
