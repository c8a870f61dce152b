// Differential test of our SHA-256 against OpenSSL's (the independent oracle): every message
// length 0..1000 with seeded pseudo-random content, fed in random splits (empty updates, partial
// blocks, several blocks at once), plus SigningKey's pattern (a state copied after a 32-byte
// prefix). Built only where OpenSSL is found (tests/libs/mavlink/CMakeLists.txt); the ci preset
// requires it.
#include <gtest/gtest.h>
#include <openssl/evp.h>

#include <random>
#include <vector>

#include "mocaplink/mavlink/sha256.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::mavlink {
namespace {

Sha256::Digest openssl_sha256(std::span<const std::uint8_t> data) {
  Sha256::Digest out{};
  unsigned int size = 0;
  if (EVP_Digest(data.data(), data.size(), out.data(), &size, EVP_sha256(), nullptr) != 1 ||
      size != out.size()) {
    ADD_FAILURE() << "EVP_Digest failed";
  }
  return out;
}

// std::mt19937's sequence is fixed by the standard, so the cases are the same on every platform
// (unlike the <random> distributions); `bound` is small, so the modulo bias does not matter.
std::size_t below(std::mt19937& rng, std::size_t bound) {
  return static_cast<std::size_t>(rng()) % bound;
}

std::vector<std::uint8_t> random_bytes(std::mt19937& rng, std::size_t n) {
  std::vector<std::uint8_t> v(n);
  for (auto& b : v) b = static_cast<std::uint8_t>(rng());
  return v;
}

// Feeds `data` to `h` in pieces of 0..150 bytes (mostly shorter than a block, sometimes more).
void update_in_random_pieces(Sha256& h, std::span<const std::uint8_t> data, std::mt19937& rng) {
  while (!data.empty()) {
    const std::size_t n = std::min(below(rng, 151), data.size());
    h.update(data.first(n));
    data = data.subspan(n);
  }
}

TEST(Sha256VsOpenssl, EveryLengthUpTo1000InRandomSplits) {
  std::mt19937 rng(20261125);
  for (std::size_t length = 0; length <= 1000; ++length) {
    const auto message = random_bytes(rng, length);
    const auto expected = openssl_sha256(message);
    Sha256 whole;
    whole.update(message);
    ASSERT_EQ(whole.finish(), expected) << "length " << length << ", one update";
    for (int split = 0; split < 3; ++split) {
      Sha256 pieces;
      update_in_random_pieces(pieces, message, rng);
      ASSERT_EQ(pieces.finish(), expected) << "length " << length << ", split " << split;
    }
  }
}

TEST(Sha256VsOpenssl, StateCopiedAfterPrefix) {
  std::mt19937 rng(7);
  const auto prefix = random_bytes(rng, 32);
  Sha256 after_prefix;
  after_prefix.update(prefix);
  for (int i = 0; i < 300; ++i) {
    const auto suffix = random_bytes(rng, below(rng, 300));
    std::vector<std::uint8_t> whole = prefix;
    whole.insert(whole.end(), suffix.begin(), suffix.end());
    Sha256 h = after_prefix;
    update_in_random_pieces(h, suffix, rng);
    ASSERT_EQ(h.finish(), openssl_sha256(whole)) << "suffix of " << suffix.size() << " bytes";
  }
}

TEST(Sha256VsOpenssl, SigningKeySignatureIsTruncatedSha256OfSecretAndFrame) {
  // mavlink-wire.md §7.2: signature = first 6 bytes of SHA-256(secret ‖ signed part).
  std::mt19937 rng(42);
  for (int i = 0; i < 200; ++i) {
    std::array<std::uint8_t, 32> secret{};
    for (auto& b : secret) b = static_cast<std::uint8_t>(rng());
    const SigningKey key(secret);
    const auto signed_part = random_bytes(rng, 12 + below(rng, 268));
    std::vector<std::uint8_t> whole(secret.begin(), secret.end());
    whole.insert(whole.end(), signed_part.begin(), signed_part.end());
    const auto digest = openssl_sha256(whole);
    const auto signature = key.signature(signed_part);
    ASSERT_TRUE(std::equal(signature.begin(), signature.end(), digest.begin())) << "case " << i;
  }
}

}  // namespace
}  // namespace mocaplink::mavlink
