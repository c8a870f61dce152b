#include "mocaplink/wire/byte_reader.hpp"

#include <array>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace mocaplink::wire {
namespace {

TEST(ByteReader, ReadsLittleAndBigEndian) {
  const std::array<std::uint8_t, 6> raw{0x01, 0x02, 0x03, 0x04, 0xAA, 0xBB};
  ByteReader r(as_bytes(raw.data(), raw.size()));
  EXPECT_EQ(r.read<std::uint32_t>(), 0x04030201u);
  EXPECT_EQ(r.read<std::uint16_t>(Endian::big), 0xAABBu);
  EXPECT_TRUE(r.empty());
}

TEST(ByteReader, ShortReadFailsWithoutMoving) {
  const std::array<std::uint8_t, 3> raw{1, 2, 3};
  ByteReader r(as_bytes(raw.data(), raw.size()));
  EXPECT_FALSE(r.read<std::uint32_t>().has_value());
  EXPECT_EQ(r.offset(), 0u);
  EXPECT_FALSE(r.skip(4));
  EXPECT_FALSE(r.bytes(4).has_value());
  EXPECT_EQ(r.read<std::uint8_t>(), 1);
}

TEST(ByteReader, FloatsAreBitExact) {
  // 1.5f little-endian is 00 00 c0 3f; -0.0 is 00 00 00 80.
  const std::array<std::uint8_t, 8> raw{0x00, 0x00, 0xc0, 0x3f, 0x00, 0x00, 0x00, 0x80};
  ByteReader r(as_bytes(raw.data(), raw.size()));
  EXPECT_EQ(r.read<float>(), 1.5f);
  const auto neg_zero = r.read<float>();
  ASSERT_TRUE(neg_zero.has_value());
  EXPECT_TRUE(std::signbit(*neg_zero));
}

TEST(ByteReader, CStringNeedsTerminatorWithinLimit) {
  const std::array<std::uint8_t, 6> raw{'a', 'b', 0, 'c', 'd', 'e'};
  ByteReader r(as_bytes(raw.data(), raw.size()));
  EXPECT_EQ(r.cstring(16), "ab");
  EXPECT_EQ(r.offset(), 3u);
  EXPECT_FALSE(r.cstring(16).has_value());  // "cde" has no terminator
  EXPECT_EQ(r.offset(), 3u);
  EXPECT_EQ(r.string(3), "cde");
}

}  // namespace
}  // namespace mocaplink::wire
