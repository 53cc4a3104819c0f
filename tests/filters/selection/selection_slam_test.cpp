// EkfSlam driven by the selection policies of SPEC S1 on the simulated landmark circuit.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <memory>

#include "filters/dense_reference.hpp"
#include "filters/landmark_circuit.hpp"
#include "filters/selection_fixtures.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"

namespace slamkit {
namespace {

const OdometryParams kOdometry{.sigma_xy_m = 0.01, .sigma_theta_rad = 0.002};
const RangeBearingParams kSensor{.max_range_m = 8.0};

EkfSlamParams PerScanKnown() {
  EkfSlamParams params;
  params.association_method = AssociationMethod::kKnown;
  params.schedule = UpdateSchedule::kPerScan;  // the policies rank the whole scan
  return params;
}

std::unique_ptr<EkfSlam> MakeSlam(const EkfSlamParams& params,
                                  std::unique_ptr<SelectionPolicy> policy) {
  return std::make_unique<EkfSlam>(params, std::make_unique<OdometryModel>(kOdometry),
                                   std::make_unique<RangeBearingModel>(kSensor), nullptr,
                                   std::move(policy));
}

// SPEC S1 item 2: the dense O(n³) gains and Sylvester's O(1) ones decide alike, step by step,
// on a run where δ both keeps and drops observations.
TEST(SelectionSlam, DenseAndFastEntropyMakeTheSameDecisions) {
  const EntropySelectionParams entropy{.min_gain_nats = 0.15};
  auto dense_policy =
      std::make_unique<testing::RecordedPolicy>(std::make_unique<SelectByEntropy>(entropy));
  auto fast_policy =
      std::make_unique<testing::RecordedPolicy>(std::make_unique<SelectByEntropyFast>(entropy));
  testing::RecordedPolicy* dense_log = dense_policy.get();
  testing::RecordedPolicy* fast_log = fast_policy.get();
  auto dense = MakeSlam(PerScanKnown(), std::move(dense_policy));
  auto fast = MakeSlam(PerScanKnown(), std::move(fast_policy));
  testing::LandmarkCircuit circuit(12, 4, kOdometry, kSensor);
  const Eigen::Matrix3d P0 = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
  dense->Reset(circuit.truth(), P0);
  fast->Reset(circuit.truth(), P0);
  std::vector<PointObservation> sightings;
  int offered = 0, kept = 0;
  for (int step = 0; step < 400; ++step) {
    const Control u = circuit.Step();
    circuit.Sight(sightings);
    for (EkfSlam* slam : {dense.get(), fast.get()}) {
      slam->Predict(u, 0.1);
      slam->Update(sightings);
    }
    offered += dense->LastSelectionStats().candidates;
    kept += dense->LastSelectionStats().applied;
  }
  EXPECT_EQ(dense_log->steps, fast_log->steps);
  EXPECT_LT(testing::MaxAbsDiff(dense->State(), fast->State()), 1e-9);
  std::printf("entropy δ = %.2f nats kept %d of %d matched observations\n",
              entropy.min_gain_nats, kept, offered);
  EXPECT_GT(kept, offered / 10);
  EXPECT_LT(kept, offered - offered / 10);
}

struct RunSummary {
  double mean_pose_nees = 0.0;
  double rms_position_error_m = 0.0;
  double rms_odometry_error_m = 0.0;
  double mean_accuracy = 0.0;
  int max_applied = 0;
};

RunSummary RunCircuit(std::unique_ptr<SelectionPolicy> policy, int steps) {
  EkfSlamParams params = PerScanKnown();
  params.selection_diagnostics = true;
  auto slam = MakeSlam(params, std::move(policy));
  testing::LandmarkCircuit circuit(30, 9, kOdometry, kSensor);
  slam->Reset(circuit.truth(), Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal());
  const OdometryModel odometry(kOdometry);
  Pose2 dead_reckoning = circuit.truth();
  std::vector<PointObservation> sightings;
  RunSummary s;
  int accuracy_steps = 0;
  for (int step = 0; step < steps; ++step) {
    const Control u = circuit.Step();
    dead_reckoning = odometry.Move(dead_reckoning, u, 0.1);
    circuit.Sight(sightings);
    slam->Predict(u, 0.1);
    slam->Update(sightings);
    const Pose2& truth = circuit.truth();
    Eigen::Vector3d e = slam->pose().vector() - truth.vector();
    e[2] = WrapAngle(e[2]);
    s.mean_pose_nees += e.dot(slam->PoseCovariance().ldlt().solve(e)) / steps;
    s.rms_position_error_m += e.head<2>().squaredNorm() / steps;
    s.rms_odometry_error_m +=
        (dead_reckoning.translation() - truth.translation()).squaredNorm() / steps;
    const SelectionStats& stats = slam->LastSelectionStats();
    s.max_applied = std::max(s.max_applied, stats.applied);
    if (stats.accuracy()) {
      s.mean_accuracy += *stats.accuracy();
      ++accuracy_steps;
    }
  }
  s.rms_position_error_m = std::sqrt(s.rms_position_error_m);
  s.rms_odometry_error_m = std::sqrt(s.rms_odometry_error_m);
  s.mean_accuracy /= std::max(accuracy_steps, 1);
  return s;
}

// SPEC S1 item 3: with a budget of 3 of about 10 matched sightings a step, two laps stay
// consistent, beat odometry, and keep most of the full update's log-determinant reduction.
TEST(SelectionSlam, CovariancePolicyStaysConsistentAndBeatsOdometry) {
  const RunSummary covariance =
      RunCircuit(std::make_unique<SelectByCovariance>(CovarianceSelectionParams{.k_max = 3}), 630);
  const RunSummary all = RunCircuit(std::make_unique<SelectAll>(), 100);  // accuracy 1
  std::printf("covariance k_max 3: NEES %.2f, RMS %.3f m (odometry %.3f m), accuracy %.3f\n",
              covariance.mean_pose_nees, covariance.rms_position_error_m,
              covariance.rms_odometry_error_m, covariance.mean_accuracy);
  std::printf("all: NEES %.2f, RMS %.3f m, accuracy %.3f\n", all.mean_pose_nees,
              all.rms_position_error_m, all.mean_accuracy);
  EXPECT_GT(covariance.mean_pose_nees, 0.5);
  EXPECT_LT(covariance.mean_pose_nees, 9.0);
  EXPECT_LT(covariance.rms_position_error_m, 0.5 * covariance.rms_odometry_error_m);
  EXPECT_EQ(covariance.max_applied, 3);
  EXPECT_GT(covariance.mean_accuracy, 0.2);
  EXPECT_LT(covariance.mean_accuracy, 1.0);
  EXPECT_NEAR(all.mean_accuracy, 1.0, 1e-12);  // numerator and denominator rounded apart
}

}  // namespace
}  // namespace slamkit
