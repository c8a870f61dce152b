// fit_line: least squares through points (the clock drifts of sender_clock and vehicle_clock).
#include "mocaplink/core/line_fit.hpp"

#include <array>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

TEST(FitLine, ExactLineIsRecovered) {
  const std::array<LinePoint, 4> points{{{0, 3}, {1, 5}, {2, 7}, {10, 23}}};
  const auto line = fit_line(points);
  ASSERT_TRUE(line);
  EXPECT_DOUBLE_EQ(line->slope, 2.0);
  EXPECT_DOUBLE_EQ(line->intercept, 3.0);
  EXPECT_DOUBLE_EQ(line->at(4), 11.0);
}

TEST(FitLine, SymmetricScatterAveragesOut) {
  // y = 1 + 0.5 x with ±1 alternately: the errors cancel in pairs at equal x spacing.
  const std::array<LinePoint, 4> points{{{0, 2}, {0, 0}, {4, 4}, {4, 2}}};
  const auto line = fit_line(points);
  ASSERT_TRUE(line);
  EXPECT_DOUBLE_EQ(line->slope, 0.5);
  EXPECT_DOUBLE_EQ(line->intercept, 1.0);
}

TEST(FitLine, NoSlopeWithoutTwoDistinctX) {
  EXPECT_FALSE(fit_line(std::array<LinePoint, 1>{{{1, 1}}}));
  EXPECT_FALSE(fit_line(std::array<LinePoint, 3>{{{2, 1}, {2, 5}, {2, 9}}}));
  EXPECT_FALSE(fit_line(std::span<const LinePoint>{}));
}

}  // namespace
}  // namespace mocaplink::core
