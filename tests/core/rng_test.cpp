#include "slamkit/core/rng.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace slamkit {
namespace {

TEST(Rng, SameSeedSameStream) {
  Rng a(42), b(42), c(43);
  bool any_differs = false;
  for (int i = 0; i < 100; ++i) {
    const double va = a.Normal();
    EXPECT_EQ(va, b.Normal());
    any_differs |= va != c.Normal();
  }
  EXPECT_TRUE(any_differs);
}

TEST(Rng, StreamsAreDistinctAndReproducible) {
  Rng s0 = Rng::ForStream(1, 0), s1 = Rng::ForStream(1, 1), s0b = Rng::ForStream(1, 0);
  const std::uint64_t a = s0.NextU64();
  EXPECT_EQ(a, s0b.NextU64());
  EXPECT_NE(a, s1.NextU64());
  EXPECT_NE(Rng::ForStream(2, 0).NextU64(), a);
}

TEST(Rng, NormalMomentsMatch) {
  Rng rng(9);
  const int n = 200000;
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = rng.Normal(1.5, 2.0);
    sum += v;
    sum_sq += v * v;
  }
  const double mean = sum / n;
  const double var = sum_sq / n - mean * mean;
  EXPECT_NEAR(mean, 1.5, 5.0 * 2.0 / std::sqrt(n));
  EXPECT_NEAR(var, 4.0, 0.05);
}

TEST(Rng, MultivariateNormalHasRequestedCovariance) {
  Rng rng(11);
  Eigen::Matrix3d cov;
  cov << 2.0, 0.6, 0.0, 0.6, 1.0, -0.3, 0.0, -0.3, 0.5;
  Eigen::Matrix3d acc = Eigen::Matrix3d::Zero();
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d v = rng.MultivariateNormal(cov);
    acc += v * v.transpose();
  }
  EXPECT_TRUE((acc / n - cov).cwiseAbs().maxCoeff() < 0.03) << acc / n;
}

}  // namespace
}  // namespace slamkit
