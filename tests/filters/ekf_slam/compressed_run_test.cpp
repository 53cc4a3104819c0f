// Issue 32: EKF-SLAM with compressed updates (Guivant & Nebot 2001) equals the dense filter on a
// long run: 5,000 steps, more than 500 landmarks mapped, nearest-neighbour association (so the
// active area decides which landmarks are candidates), new landmarks added inside areas and old
// ones met again on every lap. A slow test (Release only: `ctest -L slow`).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/ordered_draws.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

double RelativeDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

EkfSlam MakeFilter(EkfUpdateMode update, const RangeBearingParams& sensor,
                   const OdometryParams& odometry) {
  EkfSlamParams params;
  params.update = update;
  params.association.gate_chi2 = 9.21;
  params.association.new_landmark_chi2 = 30.0;
  params.association_margin_m = 1.0;
  EkfSlam slam(params, std::make_unique<OdometryModel>(odometry),
               std::make_unique<RangeBearingModel>(sensor));
  slam.Reset(Pose2(40.0, 0.0, std::numbers::pi / 2));
  return slam;
}

TEST(CompressedEkfSlam, EqualsTheDenseFilterOverFiveThousandSteps) {
  constexpr int kSteps = 5000;
  constexpr double kStepM = 0.2, kCircleM = 40.0;  // 1,257 steps a lap: 4 laps
  const RangeBearingParams sensor{.max_range_m = 10.0, .fov_rad = std::numbers::pi / 3,
                                  .sigma_range_m = 0.05, .sigma_bearing_rad = 0.005};
  const OdometryParams odometry{.sigma_xy_m = 0.01, .sigma_theta_rad = 0.001};
  const RangeBearingModel truth_sensor(sensor);
  // A jittered 2.2 m grid over 104 m × 104 m: about 520 landmarks within sight of the circle.
  Rng rng(32);
  std::vector<Eigen::Vector2d> world;
  for (double x = -52.0; x <= 52.0; x += 2.2) {
    for (double y = -52.0; y <= 52.0; y += 2.2) {
      world.push_back(Eigen::Vector2d(x, y) + testing::UniformVector2(rng, -0.8, 0.8, -0.8, 0.8));
    }
  }
  EkfSlam dense = MakeFilter(EkfUpdateMode::kDense, sensor, odometry);
  EkfSlam compressed = MakeFilter(EkfUpdateMode::kCompressed, sensor, odometry);
  Pose2 truth(kCircleM, 0.0, std::numbers::pi / 2);
  std::vector<PointObservation> scan;
  for (int step = 1; step <= kSteps; ++step) {
    const Pose2 move(kStepM, 0.0, kStepM / kCircleM);
    truth = truth.Compose(move);
    Control u(3);
    u << move.x() + rng.Normal(0, odometry.sigma_xy_m), move.y() + rng.Normal(0, odometry.sigma_xy_m),
        move.theta() + rng.Normal(0, odometry.sigma_theta_rad);
    scan.clear();
    for (const Eigen::Vector2d& l : world) {
      if (!truth_sensor.IsVisible(truth, l)) continue;
      PointObservation obs;
      obs.z = truth_sensor.Predict(truth, l) +
              testing::NormalVector2(rng, sensor.sigma_range_m, sensor.sigma_bearing_rad);
      obs.R = truth_sensor.NoiseCovariance();
      scan.push_back(obs);
    }
    dense.Predict(u, 0.1);
    compressed.Predict(u, 0.1);
    const std::vector<AssociationDecision> expected = dense.Update(scan);
    const std::vector<AssociationDecision> got = compressed.Update(scan);
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      ASSERT_EQ(got[i].kind, expected[i].kind) << "step " << step << ", sighting " << i;
      ASSERT_EQ(got[i].landmark, expected[i].landmark) << "step " << step << ", sighting " << i;
    }
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
  EXPECT_LT((compressed.pose().translation() - truth.translation()).norm(), 1.0);
}

}  // namespace
}  // namespace slamkit
