#include "slamkit/eval/spread.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace slamkit {
namespace {

TEST(Spread, IsTheMeanTheUnbiasedVarianceAndTheExtremes) {
  const std::vector<double> v = {1.0, 2.0, 3.0, 6.0};
  const Spread s = SpreadOf(v);
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.variance, 14.0 / 3.0);  // (4 + 1 + 0 + 9) / (n - 1)
  EXPECT_DOUBLE_EQ(s.sd(), std::sqrt(14.0 / 3.0));
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 6.0);
}

TEST(Spread, OneValueHasNoVarianceAndNoValueHasNoMean) {
  const std::vector<double> one = {2.5};
  EXPECT_EQ(SpreadOf(one).variance, 0.0);
  EXPECT_EQ(SpreadOf(one).min, 2.5);
  const Spread none = SpreadOf({});
  EXPECT_EQ(none.count, 0);
  EXPECT_TRUE(std::isnan(none.mean));
  EXPECT_TRUE(std::isnan(none.max));
}

TEST(Spread, ADivergedRunShowsInEveryFigure) {
  for (const std::vector<double>& v :
       {std::vector<double>{NAN, 1.0, 2.0}, std::vector<double>{1.0, NAN, 2.0},
        std::vector<double>{1.0, 2.0, NAN}}) {
    const Spread s = SpreadOf(v);
    EXPECT_TRUE(std::isnan(s.mean));
    EXPECT_TRUE(std::isnan(s.min));
    EXPECT_TRUE(std::isnan(s.max));
  }
}

}  // namespace
}  // namespace slamkit
