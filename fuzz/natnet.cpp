// Fuzz target for the NatNet parsers (libs/wire natnet_*). The input is one UDP datagram as a
// server (or, for the emulator, a client) would send it. Its payload goes through every parser in
// every bitstream version a server can announce; parsed model definitions feed the body table,
// parsed frames the mapping to MocapFrame and, as the emulator would serve them, the encoder,
// whose output must parse back.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/natnet_mocap_frame.hpp"
#include "mocaplink/wire/natnet_packet.hpp"

namespace nn = mocaplink::wire::natnet;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = mocaplink::wire::as_bytes(data, size);
  auto packet = nn::split_packet(bytes);
  if (!packet) return 0;
  const auto payload = packet.value().payload;
  (void)nn::parse_server_info(payload);
  (void)nn::parse_connect(payload);
  (void)nn::parse_string_payload(payload);
  (void)nn::parse_response_text(payload);
  (void)nn::parse_echo_request(payload);
  static constexpr std::array<nn::Version, 9> kVersions = {
      nn::Version{2, 5}, nn::Version{2, 7}, nn::Version{2, 9}, nn::Version{3, 0}, nn::Version{3, 1},
      nn::Version{4, 0}, nn::Version{4, 1}, nn::Version{4, 2}, nn::Version{4, 4}};
  for (const nn::Version v : kVersions) {
    nn::BodyTable table;
    if (auto defs = nn::parse_model_definitions(payload, v)) {
      table = nn::body_table(defs.value());
      (void)nn::encode_model_definitions(defs.value(), v);
    }
    auto frame = nn::parse_frame(payload, v);
    if (!frame) continue;
    (void)nn::to_mocap_frame(frame.value(), table, 3'312'787);
    if (!v.at_least(3, 0)) continue;
    const auto again = nn::encode_frame(frame.value(), v);
    auto reparsed = nn::split_packet(again);
    if (!reparsed || !nn::parse_frame(reparsed.value().payload, v)) std::abort();
  }
  return 0;
}
