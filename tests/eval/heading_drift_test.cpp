#include "slamkit/eval/heading_drift.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "slamkit/core/rng.hpp"

namespace slamkit {
namespace {

// A drive of `steps` increments (0.2–1 m forward, turning up to ±0.3 rad a step) and its path,
// with odometry that turns `bias` rad per metre less than the vehicle and has `noise_rad` of
// heading noise per step.
struct Drive {
  std::vector<Pose2> odometry;
  Trajectory path;
};

Drive MakeDrive(int steps, double bias_rad_per_m, double noise_rad, std::uint64_t seed) {
  Rng rng(seed);
  Drive d;
  d.path.push_back({0.0, Pose2()});
  for (int k = 0; k < steps; ++k) {
    const double forward = rng.Uniform(0.2, 1.0);
    const Pose2 truth(forward, 0.0, rng.Uniform(-0.3, 0.3));
    d.path.push_back({k + 1.0, d.path.back().pose.Compose(truth)});
    d.odometry.emplace_back(forward, 0.0,
                            truth.theta() - bias_rad_per_m * forward + rng.Normal(0.0, noise_rad));
  }
  return d;
}

TEST(FitHeadingDrift, RecoversTheBiasOfTheOdometry) {
  for (double bias : {0.002, -0.01, 0.0}) {
    const Drive d = MakeDrive(5000, bias, 0.003, 7);
    const HeadingDriftFit fit = FitHeadingDrift(d.odometry, d.path, {100});
    EXPECT_EQ(fit.windows, 50);
    // A window of ~60 m with 0.03 rad of heading noise: b to within ~0.0005 rad/m per window,
    // and fifty windows.
    EXPECT_NEAR(fit.drift_rad_per_m, bias, 2e-4) << bias;
    EXPECT_LT(fit.rms_after_rad, 0.05);
    if (bias != 0.0) {
      EXPECT_GT(fit.rms_before_rad, 3.0 * fit.rms_after_rad);
    }
  }
}

// The path turns many times around within a window; summed step by step the turn is not lost
// to wrapping.
TEST(FitHeadingDrift, CountsWholeTurnsWithinAWindow) {
  Drive d;
  d.path.push_back({0.0, Pose2()});
  for (int k = 0; k < 400; ++k) {
    const Pose2 truth(0.5, 0.0, 0.4);  // a full turn every ~16 steps
    d.path.push_back({k + 1.0, d.path.back().pose.Compose(truth)});
    d.odometry.emplace_back(0.5, 0.0, 0.4 - 0.004 * 0.5);
  }
  const HeadingDriftFit fit = FitHeadingDrift(d.odometry, d.path, {200});
  EXPECT_NEAR(fit.drift_rad_per_m, 0.004, 1e-9);
  EXPECT_NEAR(fit.rms_before_rad, 0.004 * 100.0, 1e-9);
  EXPECT_NEAR(fit.rms_after_rad, 0.0, 1e-9);
}

TEST(FitHeadingDrift, RejectsMismatchedInputs) {
  const Drive d = MakeDrive(50, 0.0, 0.0, 1);
  Trajectory short_path(d.path.begin(), d.path.end() - 1);
  try {
    FitHeadingDrift(d.odometry, short_path);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("50 odometry steps need 51 estimated poses, got 50"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(FitHeadingDrift(d.odometry, d.path, {0}), std::invalid_argument);
  EXPECT_THROW(FitHeadingDrift(d.odometry, d.path, {100}), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
