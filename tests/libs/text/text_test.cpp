// mocaplink::text against hand-worked values: edit distances counted by hand, the closeness rule
// of did_you_mean.hpp, hex of known bytes.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/text/did_you_mean.hpp"
#include "mocaplink/text/hex.hpp"

namespace mocaplink::text {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndTranspositions) {
  EXPECT_EQ(edit_distance("", ""), 0U);
  EXPECT_EQ(edit_distance("rate", "rate_hz"), 3U);         // three insertions
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3U);       // k→s, e→i, +g
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2U);            // −f, +n
  EXPECT_EQ(edit_distance("sytsem_id", "system_id"), 1U);  // one adjacent transposition
  EXPECT_EQ(edit_distance("Profile", "profile"), 0U);      // ASCII case-insensitive
}

TEST(ClosestMatch, SuggestsOnlyPlausibleTypos) {
  const std::array<std::string_view, 4> keys = {"name", "rate_hz", "system_id", "profile"};
  EXPECT_EQ(closest_match("nmae", keys), "name");     // 1 edit, 4 letters
  EXPECT_EQ(closest_match("rate", keys), "rate_hz");  // a prefix of 3+ letters
  EXPECT_EQ(closest_match("sytsem_id", keys), "system_id");
  EXPECT_FALSE(closest_match("colour", keys).has_value());
  EXPECT_FALSE(closest_match("nm", keys).has_value());  // 2 edits is too far for 2 letters
  EXPECT_EQ(did_you_mean("profle", keys), "; did you mean \"profile\"?");
  EXPECT_EQ(did_you_mean("colour", keys), "");
}

TEST(Hex, EncodesAndDecodesBothCases) {
  const std::vector<std::uint8_t> bytes = {0x00, 0x0f, 0xa5, 0xff};
  EXPECT_EQ(to_hex(bytes), "000fa5ff");
  EXPECT_EQ(from_hex("000fA5Ff"), bytes);
  EXPECT_EQ(from_hex(""), std::vector<std::uint8_t>{});
  EXPECT_FALSE(from_hex("abc").has_value());  // odd count
  EXPECT_FALSE(from_hex("0g").has_value());
  EXPECT_TRUE(is_hex("09afAF"));
  EXPECT_TRUE(is_hex(""));
  EXPECT_FALSE(is_hex("12 3"));
  EXPECT_EQ(hex_value('b'), 11);
  EXPECT_EQ(hex_value('G'), -1);
}

}  // namespace
}  // namespace mocaplink::text
