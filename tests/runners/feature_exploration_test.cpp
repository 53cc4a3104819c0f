#include "slamkit/runners/feature_exploration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numeric>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/floor_plan_reader.hpp"

namespace slamkit {
namespace {

struct Outcome {
  ExplorationRun run;
  std::vector<double> nees;  // per step, 3 dof
  double mean_error_m = 0.0;           // position, over the steps
  double odometry_mean_error_m = 0.0;
};

// The office explored with the line-and-corner EKF under `kind`, modelled timing.
Outcome Explore(SelectionKind kind, double max_time_s) {
  const FloorPlan plan{ReadFloorPlanFile(std::filesystem::path(SLAMKIT_SOURCE_DIR) /
                                         "examples/plans/office.txt")};
  ExplorationParams params;
  params.max_time_s = max_time_s;
  params.sigma_v_mps = 0.05;  // wheels that slip: odometry the SLAM has to beat
  params.sigma_omega_radps = 0.05;
  FeatureSlamParams slam_params;
  slam_params.selection = kind;
  slam_params.sigma_v_mps = params.sigma_v_mps;
  slam_params.sigma_omega_radps = params.sigma_omega_radps;
  slam_params.control_period_s = params.control_period_s;
  const Pose2 start(4.0, 15.0, 0.0);
  FeatureExplorationSlam slam(slam_params, start);
  // NEES needs the covariance at each step: a thin wrapper records it as the loop runs.
  struct Recording final : ExplorationSlam {
    FeatureExplorationSlam* inner;
    std::vector<Eigen::Matrix3d>* covariances;
    void Step(const Pose2& d, const LaserScan& s) override {
      inner->Step(d, s);
      covariances->push_back(inner->PoseCovariance());
    }
    Pose2 Estimate() const override { return inner->Estimate(); }
    double ModelledCostS() const override { return inner->ModelledCostS(); }
  };
  std::vector<Eigen::Matrix3d> covariances;
  Recording recording;
  recording.inner = &slam;
  recording.covariances = &covariances;
  Rng rng(5);
  Outcome out{RunExploration(plan, start, recording, params, rng), {}, 0.0, 0.0};
  for (std::size_t i = 1; i < out.run.truth.size(); ++i) {
    const Pose2& x = out.run.truth[i].pose;
    const Pose2& e = out.run.estimate[i].pose;
    const Eigen::Vector3d err(e.x() - x.x(), e.y() - x.y(), WrapAngle(e.theta() - x.theta()));
    out.nees.push_back(err.dot(covariances[i].ldlt().solve(err)));
  }
  const double n = static_cast<double>(out.run.truth.size());
  for (std::size_t i = 0; i < out.run.truth.size(); ++i) {
    const Eigen::Vector2d x = out.run.truth[i].pose.translation();
    out.mean_error_m += (out.run.estimate[i].pose.translation() - x).norm() / n;
    out.odometry_mean_error_m += (out.run.odometry[i].pose.translation() - x).norm() / n;
  }
  return out;
}

double Mean(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double Total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// SPEC S1: the covariance policy drives the robot through the office consistently, better than
// its odometry, and for less correction work than the full sequential update. One run's mean
// NEES moves with its path (over seeds 1-20 of 300 s each, single runs of SelectAll range from
// 0.9 to 13.5 while their mean is 3.1), hence the wide band: the ANEES over many seeds against
// its χ² band is the study's to report.
TEST(FeatureExploration, TheCovariancePolicyExploresConsistently) {
  const Outcome cov = Explore(SelectionKind::kCovariance, 200.0);
  ASSERT_GT(cov.nees.size(), 200u);
  EXPECT_LT(cov.mean_error_m, 0.5 * cov.odometry_mean_error_m);
  EXPECT_LT(Mean(cov.nees), 3.0 * 3.0) << "over-confident";
  EXPECT_GT(Mean(cov.nees), 3.0 / 10.0) << "far too cautious";
  const Outcome all = Explore(SelectionKind::kAll, 200.0);
  EXPECT_LT(all.mean_error_m, 0.5 * all.odometry_mean_error_m);
  EXPECT_LT(Mean(all.nees), 3.0 * 3.0) << "over-confident";
  EXPECT_LT(Total(cov.run.slam_time_s) / cov.nees.size(),
            Total(all.run.slam_time_s) / all.nees.size());
}

// The dense entropy policy's modelled cost carries its n³ per candidate.
TEST(FeatureExploration, DenseEntropyCostsMoreThanItsFastForm) {
  const Outcome dense = Explore(SelectionKind::kEntropy, 30.0);
  const Outcome fast = Explore(SelectionKind::kEntropyFast, 30.0);
  EXPECT_GT(Total(dense.run.slam_time_s), 5.0 * Total(fast.run.slam_time_s));
}

TEST(FeatureExploration, PolicyNamesRoundTripAndUnknownOnesAreRejected) {
  for (const char* name : {"all", "entropy", "entropy-fast", "covariance"}) {
    EXPECT_EQ(SelectionKindName(SelectionKindOf(name)), name);
  }
  EXPECT_THROW(SelectionKindOf("greedy"), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
