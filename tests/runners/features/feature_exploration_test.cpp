#include "slamkit/runners/features/explore_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numeric>
#include <utility>

#include "slamkit/io/floor_plan_reader.hpp"

namespace slamkit {
namespace {

struct Outcome {
  ExplorationRun run;
  std::vector<double> nees;  // per step, 3 dof
  double mean_error_m = 0.0;  // position, over the steps
  double odometry_mean_error_m = 0.0;
};

// The office explored with the line-and-corner EKF under `kind`, modelled timing.
Outcome Explore(SelectionKind kind, double max_time_s) {
  const FloorPlan plan{ReadFloorPlanFile(std::filesystem::path(SLAMKIT_SOURCE_DIR) /
                                         "examples/plans/office.txt")};
  ExplorationConfig config;
  config.start = Pose2(4.0, 15.0, 0.0);
  config.seed = 5;
  config.run.max_time_s = max_time_s;
  config.run.sigma_v_mps = 0.05;  // wheels that slip: odometry the SLAM has to beat
  config.run.sigma_omega_radps = 0.05;
  config.slam.selection = kind;
  config.slam.sigma_v_mps = config.run.sigma_v_mps;
  config.slam.sigma_omega_radps = config.run.sigma_omega_radps;
  config.slam.control_period_s = config.run.control_period_s;
  ExploreResult r = RunFeatureExploration(plan, config);
  const nlohmann::json m = ExploreMetrics(r, config);
  return {std::move(r.run), std::move(r.nees), m["mean_error_m"].get<double>(),
          m["odometry_mean_error_m"].get<double>()};
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
