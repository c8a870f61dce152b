// Hostile byte streams through StreamParser (mavlink-wire.md §8) with exact per-reason counts,
// independent of how the bytes are chunked; UDP datagram mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "mocaplink/mavlink/crc.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace mocaplink::mavlink {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const Frame& f) {
  return {f.bytes().begin(), f.bytes().end()};
}

bool has_magic_after_first(const Bytes& b) {
  return std::any_of(b.begin() + 1, b.end(), [](auto x) { return x == 0xFD || x == 0xFE; });
}

void append(Bytes& out, const Bytes& b) {
  out.insert(out.end(), b.begin(), b.end());
}

struct Delivered {
  std::uint32_t msgid;
  std::uint8_t seq;
  std::uint8_t version;
  bool known;
  bool operator==(const Delivered&) const = default;
};

class HostileStream : public ::testing::Test {
 protected:
  void SetUp() override {
    std::array<std::uint8_t, 32> secret{};
    secret.fill(0x42);
    key_ = SigningKey(secret);
    std::array<std::uint8_t, 32> other{};
    other.fill(0x43);
    const SigningKey wrong(other);

    Heartbeat hb;
    hb.type = 6;
    const auto frame = [&](std::uint8_t seq, const SignParams* sign = nullptr) {
      return bytes_of(encode(hb, FrameHeader{seq, 1, 1}, sign));
    };
    HilGps gps;
    gps.time_usec = 123;
    gps.lat = 7;
    gps.satellites_visible = 9;
    const Bytes gps_frame = bytes_of(encode(gps, FrameHeader{2, 1, 1}));

    // 1. garbage: 5 bytes, no magic.
    append(stream_, {'h', 'e', 'l', 'l', 'o'});
    // 2. valid HEARTBEAT seq 1.
    append(stream_, frame(1));
    // 3. fake STX: a HEARTBEAT header claiming len 40 — its claimed extent swallows the valid
    //    HIL_GPS that follows; CRC fails, resync one byte after the fake magic (9 garbage bytes).
    append(stream_, {0xFD, 40, 0x00, 0x00, 0x07, 0x01, 0x01, 0x00, 0x00, 0x00});
    append(stream_, gps_frame);
    // 4. bad CRC on an otherwise valid HEARTBEAT seq 3 (its 20 remaining bytes become garbage).
    Bytes bad = frame(3);
    bad.back() ^= 0xFF;
    append(stream_, bad);
    // 5. unknown message id 0x123456 (delivered raw, counted).
    Bytes unknown = {0xFD, 3, 0, 0, 4, 1, 1, 0x56, 0x34, 0x12, 1, 2, 3, 0x11, 0x22};
    append(stream_, unknown);
    // 6. signed with the wrong key.
    const SignParams wrong_sign{&wrong, 0, 1000};
    append(stream_, frame(5, &wrong_sign));
    // 7. correctly signed, timestamp 1000.
    const SignParams good{&key_, 0, 1000};
    const Bytes signed_ok = frame(6, &good);
    append(stream_, signed_ok);
    // 8. the same frame replayed; 9. a new frame with an equal timestamp.
    append(stream_, signed_ok);
    append(stream_, frame(7, &good));
    // 10. unknown incompat bit 0x02 with a valid CRC (dropped whole).
    Bytes flagged = frame(8);
    flagged[2] = 0x02;
    std::uint16_t crc = crc_accumulate(std::span<const std::uint8_t>(flagged).subspan(1, 18));
    crc = crc_accumulate(Heartbeat::kCrcExtra, crc);
    flagged[19] = static_cast<std::uint8_t>(crc & 0xFF);
    flagged[20] = static_cast<std::uint8_t>(crc >> 8);
    append(stream_, flagged);
    // 11. MAVLink 1 HEARTBEAT seq 9.
    append(stream_, bytes_of(encode_v1(hb, FrameHeader{9, 1, 1})));
    // 12. truncated tail: the first 10 bytes of a HEARTBEAT (9 garbage bytes after its magic).
    const Bytes full_tail = frame(10);
    const Bytes tail(full_tail.begin(), full_tail.begin() + 10);
    append(stream_, tail);

    // The exact counts below assume no stray magic inside the frames we broke or skip bytewise.
    for (const Bytes& b : {frame(1), gps_frame, bad, tail}) ASSERT_FALSE(has_magic_after_first(b));
  }

  ParserCounters expected_counters() const {
    ParserCounters c;
    c.frames = 5;  // HEARTBEAT 1, HIL_GPS 2, unknown, signed 6, v1 9
    c.v1_frames = 1;
    c.signed_frames = 1;
    c.unknown_msgid = 1;
    c.garbage_bytes = 5 + 9 + 20 + 9;
    c.bad_crc = 2;  // the fake STX and the corrupted frame
    c.unknown_incompat = 1;
    c.bad_signature = 1;
    c.replay = 2;  // replayed frame and equal timestamp
    c.truncated_tail = 1;
    return c;
  }

  const std::vector<Delivered> expected_frames_ = {{0, 1, 2, true},
                                                   {113, 2, 2, true},
                                                   {0x123456, 4, 2, false},
                                                   {0, 6, 2, true},
                                                   {0, 9, 1, true}};

  SigningKey key_{std::array<std::uint8_t, 32>{}};
  Bytes stream_;
};

TEST_F(HostileStream, ExactCountsInOneChunk) {
  SignatureVerifier verifier(key_, {.unsigned_policy = UnsignedPolicy::accept});
  StreamParser parser(&verifier);
  std::vector<Delivered> got;
  const auto on_frame = [&](const FrameView& f) {
    got.push_back({f.msgid, f.seq, f.version, f.known()});
  };
  parser.feed(stream_, 0, on_frame);
  EXPECT_EQ(parser.pending_bytes(), 10u);
  parser.finish(0, on_frame);
  EXPECT_EQ(got, expected_frames_);
  EXPECT_EQ(parser.counters(), expected_counters());
}

TEST_F(HostileStream, ChunkingDoesNotMatter) {
  for (const std::size_t chunk : {1u, 2u, 3u, 7u, 64u, 300u}) {
    SCOPED_TRACE(chunk);
    SignatureVerifier verifier(key_, {.unsigned_policy = UnsignedPolicy::accept});
    StreamParser parser(&verifier);
    std::vector<Delivered> got;
    const auto on_frame = [&](const FrameView& f) {
      got.push_back({f.msgid, f.seq, f.version, f.known()});
    };
    for (std::size_t i = 0; i < stream_.size(); i += chunk) {
      parser.feed(std::span(stream_).subspan(i, std::min(chunk, stream_.size() - i)), 0, on_frame);
    }
    parser.finish(0, on_frame);
    EXPECT_EQ(got, expected_frames_);
    EXPECT_EQ(parser.counters(), expected_counters());
  }
}

TEST_F(HostileStream, AsOneDatagram) {
  SignatureVerifier verifier(key_, {.unsigned_policy = UnsignedPolicy::accept});
  StreamParser parser(&verifier);
  std::vector<Delivered> got;
  parser.feed_datagram(stream_, 0, [&](const FrameView& f) {
    got.push_back({f.msgid, f.seq, f.version, f.known()});
  });
  EXPECT_EQ(got, expected_frames_);
  EXPECT_EQ(parser.counters(), expected_counters());
}

TEST_F(HostileStream, RequireSignedRejectsUnsigned) {
  SignatureVerifier verifier(key_, {.unsigned_policy = UnsignedPolicy::reject});
  StreamParser parser(&verifier);
  std::vector<Delivered> got;
  parser.feed_datagram(stream_, 0, [&](const FrameView& f) {
    got.push_back({f.msgid, f.seq, f.version, f.known()});
  });
  EXPECT_EQ(got, (std::vector<Delivered>{{0, 6, 2, true}}));
  EXPECT_EQ(parser.counters().unsigned_rejected, 4u);  // HEARTBEAT, HIL_GPS, unknown id, v1
}

TEST(StreamParser, WithoutVerifierSignedFramesPassUnverified) {
  std::array<std::uint8_t, 32> secret{};
  const SigningKey key(secret);
  const SignParams sign{&key, 0, 5};
  const Frame a = encode(Heartbeat{}, FrameHeader{0, 1, 1}, &sign);
  StreamParser parser;
  int n = 0;
  parser.feed_datagram(a.bytes(), 0, [&](const FrameView& f) { n += f.is_signed() ? 1 : 0; });
  parser.feed_datagram(a.bytes(), 0, [&](const FrameView& f) { n += f.is_signed() ? 1 : 0; });
  EXPECT_EQ(n, 2);
}

TEST(StreamParser, SeveralFramesPerDatagramAndTruncatedTail) {
  Bytes datagram;
  for (std::uint8_t s = 0; s < 3; ++s) append(datagram, bytes_of(encode(Timesync{}, {s, 1, 1})));
  StreamParser parser;
  std::vector<std::uint8_t> seqs;
  const auto on_frame = [&](const FrameView& f) { seqs.push_back(f.seq); };
  parser.feed_datagram(datagram, 0, on_frame);
  EXPECT_EQ(seqs, (std::vector<std::uint8_t>{0, 1, 2}));
  datagram.erase(datagram.end() - 3, datagram.end());  // cut the last frame
  parser.feed_datagram(datagram, 0, on_frame);
  EXPECT_EQ(seqs, (std::vector<std::uint8_t>{0, 1, 2, 0, 1}));
  EXPECT_EQ(parser.counters().truncated_tail, 1u);
  EXPECT_EQ(parser.counters().frames, 5u);
  // A datagram never leaves state behind for the byte-stream input.
  EXPECT_EQ(parser.pending_bytes(), 0u);
}

TEST(StreamParser, FakeMagicWithUnknownIdDoesNotHideValidFrame) {
  // 0xFD, len 30, then bytes whose "msgid" is unknown: without the known-frame check this raw
  // "frame" would swallow the valid TIMESYNC that follows.
  Bytes stream = {0xFD, 30, 0, 0, 0x10, 0x20, 0x30};
  const Bytes valid = bytes_of(encode(Timesync{}, FrameHeader{77, 1, 1}));
  append(stream, valid);
  append(stream, Bytes(40, 0x00));  // enough bytes for the fake frame to be complete
  StreamParser parser;
  std::vector<std::uint32_t> ids;
  parser.feed_datagram(stream, 0, [&](const FrameView& f) { ids.push_back(f.msgid); });
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{Timesync::kId}));
  EXPECT_EQ(parser.counters().unknown_msgid, 0u);
}

TEST(StreamParser, BoundedUnderEndlessGarbage) {
  StreamParser parser;
  const Bytes junk(100'000, 0xFD);  // every byte a magic claiming a 265-byte frame of id 0xFDFDFD
  int n = 0;
  parser.feed(junk, 0, [&](const FrameView&) { ++n; });
  EXPECT_LE(parser.pending_bytes(), kStreamBufferSize);
  EXPECT_EQ(parser.counters().bad_crc, 0u);
}

}  // namespace
}  // namespace mocaplink::mavlink
