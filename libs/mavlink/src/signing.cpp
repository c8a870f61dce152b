// MAVLink 2 signing (mavlink-wire.md §7). The SHA-256 state after the secret is precomputed once
// per key and copied by value per frame.
//
// Which SHA-256: OpenSSL's where the build has it (Linux, MOCAPLINK_SIGNING_OPENSSL): it runs on
// the CPU's SHA instructions where there are some (x86 SHA-NI, ARMv8 crypto extensions), 3.3× our
// portable code on the team's Xeon and what keeps signed parsing above issue 2's 2× the C library
// (docs/performance.md). Elsewhere (Windows, which has no OpenSSL) our own Sha256 (sha256.hpp),
// which the tests check against OpenSSL on Linux. The low-level SHA256_* API is deprecated in
// OpenSSL 3 in favour of EVP, but EVP_MD_CTX_copy allocates per copy through the provider layer;
// the plain SHA256_CTX is copied by value.
#ifdef MOCAPLINK_SIGNING_OPENSSL
#define OPENSSL_SUPPRESS_DEPRECATED
#include <openssl/sha.h>
#endif

#include "mocaplink/mavlink/signing.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/sha256.hpp"
#include "mocaplink/text/hex.hpp"

namespace mocaplink::mavlink {
namespace {

constexpr std::uint32_t kRadioStatusId = 109;  // RADIO_STATUS, common.xml

#ifdef MOCAPLINK_SIGNING_OPENSSL
using HashState = SHA256_CTX;
HashState hash_start() noexcept {
  HashState state;
  SHA256_Init(&state);
  return state;
}
void hash_update(HashState& state, std::span<const std::uint8_t> data) noexcept {
  SHA256_Update(&state, data.data(), data.size());
}
std::array<std::uint8_t, 32> hash_finish(HashState& state) noexcept {
  std::array<std::uint8_t, 32> digest{};
  SHA256_Final(digest.data(), &state);
  return digest;
}
#else
using HashState = Sha256;
HashState hash_start() noexcept {
  return Sha256{};
}
void hash_update(HashState& state, std::span<const std::uint8_t> data) noexcept {
  state.update(data);
}
std::array<std::uint8_t, 32> hash_finish(HashState& state) noexcept {
  return state.finish();
}
#endif
static_assert(std::is_trivially_copyable_v<HashState>);

}  // namespace

std::uint64_t signing_timestamp_from_unix_us(std::int64_t unix_us) noexcept {
  const std::int64_t since_us = unix_us - kSigningEpochUnixS * 1'000'000;
  if (since_us <= 0) return 0;
  return std::min(static_cast<std::uint64_t>(since_us) / 10, kMaxSigningTimestamp);
}

SigningKey::SigningKey(const std::array<std::uint8_t, 32>& secret) noexcept : secret_(secret) {
  static_assert(sizeof(HashState) <= sizeof(state_) && alignof(HashState) <= 8);
  HashState state = hash_start();
  hash_update(state, secret_);
  std::memcpy(state_.data(), &state, sizeof(state));
}

std::optional<SigningKey> SigningKey::from_hex(std::string_view hex) noexcept {
  if (hex.size() != 64) return std::nullopt;
  std::array<std::uint8_t, 32> secret{};
  for (std::size_t i = 0; i < secret.size(); ++i) {
    const int hi = text::hex_value(hex[2 * i]);
    const int lo = text::hex_value(hex[2 * i + 1]);
    if (hi < 0 || lo < 0) return std::nullopt;
    secret[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  return SigningKey(secret);
}

std::array<std::uint8_t, 6> SigningKey::signature(
    std::span<const std::uint8_t> signed_part) const noexcept {
  HashState state;
  std::memcpy(&state, state_.data(), sizeof(state));
  hash_update(state, signed_part);
  const auto digest = hash_finish(state);
  std::array<std::uint8_t, 6> out{};
  std::copy_n(digest.begin(), out.size(), out.begin());
  return out;
}

bool SigningKey::verify(std::span<const std::uint8_t> frame) const noexcept {
  if (frame.size() < kHeaderSizeV2 + kChecksumSize + kSignatureSize) return false;
  const auto expected = signature(frame.first(frame.size() - 6));
  return std::equal(expected.begin(), expected.end(), frame.end() - 6);
}

OutgoingSigner::OutgoingSigner(const SigningKey& key, std::uint8_t link_id,
                               std::uint64_t restored_timestamp_10us) noexcept
    : key_(key),
      link_id_(link_id),
      last_10us_(std::min(restored_timestamp_10us, kMaxSigningTimestamp)) {}

SignParams OutgoingSigner::next(std::uint64_t now_10us) noexcept {
  // §7.3: strictly increasing per link even within one 10 µs tick; saturate at 48 bits (year
  // 2104) rather than wrap, since a wrapped timestamp would be rejected as a replay anyway.
  last_10us_ = std::min(std::max(now_10us, last_10us_ + 1), kMaxSigningTimestamp);
  return SignParams{&key_, link_id_, last_10us_};
}

void OutgoingSigner::observe(std::uint64_t timestamp_10us) noexcept {
  last_10us_ = std::max(last_10us_, std::min(timestamp_10us, kMaxSigningTimestamp));
}

std::string_view to_string(UnsignedPolicy policy) noexcept {
  switch (policy) {
    case UnsignedPolicy::accept:
      return "accept_unsigned";
    case UnsignedPolicy::reject:
      return "require_signed";
  }
  return "?";
}

std::string_view to_string(SignatureVerdict verdict) noexcept {
  switch (verdict) {
    case SignatureVerdict::accepted_signed:
      return "accepted_signed";
    case SignatureVerdict::accepted_unsigned:
      return "accepted_unsigned";
    case SignatureVerdict::bad_signature:
      return "bad_signature";
    case SignatureVerdict::replay:
      return "replay";
    case SignatureVerdict::stale_new_stream:
      return "stale_new_stream";
    case SignatureVerdict::unsigned_rejected:
      return "unsigned_rejected";
    case SignatureVerdict::too_many_streams:
      return "too_many_streams";
  }
  return "?";
}

SignatureVerifier::SignatureVerifier(const SigningKey& key, Options options) noexcept
    : key_(key), options_(options) {}

SignatureVerdict SignatureVerifier::check(std::span<const std::uint8_t> frame, std::uint32_t msgid,
                                          std::uint8_t sysid, std::uint8_t compid,
                                          std::uint64_t now_10us) noexcept {
  local_10us_ = std::max(local_10us_, now_10us);
  const bool is_signed = frame.size() >= 3 && frame[0] == kMagicV2 &&
                         (frame[2] & kIncompatSigned) != 0 &&
                         frame.size() >= kHeaderSizeV2 + kChecksumSize + kSignatureSize;
  if (!is_signed) {
    if (options_.unsigned_policy == UnsignedPolicy::accept) {
      return SignatureVerdict::accepted_unsigned;
    }
    if (options_.accept_unsigned_radio_status && msgid == kRadioStatusId) {
      return SignatureVerdict::accepted_unsigned;
    }
    return SignatureVerdict::unsigned_rejected;
  }
  if (!key_.verify(frame)) return SignatureVerdict::bad_signature;
  // Signature block starts 13 bytes before the end: link_id, 6-byte little-endian timestamp.
  const auto block = frame.last(kSignatureSize);
  const std::uint8_t link_id = block[0];
  std::uint64_t ts = 0;
  for (std::size_t i = 0; i < 6; ++i) ts |= static_cast<std::uint64_t>(block[1 + i]) << (8 * i);

  const auto end = streams_.begin() + static_cast<std::ptrdiff_t>(stream_count_);
  auto it = std::find_if(streams_.begin(), end, [&](const Stream& s) {
    return s.sysid == sysid && s.compid == compid && s.link_id == link_id;
  });
  if (it != end) {
    // §7.4 rule 2; equal timestamps are replays too (C library, pymavlink).
    if (ts <= it->last_10us) return SignatureVerdict::replay;
    it->last_10us = ts;
  } else {
    // §7.4 rule 3: a new stream may not start more than 60 s behind local time.
    if (ts + kNewStreamWindow10us < local_10us_) return SignatureVerdict::stale_new_stream;
    if (stream_count_ == streams_.size()) return SignatureVerdict::too_many_streams;
    streams_[stream_count_++] = Stream{sysid, compid, link_id, ts};
  }
  local_10us_ = std::max(local_10us_, ts);
  return SignatureVerdict::accepted_signed;
}

}  // namespace mocaplink::mavlink
