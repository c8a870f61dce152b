// MAVLink 2 message signing (mavlink-wire.md §7; mavlink.io "Message Signing").
//
//   SigningKey        the 32-byte secret with its SHA-256 state precomputed (cheap to sign with).
//   SignParams        what one frame is signed with: key, link id, 48-bit timestamp.
//   OutgoingSigner    per-link timestamp source: strictly increasing, max(now, last + 1).
//   SignatureVerifier per-link receive policy: signature check, replay protection per
//                     (sysid, compid, link_id), 60 s rule for new streams, unsigned policy.
//
// Timestamps are in units of 10 µs since 2015-01-01 00:00:00 UTC, 48 bits (kMaxSigningTimestamp).
// The library never reads a clock: callers pass `now_10us` (signing_timestamp_from_unix_us()
// converts the wall clock) and persist OutgoingSigner::timestamp_10us() themselves.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace mocaplink::mavlink {

/// Largest 48-bit signing timestamp.
inline constexpr std::uint64_t kMaxSigningTimestamp = (std::uint64_t{1} << 48) - 1;
/// Unix time of the signing epoch 2015-01-01 00:00:00 UTC, in seconds.
inline constexpr std::int64_t kSigningEpochUnixS = 1'420'070'400;
/// A new stream's first timestamp may lag the local timestamp by at most 60 s (§7.4 rule 3).
inline constexpr std::uint64_t kNewStreamWindow10us = 6'000'000;

/// Signing timestamp (10 µs units since 2015-01-01 UTC) of a Unix time in microseconds; 0 before
/// the epoch, kMaxSigningTimestamp after year 2104.
[[nodiscard]] std::uint64_t signing_timestamp_from_unix_us(std::int64_t unix_us) noexcept;

/// A 32-byte signing secret with the SHA-256 state after absorbing it, so that signing a frame
/// copies that state instead of re-hashing the key. Copyable value; immutable after construction,
/// so one key may be shared by threads for reading. Never log it (§7.2).
class SigningKey {
 public:
  explicit SigningKey(const std::array<std::uint8_t, 32>& secret) noexcept;

  /// Parses 64 hex digits (upper or lower case); nullopt for anything else.
  [[nodiscard]] static std::optional<SigningKey> from_hex(std::string_view hex) noexcept;

  /// First 6 bytes of SHA-256(secret ‖ signed_part), where signed_part is the frame from the
  /// 0xFD magic through link_id and timestamp (everything but the 6 signature bytes).
  [[nodiscard]] std::array<std::uint8_t, 6> signature(
      std::span<const std::uint8_t> signed_part) const noexcept;

  /// True if the last 6 bytes of the signed MAVLink 2 `frame` (whole frame, signature included,
  /// at least 12 + 13 bytes) match this key. Hash check only: no replay check (see
  /// SignatureVerifier).
  [[nodiscard]] bool verify(std::span<const std::uint8_t> frame) const noexcept;

  [[nodiscard]] const std::array<std::uint8_t, 32>& secret() const noexcept { return secret_; }

 private:
  std::array<std::uint8_t, 32> secret_{};
  // The SHA-256 state after absorbing secret_: OpenSSL's SHA256_CTX (112 bytes) or our Sha256
  // (104), whichever signing.cpp uses on this platform; opaque here to keep OpenSSL out of the API.
  using State = std::array<std::byte, 112>;
  alignas(8) State state_{};
};

/// How to sign one frame. `key` must outlive the encode call.
struct SignParams {
  const SigningKey* key = nullptr;
  std::uint8_t link_id = 0;
  std::uint64_t timestamp_10us = 0;  ///< 48-bit; must strictly increase per link (§7.3)
};

/// Signing state of one outgoing link: key, link id and the last timestamp used. Not
/// thread-safe (one link is driven by one thread).
class OutgoingSigner {
 public:
  /// `restored_timestamp_10us`: the persisted value (0 if none); the first frame uses at least
  /// restored + 1.
  OutgoingSigner(const SigningKey& key, std::uint8_t link_id,
                 std::uint64_t restored_timestamp_10us = 0) noexcept;

  /// Parameters for the next frame: timestamp = max(now_10us, last + 1), saturating at
  /// kMaxSigningTimestamp. The returned SignParams points into this signer.
  [[nodiscard]] SignParams next(std::uint64_t now_10us) noexcept;

  /// Raises the last timestamp to `timestamp_10us` if larger (from a correctly signed incoming
  /// frame, §7.3; never call it for unverified frames).
  void observe(std::uint64_t timestamp_10us) noexcept;

  /// The last timestamp used (persist it; pass it back as restored_timestamp_10us).
  [[nodiscard]] std::uint64_t timestamp_10us() const noexcept { return last_10us_; }
  [[nodiscard]] std::uint8_t link_id() const noexcept { return link_id_; }
  [[nodiscard]] const SigningKey& key() const noexcept { return key_; }

 private:
  SigningKey key_;
  std::uint8_t link_id_;
  std::uint64_t last_10us_;
};

/// What a link does with unsigned frames (§7.5).
enum class UnsignedPolicy : std::uint8_t {
  accept,  ///< default when no key is configured
  reject,  ///< require_signed
};
[[nodiscard]] std::string_view to_string(UnsignedPolicy policy) noexcept;

/// Verdict of SignatureVerifier::check for one frame.
enum class SignatureVerdict : std::uint8_t {
  accepted_signed,    ///< signature valid, timestamp fresh; stream updated
  accepted_unsigned,  ///< unsigned and the policy (or the RADIO_STATUS exception) allows it
  bad_signature,      ///< signed, hash does not match the key
  replay,             ///< valid hash, timestamp not greater than the stream's last one
  stale_new_stream,   ///< valid hash, new stream more than 60 s behind the local timestamp
  unsigned_rejected,  ///< unsigned while the policy requires signing
  too_many_streams,   ///< valid, but the stream table is full (kMaxSigningStreams)
};
[[nodiscard]] std::string_view to_string(SignatureVerdict verdict) noexcept;

/// True for the accepted_* verdicts.
[[nodiscard]] constexpr bool accepted(SignatureVerdict v) noexcept {
  return v == SignatureVerdict::accepted_signed || v == SignatureVerdict::accepted_unsigned;
}

/// Streams (sysid, compid, link_id) remembered per link. New streams beyond this are rejected
/// (only holders of the key can create streams, so this only bounds memory).
inline constexpr std::size_t kMaxSigningStreams = 64;

/// Receive-side signing policy and replay state of one link. Not thread-safe.
class SignatureVerifier {
 public:
  struct Options {
    UnsignedPolicy unsigned_policy = UnsignedPolicy::reject;
    /// Accept RADIO_STATUS (#109) unsigned even when signing is required: radios inject it
    /// without a key (ArduPilot does the same).
    bool accept_unsigned_radio_status = true;
  };

  SignatureVerifier(const SigningKey& key, Options options) noexcept;

  /// Checks one complete frame (`frame` = all its bytes; `msgid`, `sysid`, `compid` from its
  /// header; MAVLink 1 frames count as unsigned) against the policy at local time `now_10us`.
  /// On accepted_signed the stream's timestamp and local_timestamp_10us() advance.
  [[nodiscard]] SignatureVerdict check(std::span<const std::uint8_t> frame, std::uint32_t msgid,
                                       std::uint8_t sysid, std::uint8_t compid,
                                       std::uint64_t now_10us) noexcept;

  /// Largest of the local times passed in and the timestamps accepted (for OutgoingSigner).
  [[nodiscard]] std::uint64_t local_timestamp_10us() const noexcept { return local_10us_; }
  [[nodiscard]] const SigningKey& key() const noexcept { return key_; }
  [[nodiscard]] const Options& options() const noexcept { return options_; }

 private:
  struct Stream {
    std::uint8_t sysid = 0;
    std::uint8_t compid = 0;
    std::uint8_t link_id = 0;
    std::uint64_t last_10us = 0;
  };
  SigningKey key_;
  Options options_;
  std::uint64_t local_10us_ = 0;
  std::array<Stream, kMaxSigningStreams> streams_{};
  std::size_t stream_count_ = 0;
};

}  // namespace mocaplink::mavlink
