// Every golden frame of shared/mavlink/golden-vectors.json (MAVLink C library and pymavlink agree
// byte for byte on each): our encoder reproduces it exactly, our decoder gives back its fields, and
// signed frames verify with the test key and fail with any other.
#include <gtest/gtest.h>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/signing.hpp"
#include "mocaplink/mavlink_json/mavlink_json.hpp"
#include "mocaplink/text/hex.hpp"
#include "test_support.hpp"

namespace mocaplink::mavlink {
namespace {

using nlohmann::json;

class Golden : public ::testing::Test {
 protected:
  const json doc_ = test::load_golden();
  const SigningKey key_ = *SigningKey::from_hex(doc_.at("key_hex").get<std::string>());
};

TEST_F(Golden, HasAllVectors) {
  EXPECT_EQ(doc_.at("vectors").size(), 20u);
}

TEST_F(Golden, EncodeIsByteExact) {
  // Each vector as `mocaplink mavlink encode` reads it: message, header and signature from the
  // JSON, encoded; the reference implementations' bytes are the oracle.
  const auto encoded = mavlink_json::encode_vectors(doc_);
  ASSERT_EQ(encoded.size(), doc_.at("vectors").size());
  for (std::size_t i = 0; i < encoded.size(); ++i) {
    const json& v = doc_.at("vectors")[i];
    SCOPED_TRACE(v.at("id").get<std::string>());
    EXPECT_EQ(encoded[i].id, v.at("id").get<std::string>());
    EXPECT_EQ(text::to_hex(encoded[i].frame.bytes()), v.at("expected_hex").get<std::string>());
  }
}

TEST_F(Golden, DecodeGivesBackFields) {
  for (const auto& v : doc_.at("vectors")) {
    SCOPED_TRACE(v.at("id").get<std::string>());
    const auto bytes = *text::from_hex(v.at("expected_hex").get<std::string>());
    const auto frame = parse_frame(bytes);
    ASSERT_TRUE(frame.ok()) << to_string(frame.error());
    EXPECT_EQ(frame->version, 2);
    EXPECT_EQ(frame->seq, v.at("seq").get<int>());
    EXPECT_EQ(frame->sysid, v.at("sysid").get<int>());
    EXPECT_EQ(frame->compid, v.at("compid").get<int>());
    ASSERT_NE(frame->info, nullptr);
    EXPECT_EQ(frame->info->name, v.at("msg").get<std::string>());
    EXPECT_EQ(frame->is_signed(), v.contains("sign"));
    const auto msg = decode_message(*frame);
    ASSERT_TRUE(msg.has_value());
    // The vector's fields as typed values (absent fields are 0), compared field by field.
    const Message expected_message = mavlink_json::message_from_json(v, "vector");
    ASSERT_EQ(expected_message.index(), msg->index());
    std::visit(
        [&](const auto& m) {
          const auto& want = std::get<std::remove_cvref_t<decltype(m)>>(expected_message);
          std::size_t field_index = 0;
          for_each_field(m, [&](const FieldInfo& info, const auto& field) {
            SCOPED_TRACE(std::string(info.name));
            std::remove_cvref_t<decltype(field)> expected{};
            std::size_t want_index = 0;
            for_each_field(want, [&](const FieldInfo&, const auto& w) {
              if constexpr (std::is_same_v<std::remove_cvref_t<decltype(w)>,
                                           std::remove_cvref_t<decltype(field)>>) {
                if (want_index == field_index) expected = w;
              }
              ++want_index;
            });
            ++field_index;
            if constexpr (requires { field.size(); }) {
              for (std::size_t i = 0; i < field.size(); ++i) {
                EXPECT_TRUE(test::same_value(field[i], expected[i])) << "index " << i;
              }
            } else {
              EXPECT_TRUE(test::same_value(field, expected)) << +field << " vs " << +expected;
            }
          });
        },
        *msg);
    if (v.contains("sign")) {
      EXPECT_EQ(frame->signature->link_id, v.at("sign").at("link_id").get<int>());
      EXPECT_EQ(frame->signature->timestamp_10us,
                std::stoull(v.at("sign").at("timestamp").get<std::string>()));
    }
  }
}

TEST_F(Golden, SignedVectorsVerifyWithKeyOnly) {
  auto wrong_secret = key_.secret();
  wrong_secret[31] ^= 0x01;
  const SigningKey wrong(wrong_secret);
  int signed_count = 0;
  for (const auto& v : doc_.at("vectors")) {
    if (!v.contains("sign")) continue;
    SCOPED_TRACE(v.at("id").get<std::string>());
    ++signed_count;
    const auto bytes = *text::from_hex(v.at("expected_hex").get<std::string>());
    EXPECT_TRUE(key_.verify(bytes));
    EXPECT_FALSE(wrong.verify(bytes));
    // Through the receive policy too (local time 0: every timestamp is fresh): accepted once,
    // then the same frame is a replay.
    SignatureVerifier verifier(key_, {});
    const auto view = *parse_frame(bytes);
    EXPECT_EQ(verifier.check(bytes, view.msgid, view.sysid, view.compid, 0),
              SignatureVerdict::accepted_signed);
    EXPECT_EQ(verifier.check(bytes, view.msgid, view.sysid, view.compid, 0),
              SignatureVerdict::replay);
    SignatureVerifier wrong_verifier(wrong, {});
    EXPECT_EQ(wrong_verifier.check(bytes, view.msgid, view.sysid, view.compid, 0),
              SignatureVerdict::bad_signature);
  }
  EXPECT_EQ(signed_count, 4);
}

// mavlink-wire.md §10 also gives the golden key's derivation: SHA-256("mocap-bridge-test-key").
TEST_F(Golden, KeyHexParsesCaseInsensitively) {
  auto upper = doc_.at("key_hex").get<std::string>();
  for (auto& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const auto k = SigningKey::from_hex(upper);
  ASSERT_TRUE(k.has_value());
  EXPECT_EQ(k->secret(), key_.secret());
  EXPECT_FALSE(SigningKey::from_hex(upper.substr(2)).has_value());
  EXPECT_FALSE(SigningKey::from_hex(upper.substr(2) + "zz").has_value());
}

}  // namespace
}  // namespace mocaplink::mavlink
