#include "slamkit/maps/likelihood_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "slamkit/core/rng.hpp"

namespace slamkit {
namespace {

// The transform against the definition: the smallest squared distance to any site.
TEST(LikelihoodField, DistanceTransformIsTheBruteForceMinimum) {
  const int width = 37, height = 23;
  Rng rng(5);
  std::vector<double> f(width * height, 1e9);
  std::vector<int> sites;
  for (int i = 0; i < 25; ++i) {
    const int k = int(rng.Uniform() * width * height) % (width * height);
    f[k] = 0.0;
    sites.push_back(k);
  }
  std::vector<double> g = f;
  SquaredDistanceTransform(g, width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double best = std::numeric_limits<double>::infinity();
      for (int k : sites) {
        best = std::min(best, std::pow(x - k % width, 2.0) + std::pow(y - k / width, 2.0));
      }
      ASSERT_EQ(g[y * width + x], best) << x << "," << y;
    }
  }
}

// A 4 m × 3 m image at 0.1 m with one occupied pixel near its top-left corner (the image's top
// row is the largest y), the rest free but one unknown pixel.
OccupancyImage OneObstacle() {
  OccupancyImage image;
  image.width = 40;
  image.height = 30;
  image.resolution_m = 0.1;
  image.origin_m = {-1.0, 2.0};
  image.pixels.assign(40 * 30, 254);
  image.pixels[2 * 40 + 5] = 0;      // row 2 from the top: cell (5, 27)
  image.pixels[10 * 40 + 10] = 205;  // unknown
  return image;
}

TEST(LikelihoodField, DistancesAreMetresToTheObstacleInTheMapFrameAndCapped) {
  LikelihoodFieldParams params;
  params.max_distance_m = 1.0;
  const LikelihoodField field(OneObstacle(), params);
  EXPECT_EQ(field.OccupiedCount(), 1);
  const Eigen::Vector2d obstacle(-1.0 + 0.55, 2.0 + 2.75);  // the centre of cell (5, 27)
  EXPECT_NEAR(field.DistanceM(obstacle), 0.0, 1e-6);
  EXPECT_NEAR(field.DistanceM(obstacle + Eigen::Vector2d(0.3, 0.0)), 0.3, 1e-6);
  EXPECT_NEAR(field.DistanceM(obstacle + Eigen::Vector2d(-0.3, -0.4)), 0.5, 1e-6);
  EXPECT_NEAR(field.DistanceM(obstacle + Eigen::Vector2d(2.0, -2.0)), 1.0, 1e-6);  // capped
  EXPECT_EQ(field.DistanceM({-5.0, 0.0}), 1.0);  // outside the image
  EXPECT_FALSE(field.IsFree(obstacle));
  EXPECT_TRUE(field.IsFree(obstacle + Eigen::Vector2d(0.3, 0.0)));
  EXPECT_FALSE(field.IsFree(Eigen::Vector2d(-1.0 + 1.05, 2.0 + 1.95)));  // the unknown pixel
  EXPECT_EQ(field.FreeCells().size(), 40u * 30u - 2u);
}

TEST(LikelihoodField, RejectsAnEmptyImage) {
  EXPECT_THROW(LikelihoodField(OccupancyImage{}), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
