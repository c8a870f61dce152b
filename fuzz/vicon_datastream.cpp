// Fuzz target for the Vicon DataStream parsers (libs/wire vicon_*). The input is a byte stream as
// a TCP peer would send it: packets are cut from it with the framing of §3 (capped body length),
// the first goes to parse_greeting, the rest through ClientStream (§7 caches) and to_mocap_frame,
// and every packet also through an emulator ServerSession, as if a client had sent it.
#include <cstddef>
#include <cstdint>
#include <span>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vicon_client_stream.hpp"
#include "mocaplink/wire/vicon_mocap_frame.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "mocaplink/wire/vicon_server_session.hpp"

namespace vw = mocaplink::wire::vicon;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto bytes = mocaplink::wire::as_bytes(data, size);
  vw::ClientStream client;
  vw::ServerSession server;
  vw::ServedFrameBuilder builder;
  bool greeted = false;
  while (bytes.size() >= vw::kPacketHeaderBytes) {
    auto length = vw::parse_packet_header(bytes.first(vw::kPacketHeaderBytes), 1u << 20);
    if (!length) return 0;
    bytes = bytes.subspan(vw::kPacketHeaderBytes);
    if (bytes.size() < length.value()) return 0;
    const auto body = bytes.first(length.value());
    bytes = bytes.subspan(length.value());

    if (!greeted) {
      greeted = true;
      (void)vw::parse_greeting(body);
    } else if (auto out = client.apply(body)) {
      if (out.value().frame) {
        const vw::MappedFrame mapped = vw::to_mocap_frame(*out.value().frame);
        // Feed the decoded frame back through the emulator, as `serve --from replay` would.
        const vw::ServedFrame served = builder.build(mapped.frame, 1'350'000);
        (void)server.on_new_frame(served);
        (void)server.encode_frame(served);
      }
    }
    (void)server.on_client_packet(body, nullptr);
  }
  return 0;
}
