// Issue 32: EKF-SLAM with compressed updates (Guivant & Nebot 2001) equals the dense filter on a
// long run: 5,000 steps, more than 500 landmarks mapped, nearest-neighbour association (so the
// active area decides which landmarks are candidates), new landmarks added inside areas and old
// ones met again on every lap. A slow test (Release only: `ctest -L slow`).
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "filters/compressed_circle.hpp"

namespace slamkit {
namespace {

using testing::RelativeDiff;

TEST(CompressedEkfSlam, EqualsTheDenseFilterOverFiveThousandSteps) {
  // 4 laps of a 40 m circle in 0.2 m steps, a 10 m 60° sensor, a jittered 2.2 m grid over
  // 104 m × 104 m: about 520 landmarks within sight of the circle.
  const RangeBearingParams sensor{.max_range_m = 10.0, .fov_rad = std::numbers::pi / 3,
                                  .sigma_range_m = 0.05, .sigma_bearing_rad = 0.005};
  testing::CircleDrive drive(40.0, 0.2, 2.2, 52.0, sensor,
                             {.sigma_xy_m = 0.01, .sigma_theta_rad = 0.001});
  EkfSlam dense = drive.MakeFilter(EkfUpdateMode::kDense);
  EkfSlam compressed = drive.MakeFilter(EkfUpdateMode::kCompressed);
  std::vector<PointObservation> scan;
  for (int step = 1; step <= 5000; ++step) {
    const Control u = drive.Step(scan);
    dense.Predict(u, 0.1);
    compressed.Predict(u, 0.1);
    const std::vector<AssociationDecision> expected = dense.Update(scan);
    const std::vector<AssociationDecision> got = compressed.Update(scan);
    testing::ExpectSameDecisions(got, expected, step);
    if (::testing::Test::HasFatalFailure()) return;
    if (step % 1000 == 0) {
      compressed.Flush();  // the global update: every block current
      ASSERT_LT(RelativeDiff(compressed.State(), dense.State()), 1e-9) << "step " << step;
      ASSERT_LT(RelativeDiff(compressed.Covariance(), dense.Covariance()), 1e-9) << "step " << step;
    }
  }
  EXPECT_GE(dense.NumLandmarks(), 500);
  // Areas were opened and closed along the way, each smaller than the state.
  const CompressionStats& stats = compressed.Compression();
  EXPECT_GT(stats.global_updates, 100);
  EXPECT_LT(stats.max_active_size, compressed.StateSize() / 3);
  // The run's pose error stays within what a filter that maps its surroundings keeps.
  EXPECT_LT((compressed.pose().translation() - drive.truth().translation()).norm(), 1.0);
}

}  // namespace
}  // namespace slamkit
