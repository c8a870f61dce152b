#include "mocaplink/mavlink/crc.hpp"

#include <array>
#include <cstdint>
#include <string_view>

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace mocaplink::mavlink {
namespace {

using test::bytes_of;

// CRC-16/MCRF4XX check value from the CRC catalogue (Greg Cook's "reveng" catalogue):
// crc("123456789") = 0x6F91.
TEST(Crc, CatalogueCheckValue) {
  EXPECT_EQ(crc_accumulate(bytes_of("123456789")), 0x6F91);
}

// crc_extra of HEARTBEAT is 50 (mavlink-wire.md §6), computed per "Packet Serialization":
// CRC over "HEARTBEAT " then "type name " per base field in wire order, folded to 8 bits.
TEST(Crc, HeartbeatCrcExtraFromDefinition) {
  std::uint16_t crc = crc_accumulate(bytes_of("HEARTBEAT "));
  for (std::string_view part :
       {"uint32_t custom_mode ", "uint8_t type ", "uint8_t autopilot ", "uint8_t base_mode ",
        "uint8_t system_status ", "uint8_t mavlink_version "}) {
    crc = crc_accumulate(bytes_of(part), crc);
  }
  EXPECT_EQ((crc & 0xFF) ^ (crc >> 8), 50);
}

// The golden HEARTBEAT frame fd0900000001c50000000000000012080004031ee4 ends in CRC 0xe41e
// (little-endian); the CRC covers bytes 1..end-of-payload plus crc_extra 50.
TEST(Crc, GoldenHeartbeatFrame) {
  const std::array<std::uint8_t, 19> covered{0x09, 0x00, 0x00, 0x00, 0x01, 0xc5, 0x00,
                                             0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x12,
                                             0x08, 0x00, 0x04, 0x03, 50};
  EXPECT_EQ(crc_accumulate(covered), 0xe41e);
}

TEST(Crc, ByteWiseEqualsSpan) {
  const auto data = bytes_of("mocaplink");
  std::uint16_t crc = kCrcInit;
  for (auto b : data) crc = crc_accumulate(b, crc);
  EXPECT_EQ(crc, crc_accumulate(data));
}

// The span path (slicing-by-8) agrees with the byte-wise definition for every length and
// alignment, including tails shorter than 8 bytes.
TEST(Crc, SpanEqualsByteWiseForAllLengths) {
  std::array<std::uint8_t, 300> data{};
  std::uint32_t x = 12345;
  for (auto& b : data) {
    x = x * 1103515245u + 12345u;
    b = static_cast<std::uint8_t>(x >> 16);
  }
  for (std::size_t start = 0; start < 8; ++start) {
    for (std::size_t len = 0; len + start <= data.size(); len += 7) {
      std::uint16_t expected = kCrcInit;
      for (std::size_t i = start; i < start + len; ++i)
        expected = crc_accumulate(data[i], expected);
      EXPECT_EQ(crc_accumulate(std::span(data).subspan(start, len)), expected)
          << start << " " << len;
    }
  }
}

}  // namespace
}  // namespace mocaplink::mavlink
