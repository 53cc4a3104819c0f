#include "slamkit/core/gaussian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace slamkit {
namespace {

TEST(Gaussian, SquaredMahalanobisUsesFullCovariance) {
  Gaussian g{Eigen::Vector2d(1.0, -1.0), Eigen::Matrix2d::Zero()};
  g.covariance << 4.0, 1.0, 1.0, 2.0;
  const Eigen::Vector2d x(2.5, 0.0);
  const Eigen::Vector2d d = x - g.mean;
  const double expected = d.dot(g.covariance.inverse() * d);
  EXPECT_NEAR(g.SquaredMahalanobis(x), expected, 1e-12);
  EXPECT_NEAR(SquaredMahalanobis2(d, g.covariance), expected, 1e-12);
  // Ignoring the correlation would give a different value.
  EXPECT_GT(std::abs(expected - (d.x() * d.x() / 4.0 + d.y() * d.y() / 2.0)), 1e-3);
}

}  // namespace
}  // namespace slamkit
