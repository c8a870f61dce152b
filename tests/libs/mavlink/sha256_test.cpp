// SHA-256 against the published vectors: the FIPS 180-4 examples (NIST CSRC "Examples with
// Intermediate Values": one block, two blocks, the 896-bit message, a million 'a') and short
// messages from CAVP SHA256ShortMsg.rsp. The expected digests are NIST's, not ours.
// sha256_oracle_test.cpp compares with OpenSSL over many lengths and update splits.
#include "mocaplink/mavlink/sha256.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/text/hex.hpp"

namespace mocaplink::mavlink {
namespace {

using test::bytes_of;

std::string sha256_hex(std::string_view message) {
  Sha256 h;
  h.update(bytes_of(message));
  return text::to_hex(h.finish());
}

TEST(Sha256, Fips180OneBlockAbc) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, Fips180TwoBlock448BitMessage) {
  // 56 bytes: the padding's length field no longer fits, so a second block is all padding.
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, Fips180Example896BitMessage) {
  EXPECT_EQ(sha256_hex("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno"
                       "ijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256, EmptyMessage) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  Sha256 h;
  h.update({});
  EXPECT_EQ(text::to_hex(h.finish()),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, Fips180MillionA) {
  // In 1000 updates of 1000 bytes (not a multiple of the 64-byte block), and in one.
  const std::vector<std::uint8_t> chunk(1000, 'a');
  Sha256 h;
  for (int i = 0; i < 1000; ++i) h.update(chunk);
  EXPECT_EQ(text::to_hex(h.finish()),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(sha256_hex(std::string(1'000'000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, CavpShortMessages) {
  // SHA256ShortMsg.rsp, Len = 8 and Len = 16.
  EXPECT_EQ(sha256_hex("\xd3"), "28969cdfa74a12c82f3bad960b0b000aca2ac329deea5c2328ebc6f2ba9802c1");
  EXPECT_EQ(sha256_hex("\x11\xaf"),
            "5ca7133fa735326081558ac312c620eeca9970d1e70a4b95533d956f072d1f98");
}

TEST(Sha256, ByteAtATimeEqualsOneUpdate) {
  const std::string_view m = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  Sha256 h;
  for (const std::uint8_t b : bytes_of(m)) h.update(std::span(&b, 1));
  EXPECT_EQ(text::to_hex(h.finish()),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, CopiesAreIndependent) {
  // What SigningKey relies on: a state copied after a common prefix continues on its own.
  Sha256 prefix;
  prefix.update(bytes_of("ab"));
  Sha256 copy = prefix;
  copy.update(bytes_of("c"));
  EXPECT_EQ(text::to_hex(copy.finish()),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(text::to_hex(prefix.finish()), sha256_hex("ab"));
  // coreutils sha256sum of "ab":
  EXPECT_EQ(sha256_hex("ab"), "fb8e20fc2e4c3f248c60c39bd652f3c1347298bb977b8b4d5903b85055620603");
}

}  // namespace
}  // namespace mocaplink::mavlink
