#include "slamkit/runners/exploration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "slamkit/io/floor_plan_reader.hpp"

namespace slamkit {
namespace {

// Dead reckoning with a fixed modelled cost: the exploration loop's SLAM at its simplest.
class DeadReckoning final : public ExplorationSlam {
 public:
  explicit DeadReckoning(double cost_s) : cost_s_(cost_s) {}
  void Step(const Pose2& odometry_delta, const LaserScan& /*scan*/) override {
    pose_ = pose_.Compose(odometry_delta);
    ++steps_;
  }
  Pose2 Estimate() const override { return pose_; }
  double ModelledCostS() const override { return cost_s_; }
  int steps() const { return steps_; }
  void Start(const Pose2& p) { pose_ = p; }

 private:
  double cost_s_;
  Pose2 pose_;
  int steps_ = 0;
};

FloorPlan Office() {
  return FloorPlan{ReadFloorPlanFile(std::filesystem::path(SLAMKIT_SOURCE_DIR) /
                                     "examples/plans/office.txt")};
}

ExplorationRun Explore(double cost_s, std::uint64_t seed, double max_time_s) {
  ExplorationParams params;
  params.max_time_s = max_time_s;
  DeadReckoning slam(cost_s);
  const Pose2 start(4.0, 15.0, 0.0);
  slam.Start(start);
  Rng rng(seed);
  return RunExploration(Office(), start, slam, params, rng);
}

// SPEC S1: a step costing t holds the previous command for ⌈t / 0.1⌉ · 0.1 s.
TEST(RunExploration, TheSlamTimeHoldsThePreviousCommand) {
  const ExplorationRun slow = Explore(0.25, 1, 60.0);
  const int steps = static_cast<int>(slow.slam_time_s.size());
  ASSERT_GT(steps, 10);
  EXPECT_NEAR(slow.open_loop_time_s, 0.3 * steps, 1e-9);
  // A step is 0.3 s held plus the 0.1 s period of the new command.
  EXPECT_NEAR(slow.truth[1].t_s - slow.truth[0].t_s, 0.4, 1e-12);
  const ExplorationRun instant = Explore(0.0, 1, 60.0);
  EXPECT_EQ(instant.open_loop_time_s, 0.0);
  EXPECT_NEAR(instant.truth[1].t_s - instant.truth[0].t_s, 0.1, 1e-12);
}

TEST(RunExploration, TheSameSeedGivesTheSamePathInTheModelledMode) {
  const ExplorationRun a = Explore(0.05, 7, 40.0);
  const ExplorationRun b = Explore(0.05, 7, 40.0);
  ASSERT_EQ(a.truth.size(), b.truth.size());
  for (std::size_t i = 0; i < a.truth.size(); ++i) {
    ASSERT_EQ(a.truth[i].pose.translation(), b.truth[i].pose.translation()) << "step " << i;
  }
  const ExplorationRun other = Explore(0.05, 8, 40.0);
  EXPECT_NE(a.odometry.back().pose.translation(), other.odometry.back().pose.translation());
}

// The robot goes where the SLAM says: the estimate, not the truth, drives it. Dead reckoning
// drifts from the truth exactly as the odometry does.
TEST(RunExploration, TheEstimateIsTheSlamsAndTheRobotExplores) {
  const ExplorationRun run = Explore(0.0, 3, 120.0);
  ASSERT_FALSE(run.truth.empty());
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    ASSERT_LT((run.estimate[i].pose.translation() - run.odometry[i].pose.translation()).norm(),
              1e-9);
  }
  EXPECT_GT((run.truth.back().pose.translation() - run.truth.front().pose.translation()).norm(),
            5.0);
  // The odometry noise is there: the SLAM is not handed the truth.
  EXPECT_GT((run.truth.back().pose.translation() - run.odometry.back().pose.translation()).norm(),
            0.01);
}

}  // namespace
}  // namespace slamkit
