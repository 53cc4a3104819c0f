#include <gtest/gtest.h>

#include <cmath>

#include "slamkit/models/odometry_sampling.hpp"

namespace slamkit {
namespace {

TEST(OdometrySampling, SamplesHaveTheStatedSpreadAndTheDensityMatchesIt) {
  const OdometryNoiseParams noise{.srr = 0.1, .srt = 0.05, .str = 0.02, .stt = 0.2};
  const Pose2 from(1.0, 2.0, 0.5);
  const Pose2 delta(0.8, 0.1, 0.3);
  const Eigen::Vector3d sigma = OdometryNoiseSigmas(delta, noise);
  // srr·|dx| + srt·|dθ| + 0.3·srr·|dy|, and so on, written out.
  EXPECT_NEAR(sigma.x(), 0.1 * 0.8 + 0.05 * 0.3 + 0.03 * 0.1, 1e-12);
  EXPECT_NEAR(sigma.y(), 0.1 * 0.1 + 0.05 * 0.3 + 0.03 * 0.8, 1e-12);
  EXPECT_NEAR(sigma.z(), 0.2 * 0.3 + 0.02 * std::hypot(0.8, 0.1), 1e-12);

  Rng rng(5);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Pose2 moved = from.Between(SampleOdometryMotion(from, delta, noise, rng));
    const Eigen::Vector3d e(moved.x() - delta.x(), moved.y() - delta.y(),
                            moved.theta() - delta.theta());
    sum += e;
    sum_sq += e.cwiseProduct(e);
  }
  const Eigen::Vector3d mean = sum / n;
  const Eigen::Vector3d stddev = (sum_sq / n - mean.cwiseProduct(mean)).cwiseSqrt();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(mean[k], 0.0, 4.0 * sigma[k] / std::sqrt(n)) << k;
    EXPECT_NEAR(stddev[k] / sigma[k], 1.0, 0.03) << k;
  }

  const Pose2 expected = from.Compose(delta);
  EXPECT_NEAR(OdometryMotionLogDensity(from, delta, expected, noise), 0.0, 1e-12);
  const Pose2 off = from.Compose(Pose2(delta.x() + 0.02, delta.y(), delta.theta() - 0.01));
  EXPECT_NEAR(OdometryMotionLogDensity(from, delta, off, noise),
              -0.5 * (std::pow(0.02 / sigma.x(), 2) + std::pow(0.01 / sigma.z(), 2)), 1e-9);
  // Standing still: the σ floor keeps the density finite and peaked at the start.
  EXPECT_NEAR(OdometryMotionLogDensity(from, Pose2(), from.Compose(Pose2(0.001, 0, 0)), noise),
              -0.5, 1e-9);
}

}  // namespace
}  // namespace slamkit

namespace slamkit {
namespace {

// Driving backwards is the same motion mirrored: the noise of an increment depends on its size,
// not its sign (no rot1-trans-rot2 split, whose first turn would flip by π when reversing), and
// the density of a reversed move mirrors the forward one's.
TEST(OdometryMotion, ReverseIncrementsHaveTheForwardNoise) {
  const OdometryNoiseParams noise{.srr = 0.1, .srt = 0.05, .str = 0.02, .stt = 0.2};
  const Pose2 forward(0.8, 0.1, 0.3);
  const Pose2 backward(-0.8, -0.1, -0.3);
  EXPECT_EQ(OdometryNoiseSigmas(forward, noise), OdometryNoiseSigmas(backward, noise));
  // The noise is added to the increment (as SampleOdometryMotion does): n forward, −n backward.
  const Pose2 from(1.0, 2.0, 0.5);
  const double forward_density =
      OdometryMotionLogDensity(from, forward, from.Compose(Pose2(0.83, 0.08, 0.31)), noise);
  EXPECT_NEAR(forward_density,
              OdometryMotionLogDensity(from, backward, from.Compose(Pose2(-0.83, -0.08, -0.31)),
                                       noise),
              1e-12);
  EXPECT_LT(forward_density, -0.01) << "the move carries noise: the test is moot";
}

}  // namespace
}  // namespace slamkit
