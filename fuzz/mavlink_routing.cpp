// Fuzz target: message_target (routing.hpp) with any message id, version and payload. Input: byte 0
// picks the version (odd: MAVLink 1), bytes 1-3 are the 24-bit message id (little-endian), the rest
// is the payload (any length, longer than MAVLink's 255 bytes too). Invariants checked: a payload
// and the same payload zero-extended to 255 bytes have the same target (a missing byte reads 0);
// MAVLink 1 gives no target or MAVLink 2's; the FrameView overload agrees with the raw one.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/routing.hpp"

namespace {

namespace mav = mocaplink::mavlink;

void check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 4) {
    (void)mav::message_target(0, std::span<const std::uint8_t>(data, size), 2);
    return 0;
  }
  const std::uint8_t version = (data[0] & 1U) != 0 ? 1 : 2;
  const std::uint32_t msgid =
      data[1] | (std::uint32_t{data[2]} << 8) | (std::uint32_t{data[3]} << 16);
  const std::span<const std::uint8_t> payload(data + 4, size - 4);

  const auto target = mav::message_target(msgid, payload, version);

  std::array<std::uint8_t, 255> extended{};
  const std::size_t kept = std::min(payload.size(), extended.size());
  std::copy_n(payload.begin(), kept, extended.begin());
  if (payload.size() <= extended.size()) {
    check(mav::message_target(msgid, extended, version) == target);
  }

  const auto v1 = mav::message_target(msgid, payload, 1);
  check(!v1 || v1 == mav::message_target(msgid, payload, 2));

  mav::FrameView frame;
  frame.version = version;
  frame.msgid = msgid;
  frame.payload = payload;
  check(mav::message_target(frame) == target);
  return 0;
}
