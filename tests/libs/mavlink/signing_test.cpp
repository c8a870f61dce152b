// Signing state machines (mavlink-wire.md §7.3–§7.5): outgoing timestamps strictly increase,
// receive-side replay protection per (sysid, compid, link_id), 60 s rule, unsigned policy.
#include <gtest/gtest.h>

#include <vector>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::mavlink {
namespace {

std::array<std::uint8_t, 32> secret(std::uint8_t fill) {
  std::array<std::uint8_t, 32> s{};
  s.fill(fill);
  return s;
}

TEST(SigningTime, EpochConversion) {
  EXPECT_EQ(signing_timestamp_from_unix_us(0), 0u);
  EXPECT_EQ(signing_timestamp_from_unix_us(1'420'070'400'000'000), 0u);
  EXPECT_EQ(signing_timestamp_from_unix_us(1'420'070'401'000'000), 100'000u);
  EXPECT_EQ(signing_timestamp_from_unix_us(1'420'070'400'000'019), 1u);
  EXPECT_EQ(signing_timestamp_from_unix_us(std::numeric_limits<std::int64_t>::max()),
            kMaxSigningTimestamp);
}

TEST(OutgoingSigner, StrictlyIncreasingEvenWithinOneTick) {
  const SigningKey key(secret(1));
  OutgoingSigner signer(key, 3);
  EXPECT_EQ(signer.next(1000).timestamp_10us, 1000u);
  EXPECT_EQ(signer.next(1000).timestamp_10us, 1001u);  // same tick: last + 1
  EXPECT_EQ(signer.next(1000).timestamp_10us, 1002u);
  EXPECT_EQ(signer.next(500).timestamp_10us, 1003u);  // clock stepped back: still increasing
  EXPECT_EQ(signer.next(5000).timestamp_10us, 5000u);
  const SignParams p = signer.next(0);
  EXPECT_EQ(p.link_id, 3);
  EXPECT_EQ(p.key, &signer.key());
  EXPECT_EQ(signer.timestamp_10us(), 5001u);
}

TEST(OutgoingSigner, RestoreObserveAndSaturate) {
  const SigningKey key(secret(1));
  OutgoingSigner restored(key, 0, 777);
  EXPECT_EQ(restored.next(10).timestamp_10us, 778u);
  restored.observe(100);  // older than ours: ignored
  EXPECT_EQ(restored.timestamp_10us(), 778u);
  restored.observe(9000);
  EXPECT_EQ(restored.next(10).timestamp_10us, 9001u);
  OutgoingSigner at_end(key, 0, kMaxSigningTimestamp);
  EXPECT_EQ(at_end.next(0).timestamp_10us, kMaxSigningTimestamp);
}

class Verifier : public ::testing::Test {
 protected:
  std::vector<std::uint8_t> signed_frame(std::uint8_t sysid, std::uint8_t link_id, std::uint64_t ts,
                                         const SigningKey* key = nullptr) {
    const SignParams p{key != nullptr ? key : &key_, link_id, ts};
    const Frame f = encode(Heartbeat{}, FrameHeader{seq_++, sysid, 1}, &p);
    return {f.bytes().begin(), f.bytes().end()};
  }
  SignatureVerdict check(SignatureVerifier& v, const std::vector<std::uint8_t>& frame,
                         std::uint64_t now) {
    return v.check(frame, Heartbeat::kId, frame[5], frame[6], now);
  }
  SigningKey key_{secret(7)};
  std::uint8_t seq_ = 0;
};

TEST_F(Verifier, ReplayAndEqualTimestampsRejected) {
  SignatureVerifier v(key_, {});
  EXPECT_EQ(check(v, signed_frame(1, 0, 100), 0), SignatureVerdict::accepted_signed);
  EXPECT_EQ(check(v, signed_frame(1, 0, 100), 0), SignatureVerdict::replay);  // equal
  EXPECT_EQ(check(v, signed_frame(1, 0, 99), 0), SignatureVerdict::replay);   // older
  EXPECT_EQ(check(v, signed_frame(1, 0, 101), 0), SignatureVerdict::accepted_signed);
  EXPECT_EQ(v.local_timestamp_10us(), 101u);
}

TEST_F(Verifier, StreamsAreSysidCompidLinkId) {
  SignatureVerifier v(key_, {});
  EXPECT_EQ(check(v, signed_frame(1, 0, 100), 0), SignatureVerdict::accepted_signed);
  // Same timestamp on other streams is fine.
  EXPECT_EQ(check(v, signed_frame(2, 0, 100), 0), SignatureVerdict::accepted_signed);
  EXPECT_EQ(check(v, signed_frame(1, 1, 100), 0), SignatureVerdict::accepted_signed);
}

TEST_F(Verifier, NewStreamSixtySecondRule) {
  SignatureVerifier v(key_, {});
  const std::uint64_t now = 100'000'000;
  EXPECT_EQ(check(v, signed_frame(1, 0, now - 6'000'001), now), SignatureVerdict::stale_new_stream);
  EXPECT_EQ(check(v, signed_frame(2, 0, now - 6'000'000), now), SignatureVerdict::accepted_signed);
  // A known stream is judged by its own last timestamp only.
  EXPECT_EQ(check(v, signed_frame(2, 0, now - 5'999'999), now + 50'000'000),
            SignatureVerdict::accepted_signed);
}

TEST_F(Verifier, BadSignatureNeverAdvancesState) {
  SignatureVerifier v(key_, {});
  const SigningKey other(secret(8));
  EXPECT_EQ(check(v, signed_frame(1, 0, 5'000, &other), 0), SignatureVerdict::bad_signature);
  EXPECT_EQ(v.local_timestamp_10us(), 0u);
  EXPECT_EQ(check(v, signed_frame(1, 0, 10), 0), SignatureVerdict::accepted_signed);
  auto tampered = signed_frame(1, 0, 20);
  tampered[14] ^= 0x40;  // payload bit: signature no longer matches
  EXPECT_EQ(check(v, tampered, 0), SignatureVerdict::bad_signature);
}

TEST_F(Verifier, UnsignedPolicy) {
  const Frame unsigned_frame = encode(Heartbeat{}, FrameHeader{0, 1, 1});
  const std::vector<std::uint8_t> bytes(unsigned_frame.bytes().begin(),
                                        unsigned_frame.bytes().end());
  SignatureVerifier accept(key_, {.unsigned_policy = UnsignedPolicy::accept});
  EXPECT_EQ(accept.check(bytes, 0, 1, 1, 0), SignatureVerdict::accepted_unsigned);
  SignatureVerifier require(key_, {.unsigned_policy = UnsignedPolicy::reject});
  EXPECT_EQ(require.check(bytes, 0, 1, 1, 0), SignatureVerdict::unsigned_rejected);
  // RADIO_STATUS (#109) is injected by radios without a key: accepted unless disabled.
  EXPECT_EQ(require.check(bytes, 109, 1, 1, 0), SignatureVerdict::accepted_unsigned);
  SignatureVerifier strict(
      key_, {.unsigned_policy = UnsignedPolicy::reject, .accept_unsigned_radio_status = false});
  EXPECT_EQ(strict.check(bytes, 109, 1, 1, 0), SignatureVerdict::unsigned_rejected);
  // MAVLink 1 frames cannot be signed: unsigned.
  const Frame v1 = encode_v1(Heartbeat{}, FrameHeader{0, 1, 1});
  const std::vector<std::uint8_t> v1_bytes(v1.bytes().begin(), v1.bytes().end());
  EXPECT_EQ(require.check(v1_bytes, 0, 1, 1, 0), SignatureVerdict::unsigned_rejected);
}

TEST_F(Verifier, StreamTableIsBounded) {
  SignatureVerifier v(key_, {});
  for (std::size_t i = 0; i < kMaxSigningStreams; ++i) {
    ASSERT_EQ(check(v, signed_frame(static_cast<std::uint8_t>(i + 1), 0, 10), 0),
              SignatureVerdict::accepted_signed);
  }
  EXPECT_EQ(check(v, signed_frame(200, 0, 10), 0), SignatureVerdict::too_many_streams);
  EXPECT_EQ(check(v, signed_frame(1, 0, 11), 0), SignatureVerdict::accepted_signed);
}

}  // namespace
}  // namespace mocaplink::mavlink
