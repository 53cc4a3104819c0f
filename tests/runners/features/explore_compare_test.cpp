// The comparison of SPEC S1's selection policies: its summary is the runs' numbers aggregated,
// its output does not depend on the thread count, and its diagnostics change nothing.
#include "slamkit/runners/features/explore_compare.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include "common/temp_dir.hpp"
#include "slamkit/io/floor_plan_reader.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

ExplorationConfig ShortConfig(double max_time_s) {
  ExplorationConfig config =
      LoadExplorationConfig(fs::path(SLAMKIT_SOURCE_DIR) / "configs/office_selection.yaml");
  config.run.max_time_s = max_time_s;
  return config;
}

FloorPlan PlanOf(const ExplorationConfig& config) {
  return FloorPlan{ReadFloorPlanFile(config.world)};
}

ExploreCompareParams TwoPoliciesThreeSeeds(int threads) {
  ExploreCompareParams params;
  params.policies = {SelectionKind::kAll, SelectionKind::kCovariance};
  params.seeds = {1, 2, 3};
  params.threads = threads;
  return params;
}

// Wall times are the only figures that may differ between two identical comparisons.
void DropWallTimes(nlohmann::json& j) {
  if (j.is_object()) {
    j.erase("wall_time_s");
    for (auto& [key, value] : j.items()) DropWallTimes(value);
  } else if (j.is_array()) {
    for (nlohmann::json& v : j) DropWallTimes(v);
  }
}

nlohmann::json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

class ExploreCompare : public testing::TempDirTest {};

TEST_F(ExploreCompare, TheSummaryIsTheRunsAggregated) {
  const ExplorationConfig config = ShortConfig(25.0);
  const ExploreCompareResult r =
      RunExploreCompare(PlanOf(config), config, TwoPoliciesThreeSeeds(0));
  ASSERT_EQ(r.runs.size(), 6u);
  ASSERT_EQ(r.policies.size(), 2u);
  ASSERT_EQ(r.first_seed.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    const ComparePolicySummary& s = r.policies[p];
    double total = 0.0, max_step = 0.0, accuracy = 0.0;
    int accuracy_steps = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const CompareRun& run = r.runs[3 * p + k];
      EXPECT_EQ(run.policy, s.policy);
      EXPECT_EQ(run.seed, k + 1);
      total += run.figures.slam_time_total_s;
      max_step = std::max(max_step, run.figures.slam_time_max_s);
      accuracy += run.accuracy_sum;
      accuracy_steps += run.accuracy_steps;
    }
    EXPECT_NEAR(s.slam_time_total_s.mean, total / 3.0, 1e-12);
    EXPECT_EQ(s.slam_time_max_s, max_step);
    ASSERT_GT(accuracy_steps, 0);
    EXPECT_NEAR(*s.accuracy_step_mean, accuracy / accuracy_steps, 1e-12);
    ASSERT_FALSE(s.anees.empty());
    const double first =
        (r.runs[3 * p].nees[0] + r.runs[3 * p + 1].nees[0] + r.runs[3 * p + 2].nees[0]) / 3.0;
    EXPECT_NEAR(s.anees[0], first, 1e-12);
    // The kept first-seed run is the run the summary counted.
    EXPECT_EQ(static_cast<int>(r.first_seed[p].run.slam_time_s.size()), r.runs[3 * p].figures.steps);
  }
  // Every update applied: the whole reduction kept. The covariance policy keeps at most k_max.
  EXPECT_NEAR(*r.policies[0].accuracy_step_mean, 1.0, 1e-9);
  EXPECT_LT(*r.policies[1].accuracy_step_mean, 1.0);
  ASSERT_EQ(r.savings.size(), 1u);
  EXPECT_NEAR(
      r.savings[0].of_means_pct,
      100.0 * (1.0 - r.policies[1].slam_time_total_s.mean / r.policies[0].slam_time_total_s.mean),
      1e-9);
  EXPECT_LE(r.savings[0].min_pct, r.savings[0].max_pct);
}

TEST_F(ExploreCompare, ParallelAndOneThreadWriteTheSameOutput) {
  const ExplorationConfig config = ShortConfig(15.0);
  const FloorPlan plan = PlanOf(config);
  for (const int threads : {1, 3}) {
    const fs::path dir = dir_ / std::to_string(threads);
    fs::create_directories(dir);
    WriteExploreCompareOutputs(dir, RunExploreCompare(plan, config, TwoPoliciesThreeSeeds(threads)),
                               config, TwoPoliciesThreeSeeds(threads), "cmd");
  }
  nlohmann::json one = ReadJson(dir_ / "1" / "metrics.json");
  nlohmann::json many = ReadJson(dir_ / "3" / "metrics.json");
  DropWallTimes(one);
  DropWallTimes(many);
  EXPECT_EQ(one, many);
  EXPECT_EQ(one["runs"].size(), 6u);
}

// The accuracy diagnostics run the full update on a copy: the path and the modelled cost are
// those without them.
TEST_F(ExploreCompare, DiagnosticsChangeNeitherPathNorCost) {
  ExplorationConfig config = ShortConfig(30.0);
  config.slam.selection = SelectionKind::kCovariance;
  const FloorPlan plan = PlanOf(config);
  const ExploreResult off = RunFeatureExploration(plan, config);
  config.slam.ekf.selection_diagnostics = true;
  const ExploreResult on = RunFeatureExploration(plan, config);
  EXPECT_TRUE(off.accuracy.empty());
  ASSERT_EQ(on.accuracy.size(), on.run.truth.size());
  ASSERT_EQ(off.run.truth.size(), on.run.truth.size());
  for (std::size_t i = 0; i < on.run.truth.size(); ++i) {
    ASSERT_EQ(off.run.truth[i].pose.translation(), on.run.truth[i].pose.translation()) << i;
    ASSERT_EQ(off.run.truth[i].pose.theta(), on.run.truth[i].pose.theta()) << i;
  }
  EXPECT_EQ(off.run.slam_time_s, on.run.slam_time_s);
  int with_ratio = 0;
  for (const std::optional<double>& a : on.accuracy) with_ratio += a.has_value();
  EXPECT_GT(with_ratio, int(on.accuracy.size()) / 2);
}

// Measured timing runs one at a time (in order), measures (not zero) and leaves the diagnostics
// off.
TEST_F(ExploreCompare, WallTimingMeasuresEachRun) {
  ExplorationConfig config = ShortConfig(5.0);
  config.run.timing = SlamTiming::kWallClock;
  ExploreCompareParams params;
  params.policies = {SelectionKind::kCovariance};
  params.seeds = {7, 8};
  std::vector<int> done;
  const ExploreCompareResult r =
      RunExploreCompare(PlanOf(config), config, params, [&done](int d, int) { done.push_back(d); });
  EXPECT_EQ(done, (std::vector<int>{1, 2}));
  ASSERT_EQ(r.runs.size(), 2u);
  EXPECT_EQ(r.runs[1].seed, 8u);
  EXPECT_GT(r.policies[0].slam_time_total_s.min, 0.0);
  EXPECT_TRUE(r.savings.empty());  // nothing to save against
  // The diagnostics' full update would be timed with the step: off.
  EXPECT_EQ(r.runs[0].accuracy_steps, 0);
  EXPECT_FALSE(r.policies[0].accuracy_step_mean.has_value());
}

TEST_F(ExploreCompare, NoPolicyOrNoSeedIsRejected) {
  const ExplorationConfig config = ShortConfig(5.0);
  ExploreCompareParams params;
  params.seeds.clear();
  EXPECT_THROW(RunExploreCompare(PlanOf(config), config, params), std::invalid_argument);
  params = {};
  params.policies.clear();
  EXPECT_THROW(RunExploreCompare(PlanOf(config), config, params), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
