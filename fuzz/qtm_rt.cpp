// Fuzz target for the QTM RT packet parsers (libs/wire qtm_*). The input is a byte stream as a TCP
// peer would send it: packets are cut with the 8-byte header framing (capped size); XML packets go
// through parse_parameters (their bodies name the following frames), data packets through
// parse_data and to_mocap_frame for every component type, the whole packet through parse_packet
// (as a UDP datagram), and every packet through an emulator ServerSession as if a client had sent
// it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/qtm_frame.hpp"
#include "mocaplink/wire/qtm_parameters.hpp"
#include "mocaplink/wire/qtm_protocol.hpp"
#include "mocaplink/wire/qtm_server_session.hpp"

namespace wq = mocaplink::wire::qtm;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto bytes = mocaplink::wire::as_bytes(data, size);
  constexpr std::uint32_t kMax = 1u << 20;
  std::vector<wq::BodyParameters> bodies;
  std::vector<std::string> names;
  wq::ServerSession server({});
  wq::ServedFrame latest;
  while (bytes.size() >= wq::kHeaderBytes) {
    const auto header = wq::parse_header(bytes.first(wq::kHeaderBytes), kMax);
    if (!header || bytes.size() < header.value().size) return 0;
    const auto packet = bytes.first(header.value().size);
    bytes = bytes.subspan(header.value().size);
    (void)wq::parse_packet(packet, kMax);
    const auto payload = packet.subspan(wq::kHeaderBytes);
    const auto type = static_cast<wq::PacketType>(header.value().type);
    if (type == wq::PacketType::xml) {
      if (auto p = wq::parse_parameters(wq::text_of(payload))) {
        bodies = p.value().bodies;
        names.clear();
        for (const auto& b : bodies) names.push_back(b.name);
      }
    } else if (type == wq::PacketType::data) {
      if (auto d = wq::parse_data(payload)) {
        for (const auto c : {wq::Component::six_d, wq::Component::six_d_euler}) {
          if (auto mapped = wq::to_mocap_frame(d.value(), c, bodies, 100.0)) {
            // Feed it back through the emulator's encoding, as `serve --from` would.
            latest = wq::served_frame(mapped.value().frame);
            (void)server.on_new_frame(latest);
          }
        }
      }
    }
    (void)server.on_client_packet(header.value().type, payload, names, &latest);
  }
  return 0;
}
