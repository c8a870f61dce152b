// Property tests over random field values for every message (fixed seed): encode → parse → decode
// gives back every field bit for bit (float specials, int64 extremes), MAVLink 2 truncation keeps
// len ≥ 1 with no trailing zero unless len == 1, MAVLink 1 carries base fields only, and receivers
// accept untruncated and over-long payloads.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "mocaplink/mavlink/crc.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/sequence.hpp"

namespace mocaplink::mavlink {
namespace {

constexpr int kSamplesPerMessage = 300;

template <typename T>
T random_scalar(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 9);
  const int p = pick(rng);
  if (p < 3) return T{};  // zeros make truncation happen
  if constexpr (std::is_floating_point_v<T>) {
    using L = std::numeric_limits<T>;
    const T specials[] = {L::quiet_NaN(), -L::quiet_NaN(), T(-0.0),
                          L::infinity(),  -L::infinity(),  L::max(),
                          L::lowest(),    L::denorm_min(), L::min()};
    if (p < 5) return specials[rng() % std::size(specials)];
    if (p < 7) return std::uniform_real_distribution<T>(T(-1000), T(1000))(rng);
    const auto bits = static_cast<std::uint32_t>(rng());  // any bit pattern, NaN payloads too
    T v{};
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  } else {
    using L = std::numeric_limits<T>;
    const T extremes[] = {L::min(), L::max(), static_cast<T>(1), static_cast<T>(L::max() - 1)};
    if (p < 5) return extremes[rng() % std::size(extremes)];
    if constexpr (std::is_signed_v<T>) {
      if (p == 5) return static_cast<T>(-1);
    }
    T v{};
    const auto bits = rng();
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
}

template <typename M>
M random_message(std::mt19937_64& rng, double zero_extension_probability) {
  M m;
  const bool zero_ext =
      std::uniform_real_distribution<double>(0, 1)(rng) < zero_extension_probability;
  for_each_field(m, [&](const FieldInfo& info, auto& field) {
    if (info.extension && zero_ext) return;  // leave 0
    if constexpr (requires { field.size(); }) {
      for (auto& e : field) e = random_scalar<std::remove_reference_t<decltype(e)>>(rng);
    } else {
      field = random_scalar<std::remove_reference_t<decltype(field)>>(rng);
    }
  });
  return m;
}

/// Object representation of every field (in order): equal iff every field is bit-identical.
template <typename M>
std::vector<std::vector<std::uint8_t>> field_bits(const M& m, bool base_only = false) {
  std::vector<std::vector<std::uint8_t>> out;
  for_each_field(m, [&](const FieldInfo& info, const auto& field) {
    if (base_only && info.extension) return;
    std::vector<std::uint8_t> bytes(sizeof(field));
    std::memcpy(bytes.data(), &field, sizeof(field));
    out.push_back(std::move(bytes));
  });
  return out;
}

template <typename M>
bool extensions_zero(const M& m) {
  bool zero = true;
  for_each_field(m, [&](const FieldInfo& info, const auto& field) {
    if (!info.extension) return;
    std::vector<std::uint8_t> bytes(sizeof(field));
    std::memcpy(bytes.data(), &field, sizeof(field));
    for (auto b : bytes) zero = zero && b == 0;
  });
  return zero;
}

template <typename M>
void check_message_roundtrips(std::mt19937_64& rng) {
  SCOPED_TRACE(std::string(M::kName));
  SequenceCounter seq(7, 191, 250);
  for (int i = 0; i < kSamplesPerMessage; ++i) {
    const M original = random_message<M>(rng, 0.3);
    const FrameHeader header = seq.next();
    const Frame frame = encode(original, header);
    const auto view = parse_frame(frame.bytes());
    ASSERT_TRUE(view.ok()) << to_string(view.error());
    EXPECT_EQ(view->msgid, M::kId);
    EXPECT_EQ(view->seq, header.seq);
    EXPECT_EQ(view->sysid, 7);
    EXPECT_EQ(view->compid, 191);
    EXPECT_EQ(view->incompat_flags, 0);
    // Truncation properties.
    ASSERT_GE(view->len, 1);
    ASSERT_LE(view->len, M::kMaxLength);
    if (view->len > 1) {
      EXPECT_NE(view->payload.back(), 0) << "trailing zero kept";
    }
    EXPECT_EQ(frame.size(), 12u + view->len);
    const auto decoded = decode_message(*view);
    ASSERT_TRUE(decoded.has_value());
    ASSERT_TRUE(std::holds_alternative<M>(*decoded));
    EXPECT_EQ(field_bits(std::get<M>(*decoded)), field_bits(original));

    if constexpr (M::kId < 256) {
      const Frame v1 = encode_v1(original, header);
      ASSERT_EQ(v1.size(), 8u + M::kBaseLength);
      const auto v1_view = parse_frame(v1.bytes());
      ASSERT_TRUE(v1_view.ok());
      EXPECT_EQ(v1_view->version, 1);
      const auto v1_msg = decode_message(*v1_view);
      ASSERT_TRUE(v1_msg.has_value());
      const M& m1 = std::get<M>(*v1_msg);
      EXPECT_EQ(field_bits(m1, true), field_bits(original, true));
      EXPECT_TRUE(extensions_zero(m1));
    } else {
      EXPECT_TRUE(encode_v1(original, header).empty());
    }
  }
}

TEST(RoundTrip, EveryMessageRandomValues) {
  std::mt19937_64 rng(20260522);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (check_message_roundtrips<std::variant_alternative_t<I, Message>>(rng), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Message>>{});
}

// Rebuilds `frame` with a different payload and a correct CRC (for receiver-tolerance tests).
std::vector<std::uint8_t> with_payload(const FrameView& frame, std::vector<std::uint8_t> payload) {
  // Built by push_back: GCC 12 at -O2 reports a false -Warray-bounds for range-insert into a
  // vector constructed from 10 elements.
  std::vector<std::uint8_t> out;
  out.reserve(10 + payload.size() + 2);
  for (std::size_t i = 0; i < 10; ++i) out.push_back(frame.bytes[i]);
  out[1] = static_cast<std::uint8_t>(payload.size());
  for (const std::uint8_t b : payload) out.push_back(b);
  std::uint16_t crc = crc_accumulate(std::span<const std::uint8_t>(out).subspan(1));
  crc = crc_accumulate(frame.info->crc_extra, crc);
  out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return out;
}

TEST(RoundTrip, ReceiverAcceptsUntruncatedAndOverlongPayloads) {
  HilGps gps;  // extensions zero: the sender truncates to 36 bytes
  gps.time_usec = 1;
  gps.lat = 2;
  gps.satellites_visible = 12;
  const Frame frame = encode(gps, FrameHeader{1, 1, 1});
  const auto view = *parse_frame(frame.bytes());
  ASSERT_EQ(view.len, 36);
  // Untruncated (non-compliant sender): 39 bytes with zero extensions.
  std::vector<std::uint8_t> full(view.payload.begin(), view.payload.end());
  full.resize(39, 0);
  const auto untruncated = with_payload(view, full);
  const auto u = parse_frame(untruncated);
  ASSERT_TRUE(u.ok());
  EXPECT_EQ(std::get<HilGps>(*decode_message(*u)), gps);
  // Longer than we know (newer dialect with more extensions): extra bytes ignored.
  full.resize(45, 0x55);
  const auto overlong_bytes = with_payload(view, full);
  const auto overlong = parse_frame(overlong_bytes);
  ASSERT_TRUE(overlong.ok());
  EXPECT_EQ(std::get<HilGps>(*decode_message(*overlong)), gps);
  // Length 0 (node-mavlink's all-zero frames, mavlink-wire.md §9.1): decodes as all zero.
  Timesync zero;
  const Frame z = encode(zero, FrameHeader{1, 1, 1});
  const auto zero_len_bytes = with_payload(*parse_frame(z.bytes()), {});
  const auto zero_len = parse_frame(zero_len_bytes);
  ASSERT_TRUE(zero_len.ok());
  EXPECT_EQ(std::get<Timesync>(*decode_message(*zero_len)), zero);
}

TEST(RoundTrip, AllZeroPayloadKeepsOneByte) {
  const Frame f = encode(Timesync{}, FrameHeader{11, 1, 197});
  ASSERT_EQ(f.size(), 13u);
  EXPECT_EQ(f.bytes()[1], 1);
}

TEST(RoundTrip, ParseFrameRejections) {
  const Frame f = encode(Heartbeat{}, FrameHeader{0, 1, 1});
  std::vector<std::uint8_t> bytes(f.bytes().begin(), f.bytes().end());
  EXPECT_EQ(parse_frame({}).error(), FrameError::too_short);
  EXPECT_EQ(parse_frame(std::span(bytes).first(5)).error(), FrameError::too_short);
  auto longer = bytes;
  longer.push_back(0);
  EXPECT_EQ(parse_frame(longer).error(), FrameError::trailing_bytes);
  auto bad_magic = bytes;
  bad_magic[0] = 0x55;
  EXPECT_EQ(parse_frame(bad_magic).error(), FrameError::bad_magic);
  auto bad_crc = bytes;
  bad_crc.back() ^= 0x01;
  EXPECT_EQ(parse_frame(bad_crc).error(), FrameError::bad_crc);
  auto flag = bytes;
  flag[2] = 0x02;  // unknown incompat bit: dropped even though fields look fine (§4)
  EXPECT_EQ(parse_frame(flag).error(), FrameError::unknown_incompat_flags);
  // Unknown message id: framed, not decoded, CRC not checkable.
  auto unknown = bytes;
  unknown[7] = 0x39;
  unknown[8] = 0x30;
  const auto u = parse_frame(unknown);
  ASSERT_TRUE(u.ok());
  EXPECT_FALSE(u->known());
  EXPECT_EQ(u->msgid, 0x3039u);
  EXPECT_FALSE(decode_message(*u).has_value());
}

TEST(RoundTrip, SequenceCounterWraps) {
  SequenceCounter c(1, 197, 254);
  EXPECT_EQ(c.next().seq, 254);
  EXPECT_EQ(c.next().seq, 255);
  const FrameHeader h = c.next();
  EXPECT_EQ(h.seq, 0);
  EXPECT_EQ(h.sysid, 1);
  EXPECT_EQ(h.compid, 197);
  EXPECT_EQ(c.peek_seq(), 1);
}

}  // namespace
}  // namespace mocaplink::mavlink
