// Fuzz target: arbitrary bytes through StreamParser (byte-stream mode with input-derived chunking,
// and datagram mode, both with a signing verifier), then parse_frame + decode_message +
// re-encode + message_target (routing.hpp) of every delivered frame. Invariants checked: delivered
// frames lie inside the input, parse_frame agrees with the stream parser on known frames, decoded
// messages re-encode.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/routing.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace {

namespace mav = mocaplink::mavlink;

void check(bool ok) {
  if (!ok) std::abort();
}

void on_frame(const mav::FrameView& f) {
  check(f.bytes.size() >= 8 && f.bytes.size() <= mav::kMaxFrameSize);
  check(f.payload.size() == f.len);
  const auto parsed = mav::parse_frame(f.bytes);
  (void)mav::message_target(f);  // any id, any length: fuzz/mavlink_routing.cpp checks its results
  if (f.known()) {
    check(parsed.ok());
    const auto msg = mav::decode_message(f);
    check(msg.has_value());
    const mav::Frame again =
        mav::encode(*msg, mav::FrameHeader{.seq = f.seq, .sysid = f.sysid, .compid = f.compid});
    check(!again.empty());
    const auto reparsed = mav::parse_frame(again.bytes());
    check(reparsed.ok() && reparsed->msgid == f.msgid);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> input(data, size);
  static const mav::SigningKey key(std::array<std::uint8_t, 32>{1, 2, 3});
  {
    mav::SignatureVerifier verifier(key, {.unsigned_policy = mav::UnsignedPolicy::accept});
    mav::StreamParser parser(&verifier);
    // Chunk sizes from the first byte, so the fuzzer explores frames split across feed() calls.
    const std::size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
    for (std::size_t i = 0; i < size; i += chunk) {
      parser.feed(input.subspan(i, std::min(chunk, size - i)), 0, on_frame);
      check(parser.pending_bytes() <= mav::kStreamBufferSize);
    }
    parser.finish(0, on_frame);
  }
  {
    mav::StreamParser parser;
    parser.feed_datagram(input, 0, on_frame);
  }
  (void)mav::parse_frame(input);
  return 0;
}
